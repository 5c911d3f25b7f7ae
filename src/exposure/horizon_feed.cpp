#include "exposure/horizon_feed.h"

#include <vector>

namespace skyview::detail {

void feed_horizons(const HorizonEngine& engine, const Terrain& terrain, const Window& window, ProgressCounter& progress,
                   std::size_t horizon_bytes, const ConsumerFactory& consumer_for, const FarHorizons* far) {
  if (engine.streams_directions()) {
    const std::unique_ptr<HorizonConsumer> consumer = consumer_for(window);
    HorizonField field;
    std::vector<float> raised;  // a batch's planes raised by the far field
    engine.compute_directions(terrain, window, field, progress,
                              [&](int first, int count, const float* upper, const float*) {
                                if (far) {
                                  const std::size_t cells = static_cast<std::size_t>(window.cells());
                                  raised.assign(upper, upper + cells * count);
                                  for (int k = 0; k < count; ++k)
                                    far->raise(terrain, window, field, first + k, raised.data() + cells * k);
                                  upper = raised.data();
                                }
                                consumer->add(first, count, upper, field);
                              });
    consumer->finish();
    return;
  }
  compute_by_row_blocks(engine, terrain, window, progress, horizon_bytes, 1,
                        [&](const Window& block, HorizonField& field) {
                          if (far) {
                            for (int k = 0; k < field.directions; ++k)
                              far->raise(terrain, block, field, k, field.upper_plane(k));
                          }
                          const std::unique_ptr<HorizonConsumer> consumer = consumer_for(block);
                          consumer->add(0, field.directions, field.upper.data(), field);
                          consumer->finish();
                        });
}

}  // namespace skyview::detail
