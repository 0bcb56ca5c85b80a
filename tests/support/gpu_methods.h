// The integrators the GPU backend runs (backends/solver_factory.h gpuImplements): what the GPU
// tests walk where the CPU tests walk kMethods.
#pragma once

#include <vector>

#include "backends/solver_factory.h"
#include "model/scene.h"

namespace cloth {

inline std::vector<Method> gpuMethods() {
    std::vector<Method> methods;
    for (Method m : kMethods)
        if (gpuImplements(m)) methods.push_back(m);
    return methods;
}

}  // namespace cloth
