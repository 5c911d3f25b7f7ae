#pragma once
// The SPA report's periodic-term tables, embedded as arrays (spa_earth_terms.cpp, spa_nutation_terms.cpp).

namespace skyview::spa {

// One row of an Earth series: A * cos(B + C * JME).
struct PeriodicTerm {
  double a, b, c;
};

// One L_i / B_i / R_i sum: the rows and how many.
struct TermSeries {
  const PeriodicTerm* terms;
  int count;
};

extern const TermSeries kLSeries[6];  // heliocentric longitude, L0..L5
extern const TermSeries kBSeries[2];  // heliocentric latitude, B0..B1
extern const TermSeries kRSeries[5];  // radius vector, R0..R4

// One nutation row: integer multipliers of X0..X4 and the coefficients in 0.0001".
struct NutationTerm {
  int y[5];
  double a, b, c, d;
};

constexpr int kNutationTermCount = 63;
extern const NutationTerm kNutationTerms[kNutationTermCount];

}  // namespace skyview::spa
