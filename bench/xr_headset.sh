#!/usr/bin/env bash
# solxr at headset sizes through the headless test runtime in its timing
# mode (no read-back, no pacing), every preset, the render scale fixed at 1
# and no refinement, so that the figures are the full frame's:
#  - 2000 x 2000 per eye, 100 degrees, 90 Hz, foveation off;
#  - 2064 x 2208 per eye, 100 degrees, 120 Hz, foveation off and on.
# FRAMES frames each (default 600). Prints CSV on stdout:
#   date,device,scene,width,height,refresh_hz,foveation,frames,mean_ms,p99_ms,missed,work_mean_ms
# The mean and p99 are solxr --stats' (the interval between frames' ends on
# the device); missed counts frames whose device work and recording did not
# fit the period. Meant for a GPU; on lavapipe pass smaller sizes:
#   bench/xr_headset.sh [BUILD_DIR] [FRAMES] > out.csv        (BUILD_DIR default build/release)
#   SIZES="256x256@90 256x256@120" PRESETS=plane bench/xr_headset.sh build/ci 60
set -euo pipefail
build=${1:-build/release}
frames=${2:-600}
presets=${PRESETS:-"plane sandwich sheets lattice-balls lattice-pillars lattice-boxes spheres"}
sizes=${SIZES:-"2000x2000@90 2064x2208@120"}
solxr=$build/xr/solxr
runtime=$build/xr/test_runtime/sol-xr-test-runtime.json
[ -x "$solxr" ] || { echo "xr_headset: $solxr not built" >&2; exit 2; }
[ -f "$runtime" ] || { echo "xr_headset: $runtime not built (the tests' OpenXR runtime)" >&2; exit 2; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
export XDG_RUNTIME_DIR=${XDG_RUNTIME_DIR:-$work}
day=$(date +%F)
echo "date,device,scene,width,height,refresh_hz,foveation,frames,mean_ms,p99_ms,missed,work_mean_ms"
for size in $sizes; do
  wh=${size%@*}; hz=${size#*@}; w=${wh%x*}; h=${wh#*x}
  foveations="off"; [ "$hz" != 90 ] && foveations="off on"
  python3 -c "import json; json.dump({'width': $w, 'height': $h, 'fov': 100, 'refresh_hz': $hz, 'read_back': False, 'frames': [{}] * $frames}, open('$work/script.json', 'w'))"
  for scene in $presets; do
    for foveation in $foveations; do
      XR_RUNTIME_JSON=$runtime SOLXR_TEST_SCRIPT=$work/script.json "$solxr" --scene "$scene" --adaptive off --refine 0 \
        --foveation "$foveation" --stats > "$work/out" 2> "$work/err" || { cat "$work/err" >&2; exit 1; }
      python3 - "$day" "$scene" "$w" "$h" "$hz" "$foveation" "$work/out" <<'PY'
import re, sys
day, scene, w, h, hz, foveation, path = sys.argv[1:]
text = open(path).read()
m = re.search(r"stereo frames: (\d+), mean ([\d.]+) ms, p99 ([\d.]+) ms, missed (\d+)", text)
work = re.search(r"device work mean ([\d.]+) ms", text)
device = re.search(r"per eye on '([^']*)'", text)
print(f'{day},"{device.group(1)}",{scene},{w},{h},{hz},{foveation},{m.group(1)},{m.group(2)},{m.group(3)},{m.group(4)},{work.group(1)}')
PY
    done
  done
done
