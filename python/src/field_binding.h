#pragma once
/// @file field_binding.h
/// terrastudio._core._field: a field file's summary and its traversability map
/// (core/field/, core/analysis/traversability.h; docs/field.md).

#include <pybind11/pybind11.h>

namespace terra::python {

void bindField(pybind11::module_& m);

}  // namespace terra::python
