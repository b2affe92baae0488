#pragma once
// The few fast-tier tests too slow under AddressSanitizer for CI's time skip themselves in the
// sanitizer tier (scripts/test_sanitizers.sh), saying so; docs/dev/architecture.md lists them.
// What they run is run there by faster tests too.
#include <gtest/gtest.h>

#if defined(__SANITIZE_ADDRESS__)
#define HVI_SKIP_UNDER_SANITIZERS(why) GTEST_SKIP() << "too slow under the sanitizers: " << why
#else
#define HVI_SKIP_UNDER_SANITIZERS(why) static_cast<void>(0)
#endif
