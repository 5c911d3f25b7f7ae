#include "horizon_keywords.h"

#include <cmath>
#include <initializer_list>

#include "skyview/core/error.h"

namespace skyview::python {

namespace {

template <class T>
void set(HorizonRequest& r, const std::optional<T>& value, T& field, const char* option) {
  if (!value) return;
  field = *value;
  r.given.insert(option);
}

void check_member(const std::optional<std::string>& value, const char* name, std::initializer_list<const char*> ok) {
  if (!value) return;
  std::string list;
  for (const char* o : ok) {
    if (*value == o) return;
    list += list.empty() ? o : std::string(", ") + o;
  }
  throw UsageError(std::string(name) + " '" + *value + "' is not one of " + list);
}

}  // namespace

void apply(HorizonRequest& r, const HorizonKeywords& k) {
  // The checks CLI11 makes on these options before the library sees them.
  check_member(k.edge, "edge", {"open", "nodata"});
  check_member(k.curvature, "curvature", {"auto", "on", "off"});
  check_member(k.azimuth_origin, "azimuth_origin", {"north", "grid"});
  check_member(k.azimuths, "azimuths", {"uniform", "grid-lines"});
  if (k.far_lines && *k.far_lines != 1 && *k.far_lines != 2) throw UsageError("far_lines must be 1 or 2");
  if (k.radius && !(std::isfinite(*k.radius) && *k.radius > 0)) throw UsageError("radius must be a positive number");
  if (k.refraction && !std::isfinite(*k.refraction)) throw UsageError("refraction must be a finite number");
  if (k.max_error && !(*k.max_error > 0.0 && *k.max_error <= 1.0)) throw UsageError("max_error must be in (0, 1]");
  set(r, k.method, r.method, r.method_option.c_str());
  set(r, k.directions, r.params.directions, "--directions");
  set(r, k.samples, r.params.samples, "--samples");
  set(r, k.far_lines, r.params.far_lines, "--far-lines");
  set(r, k.radius, r.params.radius, "--radius");
  set(r, k.rays, r.params.rays, "--rays");
  set(r, k.seed, r.params.seed, "--seed");
  set(r, k.refraction, r.params.refraction, "--refraction");
  set(r, k.azimuth_origin, r.azimuth_origin, "--azimuth-origin");
  set(r, k.azimuths, r.azimuths, "--azimuths");
  if (k.edge) r.edge = *k.edge;
  if (k.curvature) r.params.curvature = *k.curvature;
  if (k.max_error) r.max_error = *k.max_error;
  r.params.early_exit = k.early_exit;
}

}  // namespace skyview::python
