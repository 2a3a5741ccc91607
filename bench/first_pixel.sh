#!/usr/bin/env bash
# A world's first pixel on the kernel with every cache cold: solrender at
# 4x4, one sample, with the folded-SPIR-V cache, the pipeline cache and
# Mesa's shader cache off, for the scene files of docs/exact, docs/gallery
# and bench/scenes/ (worlds that hold every feature the kernel compiles: exact balls,
# mirrors, a glowing exact ball, an exact light with a reach and shadows,
# the eye inside an exact ball, the golden quotient), direct and path
# traced. The time is what a new user waits for the first picture: the
# specialisation, the driver's compile (lavapipe compiles its LLVM code at
# the first dispatch) and the render. Prints CSV on stdout:
#   scene,transport,seconds,peak_mb[,seconds_b,peak_mb_b]
# with "cpu-only" for seconds where the kernel refuses the world.
#
#   bench/first_pixel.sh [SOLRENDER [SOLRENDER_B]] > out.csv
# SOLRENDER defaults to build/release/viewer/solrender; with a second
# binary each world runs on both in turn (old and new interleaved, so that
# the machine's load falls on both alike). Run from the repository root;
# on lavapipe set VK_ICD_FILENAMES to its ICD first, as the tests do.
set -euo pipefail
a=${1:-build/release/viewer/solrender}
b=${2:-}
for bin in "$a" ${b:+"$b"}; do
  [ -x "$bin" ] || { echo "first_pixel: $bin is not an executable" >&2; exit 2; }
done
command -v /usr/bin/time > /dev/null || { echo "first_pixel: /usr/bin/time missing (Debian: time)" >&2; exit 2; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
run() {  # BINARY SCENE TRANSPORT: "seconds,peak_mb" or "cpu-only,"
  if SOL_SPIRV_CACHE=off SOL_PIPELINE_CACHE=off MESA_SHADER_CACHE_DISABLE=true \
     /usr/bin/time -f "%e %M" -o "$work/time" "$1" --scene "$2" --transport "$3" --spp 1 --width 4 --height 4 \
     --device vulkan -o "$work/out.png" > /dev/null 2> "$work/err"; then
    read -r seconds kb < "$work/time"
    echo "$seconds,$((kb / 1024))"
  elif grep -q "CPU only" "$work/err"; then
    echo "cpu-only,"
  else
    echo "first_pixel: $1 failed on $2 ($3):" >&2
    cat "$work/err" >&2
    exit 1
  fi
}
if [ -n "$b" ]; then echo "scene,transport,seconds,peak_mb,seconds_b,peak_mb_b"; else echo "scene,transport,seconds,peak_mb"; fi
for scene in docs/exact/*.json docs/gallery/*.json bench/scenes/*.json; do
  for transport in direct path; do
    line="$scene,$transport,$(run "$a" "$scene" "$transport")"
    [ -n "$b" ] && line="$line,$(run "$b" "$scene" "$transport")"
    echo "$line"
  done
done
