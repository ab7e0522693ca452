#!/usr/bin/env bash
# The sanitizer suite: the libraries, the programs and the test executables
# built with clang, AddressSanitizer + UndefinedBehaviorSanitizer (leak
# checking on), then run. Any ASan/UBSan report or leak fails the run.
#
#   tools/sanitizers/run.sh                          what CI runs (bootstrap.sh test)
#   FACIAL_SANITIZE_ALL=1 tools/sanitizers/run.sh    every test executable, every test
#   tools/sanitizers/run.sh TEST_BINARY...           these executables, every test
#                                                    (FACIAL_SANITIZE_ALL=0: CI's filters)
#
# CI runs every Vulkan-free executable and, on lavapipe with the validation
# layer on, test_engine_vk (its window tests under xvfb-run), test_cli and test_cli_demo
# (they run the sanitized `facial` program as a child), test_soak; test_cli_demo
# without its golden repeat of the seven transitions (StudyTransition*, the
# headless tour's frames again, compared by pixels), test_cli without the
# expression judge (ExpressionJudge*: the same `express` renders as the other
# express tests, 42 more of them and the region-swap tool, then Python; 160 of
# test_cli's 370 s sanitized). Left to
# FACIAL_SANITIZE_ALL=1: test_cli_demo_window and test_editor, the window demo and
# the editor driven by xdotool under Xvfb (minutes each, and they also need
# the sanitized facial-editor built); their programs' leaks are checked in CI
# by demo_leaks.sh.
#
# The driver is preloaded (LD_PRELOAD) so that it stays mapped until exit:
# the Vulkan loader dlcloses it at vkDestroyInstance, and a leak whose frames
# point into an unloaded library has no module name, which lsan.supp cannot
# match (without the preload test_engine_vk reports 240 bytes in 3 blocks of
# "<unknown module>"; with it, nothing, and no suppression is used).
# verify_asan_link_order=0 lets the preload come before ASan's runtime.
#
# The build directory (FACIAL_SANITIZE_BUILD_DIR, default build-sanitize) is
# configured with -DFACIAL_FUZZ=ON, so fuzz/run.sh reuses the same compiled
# libraries for the fuzzers.
set -euo pipefail
cd "$(dirname "$0")/../.."

build="${FACIAL_SANITIZE_BUILD_DIR:-build-sanitize}"
# Each list longest first (sanitized, on 2 cores: test_cli about 190 s,
# test_bake_head 100, test_engine_vk 60, test_soak 50, test_cli_demo 35, the rest
# under 25), so that two at a time finish together.
vulkan_free=(test_bake_head test_facial_speech test_facial_json test_audio test_facial_graph test_engine_scene test_editor_files test_facial_rig test_importers test_autorig test_bake test_engine_image test_engine_view test_facial_character)
# test_app (the landmark finder, on-the-fly rigging) and test_dataset render: the driver is preloaded for them.
vulkan_ci=(test_cli test_engine_vk test_soak test_app test_dataset test_cli_demo)
vulkan_windows=(test_cli_demo_window test_editor)
# What CI leaves out of an executable (a gtest negative filter), unless FACIAL_SANITIZE_ALL=1.
ci_excluded() {
  [ "${FACIAL_SANITIZE_ALL:-0}" = 1 ] && return
  case "$1" in
    test_cli_demo) echo "StudyTransition*" ;;
    test_cli) echo "ExpressionJudge*" ;;
  esac
}
export -f ci_excluded
tests=("$@")
[ $# -gt 0 ] && export FACIAL_SANITIZE_ALL="${FACIAL_SANITIZE_ALL:-1}"
if [ ${#tests[@]} -eq 0 ]; then
  tests=("${vulkan_ci[0]}" "${vulkan_free[0]}" "${vulkan_ci[@]:1}" "${vulkan_free[@]:1}")  # the long ones first
  [ "${FACIAL_SANITIZE_ALL:-0}" = 1 ] && tests=("${vulkan_windows[@]}" "${tests[@]}")
fi
vulkan=("${vulkan_ci[@]}" "${vulkan_windows[@]}")

if [ ! -f "$build/CMakeCache.txt" ]; then
  cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
        -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ -DFACIAL_FUZZ=ON -DFACIAL_BUILD_BENCH=OFF >/dev/null
fi
# The programs the tests run as children.
targets=("${tests[@]}")
for t in "${tests[@]}"; do
  [[ " ${vulkan[*]} " == *" $t "* ]] && targets+=(facial_cli)
  [ "$t" = test_editor ] && targets+=(facial_editor)
done
cmake --build "$build" -j"$(nproc)" --target "${targets[@]}"

libs=/usr/lib/x86_64-linux-gnu
export ASAN_OPTIONS="detect_leaks=1:abort_on_error=0:strict_string_checks=1:detect_stack_use_after_return=1:verify_asan_link_order=0"
export LSAN_OPTIONS="suppressions=$PWD/tools/sanitizers/lsan.supp:print_suppressions=0"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
export FACIAL_VALIDATION=1
mkdir -p "$build/sanitize-logs"

run_one() {
  local test="$1" log="$FACIAL_SANITIZE_LOGS/$1.log" status=0 filter
  filter="$(ci_excluded "$1")"
  local cmd=("bin/$test" --gtest_brief=1)
  [ -n "$filter" ] && cmd+=("--gtest_filter=-$filter")
  # Window tests of test_engine_vk need a display; the demo's and the editor's
  # start their own virtual X server.
  [ "$test" = test_engine_vk ] && command -v xvfb-run >/dev/null && cmd=(xvfb-run -a -s "-screen 0 1024x768x24 -noreset" "${cmd[@]}")
  local preload=""
  [[ " $FACIAL_SANITIZE_VULKAN " == *" $test "* ]] && [ -f "$FACIAL_SANITIZE_DRIVER" ] && preload="$FACIAL_SANITIZE_DRIVER"
  local start=$SECONDS
  (cd "$FACIAL_SANITIZE_BUILD" && LD_PRELOAD="$preload" "${cmd[@]}") >"$log" 2>&1 || status=$?
  if [ "$status" -ne 0 ] || grep -qE "ERROR: (Address|Leak)Sanitizer|runtime error:" "$log"; then
    echo "sanitize: $test FAILED (exit $status); log $log"
    grep -E "ERROR: (Address|Leak)Sanitizer|runtime error:|SUMMARY:|\[  FAILED  \]" "$log" | head -10 | sed 's/^/  /'
    return 1
  fi
  echo "sanitize: $test ok in $((SECONDS - start))s ($(grep -o '[0-9]* tests\? from [0-9]* test suites\? ran' "$log" | tail -1))${filter:+, CI leaves out $filter}"
}
export -f run_one
export FACIAL_SANITIZE_BUILD="$build" FACIAL_SANITIZE_LOGS="$PWD/$build/sanitize-logs"
export FACIAL_SANITIZE_VULKAN="${vulkan[*]}" FACIAL_SANITIZE_DRIVER="$libs/libvulkan_lvp.so"

failed=0
start=$SECONDS
printf '%s\n' "${tests[@]}" | xargs -P "$(nproc)" -I{} bash -c 'run_one "$@"' _ {} || failed=1
if [ "$failed" -ne 0 ]; then
  echo "sanitize: FAILED"
  exit 1
fi
echo "sanitize: ${#tests[@]} test executables clean under ASan + UBSan + LeakSanitizer in $((SECONDS - start))s"
