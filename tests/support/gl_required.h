// Whether the tests must have an OpenGL context (CLOTH_REQUIRE_GPU=1, as CI sets: DESIGN.md §6),
// and the skip of a command-line test whose child found none (exit 4). No GL here: the tests of
// a build without the GPU backend include it too.
#pragma once

#include <gtest/gtest.h>

#include <cstdlib>
#include <string>

#include "support/process.h"

namespace cloth::test {

inline bool gpuRequiredByEnvironment() {
    const char* v = std::getenv("CLOTH_REQUIRE_GPU");
    return v != nullptr && std::string(v) == "1";
}

// A child that found no OpenGL context (exit 4) skips the test, unless CLOTH_REQUIRE_GPU=1.
#define CLOTH_SKIP_IF_NO_GL(result)                                                         \
    do {                                                                                    \
        if ((result).exitCode == 4) {                                                       \
            if (::cloth::test::gpuRequiredByEnvironment())                                  \
                GTEST_FAIL() << "CLOTH_REQUIRE_GPU=1: " << ::cloth::test::describe(result); \
            GTEST_SKIP() << "no OpenGL context: " << (result).err;                          \
        }                                                                                   \
    } while (0)

}  // namespace cloth::test
