#!/usr/bin/env bash
# Renders every preset and every scene file under docs/ with solrender, on
# the CPU and on the Vulkan kernel, plus the kernel's other modes (stereo,
# panoramas, fisheye, omnidirectional stereo, RK4, anti-aliasing), as float
# EXRs with their AOVs: a fingerprint of what the renderers draw. Two
# folders made by two builds are equal file by file exactly when both
# renderers draw the same bits; a refactoring that must not change any
# picture is checked with
#
#   scripts/render_reference.sh build/ci /tmp/before     # old build
#   scripts/render_reference.sh build/ci /tmp/after      # new build
#   scripts/render_reference.sh --compare /tmp/before /tmp/after
#
# Usage: render_reference.sh BUILD_DIR OUT_DIR [SIZE]   (SIZE: WxH, default 96x72)
#        render_reference.sh --compare DIR_A DIR_B
# Exits 0 when every render succeeded (or, with --compare, every file is
# equal), 1 otherwise; 2 on bad usage.
set -uo pipefail
usage() { sed -n '2,17p' "$0" | sed 's/^# \{0,1\}//' >&2; exit 2; }
if [ "${1:-}" = "--compare" ]; then
  [ $# -eq 3 ] && [ -d "$2" ] && [ -d "$3" ] || usage
  differ=0 total=0
  while IFS= read -r f; do
    total=$((total + 1))
    if [ ! -f "$3/$f" ]; then echo "missing in $3: $f"; differ=$((differ + 1)); continue; fi
    # The pixels, not the files' headers (OpenImageIO stamps no time, but be safe).
    if ! cmp -s "$2/$f" "$3/$f" && ! oiiotool --no-clobber "$2/$f" "$3/$f" --diff --fail 0 --failpercent 0 >/dev/null 2>&1; then
      echo "differs: $f"
      differ=$((differ + 1))
    fi
  done < <(cd "$2" && find . -name '*.exr' | sort)
  echo "render_reference: $((total - differ)) of $total images equal"
  [ "$differ" -eq 0 ]
  exit
fi
[ $# -ge 2 ] && [ $# -le 3 ] || usage
build=$1 out=$2 size=${3:-96x72}
solrender=$build/viewer/solrender
[ -x "$solrender" ] || { echo "render_reference: no $solrender (build first)" >&2; exit 2; }
[[ $size =~ ^([0-9]+)x([0-9]+)$ ]] || usage
w=${BASH_REMATCH[1]} h=${BASH_REMATCH[2]}
root=$(cd "$(dirname "$0")/.." && pwd)
mkdir -p "$out"
failed=0
render() {  # NAME, then solrender's arguments
  local name=$1
  shift
  if ! "$solrender" "$@" -o "$out/$name.exr" --aov "$out/$name.aov.exr" >"$out/$name.log" 2>&1; then
    echo "render_reference: $name failed:" >&2
    cat "$out/$name.log" >&2
    failed=1
  fi
}
# The build's presets, as its --help lists them ("a preset (plane, sandwich, ...)").
presets=$("$solrender" --help | sed -n 's/.*a preset (\([^)]*\)).*/\1/p' | head -n 1 | tr -d ',')
[ -n "$presets" ] || { echo "render_reference: no presets in $solrender --help" >&2; exit 2; }
scenes=($presets)
while IFS= read -r f; do scenes+=("$f"); done < <(cd "$root" && find docs -name '*.json' ! -path 'docs/paths/*' | sort)
for s in "${scenes[@]}"; do
  name=$(echo "$s" | tr '/' '-')
  name=${name%.json}
  arg=$s
  [ -f "$root/$s" ] && arg=$root/$s
  for device in cpu vulkan; do
    render "$name.$device" --scene "$arg" --device "$device" --width "$w" --height "$h"
  done
done
# The kernel's other modes, on the presets.
for s in $presets; do
  render "$s.stereo" --scene "$s" --device vulkan --width "$w" --height "$h" --stereo
  render "$s.panorama" --scene "$s" --device vulkan --width $((2 * h)) --height "$h" --projection equirectangular
  render "$s.ods" --scene "$s" --device vulkan --width $((2 * h)) --height "$h" --projection equirectangular --stereo
  render "$s.fisheye" --scene "$s" --device vulkan --width "$w" --height "$h" --projection fisheye
  render "$s.spp3" --scene "$s" --device vulkan --width "$w" --height "$h" --spp 3
  render "$s.cpu-spp3" --scene "$s" --device cpu --width "$w" --height "$h" --spp 3
done
for s in plane sandwich lattice-balls; do
  render "$s.rk4" --scene "$s" --device vulkan --width "$w" --height "$h" --integrator rk4 --rk-step 0.02
done
echo "render_reference: $(find "$out" -name '*.exr' ! -name '*.aov.exr' | wc -l) renders in $out"
exit $failed
