// A sanitizer build runs a step 5 to 20 times slower. The bit-identity tests that repeat the
// same code on every instruction set and thread count take fewer steps there: each step runs
// every path the first one does, and make test runs them for their full length.
#pragma once

namespace cloth::test {

// GCC says so with __SANITIZE_ADDRESS__ / __SANITIZE_THREAD__; Clang 14 only with __has_feature.
#if defined(__SANITIZE_ADDRESS__)
inline constexpr bool kAddressSanitized = true;
#elif defined(__has_feature)
inline constexpr bool kAddressSanitized = __has_feature(address_sanitizer);
#else
inline constexpr bool kAddressSanitized = false;
#endif

#if defined(__SANITIZE_THREAD__)
inline constexpr bool kThreadSanitized = true;
#elif defined(__has_feature)
inline constexpr bool kThreadSanitized = __has_feature(thread_sanitizer);
#else
inline constexpr bool kThreadSanitized = false;
#endif

inline constexpr bool kSanitized = kAddressSanitized || kThreadSanitized;

// `full` steps, or `sanitized` of them in a sanitizer build.
constexpr long sanitizedSteps(long full, long sanitized) {
    return kSanitized ? sanitized : full;
}

}  // namespace cloth::test
