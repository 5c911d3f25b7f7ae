// skyview.read_las: a LAS 1.0-1.4 file's points as a NumPy structured array, read by the same
// reader as `skyview dsm` (dsm/las_file.h).
#include <pybind11/numpy.h>

#include "bindings.h"
#include "skyview/dsm/las_file.h"

#include <cstring>

namespace skyview::python {

namespace py = pybind11;

namespace {

// One row of the structured array: LasPoint's fields, packed as NumPy lays them out.
#pragma pack(push, 1)
struct PointRecord {
  double x, y, z;
  std::uint16_t intensity;
  std::uint8_t return_number, number_of_returns, classification;
};
#pragma pack(pop)

py::dtype point_dtype() {
  py::list fields;
  for (const auto& [name, type] : {std::pair{"x", "<f8"},
                                   {"y", "<f8"},
                                   {"z", "<f8"},
                                   {"intensity", "<u2"},
                                   {"return_number", "u1"},
                                   {"number_of_returns", "u1"},
                                   {"classification", "u1"}})
    fields.append(py::make_tuple(name, type));
  return py::dtype::from_args(fields);
}

py::dict header_dict(const LasHeader& h) {
  py::dict d;
  d["version"] = std::to_string(h.version_major) + "." + std::to_string(h.version_minor);
  d["point_format"] = h.point_format;
  d["point_count"] = h.point_count;
  d["scale"] = py::make_tuple(h.scale[0], h.scale[1], h.scale[2]);
  d["offset"] = py::make_tuple(h.offset[0], h.offset[1], h.offset[2]);
  d["min"] = py::make_tuple(h.min[0], h.min[1], h.min[2]);
  d["max"] = py::make_tuple(h.max[0], h.max[1], h.max[2]);
  d["crs_wkt"] = h.crs_wkt;
  d["z_unit_metres"] = h.z_unit_metres;
  return d;
}

}  // namespace

void bind_las_functions(py::module_& m) {
  using namespace pybind11::literals;
  m.def(
      "read_las",
      [](const std::string& path) {
        std::vector<PointRecord> points;
        {
          py::gil_scoped_release reading;
          const LasReader reader = LasReader::open_file(path);
          points.reserve(static_cast<std::size_t>(reader.header().point_count));
          reader.read_points([&](const std::vector<LasPoint>& chunk) {
            for (const LasPoint& p : chunk)
              points.push_back({p.x, p.y, p.z, p.intensity, p.return_number, p.number_of_returns, p.classification});
          });
        }
        const std::vector<py::ssize_t> shape{static_cast<py::ssize_t>(points.size())};
        py::array out(point_dtype(), shape);
        std::memcpy(out.mutable_data(), points.data(), points.size() * sizeof(PointRecord));
        return out;
      },
      "path"_a,
      "The points of a LAS 1.0-1.4 file (LAZ refused) as a structured array: x, y, z (float64, scaled and offset), "
      "intensity (uint16), return_number, number_of_returns, classification (uint8).");
  m.def(
      "read_las_header", [](const std::string& path) { return header_dict(LasReader::open_file(path).header()); },
      "path"_a, "A LAS file's header: version, point format and count, scale, offset, bounds and CRS (WKT).");
}

}  // namespace skyview::python
