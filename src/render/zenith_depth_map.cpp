#include "skyview/render/zenith_depth_map.h"

#include <gdal_priv.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>

#include "skyview/core/error.h"
#include "skyview/core/number_text.h"
#include "skyview/raster/raster_read.h"
#include "zenith_column.h"

namespace skyview {
namespace {

// Whether the triangle the ray hit faces up as stored (counter-clockwise seen from above).
double stored_normal_z(const Scene& scene, const RayHit& hit) {
  const SceneMesh& m = scene.meshes[hit.mesh];
  const auto& t = m.triangles[hit.triangle];
  const Vec3f &a = m.vertices[t[0]], &b = m.vertices[t[1]], &c = m.vertices[t[2]];
  const double ux = double(b[0]) - a[0], uy = double(b[1]) - a[1], vx = double(c[0]) - a[0], vy = double(c[1]) - a[1];
  const double ex = double(b[0]) - a[0], ey = double(b[1]) - a[1], ez = double(b[2]) - a[2];
  const double fx = double(c[0]) - a[0], fy = double(c[1]) - a[1], fz = double(c[2]) - a[2];
  const double nx = ey * fz - ez * fy, ny = ez * fx - ex * fz, nz = ux * vy - uy * vx;
  const double n = std::sqrt(nx * nx + ny * ny + nz * nz);
  return n > 0 ? nz / n : 0.0;
}

}  // namespace

// The solid parts under one texel centre, top down (see the header).
std::vector<float> zenith_column(const Scene& scene, const RayScene& rays, float x, float y, float top,
                                 const ZenithOptions& o, bool& truncated) {
  std::vector<float> out;
  bool inside = false;
  float t = 0.0f;
  const Vec3f origin{x, y, top}, down{0, 0, -1};
  for (int guard = 0; guard < 4096; ++guard) {
    const auto hit = rays.intersect(origin, down, t);
    if (!hit) break;
    t = hit->t + std::max(1e-4f, hit->t * 1e-6f);
    const double nz = stored_normal_z(scene, *hit);
    if (std::abs(nz) < 1e-3) continue;  // a wall met edge on
    const float z = top - hit->t;
    if (!inside) {
      // Entering: a gap thinner than merge_gap (a floor on the terrain) is no gap.
      if (!out.empty() && out.back() - z < o.merge_gap) {
        out.pop_back();
      } else {
        out.push_back(z);
      }
      inside = true;
    } else if (nz < 0) {
      out.push_back(z);  // leaving through a downward face
      inside = false;
    }
  }
  // A bottom with nothing found below it: the surface under it coincides (a floor on the ground,
  // which the next ray's start skipped) or there is none; either way the solid is taken to go on.
  if (out.size() % 2 == 0 && !out.empty()) out.pop_back();
  if (static_cast<int>(out.size()) > o.max_layers) {
    truncated = true;
    out.resize(o.max_layers % 2 ? o.max_layers : o.max_layers - 1);
  }
  return out;
}

ZenithDepthMap ZenithDepthMap::frame_of(const RayScene& rays, const ZenithOptions& o) {
  if (!(o.resolution > 0) || !std::isfinite(o.resolution)) throw UsageError("--zenith-res must be a positive number");
  if (o.max_layers < 1 || o.max_layers > 255) throw UsageError("--zenith-layers must be from 1 to 255");
  const auto bounds = rays.bounds();
  ZenithDepthMap m;
  m.resolution_ = o.resolution;
  m.max_layers_ = o.max_layers;
  m.x0_ = bounds[0][0] - o.margin;
  m.y0_ = bounds[1][1] + o.margin;
  const double w = std::ceil((bounds[1][0] + o.margin - m.x0_) / o.resolution);
  const double h = std::ceil((m.y0_ - bounds[0][1] + o.margin) / o.resolution);
  if (w * h > double(o.max_texels)) {
    throw UsageError("--zenith-res " + number_text(o.resolution) + " makes a zenith map of " + number_text(w) + "x" +
                     number_text(h) + " texels, more than " + std::to_string(o.max_texels) +
                     ": take a coarser resolution");
  }
  m.width_ = std::max(1, static_cast<int>(w));
  m.height_ = std::max(1, static_cast<int>(h));
  // The rays start above everything, at a height rounded up to whole 16 m so that a change below
  // it (an object moved, added or removed, not the tallest by a margin) keeps every ray's start
  // and update_region can stand in for a new build.
  m.ray_top_ = 16.0f * std::ceil((bounds[1][2] + 1.0f) / 16.0f);
  m.merge_gap_ = o.merge_gap;
  return m;
}

ZenithDepthMap ZenithDepthMap::build(const Scene& scene, const RayScene& rays, const ZenithOptions& o) {
  ZenithDepthMap m = frame_of(rays, o);
  const float top = m.ray_top_;
  std::vector<std::vector<std::vector<float>>> rows(m.height_);
  std::vector<std::int64_t> truncated(m.height_, 0);
  m.cut_.assign(static_cast<std::size_t>(m.width_) * m.height_, 0);
  tbb::parallel_for(0, m.height_, [&](int row) {
    rows[row].resize(m.width_);
    const float y = float(m.y0_ - (row + 0.5) * o.resolution);
    for (int col = 0; col < m.width_; ++col) {
      bool cut = false;
      rows[row][col] = zenith_column(scene, rays, float(m.x0_ + (col + 0.5) * o.resolution), y, top, o, cut);
      truncated[row] += cut;
      m.cut_[m.index(col, row)] = cut;
    }
  });
  m.counts_.resize(static_cast<std::size_t>(m.width_) * m.height_);
  m.offsets_.resize(m.counts_.size());
  for (int row = 0; row < m.height_; ++row) {
    m.truncated_ += truncated[row];
    for (int col = 0; col < m.width_; ++col) {
      const std::size_t i = m.index(col, row);
      m.counts_[i] = static_cast<std::uint8_t>(rows[row][col].size());
      m.offsets_[i] = m.values_.size();
      m.values_.insert(m.values_.end(), rows[row][col].begin(), rows[row][col].end());
    }
    std::vector<std::vector<float>>().swap(rows[row]);
  }
  m.values_.push_back(0.0f);  // heights() of an empty last texel stays in bounds
  m.pack();
  return m;
}

void ZenithDepthMap::pack() {
  packed_.resize(counts_.size());
  for (std::size_t i = 0; i < counts_.size(); ++i) packed_[i] = {counts_[i] ? values_[offsets_[i]] : 0.0f, counts_[i]};
}

std::int64_t ZenithDepthMap::layered_texels() const {
  return std::count_if(counts_.begin(), counts_.end(), [](std::uint8_t c) { return c > 1; });
}

int ZenithDepthMap::deepest() const { return counts_.empty() ? 0 : *std::max_element(counts_.begin(), counts_.end()); }

void ZenithDepthMap::save(const std::string& path, const Scene& scene, const WriteOptions& options) const {
  const int layers = std::max(1, deepest());
  GeoReference g;
  g.has_geotransform = true;
  g.crs_wkt = scene.crs_wkt;
  g.geotransform = {x0_ + scene.origin[0], resolution_, 0, y0_ + scene.origin[1], 0, -resolution_};
  const std::size_t n = counts_.size();
  std::vector<std::vector<float>> bands(layers, std::vector<float>(n, std::numeric_limits<float>::quiet_NaN()));
  for (std::size_t i = 0; i < n; ++i) {
    for (int k = 0; k < counts_[i]; ++k) bands[k][i] = float(values_[offsets_[i] + k] + scene.origin[2]);
  }
  std::vector<OutputBand> out;
  for (int k = 0; k < layers; ++k) {
    out.push_back({"layer_" + std::to_string(k + 1),
                   "metre",
                   bands[k].data(),
                   {{"DEFINITION", k % 2 == 0 ? "top of a solid part (the first: the highest surface)"
                                              : "bottom of the solid part above (free space below it)"}}});
  }
  WriteOptions wo = options;
  wo.metadata["ZENITH_RESOLUTION"] = number_text(resolution_);
  wo.metadata["ZENITH_MAX_LAYERS"] = std::to_string(max_layers_);
  wo.metadata["ZENITH_TRUNCATED_TEXELS"] = std::to_string(truncated_);
  wo.metadata["ZENITH_LAYERS"] =
      "heights from the top down alternate top and bottom of solid parts; the last reaches down";
  wo.metadata["SCENE_TRIANGLES"] = std::to_string(scene.triangle_count());
  write_bands(path, width_, height_, g, out, wo);
}

ZenithDepthMap ZenithDepthMap::load(const std::string& path, const Scene& scene) {
  init_gdal();
  std::unique_ptr<GDALDataset> ds(GDALDataset::Open(path.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY));
  if (!ds) throw Error("--zenith '" + path + "' cannot be opened as a raster");
  const char* res = ds->GetMetadataItem("ZENITH_RESOLUTION");
  const char* max_layers = ds->GetMetadataItem("ZENITH_MAX_LAYERS");
  if (!res || !max_layers || ds->GetRasterCount() < 1) {
    throw Error("--zenith '" + path + "' is not a zenith map written by skyview render --save-zenith");
  }
  const char* triangles = ds->GetMetadataItem("SCENE_TRIANGLES");
  if (triangles && std::to_string(scene.triangle_count()) != triangles) {
    throw Error("--zenith '" + path + "' was made for a scene of " + triangles + " triangles, this one has " +
                std::to_string(scene.triangle_count()) + ": make it again with --save-zenith");
  }
  ZenithDepthMap m;
  m.ray_top_ = std::numeric_limits<float>::quiet_NaN();  // unknown: update_region refuses
  const int layers = ds->GetRasterCount();
  m.max_layers_ = std::atoi(max_layers);  // before the dataset (which owns the text) is closed
  ds.reset();
  std::vector<RasterBand> bands;
  for (int k = 1; k <= layers; ++k) bands.push_back(read_band(path, k));
  const GeoReference& g = bands[0].georef;
  m.width_ = bands[0].values.width();
  m.height_ = bands[0].values.height();
  m.resolution_ = g.geotransform[1];
  m.x0_ = g.geotransform[0] - scene.origin[0];
  m.y0_ = g.geotransform[3] - scene.origin[1];
  if (!(m.resolution_ > 0) || std::abs(g.geotransform[5] + m.resolution_) > 1e-9 * m.resolution_) {
    throw Error("--zenith '" + path + "' has no north-up square grid");
  }
  const auto b = scene.bounds();
  const double tol = m.resolution_;
  if (m.x0_ > b[0][0] + tol || m.y0_ < b[1][1] - tol || m.x0_ + m.width_ * m.resolution_ < b[1][0] - tol ||
      m.y0_ - m.height_ * m.resolution_ > b[0][1] + tol) {
    throw Error("--zenith '" + path + "' does not cover the scene (another scene or another CRS?)");
  }
  const std::size_t n = static_cast<std::size_t>(m.width_) * m.height_;
  m.counts_.resize(n);
  m.offsets_.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    m.offsets_[i] = m.values_.size();
    int c = 0;
    while (c < layers && !std::isnan(bands[c].values.values()[i])) {
      m.values_.push_back(float(bands[c].values.values()[i] - scene.origin[2]));
      ++c;
    }
    m.counts_[i] = static_cast<std::uint8_t>(c);
  }
  m.values_.push_back(0.0f);
  m.pack();
  return m;
}

}  // namespace skyview
