#pragma once
/// @file inputs_binding.h
/// terrastudio.Soil and terrastudio.Wheel: the core's parameter structs, made from a preset name,
/// a JSON file or a dict, read by the core's strict readers (io/parameters_json.h).

#include <pybind11/pybind11.h>

#include "core/soil/soil_parameters.h"
#include "core/wheel/wheel_parameters.h"

namespace terra::python {

/// Registers Soil, Wheel, soil(), wheel(), presets(), soil_fields() and identified_parameters()
/// (the identification's parameter table, core/identification/parameters.h).
void bindInputs(pybind11::module_& m);

}  // namespace terra::python
