#!/usr/bin/env bash
# The peer, side by side: `facial bench frames` and three.js (headless
# Chromium, SwiftShader) on the same face, the same animation (every morph
# target re-weighted every frame), 512x512, 4x MSAA, 30 degree fov, camera on
# +Z at 1.6x the box diagonal. Runs alternate (facial, three.js, facial, ...)
# so load on the machine hits both alike; prints every run, then both median
# frame rates and their ratio per quality tier. A comparison script: never
# part of the product build; installs what it needs (node, npm, chromium from
# Debian, three from npm into tools/threejs-compare/).
#
#   bench/peer/run.sh [--model M.glb] [--rounds N] [--frames N] [--size WxH] [--quality "high balanced fast"]
set -euo pipefail
cd "$(dirname "$0")/../.."
root=$PWD

model=../shared/assets/facecap.glb
rounds=3
frames=60
size=512x512
qualities="high"
while [ $# -gt 0 ]; do
  case "$1" in
    --model) model=$2; shift 2 ;;
    --rounds) rounds=$2; shift 2 ;;
    --frames) frames=$2; shift 2 ;;
    --size) size=$2; shift 2 ;;
    --quality) qualities=$2; shift 2 ;;
    *) echo "usage: $0 [--model M.glb] [--rounds N] [--frames N] [--size WxH] [--quality \"high balanced fast\"]" >&2
       exit 2 ;;
  esac
done
[ -f "$model" ] || { echo "peer: $model: not found (../shared beside the checkout?)" >&2; exit 1; }
width=${size%x*}
[ "$width" = "${size#*x}" ] || { echo "peer: --size must be square (the page is square)" >&2; exit 2; }

missing=()
for tool in node:nodejs npm:npm chromium:chromium; do
  command -v "${tool%%:*}" >/dev/null || missing+=("${tool#*:}")
done
if [ ${#missing[@]} -gt 0 ]; then
  sudo=""; [ "$(id -u)" -ne 0 ] && sudo=sudo
  $sudo apt-get update -qq
  $sudo env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi
[ -d tools/threejs-compare/node_modules/three ] ||
  (cd tools/threejs-compare && npm install --no-audit --no-fund --loglevel=error)
if [ ! -x build/bin/facial ]; then
  cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
  cmake --build build -j"$(nproc)" --target facial_cli
fi

# The camera the C++ bench uses (target and distance), for the page.
settings=$(build/bin/facial bench frames "$model" --size "$size" --frames 1 --warmup 0 | grep '^settings:')
target=$(sed -n 's/.*camera_target=\([^ ]*\).*/\1/p' <<<"$settings")
distance=$(sed -n 's/.*camera_distance=\([^ ]*\).*/\1/p' <<<"$settings")

fps_of() { sed -n 's/.* fps=\([0-9.]*\)$/\1/p'; }
median() { sort -g | awk '{v[NR]=$1} END {print (NR % 2) ? v[(NR+1)/2] : (v[NR/2] + v[NR/2+1]) / 2}'; }
declare -A ours
peer=()
for ((r = 1; r <= rounds; ++r)); do
  for q in $qualities; do
    line=$(build/bin/facial bench frames "$model" --size "$size" --frames "$frames" --quality "$q" | tail -1)
    echo "round $r: $line"
    ours[$q]+="$(fps_of <<<"$line") "
  done
  line=$(node bench/peer/peer.mjs "$model" --size "$width" --frames "$frames" --target "$target" --distance "$distance")
  echo "round $r: $line"
  peer+=("$(fps_of <<<"$line")")
done
peer_fps=$(printf '%s\n' "${peer[@]}" | median)
for q in $qualities; do
  our_fps=$(tr ' ' '\n' <<<"${ours[$q]}" | grep . | median)
  awk -v q="$q" -v a="$our_fps" -v b="$peer_fps" -v n="$rounds" \
    'BEGIN {printf "peer summary: quality=%s facial_fps=%.2f threejs_fps=%.2f ratio=%.2f (medians of %d alternating runs)\n", q, a, b, a / b, n}'
done
