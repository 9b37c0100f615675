#pragma once
/// @file convert.h
/// What the bindings share: the preset locations of the package, JSON between Python and the
/// core (through Python's json module: the settings a Python call passes are read by the same
/// ObjectReader code as a run script's), tables as dicts of numpy arrays, and the errors.

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/common/issue.h"
#include "core/common/table.h"
#include "core/io/parameters_json.h"

namespace terra::python {

namespace py = pybind11;

/// Where presets are found: $TERRASTUDIO_RESOURCES, then the package's data folder (set once by
/// the package's __init__.py through _set_data_dir).
const io::PresetLocations& presetLocations();
void setDataDir(const std::string& dir);

/// A Python object (dict, list, numbers, strings, numpy scalars and arrays) as JSON.
nlohmann::json toJson(py::handle object);
/// JSON as Python objects.
py::object fromJson(const nlohmann::json& json);

/// Raises ValueError with every issue, one line each (the CLI's and the scripts' messages).
[[noreturn]] void raiseIssues(const std::vector<Issue>& issues);

/// A copy of the values as a new 1-D numpy array.
py::array_t<double> toArray(const std::vector<double>& values);
/// {column: 1-D array} of a table.
py::dict tableToDict(const Table& table);

}  // namespace terra::python
