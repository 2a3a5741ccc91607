#!/usr/bin/env bash
# The presenters against the kernel, in one run on one device, every preset:
#  - solxr's mean stereo frame time (--stats, the render scale fixed at 1,
#    no refinement, through the headless test runtime in its timing mode:
#    no image read back, no pacing) against
#    render_bench's stereo frame of two EYE x EYE eyes (--only gpu), with the
#    runtime's field of view set to the scene camera's;
#  - solview's mean frame time (--stats: mono, 640x360, render scale 1, no
#    refinement, no vsync, under Xvfb) against render_bench's mono frame of
#    640 x 360 (skipped with SOLVIEW=off, or where xvfb-run is missing).
# Each presenter figure is the mean interval between frames' ends on the
# device; the kernel's, the best of render_bench's batches of frames
# recorded back to back. Prints CSV on stdout:
#   date,program,scene,device,width,height,frames,kernel_ms,mean_ms,p99_ms,ratio
#
#   bench/presenter_ratio.sh [BUILD_DIR] [EYE] [FRAMES] > out.csv
# (BUILD_DIR default build/release; EYE 256; FRAMES 120). On lavapipe set
# VK_ICD_FILENAMES to its ICD first, as the tests do.
set -euo pipefail
build=${1:-build/release}
eye=${2:-256}
frames=${3:-120}
presets=${PRESETS:-"plane sandwich sheets lattice-balls lattice-pillars lattice-boxes spheres"}
for f in "$build/xr/solxr" "$build/bench/render_bench" "$build/viewer/solrender"; do
  [ -x "$f" ] || { echo "presenter_ratio: $f not built" >&2; exit 2; }
done
runtime=$build/xr/test_runtime/sol-xr-test-runtime.json
[ -f "$runtime" ] || { echo "presenter_ratio: $runtime not built (the tests' OpenXR runtime)" >&2; exit 2; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
export XDG_RUNTIME_DIR=${XDG_RUNTIME_DIR:-$work}
solview=${SOLVIEW:-on}
if [ "$solview" = on ] && ! command -v xvfb-run > /dev/null; then solview=off; fi
day=$(date +%F)
# The stereo (or mono) frame time render_bench measured for one preset at W x H.
kernel_ms() {  # SCENE W H COLUMN(mono_ms|stereo_ms)
  mkdir -p "$work/bench"
  "$build/bench/render_bench" --only gpu --gpu-size "$2" --gpu-height "$3" --scene "$1" --out-dir "$work/bench" 2> /dev/null
  python3 - "$work/bench/render_gpu.csv" "$4" <<'PY'
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
print(rows[0][sys.argv[2]], rows[0]["device"])
PY
}
# "mean p99" of a presenter's --stats line on stdin.
stats() { sed -n 's/^\(mono\|stereo\) frames: [0-9]*, mean \([0-9.]*\) ms, p99 \([0-9.]*\) ms.*/\2 \3/p'; }
echo "date,program,scene,device,width,height,frames,kernel_ms,mean_ms,p99_ms,ratio"
for scene in $presets; do
  fov=$("$build/viewer/solrender" --scene "$scene" --print-scene | python3 -c "import json,sys; print(json.load(sys.stdin)['camera']['fov'])")
  python3 -c "import json; json.dump({'width': $eye, 'height': $eye, 'fov': $fov, 'read_back': False, 'frames': [{}] * $frames}, open('$work/script.json', 'w'))"
  read -r kernel device < <(kernel_ms "$scene" "$eye" "$eye" stereo_ms)
  read -r mean p99 < <(XR_RUNTIME_JSON=$runtime SOLXR_TEST_SCRIPT=$work/script.json \
    "$build/xr/solxr" --scene "$scene" --adaptive off --refine 0 --stats 2> /dev/null | stats)
  echo "$day,solxr,$scene,\"$device\",$eye,$eye,$frames,$kernel,$mean,$p99,$(python3 -c "print(f'{$mean / $kernel:.3f}')")"
  if [ "$solview" = on ]; then
    read -r kernel device < <(kernel_ms "$scene" 640 360 mono_ms)
    read -r mean p99 < <(xvfb-run -a -s "-screen 0 1024x768x24" "$build/viewer/solview" --scene "$scene" --size 640x360 \
      --scale 1 --refine 0 --vsync off --frames "$frames" --stats 2> /dev/null | stats)
    echo "$day,solview,$scene,\"$device\",640,360,$frames,$kernel,$mean,$p99,$(python3 -c "print(f'{$mean / $kernel:.3f}')")"
  fi
done
