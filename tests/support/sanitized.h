// A sanitizer build runs a step 5 to 20 times slower. The bit-identity tests that repeat the
// same code on every instruction set and thread count take fewer steps there: each step runs
// every path the first one does, and make test runs them for their full length.
#pragma once

namespace cloth::test {

#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
inline constexpr bool kSanitized = true;
#else
inline constexpr bool kSanitized = false;
#endif

// `full` steps, or `sanitized` of them in a sanitizer build.
constexpr long sanitizedSteps(long full, long sanitized) {
    return kSanitized ? sanitized : full;
}

}  // namespace cloth::test
