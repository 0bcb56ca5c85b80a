// A sanitizer build runs a step 5 to 20 times slower. The bit-identity tests that repeat the
// same code on every instruction set and thread count take fewer steps there: each step runs
// every path the first one does, and make test runs them for their full length.
#pragma once

// GCC says so with __SANITIZE_ADDRESS__ / __SANITIZE_THREAD__; Clang 14 only with __has_feature.
#if defined(__has_feature)
#define CLOTH_TEST_HAS_FEATURE(x) __has_feature(x)
#else
#define CLOTH_TEST_HAS_FEATURE(x) 0
#endif

namespace cloth::test {

#if defined(__SANITIZE_ADDRESS__) || CLOTH_TEST_HAS_FEATURE(address_sanitizer)
inline constexpr bool kAddressSanitized = true;
#else
inline constexpr bool kAddressSanitized = false;
#endif

#if defined(__SANITIZE_THREAD__) || CLOTH_TEST_HAS_FEATURE(thread_sanitizer)
inline constexpr bool kThreadSanitized = true;
#else
inline constexpr bool kThreadSanitized = false;
#endif

inline constexpr bool kSanitized = kAddressSanitized || kThreadSanitized;

// `full` steps, or `sanitized` of them in a sanitizer build.
constexpr long sanitizedSteps(long full, long sanitized) {
    return kSanitized ? sanitized : full;
}

}  // namespace cloth::test
