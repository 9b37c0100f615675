#include "python/src/convert.h"

#include <pybind11/stl.h>

#include <cstdlib>
#include <mutex>
#include <stdexcept>

namespace terra::python {
namespace {

std::mutex locations_mutex;
io::PresetLocations locations = io::PresetLocations::standard({});

}  // namespace

const io::PresetLocations& presetLocations() {
    std::lock_guard lock(locations_mutex);
    return locations;
}

void setDataDir(const std::string& dir) {
    std::lock_guard lock(locations_mutex);
    locations = io::PresetLocations::standard({});  // $TERRASTUDIO_RESOURCES first, as the CLI
    locations.directories.emplace_back(dir);
}

nlohmann::json toJson(py::handle object) {
    // numpy arrays and scalars become lists and floats first (tolist), then Python's encoder
    // writes what nlohmann parses: one conversion, the same for every binding.
    py::module_ json = py::module_::import("json");
    py::object plain = py::module_::import("terrastudio").attr("_plain");
    const std::string text = py::str(json.attr("dumps")(object, py::arg("default") = plain));
    try {
        return nlohmann::json::parse(text);
    } catch (const nlohmann::json::exception& e) {
        // Python's encoder writes NaN and Infinity, which JSON has not: name the key instead.
        const py::object named = py::module_::import("terrastudio").attr("_non_finite")(object);
        if (!named.is_none()) throw std::invalid_argument(py::str(named));
        throw std::invalid_argument(std::string("not JSON: ") + e.what());
    }
}

py::object fromJson(const nlohmann::json& json) {
    return py::module_::import("json").attr("loads")(json.dump());
}

void raiseIssues(const std::vector<Issue>& issues) {
    throw std::invalid_argument(formatIssues(issues));
}

py::array_t<double> toArray(const std::vector<double>& values) {
    py::array_t<double> out(static_cast<py::ssize_t>(values.size()));
    std::copy(values.begin(), values.end(), out.mutable_data());
    return out;
}

py::dict tableToDict(const Table& table) {
    py::dict out;
    if (!table.label_column.empty()) out[py::str(table.label_column)] = table.labels;
    for (std::size_t c = 0; c < table.columns.size(); ++c) {
        py::array_t<double> column(static_cast<py::ssize_t>(table.rows.size()));
        double* data = column.mutable_data();
        for (std::size_t r = 0; r < table.rows.size(); ++r) data[r] = table.rows[r][c];
        out[py::str(table.columns[c])] = column;
    }
    return out;
}

}  // namespace terra::python
