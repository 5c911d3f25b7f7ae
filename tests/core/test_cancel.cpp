// A cancelled ProgressCounter stops every horizon method with Cancelled before it computes a cell,
// and the streaming sweep hands over no direction after it (nothing waits for one never taken).
#include "skyview/core/error.h"
#include "test_support.h"

using namespace skyview;
using namespace skyview::test;

TEST(Cancel, EveryMethodStopsWithCancelled) {
  const Terrain t = rasterize(synthetic_city(3), 61, 51, local_grid(61, 51, 1.0));
  HorizonParams p;
  p.directions = 16;
  p.radius = 20;
  for (const std::string& method : horizon_method_names()) {
    ProgressCounter progress;
    progress.cancel();
    HorizonField field;
    EXPECT_THROW(make_horizon_engine(method, p)->compute(t, Window::whole(t), field, progress), Cancelled) << method;
    EXPECT_EQ(progress.fraction(), 0.0) << method << ": no cell was computed";
  }
  const auto sweep = make_horizon_engine("sweep", p);
  ProgressCounter progress;
  progress.cancel();
  HorizonField rest;
  int handed = 0;
  EXPECT_THROW(sweep->compute_directions(t, Window::whole(t), rest, progress,
                                         [&](int, int, const float*, const float*) { ++handed; }),
               Cancelled);
  EXPECT_EQ(handed, 0);
  try {
    progress.stop_if_cancelled();
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(), "cancelled");  // what Python raises as skyview.Error
  }
}
