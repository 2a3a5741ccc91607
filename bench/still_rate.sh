#!/usr/bin/env bash
# solrender end to end against its kernel, for stills: two sizes of one
# preset in one run (default plane, 1536 x 1536 and 3840 x 2160), each
# timed with /usr/bin/time (wall seconds, peak resident memory). The
# marginal rate is the extra pixels over the extra wall time, set against
# the kernel's own marginal rate (the extra pixels over the extra device
# time solrender reports, "kernel N ms"); the memory as bytes per pixel
# above a fixed 300 MB. Prints CSV on stdout:
#   date,scene,device,small,large,small_s,large_s,small_kernel_ms,large_kernel_ms,marginal_mpx_s,kernel_marginal_mpx_s,ratio,large_peak_mb,bytes_per_pixel_above_300mb
#
#   bench/still_rate.sh [BUILD_DIR] [SCENE] > out.csv   (BUILD_DIR default build/release)
# On lavapipe set VK_ICD_FILENAMES to its ICD first, as the tests do.
set -euo pipefail
build=${1:-build/release}
scene=${2:-plane}
solrender=$build/viewer/solrender
[ -x "$solrender" ] || { echo "still_rate: $solrender not built" >&2; exit 2; }
command -v /usr/bin/time > /dev/null || { echo "still_rate: /usr/bin/time missing (Debian: time)" >&2; exit 2; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
run() {  # W H: "wall_s peak_kb kernel_ms device"
  /usr/bin/time -f "%e %M" -o "$work/time" "$solrender" --scene "$scene" --width "$1" --height "$2" -o "$work/out.png" \
    2> "$work/err"
  local kernel device
  kernel=$(sed -n 's/.*(kernel \([0-9.]*\) ms).*/\1/p' "$work/err")
  device=$(sed -n "s/.* on \(vulkan '[^']*'\).*/\1/p" "$work/err")
  echo "$(cat "$work/time") ${kernel:-0} $device"
}
read -r small_s _ small_k _ < <(run 1536 1536)
read -r large_s large_kb large_k device < <(run 3840 2160)
python3 - "$(date +%F)" "$scene" "$device" "$small_s" "$large_s" "$small_k" "$large_k" "$large_kb" <<'PY'
import sys
day, scene, device, small_s, large_s, small_k, large_k, large_kb = sys.argv[1:]
small_px, large_px = 1536 * 1536, 3840 * 2160
extra = large_px - small_px
marginal = extra / (float(large_s) - float(small_s)) / 1e6
kernel = extra / ((float(large_k) - float(small_k)) / 1e3) / 1e6
peak_mb = float(large_kb) / 1024
print("date,scene,device,small,large,small_s,large_s,small_kernel_ms,large_kernel_ms,marginal_mpx_s,kernel_marginal_mpx_s,ratio,large_peak_mb,bytes_per_pixel_above_300mb")
print(f'{day},{scene},"{device}",1536x1536,3840x2160,{small_s},{large_s},{small_k},{large_k},{marginal:.2f},{kernel:.2f},{marginal / kernel:.2f},{peak_mb:.0f},{(peak_mb - 300) * 2**20 / large_px:.1f}')
PY
