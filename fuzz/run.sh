#!/usr/bin/env bash
# Builds the libFuzzer targets (clang, -fsanitize=fuzzer,address,undefined) and
# runs each for a bounded time on its seed corpus. Any crash, sanitizer report,
# leak, timeout (one input over FUZZ_TIMEOUT s), out-of-memory (over
# FUZZ_RSS_MB in all) or one allocation over FUZZ_MALLOC_MB fails: the script
# exits 1 and names the input libFuzzer saved. So an input that makes a
# loader work or allocate far beyond its size is a finding, like a crash.
#
#   fuzz/run.sh SECONDS [FUZZER...]     SECONDS per fuzzer (default 20), all fuzzers when none named
#
# Environment: FUZZ_BUILD_DIR (default build-sanitize: the same build serves the
# sanitizer test suite), FUZZ_JOBS (fuzzers run at once, default nproc),
# FUZZ_TIMEOUT (default 10 s), FUZZ_RSS_MB (default 2048), FUZZ_MALLOC_MB
# (default 1024: above any default load budget).
# Corpora: seeds are assembled at run time by fuzz/make_corpus.py from
# fuzz/seeds/, data/ and ../shared into $FUZZ_BUILD_DIR/fuzz-seeds/; what the
# fuzzers find grows $FUZZ_BUILD_DIR/fuzz-corpus/ (kept between local runs);
# failing inputs land in $FUZZ_BUILD_DIR/fuzz-artifacts/. A fixed finding
# becomes a regression test in the loader's test area (tests/<area>/) with its
# input file beside it. Replay one input: $FUZZ_BUILD_DIR/fuzz/fuzz_NAME FILE
set -euo pipefail
cd "$(dirname "$0")/.."

seconds="${1:-20}"
[ $# -gt 0 ] && shift
build="${FUZZ_BUILD_DIR:-build-sanitize}"
jobs="${FUZZ_JOBS:-$(nproc)}"
export FUZZ_TIMEOUT="${FUZZ_TIMEOUT:-10}" FUZZ_RSS_MB="${FUZZ_RSS_MB:-2048}" FUZZ_MALLOC_MB="${FUZZ_MALLOC_MB:-1024}"
export FUZZ_SECONDS="$seconds" FUZZ_BUILD="$build"

if [ ! -f "$build/CMakeCache.txt" ]; then
  cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
        -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ -DFACIAL_FUZZ=ON -DFACIAL_BUILD_BENCH=OFF >/dev/null
fi
cmake --build "$build" -j"$(nproc)" --target fuzzers

python3 fuzz/make_corpus.py "$build/fuzz-seeds" >/dev/null
mkdir -p "$build/fuzz-artifacts" "$build/fuzz-logs"

fuzzers=("$@")
if [ ${#fuzzers[@]} -eq 0 ]; then
  for f in "$build"/fuzz/fuzz_*; do fuzzers+=("$(basename "$f" | sed 's/^fuzz_//')"); done
fi

run_one() {
  local name="$1" dict=json.dict maxlen=()
  case "$name" in
    candide|obj_set|ply|stl) dict=text.dict ;;
    image) dict=image.dict ;;
    fbx) dict=fbx.dict ;;
    # Mutating whole 500 kB models runs at ~20 inputs/s under ASan; small
    # inputs (the big seeds truncated) run hundreds per second.
    gltf|vrm) maxlen=(-max_len=32768) ;;
  esac
  local corpus="$FUZZ_BUILD/fuzz-corpus/$name" log="$FUZZ_BUILD/fuzz-logs/$name.log"
  mkdir -p "$corpus"
  local status=0
  ASAN_OPTIONS="detect_leaks=1:allocator_may_return_null=1" UBSAN_OPTIONS="print_stacktrace=1" \
    "$FUZZ_BUILD/fuzz/fuzz_$name" -max_total_time="$FUZZ_SECONDS" -timeout="$FUZZ_TIMEOUT" \
      -rss_limit_mb="$FUZZ_RSS_MB" -malloc_limit_mb="$FUZZ_MALLOC_MB" -dict="fuzz/$dict" -print_final_stats=1 "${maxlen[@]}" \
      -artifact_prefix="$FUZZ_BUILD/fuzz-artifacts/${name}-" \
      "$corpus" "$FUZZ_BUILD/fuzz-seeds/$name" >"$log" 2>&1 || status=$?
  local runs cov
  runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)
  cov=$(grep -o 'cov: [0-9]*' "$log" | tail -1 | sed 's/cov: //')
  if [ "$status" -ne 0 ]; then
    echo "fuzz: $name FAILED (exit $status); log $log"
    grep -E "ERROR: |SUMMARY: |property does not hold|malloc\(|Test unit written to" "$log" | head -8 | sed 's/^/  /'
    return 1
  fi
  echo "fuzz: $name ok: ${runs:-?} inputs in ${FUZZ_SECONDS}s, ${cov:-?} coverage points, corpus $(ls "$corpus" | wc -l) files"
}
export -f run_one

failed=0
printf '%s\n' "${fuzzers[@]}" | xargs -P "$jobs" -I{} bash -c 'run_one "$@"' _ {} || failed=1
if [ "$failed" -ne 0 ]; then
  echo "fuzz: FAILED (inputs in $build/fuzz-artifacts/)"
  exit 1
fi
echo "fuzz: all ${#fuzzers[@]} fuzzers ran ${seconds}s each without a finding"
