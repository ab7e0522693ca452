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
# CI runs every test executable but the two window ones, each without its
# slowest tests: the sanitizers look for memory and undefined-behaviour
# errors, and those live in code paths, not in how many renders take them.
# What CI leaves out (ci_excluded below) repeats paths the kept tests take:
# renders and judgements of more faces and states (test_cli's expression
# judge, say, sheet, bench and face-format renders, and the rig report of a
# face with unknown target names, whose 60-view search for a face (69 s
# sanitized) AutorigCommand's mesh with no face takes too; test_cli_demo's golden
# repeat of the seven transitions), the landmark finder and on-the-fly rigging
# on whole avatars (test_app; and its FaceSetup twin of the rig report above,
# 66 s sanitized for the same search), the dataset and batch commands end to end
# (test_dataset), more whole-face transfers (test_autorig: the head bent,
# wound the other way, at a thousandth of its size; facecap's layers, the
# avatar without teeth: the head's layers and the avatar with its teeth take
# the same paths; two of the three layer validity tests, each a whole
# transfer of the head for a one-line early out: the UV overlap one, which
# reads hostile UVs, stays). Kept: the
# other Vulkan-free tests, test_engine_vk (window tests under xvfb-run),
# test_soak, and test_cli's, test_app's and test_dataset's bad input, express, autorig, timeline, files, device-loss and
# headless-demo tests through the sanitized `facial` program. Left to
# FACIAL_SANITIZE_ALL=1: those left-out tests and test_cli_demo_window and
# test_editor, the window demo and the editor driven by xdotool under Xvfb
# (minutes each, and they also need the sanitized facial-editor built); their
# programs' leaks are checked in CI by demo_leaks.sh. docs/testing.md has the
# times.
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
# Each list longest first (sanitized, CI's filters, a clean clone on 2 cores,
# 2026-12-05: test_cli 283 s, test_autorig 281, test_engine_vk 118,
# test_dataset 69, test_app 63, test_bake_head 61, test_cli_demo 44,
# test_soak 36, test_importers 36, the rest under 30; since the cheaper
# sanitized transfer of 2026-12-06, test_autorig 152 s and test_cli 129 s
# alone), so that two at a time finish together.
vulkan_free=(test_autorig test_bake_head test_importers test_editor_files test_facial_graph test_engine_scene test_bake test_audio test_facial_rig test_facial_speech test_facial_character test_engine_view test_facial_json test_engine_image)
# test_app (the landmark finder, on-the-fly rigging) and test_dataset render: the driver is preloaded for them.
vulkan_ci=(test_cli test_engine_vk test_dataset test_app test_cli_demo test_soak)
vulkan_windows=(test_cli_demo_window test_editor)
# What CI leaves out of an executable (a gtest negative filter), unless FACIAL_SANITIZE_ALL=1.
ci_excluded() {
  [ "${FACIAL_SANITIZE_ALL:-0}" = 1 ] && return
  case "$1" in
    test_cli_demo) echo "StudyTransition*" ;;
    test_cli) echo "ExpressionJudge*:SayCommand.*:SaySync*:SheetCommand.*:BenchCommand.*:FaceFormats.*:ObjKeyframeSet*:AutorigAvatar*:FullBodyAvatar*:AutorigCommand.PosingAFaceWithoutOne*:AutorigCommand.TheLandmarkNoiseTool*:RigCommandValidity.UnrecognisedTargetNames*" ;;
    test_app) echo "FaceLandmarkFinder*:FaceSetupAutorig*:FaceSetupValidity.ModelNoSchemeRecognises*:FaceAutorigRig.AFlatShaded*" ;;
    test_dataset) echo "DatasetCommand*:BatchCommand*" ;;
    test_autorig) echo "TargetTransfer.BentHead*:TargetTransfer.LandmarksALittleOff*:TargetTransfer.Winding*:TargetTransfer.AFaceAThousandth*:TargetTransfer.AFaceInTinyUnits*:ExpressionAmounts.*:DetailTransfer.FacecapsSkin*:AvatarTransfer.AnAvatarWithoutTeeth*:DetailTransferValidity.AFaceWithLayersOfItsOwn*:DetailTransferValidity.ASkinWithoutUvs*" ;;
  esac
}
export -f ci_excluded
tests=("$@")
[ $# -gt 0 ] && export FACIAL_SANITIZE_ALL="${FACIAL_SANITIZE_ALL:-1}"
if [ ${#tests[@]} -eq 0 ]; then
  tests=("${vulkan_free[0]}" "${vulkan_ci[0]}" "${vulkan_ci[1]}" "${vulkan_free[1]}" "${vulkan_ci[@]:2}" "${vulkan_free[@]:2}")  # the long ones first
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
