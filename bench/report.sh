#!/usr/bin/env bash
# Reproduces the figures of docs/performance.md on this machine, from a clean
# checkout (../shared beside it): builds what it needs, runs every
# measurement, and writes bench/out/report.md (tables) and
# bench/out/morph_cost.png (the plot). About 15 minutes on 2 cores with
# lavapipe. Measurements compared with each other (animated vs static, tiers,
# this project vs three.js) alternate in one run, so load hits both alike.
#
#   bench/report.sh [--rounds N] [--skip-peer] [--skip-window]
set -euo pipefail
cd "$(dirname "$0")/.."

rounds=3
peer=1
window=1
while [ $# -gt 0 ]; do
  case "$1" in
    --rounds) rounds=$2; shift 2 ;;
    --skip-peer) peer=0; shift ;;
    --skip-window) window=0; shift ;;
    *) echo "usage: $0 [--rounds N] [--skip-peer] [--skip-window]" >&2; exit 2 ;;
  esac
done
facecap=../shared/assets/facecap.glb
[ -f "$facecap" ] || { echo "report: $facecap: not found (../shared beside the checkout?)" >&2; exit 1; }

sudo=""; [ "$(id -u)" -ne 0 ] && sudo=sudo
if ! /usr/bin/python3 -c 'import matplotlib' 2>/dev/null; then
  $sudo apt-get update -qq
  $sudo env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends python3-matplotlib
fi
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
cmake --build build -j"$(nproc)" --target facial_cli facial_bench facial-editor

out=bench/out
rm -rf "$out"
mkdir -p "$out"
{
  echo "date=$(date -u +%Y-%m-%dT%H:%MZ)"
  echo "cpu=$(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2- | sed 's/^ //') cores=$(nproc)"
  echo "load=$(cut -d' ' -f1-3 /proc/loadavg)"
} > "$out/machine.txt"

# 1. Whole frames: facecap, every target animated vs static, per tier, alternating.
echo "report: frames (facecap, 512x512, tiers x animated/static, $rounds rounds)"
for ((r = 1; r <= rounds; ++r)); do
  for q in high balanced fast; do
    for a in all none; do
      build/bin/facial bench frames "$facecap" --frames 60 --quality "$q" --animate "$a" 2>/dev/null | tail -1 >> "$out/frames.txt"
    done
  done
done
build/bin/facial bench frames "$facecap" --frames 2 --warmup 0 2>/dev/null | grep '^memory:' | sed 's/^/facecap /' > "$out/memory.txt"
build/bin/facial bench frames data/head.glb --frames 2 --warmup 0 2>/dev/null | grep '^memory:' | sed 's/^/head /' >> "$out/memory.txt"

# 2. The built-in head at the window size, headless (what the window draws, without presenting).
echo "report: built-in head at 1280x800 per tier"
for ((r = 1; r <= rounds; ++r)); do
  for q in high balanced fast; do
    build/bin/facial bench frames data/head.glb --size 1280x800 --frames 30 --quality "$q" 2>/dev/null | tail -1 >> "$out/head1280.txt"
  done
done

# 3. The window demo and the editor themselves, under Xvfb (presenting included).
if [ "$window" = 1 ] && command -v xvfb-run >/dev/null; then
  echo "report: window demo and editor at 1280x800 per tier (Xvfb)"
  for q in high balanced fast; do
    xvfb-run -a -s "-screen 0 1280x800x24" build/bin/facial demo --quality "$q" --quit-after 8 2>/dev/null |
      grep '^window:' | sed "s/^/demo quality=$q /" >> "$out/window.txt" || true
    xvfb-run -a -s "-screen 0 1280x800x24" build/bin/facial-editor --quality "$q" --quit-after 8 2>/dev/null |
      grep '^window:' | sed "s/^/editor quality=$q /" >> "$out/window.txt" || true
  done
fi

# 4. The three.js peer, alternating with facial bench frames.
if [ "$peer" = 1 ]; then
  echo "report: three.js peer ($rounds rounds)"
  bench/peer/run.sh --rounds "$rounds" --frames 60 --quality "high balanced fast" 2>/dev/null | grep -E '^(round|peer summary)' > "$out/peer.txt"
fi

# 5. Morph paths, bandwidth, graph update (Google Benchmark, JSON).
echo "report: morph path sweep and copy bandwidth"
build/bin/facial_bench --benchmark_filter='MorphSweep|MorphCopyBandwidth' --benchmark_min_time=0.05 \
  --benchmark_format=json --benchmark_out="$out/morph.json" --benchmark_out_format=json > /dev/null 2>&1
echo "report: graph update"
build/bin/facial_bench --benchmark_filter='GraphUpdate60Channels' --benchmark_min_time=0.2 \
  --benchmark_format=json --benchmark_out="$out/graph.json" --benchmark_out_format=json > /dev/null 2>&1

/usr/bin/python3 bench/report.py "$out"
echo "report: wrote $out/report.md and $out/morph_cost.png"
