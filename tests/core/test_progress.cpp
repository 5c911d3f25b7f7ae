#include <gtest/gtest.h>

#include "skyview/core/progress.h"

TEST(ProgressCounter, FractionIsClampedAndCounts) {
  skyview::ProgressCounter c;
  c.set_total(4);
  EXPECT_DOUBLE_EQ(c.fraction(), 0.0);
  c.advance(2);
  EXPECT_DOUBLE_EQ(c.fraction(), 0.5);
  c.advance(10);
  EXPECT_DOUBLE_EQ(c.fraction(), 1.0);
}
