#!/usr/bin/env bash
# One-command set-up: installs missing Debian packages, configures (CMake +
# Ninja) into build/, builds, then runs what was asked:
#   ./bootstrap.sh demo [facial demo options...]   the main job
#   ./bootstrap.sh deps                            the packages only (the container
#                                                  image's build stage runs this)
#   ./bootstrap.sh test [ctest options...]         the whole test suite, then the
#                                                  reliability checks (issue 12): the
#                                                  sanitizer suite, the fuzzers and
#                                                  the programs' leak check
# FACIAL_FUZZ_SECONDS (default 15) is each fuzzer's time in `test`;
# FACIAL_RELIABILITY=0 runs the plain suite only.
set -euo pipefail
cd "$(dirname "$0")"

PACKAGES=(
  build-essential cmake ninja-build pkg-config
  libvulkan-dev mesa-vulkan-drivers vulkan-validationlayers glslang-tools glslang-dev
  libglfw3-dev libx11-dev libxext-dev libglm-dev libtinygltf-dev libimgui-dev libstb-dev nlohmann-json3-dev
  libeigen3-dev libgtest-dev libgmock-dev libbenchmark-dev libcli11-dev libtinyobjloader-dev
  libcgif-dev libimagequant-dev fonts-dejavu-core xvfb xauth xdotool
  libmeshoptimizer-dev libdraco-dev libwebp-dev zlib1g-dev libpng-dev
  libespeak-ng-dev espeak-ng-data libsndfile1-dev libavformat-dev libavcodec-dev libswscale-dev
  libswresample-dev portaudio19-dev libasound2-dev libjack-jackd2-dev
  libpocketsphinx-dev pocketsphinx-en-us
  libdlib-dev libdlib-data
  clang libclang-rt-14-dev llvm lld liblsan0
  python3-numpy python3-opencv opencv-data python3-matplotlib
  # tests/cluster: a single-node Slurm, the deploy/ files' checks
  slurm-wlm munge python3-yaml shellcheck
)

install_missing_packages() {
  local missing=()
  for p in "${PACKAGES[@]}"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
  done
  [ ${#missing[@]} -eq 0 ] && return 0
  echo "bootstrap: installing ${missing[*]}"
  local sudo=""
  [ "$(id -u)" -ne 0 ] && sudo="sudo"
  $sudo apt-get update -qq
  $sudo env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends "${missing[@]}"
}

build() {
  local jobs
  jobs=$(nproc)
  # -O2 with line tables only (-g1): backtraces and sanitizer reports keep
  # file:line, and the build takes about a third less time than with full -g
  # on two cores. Configure build/ yourself for full debug info.
  cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
        -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O2 -g1 -DNDEBUG" -DCMAKE_C_FLAGS_RELWITHDEBINFO="-O2 -g1 -DNDEBUG" >/dev/null
  cmake --build build -j"$jobs"
}

# Runs a phase of `test` and says how long it took: CI must stay under 45
# minutes on 2 cores, and docs/testing.md keeps the phases' times.
timed() {
  local what="$1" start=$SECONDS
  shift
  "$@"
  echo "test: $what took $((SECONDS - start)) s"
}

mode="${1:-}"
[ $# -gt 0 ] && shift
case "$mode" in
  deps)
    install_missing_packages
    ;;
  demo)
    install_missing_packages
    build
    exec build/bin/facial demo "$@"
    ;;
  test)
    install_missing_packages
    timed "the build" build
    # Validation layer on: any validation message fails the test that caused it.
    # The short soak (test_soak) is one of the ctest entries.
    export FACIAL_VALIDATION=1
    timed ctest ctest --test-dir build --output-on-failure -j"$(nproc)" "$@"
    if [ "${FACIAL_RELIABILITY:-1}" != 0 ]; then
      # The demo (headless, and in a window) and the editor of build/, Vulkan
      # and all, under LeakSanitizer, then
      # ASan + UBSan + leak checking over the libraries, the `facial` program
      # and the test executables (clang, build-sanitize/; the Vulkan ones on
      # lavapipe, see tools/sanitizers/run.sh for the few left to
      # FACIAL_SANITIZE_ALL=1), then every fuzzer for a bounded time on the
      # same build. Any report, crash, leak, timeout or OOM fails.
      timed "the leak check" tools/sanitizers/demo_leaks.sh
      timed "the sanitizer build and runs" tools/sanitizers/run.sh
      timed "the fuzzers" fuzz/run.sh "${FACIAL_FUZZ_SECONDS:-15}"
    fi
    echo "test: done in $SECONDS s"
    ;;
  *)
    echo "usage: $0 demo [options] | $0 test [ctest options] | $0 deps" >&2
    exit 2
    ;;
esac
