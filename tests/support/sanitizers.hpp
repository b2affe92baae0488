#pragma once
// The few fast-tier tests too slow under AddressSanitizer for CI's time skip themselves in the
// sanitizer tier (scripts/test_sanitizers.sh), saying so; docs/dev/architecture.md lists them.
// What they run is run there by faster tests too.
#include <string>

#include <gtest/gtest.h>

#if defined(__SANITIZE_ADDRESS__)
#define HVI_SKIP_UNDER_SANITIZERS(why) GTEST_SKIP() << "too slow under the sanitizers: " << why
#else
#define HVI_SKIP_UNDER_SANITIZERS(why) static_cast<void>(0)
#endif

// A test that starts hvi under mpirun: skipped without MPI, and under the sanitizers, where Open
// MPI's plug-ins keep allocations to exit (tests/sanitizers/lsan.supp).
#if defined(__SANITIZE_ADDRESS__)
#define HVI_SKIP_WITHOUT_MPIRUN(mpirun) \
  GTEST_SKIP() << "under the sanitizers: Open MPI's plug-ins keep allocations to exit"
#else
#define HVI_SKIP_WITHOUT_MPIRUN(mpirun) \
  if (std::string(mpirun).empty()) GTEST_SKIP() << "hvi is built without MPI"
#endif
