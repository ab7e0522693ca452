#!/usr/bin/env bash
# Leak check of the programs of the ordinary build (build/, RelWithDebInfo,
# GCC): the headless demo plays short tours on lavapipe with validation on,
# under LeakSanitizer; with xvfb-run, the window demo and the editor run a
# second each too. No rebuild: LeakSanitizer needs no instrumentation, so
# GCC's runtime (liblsan0) is preloaded; it takes over malloc/free and, at
# exit, reports every block nothing points to any more. The runs cover what a
# program embedding the runtime does: load the face and its rig, create the
# Vulkan device, upload, draw and read back frames (present them, with ImGui,
# in the windows), write the GIF and the contact sheet, tear everything down.
#
#   tools/sanitizers/demo_leaks.sh [BUILD_DIR]      default: build
#
# A leak whose stack reaches only the project's code (and the C/C++ runtime)
# fails the check (exit 1, LeakSanitizer's report in the log). The drivers'
# own leaks would be suppressed by tools/sanitizers/lsan.supp, where each entry
# says why. Vulkan objects the project forgets to destroy are the validation
# layer's to report at vkDestroyDevice: any validation message fails too.
set -euo pipefail
self="$(cd "$(dirname "$0")" && pwd)/$(basename "$0")"
cd "$(dirname "$0")/../.."

build="${1:-build}"
libs=/usr/lib/x86_64-linux-gnu
lsan="$libs/liblsan.so.0"
[ -f "$lsan" ] || { echo "demo leaks: GCC's LeakSanitizer runtime ($lsan, package liblsan0) is missing" >&2; exit 1; }
for program in facial facial-editor; do
  [ -x "$build/bin/$program" ] || { echo "demo leaks: $build/bin/$program is not built" >&2; exit 1; }
done
# The Vulkan loader dlcloses the driver at vkDestroyInstance; its globals go
# with it, and what they pointed to would look leaked (with no module to
# name). Preloaded, lavapipe stays mapped until exit. (Not the validation
# layer: it exports vkGetInstanceProcAddr, which would then shadow the
# loader's for GLFW.)
preload="$lsan"
[ -f "$libs/libvulkan_lvp.so" ] && preload="$preload:$libs/libvulkan_lvp.so"

out="$build/demo-leaks"
mkdir -p "$out"
failed=0
# check NAME COMMAND...: runs one program under LeakSanitizer, logs to $out/NAME.log.
check() {
  local name="$1" log="$out/$1.log" status=0 problem=""
  shift
  rm -rf "${out:?}/$name"
  # Stacks come from the fast unwinder (frame pointers): the slow one deadlocks
  # in libgcc when LLVM allocates while registering its JIT code's unwind
  # tables. Without frame pointers in Debian's libraries a stack may end early,
  # but its first frame is always the code that called malloc/new.
  FACIAL_VALIDATION=1 FACIAL_DEVICE=cpu LD_PRELOAD="$preload" \
    LSAN_OPTIONS="suppressions=$PWD/tools/sanitizers/lsan.supp:print_suppressions=0:exitcode=23" \
    "$@" >"$log" 2>&1 || status=$?
  [ "$status" -ne 0 ] && problem="exit $status"
  # Messages at vkDestroyDevice (objects never destroyed) come after the
  # programs' own validation check: the log is where they show.
  grep -q "vulkan validation:" "$log" && problem="${problem:+$problem, }validation messages"
  if [ -n "$problem" ]; then
    echo "demo leaks: $name FAILED ($problem: ${*#"$build/bin/"}); log $log"
    grep -E "ERROR: LeakSanitizer|SUMMARY:|Direct leak|Indirect leak|#[0-9]+ 0x|error:|vulkan validation:" "$log" |
      head -40 | sed 's/^/  /'
    failed=1
  fi
  checked+=("$name")
}
checked=()
start=$(date +%s)

if [ -n "${DEMO_LEAKS_WINDOWS_STATUS:-}" ]; then
  # Inside xvfb-run (below): the window demo and the editor, a second or so
  # each. The status goes to a file: xvfb-run's own exit status is 5 whenever
  # its clean-up of the temporary X authority fails.
  check window "$build/bin/facial" demo --size 320x200 --quit-after 1.5
  check editor "$build/bin/facial-editor" --size 480x300 --quit-after 1.5
  echo "$failed" >"$DEMO_LEAKS_WINDOWS_STATUS"
  exit 0
fi

# Headless: 64x64, 6 frames (0.6 s at 10 fps), every stage runs, none for long.
# The built-in head alone and as a crowd; with ../shared, an untextured scan
# (dressing: procedural eyes, occlusion, painted brows), a skinned and textured
# avatar playing its clips, a VRM 1.0 face.
tour=("$build/bin/facial" demo --headless --size 64x64 --fps 10 --seconds 0.6)
shared=../shared/assets
check head "${tour[@]}" --out "$out/head"
check crowd "${tour[@]}" --out "$out/crowd" --crowd 4
[ -f "$shared/facecap.glb" ] && check facecap "${tour[@]}" --out "$out/facecap" --model "$shared/facecap.glb"
[ -f "$shared/RobotExpressive.glb" ] &&
  check robot "${tour[@]}" --out "$out/robot" --model "$shared/RobotExpressive.glb" --clip all
[ -f "$shared/vrm/modifier_shapekey_vrm1.vrm" ] &&
  check vrm1 "${tour[@]}" --out "$out/vrm1" --model "$shared/vrm/modifier_shapekey_vrm1.vrm"

if command -v xvfb-run >/dev/null; then
  windows="$out/windows.status"
  rm -f "$windows"
  DEMO_LEAKS_WINDOWS_STATUS="$PWD/$windows" xvfb-run -a -s '-screen 0 1280x800x24' "$self" "$build" 2>&1 |
    grep -v "^xvfb-run: error: problem while cleaning up" || true
  if [ "$(cat "$windows" 2>/dev/null)" = 0 ]; then
    checked+=(window editor)
  else
    [ -f "$windows" ] || echo "demo leaks: the window demo and the editor did not run under xvfb-run"
    failed=1
  fi
else
  echo "demo leaks: xvfb-run is not installed: the window demo and the editor are not checked"
fi

seconds=$(($(date +%s) - start))
if [ "$failed" -ne 0 ]; then
  echo "demo leaks: FAILED after ${seconds}s"
  exit 1
fi
echo "demo leaks: ${#checked[@]} runs (${checked[*]}) clean under LeakSanitizer in ${seconds}s"
