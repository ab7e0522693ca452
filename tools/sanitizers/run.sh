#!/usr/bin/env bash
# The sanitizer suite: the Vulkan-free libraries (eng_core, eng_scene,
# eng_image, facial, facial_bake, the editor's models) and their test
# executables built with clang, AddressSanitizer + UndefinedBehaviorSanitizer
# (leak checking on), then run. Any ASan/UBSan report or leak fails the run.
#
#   tools/sanitizers/run.sh [TEST_BINARY...]      default: every Vulkan-free test executable
#
# The build directory (FACIAL_SANITIZE_BUILD_DIR, default build-sanitize) is
# configured with -DFACIAL_FUZZ=ON, so fuzz/run.sh reuses the same compiled
# libraries for the fuzzers. The Vulkan parts build under FACIAL_SANITIZE too
# (cmake --build build-sanitize --target test_vk ...) with lsan.supp for the
# driver's leaks; CI leaves them out to stay within its time.
set -euo pipefail
cd "$(dirname "$0")/../.."

build="${FACIAL_SANITIZE_BUILD_DIR:-build-sanitize}"
tests=("$@")
[ ${#tests[@]} -eq 0 ] && tests=(test_scene test_image test_facial_graph test_facial_rig test_facial_head test_editor_files)

if [ ! -f "$build/CMakeCache.txt" ]; then
  cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
        -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ -DFACIAL_FUZZ=ON -DFACIAL_BUILD_BENCH=OFF >/dev/null
fi
cmake --build "$build" -j"$(nproc)" --target "${tests[@]}"

export ASAN_OPTIONS="detect_leaks=1:abort_on_error=0:strict_string_checks=1:detect_stack_use_after_return=1"
export LSAN_OPTIONS="suppressions=$PWD/tools/sanitizers/lsan.supp:print_suppressions=0"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
export FACIAL_VALIDATION=1
mkdir -p "$build/sanitize-logs"

run_one() {
  local test="$1" log="$FACIAL_SANITIZE_LOGS/$1.log" status=0
  (cd "$FACIAL_SANITIZE_BUILD" && "bin/$test" --gtest_brief=1) >"$log" 2>&1 || status=$?
  if [ "$status" -ne 0 ]; then
    echo "sanitize: $test FAILED (exit $status); log $log"
    grep -E "ERROR: (Address|Leak)Sanitizer|runtime error:|SUMMARY:|\[  FAILED  \]" "$log" | head -10 | sed 's/^/  /'
    return 1
  fi
  echo "sanitize: $test ok ($(grep -o '[0-9]* tests\? from [0-9]* test suites\? ran' "$log" | tail -1))"
}
export -f run_one
export FACIAL_SANITIZE_BUILD="$build" FACIAL_SANITIZE_LOGS="$PWD/$build/sanitize-logs"

failed=0
printf '%s\n' "${tests[@]}" | xargs -P "$(nproc)" -I{} bash -c 'run_one "$@"' _ {} || failed=1
if [ "$failed" -ne 0 ]; then
  echo "sanitize: FAILED"
  exit 1
fi
echo "sanitize: ${#tests[@]} test executables clean under ASan + UBSan + LeakSanitizer"
