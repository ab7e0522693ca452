#!/usr/bin/env bash
# Leak check of the headless demo: the `facial` program of the ordinary build
# (build/, RelWithDebInfo, GCC) plays a short tour headless on lavapipe with
# validation on, under LeakSanitizer. No rebuild: LeakSanitizer needs no
# instrumentation, so GCC's runtime (liblsan0) is preloaded; it takes over
# malloc/free and, at exit, reports every block nothing points to any more.
# The run covers what a program embedding the runtime does once: load the face
# and its rig, create the Vulkan device, upload, draw and read back frames,
# write the GIF and the contact sheet, tear everything down.
#
#   tools/sanitizers/demo_leaks.sh [BUILD_DIR]      default: build
#
# A leak whose stack reaches only the project's code (and the C/C++ runtime)
# fails the check (exit 1, LeakSanitizer's report in the log). The driver's own
# leaks (lavapipe, LLVM, the validation layer, the Vulkan loader) are
# suppressed by tools/sanitizers/lsan.supp, where each entry says why. Vulkan
# objects the project forgets to destroy are the validation layer's to report
# at vkDestroyDevice: any validation message in the log fails the check too.
set -euo pipefail
cd "$(dirname "$0")/../.."

build="${1:-build}"
program="$build/bin/facial"
[ -x "$program" ] || { echo "demo leaks: $program is not built" >&2; exit 1; }
libs=/usr/lib/x86_64-linux-gnu
lsan="$libs/liblsan.so.0"
[ -f "$lsan" ] || { echo "demo leaks: GCC's LeakSanitizer runtime ($lsan, package liblsan0) is missing" >&2; exit 1; }
# The Vulkan loader dlcloses the driver and the layer at vkDestroyInstance;
# their globals go with them, and what those pointed to would look leaked
# (with no module to name). Preloaded, they stay mapped until exit.
preload="$lsan"
for keep in "$libs/libvulkan_lvp.so" "$libs/libVkLayer_khronos_validation.so"; do
  [ -f "$keep" ] && preload="$preload:$keep"
done

out="$build/demo-leaks"
rm -rf "$out"
mkdir -p "$out"
shared=../shared/assets
# name | demo arguments: the built-in head alone and as a crowd; with ../shared,
# an untextured scan (dressing: procedural eyes, occlusion, painted brows), a
# skinned and textured avatar playing its clips, a VRM 1.0 face.
runs=("head|" "crowd|--crowd 4")
[ -f "$shared/facecap.glb" ] && runs+=("facecap|--model $shared/facecap.glb")
[ -f "$shared/RobotExpressive.glb" ] && runs+=("robot|--model $shared/RobotExpressive.glb --clip all")
[ -f "$shared/vrm/modifier_shapekey_vrm1.vrm" ] && runs+=("vrm1|--model $shared/vrm/modifier_shapekey_vrm1.vrm")

start=$(date +%s)
failed=0
for run in "${runs[@]}"; do
  name="${run%%|*}" arguments="${run#*|}" log="$out/$name.log" status=0
  # Stacks come from the fast unwinder (frame pointers): the slow one deadlocks
  # in libgcc when LLVM allocates while registering its JIT code's unwind
  # tables. Without frame pointers in Debian's libraries a stack may end early,
  # but its first frame is always the code that called malloc/new.
  # 64x64, 6 frames (0.6 s at 10 fps): every stage runs, none for long.
  # shellcheck disable=SC2086  # the arguments are words
  FACIAL_VALIDATION=1 FACIAL_DEVICE=cpu LD_PRELOAD="$preload" \
    LSAN_OPTIONS="suppressions=$PWD/tools/sanitizers/lsan.supp:print_suppressions=0:exitcode=23" \
    "$program" demo --headless --size 64x64 --fps 10 --seconds 0.6 --out "$out/$name" $arguments >"$log" 2>&1 || status=$?
  # Messages at vkDestroyDevice (objects never destroyed) come after the
  # demo's own validation check: the log is where they show.
  problem=""
  [ "$status" -ne 0 ] && problem="exit $status"
  grep -q "vulkan validation:" "$log" && problem="${problem:+$problem, }validation messages"
  if [ -n "$problem" ]; then
    echo "demo leaks: $name FAILED ($problem${arguments:+; demo $arguments}); log $log"
    grep -E "ERROR: LeakSanitizer|SUMMARY:|Direct leak|Indirect leak|#[0-9]+ 0x|error:|vulkan validation:" "$log" | head -40 | sed 's/^/  /'
    failed=1
  fi
done
seconds=$(($(date +%s) - start))
if [ "$failed" -ne 0 ]; then
  echo "demo leaks: FAILED after ${seconds}s"
  exit 1
fi
echo "demo leaks: ${#runs[@]} headless demo runs (${runs[*]%%|*}) clean under LeakSanitizer in ${seconds}s"
