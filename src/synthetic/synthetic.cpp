#include "skyview/synthetic/synthetic.h"

#include <ogr_spatialref.h>
#include <GeographicLib/LocalCartesian.hpp>

#include <cmath>
#include <memory>
#include <random>
#include <vector>

#include "skyview/core/error.h"
#include "skyview/core/number_text.h"
#include "skyview/raster/raster_io.h"

namespace skyview {

GeoReference local_grid(int width, int height, double cell) {
  GeoReference g;
  g.has_geotransform = true;
  g.geotransform = {-0.5 * width * cell, cell, 0, 0.5 * height * cell, 0, -cell};
  return g;
}

Terrain rasterize(const HeightFunction& f, int width, int height, const GeoReference& georef, double base) {
  Terrain t;
  t.georef = georef;
  t.heights = Grid<float>(width, height);
  t.base_height = base;
  t.full_width = width;
  t.full_height = height;
  std::vector<double> xs(static_cast<std::size_t>(width) * height), ys(xs.size());
  for (int r = 0; r < height; ++r) {
    for (int c = 0; c < width; ++c) {
      xs[t.heights.index(c, r)] = georef.x_of(c, r);
      ys[t.heights.index(c, r)] = georef.y_of(c, r);
    }
  }
  if (!georef.crs_wkt.empty()) {
    init_gdal();
    OGRSpatialReference srs;
    srs.importFromWkt(georef.crs_wkt.c_str());
    srs.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
    std::unique_ptr<OGRSpatialReference> geog(srs.CloneGeogCS());
    geog->SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
    std::unique_ptr<OGRCoordinateTransformation> ct(OGRCreateCoordinateTransformation(&srs, geog.get()));
    double cx = georef.x_of((width - 1) / 2.0, (height - 1) / 2.0),
           cy = georef.y_of((width - 1) / 2.0, (height - 1) / 2.0);
    std::string centre = number_text(cx);  // appended: GCC 12 warns falsely (-Wrestrict) on "(" + ...
    centre += ", " + number_text(cy);
    if (!ct) throw Error("cannot rasterise: the CRS has no transformation to its geographic CRS");
    if (!ct->Transform(static_cast<int>(xs.size()), xs.data(), ys.data()) || !ct->Transform(1, &cx, &cy)) {
      throw Error("cannot rasterise: the grid around (" + centre + ")" +
                  " lies partly outside where its CRS projects (choose --origin and --northing inside it)");
    }
    const double invf = srs.GetInvFlattening();  // 0 for a sphere
    const GeographicLib::LocalCartesian local(
        cy, cx, 0.0, GeographicLib::Geocentric(srs.GetSemiMajor(), invf == 0.0 ? 0.0 : 1.0 / invf));
    for (std::size_t i = 0; i < xs.size(); ++i) {
      double e, n, u;
      local.Forward(ys[i], xs[i], 0.0, e, n, u);
      xs[i] = e;
      ys[i] = n;
    }
  } else {
    const double cx = georef.x_of((width - 1) / 2.0, (height - 1) / 2.0);
    const double cy = georef.y_of((width - 1) / 2.0, (height - 1) / 2.0);
    for (std::size_t i = 0; i < xs.size(); ++i) {
      xs[i] -= cx;
      ys[i] -= cy;
    }
  }
  for (std::size_t i = 0; i < xs.size(); ++i) t.heights.values()[i] = static_cast<float>(f(xs[i], ys[i]));
  t.frame = GroundFrame(georef, width, height);
  return t;
}

HeightFunction street_canyon(double width, double height) {
  return [=](double e, double) { return std::abs(e) < 0.5 * width - 1e-9 ? 0.0 : height; };
}

HeightFunction circular_pit(double radius, double depth) {
  return [=](double e, double n) { return std::hypot(e, n) < radius ? -depth : 0.0; };
}

HeightFunction tilted_plane(double slope, double aspect) {
  const double g = std::tan(slope);
  return [=](double e, double n) { return -g * (e * std::sin(aspect) + n * std::cos(aspect)); };
}

HeightFunction synthetic_city(std::uint64_t seed) {
  // Blocks of 40 m separated by streets of varying width; each block is a row of buildings,
  // a courtyard block, or a tower; a sunken plaza near the centre.
  struct Block {
    double e0, n0, e1, n1, height;
    bool courtyard;
  };
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<Block> blocks;
  const double pitch = 52.0;
  for (int i = -5; i <= 5; ++i) {
    for (int j = -5; j <= 5; ++j) {
      const double street = 8.0 + 10.0 * u(rng);
      const double e0 = i * pitch - 0.5 * (pitch - street), n0 = j * pitch - 0.5 * (pitch - street);
      const double size = pitch - street;
      const double kind = u(rng);
      if (i == 0 && j == 0) continue;  // the plaza
      if (kind < 0.15) {
        blocks.push_back(
            {e0 + 0.3 * size, n0 + 0.3 * size, e0 + 0.7 * size, n0 + 0.7 * size, 60.0 + 60.0 * u(rng), false});
      } else if (kind < 0.45) {
        blocks.push_back({e0, n0, e0 + size, n0 + size, 12.0 + 15.0 * u(rng), true});
      } else {
        blocks.push_back({e0, n0, e0 + size, n0 + size, 6.0 + 24.0 * u(rng), false});
      }
    }
  }
  return [blocks](double e, double n) {
    double z = 0.002 * e + 0.001 * n;  // a gentle slope of the ground
    const double r = std::hypot(e, n);
    if (r < 15.0) return z - 4.0;  // sunken plaza
    for (const Block& b : blocks) {
      if (e < b.e0 || e >= b.e1 || n < b.n0 || n >= b.n1) continue;
      if (b.courtyard) {
        const double m = 0.3 * (b.e1 - b.e0);
        if (e > b.e0 + m && e < b.e1 - m && n > b.n0 + m && n < b.n1 - m) return z;
      }
      return z + b.height;
    }
    return z;
  };
}

HeightFunction synthetic_mountains(std::uint64_t seed) {
  struct Peak {
    double e, n, height, width;
  };
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<Peak> peaks;
  for (int i = 0; i < 40; ++i) {
    peaks.push_back({(u(rng) - 0.5) * 6000.0, (u(rng) - 0.5) * 6000.0, 200.0 + 900.0 * u(rng), 300.0 + 900.0 * u(rng)});
  }
  return [peaks](double e, double n) {
    double z = 600.0 + 40.0 * std::sin(e / 700.0) * std::cos(n / 900.0);
    for (const Peak& p : peaks) {
      const double d2 = ((e - p.e) * (e - p.e) + (n - p.n) * (n - p.n)) / (p.width * p.width);
      z += p.height * std::exp(-d2);
    }
    // A sharp ridge line crossing the area.
    z += 250.0 * std::exp(-std::pow((n - 0.3 * e - 800.0) / 150.0, 2));
    return z;
  };
}

}  // namespace skyview
