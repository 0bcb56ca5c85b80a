// The module's exceptions, clothsim.SceneError, UnstableError and GpuUnavailableError, and the
// translation of the libraries' C++ exceptions into them with what each carries as attributes.
#pragma once

#include <pybind11/pybind11.h>

namespace cloth::python {

// Adds the exception types to `m` and registers their translators.
void registerErrors(pybind11::module_& m);

}  // namespace cloth::python
