#pragma once
// What makes a preview a map: a scale bar, a north arrow and the files that place the PNG on
// the Earth (a world file, the CRS in a PAM .aux.xml), drawn for raster_preview.cpp.
#include <opencv2/core.hpp>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "skyview/raster/georeference.h"

namespace skyview::detail {

// Metres on the ground per pixel of a picture showing `cells_per_pixel` cells of `georef` per
// pixel; unset without a geotransform or where the CRS is geographic (no metres to draw).
std::optional<double> metres_per_pixel(const GeoReference& georef, double cells_per_pixel);

// A scale bar of a round length (1, 2 or 5 times a power of ten metres) no longer than
// `max_pixels`, its left end at `origin`, labelled "0" and "500 m" or "2 km". Returns its length
// in pixels.
int draw_scale_bar(cv::Mat& rgba, cv::Point origin, double metres_per_pixel, int max_pixels);

// An arrow towards grid north (the CRS's +y; where the geotransform rotates the grid, turned with
// it) with an "N", centred on `centre`.
void draw_north_arrow(cv::Mat& rgba, cv::Point centre, int length, const GeoReference& georef);

// The world file's six lines for a picture whose pixel (0, 0) has its top-left corner at cell
// (col0, row0) of `georef`, `cells_per_pixel` cells per pixel.
std::string world_file_text(const GeoReference& georef, double col0, double row0, double cells_per_pixel);

// A GDAL PAM file (.aux.xml) holding the CRS (if any), so that QGIS and GDAL read the picture in
// it, and `items` as the picture's metadata (what it draws, for gdalinfo and the tests).
std::string pam_text(const std::string& crs_wkt, const std::vector<std::pair<std::string, std::string>>& items);

}  // namespace skyview::detail
