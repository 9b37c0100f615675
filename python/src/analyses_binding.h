#pragma once
/// @file analyses_binding.h
/// terrastudio._run: any analysis of the registry (core/analysis/registry.h) on a soil, a wheel
/// and operating conditions, its settings read by the analysis's own reader (the keys and
/// messages of a run script's analysis object), its outcome as dicts of numpy arrays.

#include <pybind11/pybind11.h>

namespace terra::python {

void bindAnalyses(pybind11::module_& m);

}  // namespace terra::python
