#!/usr/bin/env bash
# Frame rates of solview for every preset at 640x360 on the Vulkan device the
# loader picks (lavapipe here: VK_ICD_FILENAMES), at render scale 1 and with
# the adaptive scale holding TARGET fps (default 20); prints a Markdown table
# for docs/solview.md.
# With `present`: plane at scale 1 on the direct path (--present auto) and
# through the blit (--present blit), four interleaved runs of each.
# With `refine`: per preset, walking 0.3 s with the adaptive scale, then
# still: the time from the end of the 0.25 s pause to the full-resolution
# frame and to 16 accumulated samples (progressive refinement).
# The frame-rate runs keep the observer still with --refine 0 (what they
# measure is the moving view).
#   [TARGET=20] viewer/measure_fps.sh [BUILD_DIR] [present|refine]    (needs xvfb-run, or a DISPLAY)
set -euo pipefail
build=${1:-build/release}
solview=$build/viewer/solview
run() {
  if [ -n "${DISPLAY:-}" ]; then "$solview" "$@"; else xvfb-run -a -s "-screen 0 1024x768x24" "$solview" "$@"; fi
}
field() { sed -n "s/.*: \([0-9.]*\) fps (mean over the \([0-9]*\) rendered frames of \([0-9]*\)\.\.[0-9]*[^)]*), mean render scale \([0-9.]*\)/\\$1/p"; }
if [ "${2:-}" = present ]; then
  echo "| run | direct (--present auto) fps | blit (--present blit) fps |"
  echo "|---|---|---|"
  for i in 1 2 3 4; do
    out=$(run --scene plane --size 640x360 --vsync off --refine 0 --frames 120 --present auto 2>&1)
    # The direct path must have presented every frame, else the column is not what it says.
    direct=$(echo "$out" | grep -q "present: direct 120 frames" && echo "$out" | grep "fps (mean" | field 1 || echo "not direct")
    blit=$(run --scene plane --size 640x360 --vsync off --refine 0 --frames 120 --present blit 2>&1 | grep "fps (mean" | field 1)
    echo "| $i | $direct | $blit |"
  done
  exit 0
fi
target=${TARGET:-20}
if ! [[ $target =~ ^[0-9]+([.][0-9]+)?$ ]] || [ "$target" = 0 ]; then
  echo "measure_fps.sh: TARGET must be a positive number of frames per second, got '$target'" >&2
  exit 2
fi
if [ "${2:-}" = refine ]; then
  script=$(mktemp)
  trap 'rm -f "$script"' EXIT
  printf '0 down W\n0.3 up W\n' > "$script"
  echo "| preset | full resolution after the pause (s) | 16 samples after the pause (s) |"
  echo "|---|---|---|"
  for scene in plane sandwich sheets lattice-balls lattice-pillars spheres; do
    line=$(run --scene "$scene" --size 640x360 --vsync off --target-fps "$target" --refine 16 --script "$script" --frames 60 2>&1 |
      grep "refined:" || true)
    full=$(echo "$line" | sed -n 's/.*full resolution \([0-9.]*\) s and.*/\1/p')
    all=$(echo "$line" | sed -n 's/.* samples \([0-9.]*\) s after.*/\1/p')
    echo "| $scene | ${full:-not reached} | ${all:-not reached} |"
  done
  exit 0
fi
echo "| preset | fps at scale 1 | adaptive (--target-fps $target): fps | mean scale |"
echo "|---|---|---|---|"
for scene in plane sandwich sheets lattice-balls lattice-pillars spheres; do
  full_frames=60; case $scene in lattice-* | spheres) full_frames=8;; esac
  full=$(run --scene "$scene" --size 640x360 --vsync off --refine 0 --frames $full_frames 2>&1 | grep "fps (mean")
  adaptive=$(run --scene "$scene" --size 640x360 --vsync off --refine 0 --frames 240 --target-fps "$target" 2>&1 | grep "fps (mean")
  echo "| $scene | $(echo "$full" | field 1) | $(echo "$adaptive" | field 1) | $(echo "$adaptive" | field 4) |"
done
