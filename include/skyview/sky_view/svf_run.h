#pragma once
// A whole `skyview svf` run on a raster already read: the products asked for, with --check-cells'
// measurement and --max-error's reruns, and the bands as the output holds them. The command line,
// the Python module and tiled runs call this one function.
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "skyview/core/progress.h"
#include "skyview/sky_view/horizon_request.h"
#include "skyview/sky_view/sky_view.h"

namespace skyview {

// A band `skyview svf` can write: its name, unit, definition and product.
struct SvfProductInfo {
  const char* name;
  const char* unit;
  const char* definition;
  Product product;
};
// In their default order.
const std::vector<SvfProductInfo>& svf_products();
// "svf,svf_surface,..." parsed; throws skyview::Error for an unknown or repeated name or none.
std::vector<const SvfProductInfo*> parse_svf_products(const std::string& list);
// The default --products list.
std::string default_svf_products();

// The horizon options of an svf run before any is given: HorizonRequest's, with the sectors
// centred from grid north (every band sums over azimuth, and the sweep finds the grid's axes and
// diagonals exactly and fastest). `skyview svf` and skyview.svf() start from it.
HorizonRequest default_svf_horizon_request();

struct SvfRequest {
  HorizonRequest horizon = default_svf_horizon_request();
  std::string products = default_svf_products();
  // Cells to measure the svf's error on (SVF_CHECK_*); -1: 1000 with --max-error, else none.
  int check_cells = -1;
  // Horizons beyond the method's radius (a tiled run's far field, docs/tiling.md); null: none.
  std::shared_ptr<const FarHorizons> far_field;
};

struct SvfBand {
  std::string name, unit;
  std::map<std::string, std::string> metadata;  // DEFINITION
  Grid<float> values;                           // NaN = nodata
};

struct SvfResult {
  std::vector<SvfBand> bands;                   // in the order asked, then any Monte-Carlo bands
  std::map<std::string, std::string> metadata;  // the method's and the check's (not the input's)
  std::vector<std::string> messages;            // progress lines for stderr (the check, reruns)
  std::vector<std::string> warnings;            // for stderr even under -q
};

// Throws skyview::Error for a request that cannot run (before any input is read).
void check_svf_request(const SvfRequest& request);

// The products of the cells of `window` (all of `terrain` when empty), the rest of the buffer
// occluding as halo. `setup` comes from plan_horizon and fit_horizon on the same request and
// terrain; --max-error's reruns change its engine. `run` wraps the computation (progress on a
// terminal): it gets the counter to advance by the window's cells.
SvfResult run_svf(const Terrain& terrain, const SvfRequest& request, HorizonSetup& setup,
                  const std::function<void(const std::function<void(ProgressCounter&)>&)>& run,
                  const Window& window = {});

}  // namespace skyview
