// Whether this test was built with AddressSanitizer (-DASGARD_SANITIZE=ON).
// ASan reserves terabytes of address space for its shadow memory, so a
// process under an address-space limit (ulimit -v) cannot even start: tests
// that apply one drop the limit, or skip when the limit is their point.
#pragma once

namespace asgard::tests {

#if defined(__SANITIZE_ADDRESS__)
inline constexpr bool kAddressSanitizer = true;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
inline constexpr bool kAddressSanitizer = true;
#else
inline constexpr bool kAddressSanitizer = false;
#endif
#else
inline constexpr bool kAddressSanitizer = false;
#endif

}  // namespace asgard::tests
