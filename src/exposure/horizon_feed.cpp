#include "exposure/horizon_feed.h"

namespace skyview::detail {

void feed_horizons(const HorizonEngine& engine, const Terrain& terrain, const Window& window, ProgressCounter& progress,
                   std::size_t horizon_bytes, const ConsumerFactory& consumer_for) {
  if (engine.streams_directions()) {
    const std::unique_ptr<HorizonConsumer> consumer = consumer_for(window);
    HorizonField field;
    engine.compute_directions(
        terrain, window, field, progress,
        [&](int first, int count, const float* upper, const float*) { consumer->add(first, count, upper, field); });
    consumer->finish();
    return;
  }
  compute_by_row_blocks(engine, terrain, window, progress, horizon_bytes, 1,
                        [&](const Window& block, HorizonField& field) {
                          const std::unique_ptr<HorizonConsumer> consumer = consumer_for(block);
                          consumer->add(0, field.directions, field.upper.data(), field);
                          consumer->finish();
                        });
}

}  // namespace skyview::detail
