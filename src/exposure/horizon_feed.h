#pragma once
// Horizons from an engine to whatever sums them per cell, without holding every direction of a
// large window: engines that find one direction at a time (the sweep) hand the whole window's
// planes over as they finish them; the others compute blocks of whole rows, each summed before the
// next (compute_by_row_blocks). What exposure, sun hours and shadows share.
#include <functional>
#include <memory>

#include "skyview/horizon/horizon_engine.h"
#include "skyview/sky_view/sky_view.h"

namespace skyview::detail {

// Sums over one window (or block of rows) of the window computed.
class HorizonConsumer {
 public:
  virtual ~HorizonConsumer() = default;
  // Directions [first, first + count) in order from 0, planes laid out as in HorizonField; `field`
  // for the cells' rotations and the set's.
  virtual void add(int first, int count, const float* upper, const HorizonField& field) = 0;
  // Every direction has been added.
  virtual void finish() = 0;
};

using ConsumerFactory = std::function<std::unique_ptr<HorizonConsumer>(const Window& block)>;

// With `far` (a tiled run's far field), every direction's upper angles are raised by it before the
// consumer sees them.
void feed_horizons(const HorizonEngine& engine, const Terrain& terrain, const Window& window, ProgressCounter& progress,
                   std::size_t horizon_bytes, const ConsumerFactory& consumer_for, const FarHorizons* far = nullptr);

}  // namespace skyview::detail
