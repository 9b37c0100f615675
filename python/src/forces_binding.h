#pragma once
/// @file forces_binding.h
/// terrastudio._forces: the wheel model at N operating points, each with its own soil overrides,
/// through gsa::evaluateBatch (core/gsa/batch.h) with the GIL released and the samples split over
/// threads. The package's forces() broadcasts the arrays and calls it with flat ones.

#include <pybind11/pybind11.h>

namespace terra::python {

void bindForces(pybind11::module_& m);

}  // namespace terra::python
