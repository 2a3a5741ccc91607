#!/usr/bin/env bash
# Frame rates of solview for every preset at 640x360 on the Vulkan device the
# loader picks (lavapipe here: VK_ICD_FILENAMES), at render scale 1 and with
# the adaptive scale holding 30 fps; prints a Markdown table for README.md.
#   viewer/measure_fps.sh [BUILD_DIR]    (needs xvfb-run, or a DISPLAY)
set -euo pipefail
build=${1:-build/ci}
solview=$build/viewer/solview
run() {
  if [ -n "${DISPLAY:-}" ]; then "$solview" "$@"; else xvfb-run -a -s "-screen 0 1024x768x24" "$solview" "$@"; fi
}
field() { sed -n "s/.*: \([0-9.]*\) fps (mean over frames \([0-9]*\)\.\.\([0-9]*\)), mean render scale \([0-9.]*\)/\\$1/p"; }
echo "| preset | fps at scale 1 | adaptive (--target-fps 30): fps | mean scale |"
echo "|---|---|---|---|"
for scene in plane sandwich sheets lattice-balls; do
  full_frames=60; [ "$scene" = lattice-balls ] && full_frames=8
  full=$(run --scene "$scene" --size 640x360 --vsync off --frames $full_frames 2>&1 | grep "fps (mean")
  adaptive=$(run --scene "$scene" --size 640x360 --vsync off --frames 240 --target-fps 30 2>&1 | grep "fps (mean")
  echo "| $scene | $(echo "$full" | field 1) | $(echo "$adaptive" | field 1) | $(echo "$adaptive" | field 4) |"
done
