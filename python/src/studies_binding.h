#pragma once
/// @file studies_binding.h
/// terrastudio._SobolPlan and _MorrisPlan: a wheel study (core/gsa/wheel_studies.h) with its
/// design, run locally (sobolStudy, morrisStudy) or row range by row range (WheelTarget::evaluate
/// on the design's rows, GIL released) so that Dask workers can evaluate chunks and the caller
/// gather them (concatenate, sobolResult): every row is a pure function of the design, so the
/// result is bit for bit the local one.

#include <pybind11/pybind11.h>

namespace terra::python {

void bindStudies(pybind11::module_& m);

}  // namespace terra::python
