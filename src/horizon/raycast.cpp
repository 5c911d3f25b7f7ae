// The ray-cast reference. The terrain (the buffer as HorizonEngine::compute extends it at the
// raster's edges, so at least three cells each way) becomes the surface mesh every method reads
// (surface_mesh.h: triangles over cell centres, creases that are valleys, skirts on open edges),
// in the ground frame at the buffer's centre (the raster's, but for blocks cut with a radius). Per cell
// and direction, rays leave the cell's own vertex and ignore the triangles around it; a
// heightfield seen from its surface is blocked below the horizon and open above it, and the
// horizon is bracketed to 1e-5 rad by rays that climb over each occluder's top (climb_horizon).
// The svf is also estimated directly by stratified cosine-weighted hemisphere sampling, with its
// standard error, as an independent check of the per-sector integration.
#include <embree3/rtcore.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "core/embree_device.h"
#include "methods.h"
#include "ray_scan.h"
#include "skyview/core/error.h"
#include "skyview/core/number_text.h"
#include "skyview/horizon/surface_mesh.h"
#include "track_box.h"

namespace skyview::detail {
namespace {

// The eye sits exactly on its own vertex, so its rays would hit the triangles around it at
// distance zero. (Lifting it instead, by 64 float steps of the mesh's extent, 7.6 mm on a 1 km
// raster, lowered the horizons that the nearest cells make on rough terrain: p99 |svf error| 0.0018
// between the march and the reference on a real 1 m lidar DEM.) The occlusion filter rejects hits
// on triangles that share a vertex with the eye; a ray through one of them meets the plane only at
// the eye. What those triangles block is decided without Embree: a ray below the slope to where its
// ground track leaves them (its first row or column crossing, TerrainMesh::first_crossing_slope)
// goes into the terrain at once; above it, it clears them (their far edges lie on grid lines, and
// inside a quad the mesh's crease is a valley).
struct EyeContext {
  RTCIntersectContext base;  // first, so that Embree's pointer to it is one to the whole
  unsigned vertex = 0;       // the eye's vertex in the mesh over cell centres
};

// Where rays leave: a cell's vertex, or (point queries) any point above the surface, which has no
// vertex and whose rays need no filter (kNoVertex matches none).
constexpr unsigned kNoVertex = 0xFFFFFFFFu;
struct Eye {
  double col = 0, row = 0;  // pixel position in the buffer
  double z = 0;             // height in the mesh's sign
  unsigned vertex = kNoVertex;
};

// What the filter and the horizon search know of the mesh: its triangles and vertices (Embree
// owns both buffers).
struct Triangles {
  const unsigned* indices = nullptr;
  const float* vertices = nullptr;  // x, y, z per vertex
};

void reject_own_triangles(const RTCFilterFunctionNArguments* args) {
  const auto* mesh = static_cast<const Triangles*>(args->geometryUserPtr);
  const auto* eye = reinterpret_cast<const EyeContext*>(args->context);
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] != -1) continue;
    const unsigned* v = mesh->indices + 3 * RTCHitN_primID(args->hit, args->N, i);
    if (v[0] == eye->vertex || v[1] == eye->vertex || v[2] == eye->vertex) args->valid[i] = 0;
  }
}

// Vertices in metres east/north of the buffer's first cell and height relative to the base.
class TerrainMesh {
 public:
  TerrainMesh(RTCDevice device, const Terrain& t, double sign) : t_(t), sign_(sign), box_(track_box(t)) {
    const int w = t.width(), h = t.height();
    width_ = w;
    j_ = t.frame.at(t.origin_col + 0.5 * w, t.origin_row + 0.5 * h);
    scene_.reset(rtcNewScene(device));
    rtcSetSceneFlags(scene_.get(), RTC_SCENE_FLAG_ROBUST);
    RTCGeometry geom = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
    SurfaceMesh mesh = surface_mesh(t, sign, 1000 * kSkirtOut * j_.min_cell_size());
    std::vector<unsigned>& idx = mesh.triangles;
    const std::vector<SurfaceMesh::SkirtVertex>& skirt = mesh.skirt_vertices;
    const std::size_t grid = static_cast<std::size_t>(w) * h;
    auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                          3 * sizeof(float), grid + skirt.size()));
    auto put = [&](std::size_t i, double c, double r, float z) {
      v[3 * i + 0] = static_cast<float>(j_.a * c + j_.b * r);
      v[3 * i + 1] = static_cast<float>(j_.c * c + j_.d * r);
      v[3 * i + 2] = std::isnan(z) ? 0.0f : static_cast<float>(sign * z);
    };
    for (int r = 0; r < h; ++r) {
      for (int c = 0; c < w; ++c) put(t.heights.index(c, r), c, r, t.heights(c, r));
    }
    for (std::size_t i = 0; i < skirt.size(); ++i) put(grid + i, skirt[i].col, skirt[i].row, skirt[i].z);
    if (idx.empty()) idx = {0, 0, 0};  // a degenerate triangle keeps Embree happy where all is nodata
    auto* ib = static_cast<unsigned*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                              3 * sizeof(unsigned), idx.size() / 3));
    std::copy(idx.begin(), idx.end(), ib);
    mesh_ = {ib, v};
    rtcSetGeometryUserData(geom, &mesh_);
    rtcSetGeometryOccludedFilterFunction(geom, reject_own_triangles);
    rtcSetGeometryIntersectFilterFunction(geom, reject_own_triangles);
    rtcCommitGeometry(geom);
    rtcAttachGeometry(scene_.get(), geom);
    rtcReleaseGeometry(geom);
    rtcCommitScene(scene_.get());
  }

  // The eye of cell (col, row), on its vertex at its height (in this mesh's sign).
  Eye cell_eye(int col, int row) const {
    return {static_cast<double>(col), static_cast<double>(row), sign_ * t_.heights(col, row),
            static_cast<unsigned>(row * width_ + col)};
  }

  // The context that tells the filter whose triangles to ignore.
  static EyeContext context_of(const Eye& e) {
    EyeContext context;
    rtcInitIntersectContext(&context.base);
    context.vertex = e.vertex;
    return context;
  }

  // A ray from the eye (for a cell, the same floats as its vertex).
  RTCRay ray_from(const Eye& e, double sin_az, double cos_az, double elevation, double range) const {
    RTCRay ray{};
    ray.org_x = static_cast<float>(j_.a * e.col + j_.b * e.row);
    ray.org_y = static_cast<float>(j_.c * e.col + j_.d * e.row);
    ray.org_z = static_cast<float>(e.z);
    const double ce = std::cos(elevation);
    ray.dir_x = static_cast<float>(ce * sin_az);
    ray.dir_y = static_cast<float>(ce * cos_az);
    ray.dir_z = static_cast<float>(std::sin(elevation));
    // No tnear: a wall one cell away may be hit arbitrarily close to the eye. The filter alone keeps
    // the rays off the eye's own triangles.
    ray.tnear = 0.0f;
    // The search radius is a ground distance: a steep ray may travel farther before it is reached.
    ray.tfar =
        std::isinf(range) ? std::numeric_limits<float>::infinity() : static_cast<float>(range / std::max(ce, 1e-9));
    ray.mask = 0xFFFFFFFFu;
    return ray;
  }

  // The ground distance, along the azimuth, of the last row or column crossing within `range`; 0
  // where none is. The mesh peaks only on grid lines, and the march and the sweep read it there up
  // to the last crossing within their radius, so with a radius the ray cast stops there too. Until
  // Dec 3 it stopped at the radius itself, inside a quad, where the ramp up to a building just
  // beyond the last crossing counted: 69° where the march, seeing nothing, read 0.06°.
  double reach(double sin_az, double cos_az, double range) const {
    if (std::isinf(range)) return range;
    double pc, pr;
    j_.pixel_step(sin_az, cos_az, pc, pr);
    double d = 0.0;
    for (const double per_metre : {std::abs(pc), std::abs(pr)}) {
      if (per_metre > 0.0) d = std::max(d, std::floor(range * per_metre * (1.0 + 1e-12)) / per_metre);
    }
    return std::min(d, range);
  }

  // Where the eye's track along the azimuth ends: at `range` (for a cell already the last crossing
  // within the radius: reach), or at the last row or column crossing before it leaves the raster's
  // extent (track_box.h), where the march and the sweep stop reading. The mesh goes on over the
  // ring beyond the extent; what rays meet beyond `end` is not terrain (blocking_angle). Negative
  // or 0 where no crossing is left.
  struct Track {
    double end = 0;      // the last crossing read
    double through = 0;  // where the track leaves the extent (or the radius): rays run this far
  };
  Track track(const Eye& e, double sin_az, double cos_az, double range) const {
    double pc, pr;
    j_.pixel_step(sin_az, cos_az, pc, pr);
    const double exit = box_.exit(e.col, e.row, pc, pr);
    return {std::min(range, last_crossing_within(e.col, e.row, pc, pr, exit)), std::min(range, exit)};
  }

  // Slope, in this mesh's sign, from cell (col, row) to where the ground track along the azimuth
  // first crosses a row or column line (read linearly along it, as the march reads it): the far
  // edge of the triangles around the cell's vertex. -inf where that crossing leaves the raster's extent, NaN
  // where it touches nodata (which never occludes): neither bounds anything.
  double first_crossing_slope(int col, int row, double sin_az, double cos_az) const {
    double pc, pr;
    j_.pixel_step(sin_az, cos_az, pc, pr);
    const double to_col = pc != 0.0 ? 1.0 / std::abs(pc) : kInf, to_row = pr != 0.0 ? 1.0 / std::abs(pr) : kInf;
    const double d = std::min(to_col, to_row);  // metres
    double x = to_col <= to_row ? col + (pc > 0 ? 1 : -1) : col + pc * d;
    double y = to_col <= to_row ? row + pr * d : row + (pr > 0 ? 1 : -1);
    if (to_col <= to_row) y = std::abs(y - std::round(y)) < 1e-9 ? std::round(y) : y;
    if (to_col > to_row) x = std::abs(x - std::round(x)) < 1e-9 ? std::round(x) : x;
    if (!box_.contains(x, y)) return -kInf;
    return sign_ * (surface(x, y) - t_.heights(col, row)) / d;  // NaN (nodata) compares false: no bound
  }

  // Slope, in this mesh's sign, from cell (col, row) to the terrain where its ground track ends:
  // at the buffer's edge or at `range`, or, where it ends over nodata, at the last point of the
  // track (half a cell apart) that has terrain. A ray that Embree lets through but that is below
  // that terrain went into it through a hit lost in rounding (a ray along a grid line meets the
  // mesh on its edges), or under a hole's skirt, and never came out: it is blocked. Until Dec 3 a
  // track ending on nodata (a collar of nodata around a city) bounded nothing, and such rays
  // escaped: 50° below a building's top at one cell. NaN where the track ends at once or meets
  // no terrain.
  double end_slope(const Eye& e, double sin_az, double cos_az, double range) const {
    const double col = e.col, row = e.row;
    double pc, pr;
    j_.pixel_step(sin_az, cos_az, pc, pr);
    const double end = std::min(box_.exit(col, row, pc, pr), range);
    if (!(end > 0.0) || std::isinf(end)) return std::numeric_limits<double>::quiet_NaN();
    const double back = 0.5 / std::max(std::abs(pc), std::abs(pr));  // metres per half cell
    for (double d = end; d > 0.0; d -= back) {
      const double x = std::clamp(col + pc * d, box_.col_lo, box_.col_hi);
      const double y = std::clamp(row + pr * d, box_.row_lo, box_.row_hi);
      const double z = surface(x, y);
      if (!std::isnan(z)) return (sign_ * z - e.z) / d;
    }
    return std::numeric_limits<double>::quiet_NaN();
  }

  // True when the ray meets triangle `prim` from inside the terrain: along the triangle's upward
  // normal. A skirt leans outward as it hangs, so its upward normal points away from the mesh: a ray
  // meets it from inside when it heads out from under the mesh's edge.
  bool from_inside(unsigned prim, const RTCRay& ray) const {
    const unsigned* tri = mesh_.indices + 3 * prim;
    const float* a = mesh_.vertices + 3 * tri[0];
    const float* b = mesh_.vertices + 3 * tri[1];
    const float* c = mesh_.vertices + 3 * tri[2];
    const double ux = double(b[0]) - a[0], uy = double(b[1]) - a[1], uz = double(b[2]) - a[2];
    const double vx = double(c[0]) - a[0], vy = double(c[1]) - a[1], vz = double(c[2]) - a[2];
    double nx = uy * vz - uz * vy, ny = uz * vx - ux * vz, nz = ux * vy - uy * vx;
    if (nz < 0) nx = -nx, ny = -ny, nz = -nz;  // the surface's upward normal
    return nx * ray.dir_x + ny * ray.dir_y + nz * ray.dir_z > 0.0;
  }

  // The mesh's height at pixel position (x, y) inside the buffer, from the triangle holding it (the
  // quad's split as built); NaN where that triangle has a nodata corner.
  double surface(double x, double y) const { return surface_height(t_, x, y, sign_); }

  // True when the ray from the eye along azimuth/elevation hits terrain within `range`; `first_slope`
  // from first_crossing_slope for a cell's eye, -inf for a point's.
  bool occluded(const Eye& e, double sin_az, double cos_az, double elevation, double range, double first_slope) const {
    if (std::tan(elevation) < first_slope) return true;
    EyeContext context = context_of(e);
    RTCRay ray = ray_from(e, sin_az, cos_az, elevation, range);
    rtcOccluded1(scene_.get(), &context.base, &ray);
    return ray.tfar < 0.0f || std::tan(elevation) < end_slope(e, sin_az, cos_az, range);
  }

  // The highest elevation angle (radians) of terrain that the ray from (col,row) at height z,
  // along azimuth/elevation, meets within `range`: the top of the first triangle it hits, cut by
  // the azimuth's vertical plane. NaN when it meets nothing. Rays below `first_slope` (from
  // first_crossing_slope) meet the terrain at once, and that crossing's angle is the answer.
  // The ray runs on to `through` (>= range, where the track leaves the raster's extent): a ray that
  // went into the terrain through a hit lost in rounding (a ray along a grid line meets the mesh on
  // its edges) comes out through the surface from below before it, and is blocked; what it meets
  // from above beyond `range`, the strip between the last crossing and the extent, is not read (the
  // march and the sweep stop at the last crossing).
  double blocking_angle(const Eye& e, double sin_az, double cos_az, double elevation, double range, double first_slope,
                        double through) const {
    if (std::tan(elevation) < first_slope) return std::atan(first_slope);
    const double z = e.z;
    EyeContext context = context_of(e);
    RTCRayHit hit{};
    hit.ray = ray_from(e, sin_az, cos_az, elevation, std::max(range, through));
    hit.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(scene_.get(), &context.base, &hit);
    if (hit.hit.geomID != RTC_INVALID_GEOMETRY_ID && hit.ray.tfar * std::cos(elevation) > range) {
      if (from_inside(hit.hit.primID, hit.ray)) return elevation;
      hit.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    }
    if (hit.hit.geomID == RTC_INVALID_GEOMETRY_ID) {
      const double end = end_slope(e, sin_az, cos_az, range);
      return std::tan(elevation) < end ? std::atan(end) : std::numeric_limits<double>::quiet_NaN();
    }
    const unsigned* tri = mesh_.indices + 3 * hit.hit.primID;
    // The vertical plane through the eye along (sin_az, cos_az) cuts the triangle along a segment;
    // along a straight segment the elevation angle is monotone, so its top is at an end (the end
    // beyond the radius moved back to it).
    const double ex = hit.ray.org_x, ey = hit.ray.org_y;
    double near_h = kInf, near_up = 0, far_h = -kInf, far_up = 0;
    for (int e = 0; e < 3; ++e) {
      const float* a = mesh_.vertices + 3 * tri[e];
      const float* b = mesh_.vertices + 3 * tri[(e + 1) % 3];
      const double sa = cos_az * (a[0] - ex) - sin_az * (a[1] - ey), sb = cos_az * (b[0] - ex) - sin_az * (b[1] - ey);
      if ((sa > 0 && sb > 0) || (sa < 0 && sb < 0)) continue;  // the edge stays on one side of the plane
      const double f = sa == sb ? 0.0 : sa / (sa - sb);
      const double h = sin_az * (a[0] - ex) + cos_az * (a[1] - ey) +
                       f * (sin_az * (double(b[0]) - a[0]) + cos_az * (double(b[1]) - a[1]));
      const double up = a[2] + f * (double(b[2]) - a[2]) - z;
      if (h < near_h) near_h = h, near_up = up;
      if (h > far_h) far_h = h, far_up = up;
    }
    double top = elevation;              // the hit point itself is on the segment
    if (!(near_h <= far_h)) return top;  // a grazing hit whose triangle misses the plane in rounding
    if (far_h > range && far_h > near_h) {
      far_up = near_up + (range - near_h) / (far_h - near_h) * (far_up - near_up);
      far_h = range;
    }
    if (near_h > 0) top = std::max(top, std::atan2(near_up, near_h));
    if (far_h > 0) top = std::max(top, std::atan2(far_up, far_h));
    return top;
  }

 private:
  static constexpr double kInf = std::numeric_limits<double>::infinity();
  const Terrain& t_;
  double sign_;
  Jacobian j_;
  TrackBox box_;
  EmbreeScene scene_;
  int width_ = 0;
  Triangles mesh_;  // the geometry's buffers (Embree owns them)
};

class RaycastEngine final : public HorizonEngine {
 public:
  explicit RaycastEngine(const HorizonParams& p) : p_(p) {
    if (p_.rays < 0 || p_.rays > 1 << 20) throw UsageError("--rays must be between 0 and 1048576");
    if (p_.curvature == "on") throw UsageError("--method raycast models no Earth curvature; use --curvature off");
  }
  std::string_view name() const override { return "raycast"; }
  std::string_view citation() const override {
    return "Embree 3 rays on a triangle mesh over cell centres; horizon bracketed to 1e-5 rad by rays that climb over "
           "each occluder's top, svf also by stratified cosine-weighted Monte Carlo";
  }
  std::map<std::string, std::string> describe() const override {
    return {{"METHOD", "raycast"},
            {"DIRECTIONS", std::to_string(p_.directions)},
            {"RADIUS_M", p_.radius == 0.0 ? "unlimited" : number_text(p_.radius)},
            {"MC_RAYS_PER_CELL", std::to_string(p_.rays)},
            {"HORIZON_PRECISION_RAD", "1e-5"}};
  }
  double radius() const override { return p_.radius == 0.0 ? std::numeric_limits<double>::infinity() : p_.radius; }
  double curvature_coefficient(const Terrain&) const override { return 0.0; }  // none modelled
  const HorizonParams& params() const override { return p_; }

  void compute_window(const Terrain& terrain, const Window& window, HorizonField& out,
                      ProgressCounter& progress) const override {
    std::string embree_failure;
    EmbreeDevice device = new_embree_device(embree_failure, /*need_filters=*/true);
    TerrainMesh upper(device.get(), terrain, 1.0);
    std::unique_ptr<TerrainMesh> lower;
    if (p_.lower) lower = std::make_unique<TerrainMesh>(device.get(), terrain, -1.0);
    if (!embree_failure.empty()) throw Error(embree_failure);
    out.resize(window.cols, window.rows, p_.directions, p_.lower);
    if (p_.rays > 0) {
      out.svf_direct.assign(static_cast<std::size_t>(window.cols) * window.rows,
                            std::numeric_limits<float>::quiet_NaN());
      out.svf_stderr.assign(out.svf_direct.size(), std::numeric_limits<float>::quiet_NaN());
    }
    const int n = p_.directions;
    std::vector<double> sin_k(n), cos_k(n);
    for (int k = 0; k < n; ++k) {
      sin_k[k] = std::sin(out.set_azimuth(k));
      cos_k[k] = std::cos(out.set_azimuth(k));
    }
    const double range = radius();
    std::vector<double> reach_k(n);
    for (int k = 0; k < n; ++k) reach_k[k] = upper.reach(sin_k[k], cos_k[k], range);
    tbb::parallel_for(tbb::blocked_range<int>(0, window.rows), [&](const tbb::blocked_range<int>& rows) {
      for (int wr = rows.begin(); wr != rows.end(); ++wr) {
        progress.stop_if_cancelled();
        const int row = window.row0 + wr;
        for (int wc = 0; wc < window.cols; ++wc) {
          const int col = window.col0 + wc;
          if (!terrain.valid(col, row)) continue;
          const std::size_t cell_index = out.cell(wc, wr);
          const Eye eye = upper.cell_eye(col, row);
          for (int k = 0; k < n; ++k) {
            const double first = upper.first_crossing_slope(col, row, sin_k[k], cos_k[k]);
            const TerrainMesh::Track end = upper.track(eye, sin_k[k], cos_k[k], reach_k[k]);
            out.upper_at(cell_index, k) = static_cast<float>(climb_horizon(upper, eye, sin_k[k], cos_k[k], end, first));
            if (lower) {
              const double lower_first = lower->first_crossing_slope(col, row, sin_k[k], cos_k[k]);
              out.lower_at(cell_index, k) = static_cast<float>(
                  -climb_horizon(*lower, lower->cell_eye(col, row), sin_k[k], cos_k[k], end, lower_first));
            }
          }
          if (p_.rays > 0) monte_carlo_svf(upper, terrain, col, row, range, out, cell_index);
        }
        progress.advance(window.cols);
      }
    });
  }

  // Also for point queries (raycast_point_horizons).
  static constexpr double kPrecision = 1e-5;  // radians: rays this far above terrain graze nothing
  static constexpr int kClimbs = 6;           // climbing rays before the bracket is halved instead

  // The horizon is the lowest elevation whose ray escapes. Every blocked ray meets terrain whose top
  // along the azimuth (TerrainMesh::blocking_angle) is seen from the eye, so the horizon is at least
  // that high, and the next ray climbs to kPrecision above it; once one escapes, the highest top is
  // the horizon to within kPrecision (and exactly, where it is the highest point along the azimuth).
  // Closer rays would run along the cell's own slope, a plane, and may slip past the wall at its end.
  // On city.tif a direction takes 4 rays on average where a bisection took 25, and the run is 1.5 to
  // 1.9 times faster, not 6: the rays that skim the terrain and escape, which both need, cost most,
  // and rays that must find their nearest hit cost more than rays that stop at any. Over long smooth
  // slopes, where a climb gains only a triangle, the rays after the first kClimbs halve the bracket:
  // on a 1 m lidar DEM 13 rays per direction, and no faster than the bisection.
  // `first`: the slope to the first crossing for a cell's eye (first_crossing_slope), -inf for a point's.
  // `track`: where the eye's track ends (TerrainMesh::track).
  static double climb_horizon(const TerrainMesh& mesh, const Eye& eye, double s, double c,
                              const TerrainMesh::Track& track, double first) {
    const double range = track.end;
    if (!(range > 0.0)) return 0.0;            // no crossing within the radius: nothing in range
    double lo = -0.5 * M_PI, hi = 0.5 * M_PI;  // the horizon is in [lo, hi): lo seen (or the nadir), hi open
    bool blocked = false;
    auto probe = [&](double elevation) {
      const double top = mesh.blocking_angle(eye, s, c, elevation, range, first, track.through);
      if (std::isnan(top)) {
        hi = elevation;
      } else {
        lo = std::max(elevation, top);
        blocked = true;
      }
    };
    if (std::isfinite(first)) {
      lo = std::atan(first);
      blocked = true;
    } else {
      probe(0.0);  // no crossing to start from: from the horizontal, as a bisection would
    }
    for (int rays = 0; hi - lo > kPrecision; ++rays) {
      const double mid = 0.5 * (lo + hi);
      probe(blocked && rays < kClimbs ? std::min(lo + kPrecision, mid) : mid);
    }
    // Nothing in range at all: the same convention as the other methods.
    return blocked ? lo : 0.0;
  }

 private:
  void monte_carlo_svf(const TerrainMesh& mesh, const Terrain& t, int col, int row, double range, HorizonField& out,
                       std::size_t cell_index) const {
    const Eye eye = mesh.cell_eye(col, row);
    // Stratified cosine-weighted directions: strata in (u, v) map through Malley's method.
    const int side = std::max(1, static_cast<int>(std::sqrt(static_cast<double>(p_.rays))));
    const int total = side * side;
    std::uint64_t state = splitmix64(t.global_id(col, row) ^ (p_.seed * 0x9E3779B97F4A7C15ull));
    auto uniform = [&state] {
      state = splitmix64(state);
      return static_cast<double>(state >> 11) * 0x1.0p-53;
    };
    int open = 0;
    for (int i = 0; i < side; ++i) {
      for (int j = 0; j < side; ++j) {
        const double u = (i + uniform()) / side, v = (j + uniform()) / side;
        const double sin_zenith = std::sqrt(u), azimuth = 2.0 * M_PI * v;
        const double elevation = std::acos(sin_zenith);  // elevation = 90° - zenith
        const double sa = std::sin(azimuth), ca = std::cos(azimuth);
        const double reach = mesh.track(eye, sa, ca, mesh.reach(sa, ca, range)).end;
        open += !(reach > 0.0) ||
                !mesh.occluded(eye, sa, ca, elevation, reach, mesh.first_crossing_slope(col, row, sa, ca));
      }
    }
    const double p = static_cast<double>(open) / total;
    out.svf_direct[cell_index] = static_cast<float>(p);
    // Binomial standard error; stratification makes the true error smaller, so this is an upper bound.
    out.svf_stderr[cell_index] = static_cast<float>(std::sqrt(p * (1.0 - p) / total));
  }

  HorizonParams p_;
};

}  // namespace

void raycast_point_horizons(const Terrain& extended, const std::vector<EyePoint>& eyes, int directions,
                            double sector_rotation, double radius, std::vector<float>& out, ProgressCounter* progress) {
  std::string embree_failure;
  EmbreeDevice device = new_embree_device(embree_failure, /*need_filters=*/true);
  const TerrainMesh mesh(device.get(), extended, 1.0);
  if (!embree_failure.empty()) throw Error(embree_failure);
  const double range = radius > 0.0 ? radius : std::numeric_limits<double>::infinity();
  const std::size_t n = eyes.size();
  out.assign(n * directions, std::numeric_limits<float>::quiet_NaN());
  // A point's eye is above the surface, off every vertex: no triangle to ignore, no first crossing
  // to judge by hand, and with a radius its rays stop at the radius itself (the march for points
  // stops at the last crossing within it).
  constexpr double kNoFirstSlope = -std::numeric_limits<double>::infinity();
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t i = r.begin(); i != r.end(); ++i) {
      if (std::isnan(eyes[i].z)) continue;
      const Eye eye{eyes[i].col, eyes[i].row, eyes[i].z, kNoVertex};
      for (int k = 0; k < directions; ++k) {
        const double az = sector_rotation + sector_azimuth(k, directions);
        const double s = std::sin(az), c = std::cos(az);
        out[i * directions + k] = static_cast<float>(
            RaycastEngine::climb_horizon(mesh, eye, s, c, mesh.track(eye, s, c, range), kNoFirstSlope));
      }
      if (progress) progress->advance(1);
    }
  });
}

std::unique_ptr<HorizonEngine> make_raycast_engine(const HorizonParams& params) {
  return std::make_unique<RaycastEngine>(params);
}

}  // namespace skyview::detail
