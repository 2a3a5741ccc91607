#!/usr/bin/env bash
# solview --scene FILE reads the file again when it is saved: a good edit
# changes the frame; a broken edit keeps the last good frame and reports the
# error (field, line and column) on stderr; SIGTERM ends the session cleanly
# (exit 0, the validation layer's report, no errors). Frames come from
# --record (each file complete or absent), compared with idiff.
#   hot_reload.sh SOLVIEW IDIFF WORK_DIR    (needs a display: run under xvfb-run)
set -euo pipefail
solview=$1 idiff=$2 dir=$3
rm -rf "$dir"
mkdir -p "$dir"
cd "$dir"
scene() {  # a plane z = -1 of the given colour, seen from above
  printf '{"camera": {"position": [0, 0, 0], "forward": [0, 0, -1], "up": [0, 1, 0], "fov": 90},\n "objects": [{"type": "plane_z", "c": -1, "color": [%s]}]}\n' "$1"
}
scene "0.9, 0.5, 0.2" > scene.json
"$solview" --scene scene.json --size 32x18 --vsync off --refine 0 --record rec --validation 2> log &
pid=$!
trap 'kill -KILL $pid 2>/dev/null || true' EXIT
fail() {
  echo "hot_reload: $*" >&2
  echo "--- solview's stderr:" >&2
  cat log >&2
  exit 1
}
# The newest frame written so far (its number).
newest() { { ls rec 2>/dev/null || true; } | sed -n 's/^frame-\([0-9]*\)\.png$/\1/p' | sort -n | tail -1; }
# Waits up to 60 s for `frames` more frames after frame `after`.
wait_frames() {
  local after=$1 frames=$2
  for _ in $(seq 600); do
    local n
    n=$(newest)
    if [ -n "$n" ] && [ $((10#$n)) -ge $((10#${after:-0} + frames)) ]; then return 0; fi
    kill -0 $pid 2>/dev/null || fail "solview ended early"
    sleep 0.1
  done
  fail "no frames after frame ${after:-none}"
}
wait_log() {
  for _ in $(seq 600); do
    grep -q "$1" log && return 0
    kill -0 $pid 2>/dev/null || fail "solview ended early"
    sleep 0.1
  done
  fail "no '$1' on stderr"
}
# Saves the scene text $1, waits for the message $2 and three more frames,
# and checks that the frame is still the last good one ($good); $3 says
# what the edit was. Sets $kept to the newest frame's number.
expect_kept() {
  sleep 1.1  # a new modification time even where it has one-second resolution
  printf '%s' "$1" > scene.json
  wait_log "$2"
  local mark
  mark=$(newest)
  wait_frames "$mark" 3
  kept=$(newest)
  "$idiff" -q "rec/frame-$good.png" "rec/frame-$kept.png" > /dev/null 2>&1 ||
    fail "the frame changed after $3 (frames $good and $kept differ)"
}
wait_frames 0 3
first=$(newest)

# A good edit: another colour.
sleep 1.1  # a new modification time even where it has one-second resolution
scene "0.2, 0.4, 0.9" > scene.json
wait_log "reloaded scene.json"
mark=$(newest)
wait_frames "$mark" 3
good=$(newest)
if "$idiff" -q "rec/frame-$first.png" "rec/frame-$good.png" > /dev/null 2>&1; then
  fail "the frame did not change after a good edit (frames $first and $good are the same)"
fi

# A broken edit: a misspelt key on line 2; the last good scene stays.
expect_kept '{"camera": {"position": [0, 0, 0], "forward": [0, 0, -1], "up": [0, 1, 0], "fov": 90},
 "objects": [{"type": "plane_z", "colour": [1, 0, 0]}]}
' "scene.json.*unknown key 'colour'.*line 2.*the last good scene stays" "a broken edit"
broken=$kept

# A scene that validates but cannot be prepared (a monodromy of trace 3,
# within the kernel's bound, whose entries of a million make its lattice
# need over a million words): solview goes on with the last good scene (it
# exited 4), and says why.
expect_kept '{"camera": {"position": [0.1, 0.1, 0.1], "forward": [0, 0, -1], "up": [0, 1, 0], "fov": 90},
 "quotient": {"monodromy": [[1002, -1000999], [1, -999]]},
 "objects": [{"type": "ball", "center": [0, 0, 0], "radius": 0.1}]}
' "million.*the last good scene stays" "a scene that cannot be prepared"

# A clean end on SIGTERM: the session's summary, exit 0, nothing from the validation layer.
kill -TERM $pid
status=0
wait $pid || status=$?
trap - EXIT
[ "$status" -eq 0 ] || fail "solview exited with $status after SIGTERM"
grep -q "signal 15: ending the session" log || fail "no clean end on SIGTERM"
if grep -Eq "validation|VUID" log; then fail "validation messages"; fi
echo "hot_reload: frames $first (first), $good (after the good edit), $broken (after the broken edit), $kept (after the scene that cannot be prepared)"
