#pragma once
/// @file convert.h
/// What the bindings share: the preset locations of the package, JSON between Python and the
/// core (through Python's json module: the settings a Python call passes are read by the same
/// ObjectReader code as a run script's), tables as dicts of numpy arrays, and the errors.

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <cstdint>
#include <cstring>
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

/// `object` as a C-contiguous numpy array of T (converted when it is of another type or layout),
/// or an empty handle when it is not numeric; copied also when its data are not aligned for T. A
/// numpy array rebuilt from a pickle or a byte buffer (how dask returns a worker's chunk) may start
/// at any byte, and reading a double there is undefined behaviour (UBSan: "misaligned address"),
/// although x86 tolerates it.
template <typename T>
py::array_t<T, py::array::c_style | py::array::forcecast> alignedArray(py::handle object) {
    using Array = py::array_t<T, py::array::c_style | py::array::forcecast>;
    Array a = Array::ensure(object);
    if (a && reinterpret_cast<std::uintptr_t>(a.data()) % alignof(T) != 0) {
        Array copy(std::vector<py::ssize_t>(a.shape(), a.shape() + a.ndim()));
        std::memcpy(copy.mutable_data(), a.data(), static_cast<std::size_t>(a.nbytes()));
        a = std::move(copy);
    }
    return a;
}

/// A copy of the values as a new 1-D numpy array.
py::array_t<double> toArray(const std::vector<double>& values);
/// {column: 1-D array} of a table.
py::dict tableToDict(const Table& table);

}  // namespace terra::python
