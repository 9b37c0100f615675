// The extension module terrastudio._core; the package's __init__.py gives it its Python face
// (docs/python.md). std::invalid_argument raised by the core becomes ValueError.
#include <pybind11/pybind11.h>

#include "core/common/build_info.h"
#include "python/src/analyses_binding.h"
#include "python/src/field_binding.h"
#include "python/src/forces_binding.h"
#include "python/src/inputs_binding.h"
#include "python/src/studies_binding.h"

PYBIND11_MODULE(_core, m) {
    m.doc() = "TerraStudio's core: the wheel-soil model, its analyses and global sensitivity.";
    m.attr("__version__") = terra::build_info::kVersion;
    terra::python::bindInputs(m);
    terra::python::bindForces(m);
    terra::python::bindAnalyses(m);
    terra::python::bindStudies(m);
    terra::python::bindField(m);
}
