// The module's exceptions, clothsim.SceneError, UnstableError and GpuUnavailableError, and the
// translation of the libraries' C++ exceptions into them with what each carries as attributes.
#pragma once

#include <pybind11/pybind11.h>

#include <string>

namespace cloth::python {

// Adds the exception types to `m` and registers their translators.
void registerErrors(pybind11::module_& m);

// A message as Python text: UTF-8, with any byte that is not (a path given as bytes that are not
// UTF-8) written as \xNN, as Python writes such a path in its own errors.
pybind11::str text(const std::string& message);

}  // namespace cloth::python
