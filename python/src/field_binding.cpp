#include "python/src/field_binding.h"

#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <stdexcept>

#include "core/analysis/traversability.h"
#include "core/io/field_json.h"
#include "core/io/json_reader.h"
#include "core/scenario/scenario_json.h"
#include "python/src/convert.h"

namespace py = pybind11;

namespace terra::python {

namespace {

// A raster as a 2-D array, the northern row first (as the file).
py::array_t<double> rasterArray(const field::Raster& r) {
    py::array_t<double> out({static_cast<py::ssize_t>(r.rows), static_cast<py::ssize_t>(r.cols)});
    std::copy(r.values.begin(), r.values.end(), out.mutable_data());
    return out;
}

py::dict field(const std::string& path, py::object traversability) {
    Result<io::FieldFile> file = io::loadField(path, presetLocations());
    if (!file) throw std::invalid_argument(file.message());
    py::dict out = fromJson(io::toJson(field::summarize(file->map, file->labels)));
    if (traversability.is_none()) return out;
    nlohmann::json settings = toJson(traversability);
    std::string robot_name = "default";
    if (settings.contains("robot")) {
        if (!settings["robot"].is_string())
            throw std::invalid_argument("traversability.robot: a robot preset name or file");
        robot_name = settings["robot"].get<std::string>();
        settings.erase("robot");
    }
    Result<dynamics::RobotParameters> robot = scenario::resolveRobot(presetLocations(), robot_name);
    if (!robot) throw std::invalid_argument("traversability.robot: " + robot.message());
    std::vector<Issue> issues;
    io::ObjectReader reader(settings, issues, {}, "traversability");
    analysis::TraversabilitySettings s;
    analysis::readTraversabilitySettings(reader, s);
    reader.finish();
    if (!issues.empty()) throw std::invalid_argument(formatIssues(issues));
    analysis::TraversabilityResult r;
    {
        py::gil_scoped_release release;
        r = analysis::computeTraversability(file->map, *robot, s);
    }
    py::dict t = fromJson(analysis::toJson(r));
    std::vector<double> xs, ys, headings;
    for (int c = 0; c < r.grid.cols; ++c) xs.push_back(r.grid.centreX(c));
    for (int row = 0; row < r.grid.rows; ++row) ys.push_back(r.grid.centreY(row));
    py::list slip, status;
    for (const analysis::HeadingMap& m : r.headings) {
        headings.push_back(m.heading_rad * 180.0 / 3.14159265358979323846);
        slip.append(rasterArray(m.slip));
        status.append(rasterArray(m.status));
    }
    t["x_m"] = toArray(xs);
    t["y_m"] = toArray(ys);
    t["heading_deg"] = toArray(headings);
    t["slip"] = slip;
    t["status"] = status;
    t["worst_slip"] = rasterArray(r.worst_slip);
    t["stall_share"] = rasterArray(r.stall_share);
    t["slope_deg"] = rasterArray(r.grid);
    out["traversability"] = t;
    return out;
}

}  // namespace

void bindField(py::module_& m) {
    m.def("_field", &field, py::arg("path"), py::arg("traversability") = py::none());
}

}  // namespace terra::python
