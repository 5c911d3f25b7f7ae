// DSM rasters (any GDAL raster with a geotransform) as the ray cast meshes them: the triangles of
// surface_mesh.h over cell centres, nodata left open, skirts on the open edges (ten cells deep, as
// the ray cast hangs them), turned so that the surface faces up. They also give the ground that
// footprint prisms stand on.
#include <gdal_priv.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <memory>

#include "scene/scene_crs.h"
#include "scene/scene_input.h"
#include "skyview/core/error.h"
#include "skyview/horizon/surface_mesh.h"
#include "skyview/raster/raster_io.h"

namespace skyview {
namespace {

constexpr double kMaxCells = 25e6;

class DsmInput : public SceneInput {
 public:
  DsmInput(const std::string& path, const SceneLoadOptions& o) : path_(path), skirts_(o.dsm_skirts) {
    init_gdal();
    {
      GDALDatasetUniquePtr ds(GDALDataset::Open(path.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY));
      if (!ds) throw Error("cannot open '" + path + "' as a raster");
      driver_ = ds->GetDriverName();
      double gt[6];
      if (ds->GetGeoTransform(gt) != CE_None) {
        throw Error("'" + path + "' is a raster without georeferencing (no geotransform): not a DSM");
      }
      // Two triangles a cell, in double before the scene's floats: about 100 bytes a cell at the peak.
      const double cells = static_cast<double>(ds->GetRasterXSize()) * ds->GetRasterYSize();
      if (cells > kMaxCells) {
        throw Error("'" + path + "' has " + std::to_string(ds->GetRasterXSize()) + " x " +
                    std::to_string(ds->GetRasterYSize()) +
                    " cells, more than a scene meshes (25 million): cut out the part in view (gdal_translate "
                    "-projwin) or coarsen it (gdalwarp -tr)");
      }
    }
    ReadOptions ro;
    ro.z_scale = o.z_scale;
    terrain_ = std::make_shared<Terrain>(read_terrain(path, ro));
  }

  std::string format() const override { return "raster (" + driver_ + ")"; }
  std::string declared_crs() const override { return terrain_->georef.crs_wkt; }
  bool is_ground() const override { return true; }

  std::optional<std::array<Vec3d, 2>> extent() const override {
    const GeoReference& g = terrain_->georef;
    const int w = terrain_->width(), h = terrain_->height();
    std::array<Vec3d, 2> box{Vec3d{kInf, kInf, 0}, Vec3d{-kInf, -kInf, 0}};
    for (const auto& [c, r] : {std::pair{-0.5, -0.5}, {w - 0.5, -0.5}, {-0.5, h - 0.5}, {w - 0.5, h - 0.5}}) {
      const double x = g.x_of(c, r), y = g.y_of(c, r);
      box[0][0] = std::min(box[0][0], x), box[0][1] = std::min(box[0][1], y);
      box[1][0] = std::max(box[1][0], x), box[1][1] = std::max(box[1][1], y);
    }
    return box;
  }

  void add_to(SceneAssembly& scene) override {
    const Terrain& t = *terrain_;
    // The ray cast's skirts: ten of the smallest cells deep (raycast.cpp).
    const double drop = 1000 * kSkirtOut * raster_centre_jacobian(t).min_cell_size();
    const SurfaceMesh m = surface_mesh(t, 1.0, drop);
    const std::size_t triangles = skirts_ ? m.triangles.size() / 3 : m.surface_triangles;
    if (m.surface_triangles == 0) {
      scene.skip("dsm " + path_, "no quad of valid cells to mesh");
      return;
    }
    const GeoReference& g = t.georef;
    SourceMesh mesh;
    mesh.name = "dsm " + std::filesystem::path(path_).filename().string();
    const std::size_t grid = static_cast<std::size_t>(t.width()) * t.height();
    mesh.vertices.resize(grid + (skirts_ ? m.skirt_vertices.size() : 0));
    for (std::size_t i = 0; i < grid; ++i) {
      const double c = static_cast<double>(i % t.width()), r = static_cast<double>(i / t.width());
      mesh.vertices[i] = {g.x_of(c, r), g.y_of(c, r), t.base_height + t.heights.values()[i]};
    }
    for (std::size_t k = 0; grid + k < mesh.vertices.size(); ++k) {
      const SurfaceMesh::SkirtVertex& s = m.skirt_vertices[k];
      mesh.vertices[grid + k] = {g.x_of(s.col, s.row), g.y_of(s.col, s.row), t.base_height + s.z};
    }
    // surface_mesh turns its triangles clockwise in pixel space; on a north-up raster (negative
    // determinant) that faces them down.
    const double det = g.geotransform[1] * g.geotransform[5] - g.geotransform[2] * g.geotransform[4];
    const bool flip = det < 0;
    mesh.triangles.resize(triangles);
    for (std::size_t k = 0; k < triangles; ++k) {
      const unsigned* tri = &m.triangles[3 * k];
      mesh.triangles[k] = flip ? std::array<std::uint32_t, 3>{tri[0], tri[2], tri[1]}
                               : std::array<std::uint32_t, 3>{tri[0], tri[1], tri[2]};
    }
    scene.add(std::move(mesh));
    register_ground(scene);
  }

 private:
  static constexpr double kInf = std::numeric_limits<double>::infinity();

  // Bilinear heights between cell centres, for the footprints: points come in the scene's CRS.
  void register_ground(SceneAssembly& scene) {
    std::shared_ptr<OGRCoordinateTransformation> to_raster;
    if (scene.to_scene()) {
      to_raster.reset(scene.to_scene()->GetInverse(), TransformDeleter());
      if (!to_raster) return;
    }
    double inv[6];
    if (!GDALInvGeoTransform(terrain_->georef.geotransform.data(), inv)) return;
    std::array<double, 6> pixel;
    std::copy(inv, inv + 6, pixel.begin());
    scene.add_ground([terrain = terrain_, to_raster, pixel](const std::vector<Vec3d>& points) {
      const Terrain& t = *terrain;
      double lowest = std::numeric_limits<double>::quiet_NaN();
      for (const Vec3d& p : points) {
        double x = p[0], y = p[1];
        if (to_raster && !to_raster->Transform(1, &x, &y)) continue;
        // Pixel position, less half a cell: cell centres at whole numbers.
        const double c = pixel[0] + pixel[1] * x + pixel[2] * y - 0.5, r = pixel[3] + pixel[4] * x + pixel[5] * y - 0.5;
        if (!(c >= 0 && r >= 0 && c <= t.width() - 1 && r <= t.height() - 1)) continue;
        const int c0 = std::min(static_cast<int>(c), t.width() - 2), r0 = std::min(static_cast<int>(r), t.height() - 2);
        const double fc = c - c0, fr = r - r0;
        const double a = t.heights(c0, r0), b = t.heights(c0 + 1, r0), d = t.heights(c0, r0 + 1),
                     e = t.heights(c0 + 1, r0 + 1);
        const double z = (1 - fr) * ((1 - fc) * a + fc * b) + fr * ((1 - fc) * d + fc * e);
        if (std::isnan(z)) continue;
        lowest = std::isnan(lowest) ? z : std::min(lowest, z);
      }
      return std::isnan(lowest) ? lowest : t.base_height + lowest;
    });
  }

  std::string path_, driver_;
  bool skirts_;
  std::shared_ptr<Terrain> terrain_;
};

}  // namespace

std::unique_ptr<SceneInput> open_dsm(const std::string& path, const SceneLoadOptions& options) {
  return std::make_unique<DsmInput>(path, options);
}

}  // namespace skyview
