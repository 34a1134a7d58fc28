// How much of a long property test runs: all of it in the Release run (scripts/test), which is the
// proof; a tenth under ASan or TSan (scripts/sanitize, 10–50× slower), which checks memory and
// undefined behaviour, for which a tenth of the poses is plenty.
#pragma once

namespace gdc::testing {

#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
constexpr bool kUnderSanitizer = true;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(thread_sanitizer)
constexpr bool kUnderSanitizer = true;
#else
constexpr bool kUnderSanitizer = false;
#endif
#else
constexpr bool kUnderSanitizer = false;
#endif

/// `count` in the Release run, a tenth of it under a sanitizer.
constexpr int scaledForSanitizers(int count) { return kUnderSanitizer ? count / 10 : count; }

}  // namespace gdc::testing
