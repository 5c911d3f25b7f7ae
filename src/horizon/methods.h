#pragma once
// Constructors of the HorizonEngine implementations, one file each; only the factory calls them.
#include <memory>

#include "skyview/horizon_engine.h"

namespace skyview::detail {

std::unique_ptr<HorizonEngine> make_sampled_engine(const HorizonParams& params);
std::unique_ptr<HorizonEngine> make_march_engine(const HorizonParams& params);
std::unique_ptr<HorizonEngine> make_sweep_engine(const HorizonParams& params);
std::unique_ptr<HorizonEngine> make_raycast_engine(const HorizonParams& params);

}  // namespace skyview::detail
