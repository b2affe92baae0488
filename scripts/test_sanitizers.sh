#!/usr/bin/env bash
# The sanitizer tier: the fast tier built with AddressSanitizer and UndefinedBehaviorSanitizer
# (build type Sanitize, in build-sanitize/: the libraries at -O1, the tests at -O0) and run with
# every finding fatal. Findings inside third-party libraries are suppressed in tests/sanitizers/,
# each with its reason; ours are fixed. Tests that cannot run there carry the label no_sanitize or
# skip themselves, saying why (tests/support/sanitizers.hpp; docs/dev/architecture.md lists them).
#
#   scripts/test_sanitizers.sh          the whole fast tier: what CI runs
#   scripts/test_sanitizers.sh --quick  hvi and the tests of what users hand it (scenes, surface
#                                       files, checkpoints, the fuzzers, the memory estimate) and
#                                       of the particle core, for a quicker look
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
export HVI_BUILD="${HVI_BUILD:-$root/build-sanitize}" HVI_BUILD_TYPE=Sanitize
export HVI_CMAKE_ARGS="-DHVI_BUILD_BENCH=OFF"
targets=(all)
if [ "${1:-}" = "--quick" ]; then
  targets=(hvi test_hostile_input test_fuzz test_memory_estimate test_resume_guard test_kill_resume
           test_scene_schema test_scene test_geometry test_geometry_scene test_mpm_unit
           test_material_laws test_materials)
fi
HVI_BUILD_TARGETS="${targets[*]}" source "$root/scripts/setup.sh"
supp="$root/tests/sanitizers"
# allocator_may_return_null: an allocation too large for the machine throws std::bad_alloc, as it
# does without the sanitizer (a surface file declaring 4e9 indices is refused by that message),
# instead of ending the process.
export ASAN_OPTIONS="detect_leaks=1:allocator_may_return_null=1:check_initialization_order=1"
export LSAN_OPTIONS="suppressions=$supp/lsan.supp:print_suppressions=0"
export UBSAN_OPTIONS="suppressions=$supp/ubsan.supp:print_stacktrace=1:halt_on_error=1:print_suppressions=0"
# The test executables not built stand in ctest's list as <target>_NOT_BUILT: left out. The
# Python tests run the sanitized hvi.
ctest --test-dir "$HVI_BUILD" --output-on-failure -LE 'long|no_sanitize' -E '_NOT_BUILT$' \
  --parallel "$(nproc)"
