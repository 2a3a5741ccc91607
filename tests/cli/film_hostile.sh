#!/usr/bin/env bash
# Films that never mix, never come out short and never hang: solrender
# --path against what a busy folder holds.
#  - Two films with other settings started at once into one folder: one
#    renders, the other is refused (exit 2), and every frame and the
#    manifest are the winner's (four tries).
#  - Frame files that are empty or truncated are rendered again, not
#    counted as done; a directory in a frame's place is refused.
#  - A manifest that is a FIFO, a link to /dev/zero or a sparse terabyte is
#    refused at once (exit 2), never read.
#  - The temporary a killed run left beside a frame is removed by the next
#    run alone in the folder.
#  - --video into a folder that does not exist is refused before any frame.
#  - With ffmpeg: --frames A:B --video encodes frames A..B-1 only, whatever
#    frames lie beyond; and a hung ffmpeg under --video-only ends with
#    solrender's SIGINT.
#   film_hostile.sh SOLRENDER WORK_DIR FFMPEG_OR_EMPTY FFPROBE_OR_EMPTY
set -u
solrender=$1 work=$2/film-hostile ffmpeg=${3:-} ffprobe=${4:-}
rm -rf "$work" && mkdir -p "$work" || exit 1
fail() { echo "FAIL: $*"; exit 1; }
cat > "$work/walk.json" <<'EOF'
{"segments": [{"walk": "forward", "distance": 0.5, "duration": 1}]}
EOF
film=(--device cpu --scene sandwich --path "$work/walk.json" --fps 5 --width 8 --height 6)  # frames 0..5

# Two films at once into one folder: one wins.
for try in 1 2 3 4; do
  out=$work/race$try
  "$solrender" "${film[@]}" --spp 1 -o "$out/f-%02d.png" 2> "$work/a.err" & a=$!
  "$solrender" "${film[@]}" --spp 2 -o "$out/f-%02d.png" 2> "$work/b.err" & b=$!
  wait $a; sa=$?
  wait $b; sb=$?
  if [ "$sa" -eq 0 ] && [ "$sb" -eq 2 ]; then spp=1; elif [ "$sa" -eq 2 ] && [ "$sb" -eq 0 ]; then spp=2;
  else fail "try $try: two films into one folder exited $sa and $sb ($(cat "$work/a.err" "$work/b.err"))"; fi
  grep -q "\"spp\": $spp" "$out/f-film.json" || fail "try $try: the manifest is not the winner's (spp $spp)"
  [ "$(ls "$out"/f-0*.png | wc -l)" -eq 6 ] || fail "try $try: not every frame is there"
  grep -q "rendered with other settings\|rendering the film" "$work/a.err" "$work/b.err" || fail "try $try: the loser did not say why"
done
# Both films once more, each again: the loser's settings are refused, the winner's film is done.
"$solrender" "${film[@]}" --spp $spp -o "$work/race4/f-%02d.png" 2>&1 | grep -q "0 rendered in .* 6 already there" ||
  fail "the winner's film is not whole"

# Frames that are not whole are rendered again; a directory is refused.
out=$work/broken
"$solrender" "${film[@]}" -o "$out/f-%02d.png" 2>/dev/null || fail "the first run failed"
: > "$out/f-02.png"
head -c 40 "$out/f-04.png" > "$work/cut.png" && mv "$work/cut.png" "$out/f-04.png"
err=$("$solrender" "${film[@]}" -o "$out/f-%02d.png" 2>&1) || fail "the run over broken frames failed: $err"
grep -q "f-02.png is not a whole frame (empty)" <<<"$err" || fail "the empty frame was not named: $err"
grep -q "f-04.png is not a whole frame" <<<"$err" || fail "the truncated frame was not named: $err"
grep -q "2 rendered in .* 4 already there" <<<"$err" || fail "the broken frames were not rendered again: $err"
[ "$(head -c 8 "$out/f-04.png" | od -An -tx1 | tr -d ' \n')" = "89504e470d0a1a0a" ] || fail "f-04.png is not a PNG again"
rm "$out/f-03.png" && mkdir "$out/f-03.png"
err=$("$solrender" "${film[@]}" -o "$out/f-%02d.png" 2>&1); status=$?
[ $status -eq 2 ] && grep -q "f-03.png is a directory, not a frame" <<<"$err" || fail "a directory frame: exit $status: $err"
rmdir "$out/f-03.png"

# A manifest that is not a file: refused at once.
for kind in fifo zero sparse; do
  out=$work/manifest-$kind
  mkdir -p "$out"
  case $kind in
    fifo) mkfifo "$out/f-film.json" ;;
    zero) ln -s /dev/zero "$out/f-film.json" ;;
    sparse) truncate -s 1T "$out/f-film.json" ;;
  esac
  err=$(timeout 60 "$solrender" "${film[@]}" -o "$out/f-%02d.png" 2>&1); status=$?
  [ $status -eq 2 ] && grep -q "f-film.json is not a film manifest" <<<"$err" ||
    fail "a manifest that is a $kind: exit $status (124: it hung): $err"
  [ -e "$out/f-00.png" ] && fail "a frame was written beside a $kind manifest"
done

# A killed run's temporary is removed by the next run.
out=$work/stale
mkdir -p "$out" && "$solrender" "${film[@]}" -o "$out/f-%02d.png" 2>/dev/null || fail "the stale-folder film failed"
: > "$out/.f-03.png.Ab12Cd"
"$solrender" "${film[@]}" -o "$out/f-%02d.png" 2>/dev/null || fail "the rerun failed"
[ -e "$out/.f-03.png.Ab12Cd" ] && fail "the stale temporary .f-03.png.Ab12Cd is still there"

# --video where it cannot be written: refused before the first frame.
err=$("$solrender" "${film[@]}" -o "$work/novideo/f-%02d.png" --video "$work/no/such/folder/x.mp4" 2>&1); status=$?
[ $status -eq 2 ] && grep -q -- "--video .*x.mp4" <<<"$err" || fail "--video into a missing folder: exit $status: $err"
[ -e "$work/novideo/f-00.png" ] && fail "a frame was rendered before the bad --video was refused"

if [ -x "$ffmpeg" ] && [ -x "$ffprobe" ]; then
  # --frames 0:3 --video: frames 0..2 alone, though 3..5 are there too.
  out=$work/range
  "$solrender" "${film[@]}" -o "$out/f-%02d.png" 2>/dev/null || fail "the range film failed"
  "$solrender" "${film[@]}" -o "$out/f-%02d.png" --frames 0:3 --video "$out/v.mp4" 2>/dev/null || fail "--frames 0:3 --video failed"
  frames=$("$ffprobe" -v error -count_frames -select_streams v:0 -show_entries stream=nb_read_frames -of csv=p=0 "$out/v.mp4")
  [ "$frames" = "3" ] || fail "--frames 0:3 --video encoded $frames frames"
  # A hung encoder: SIGINT ends solrender and it.
  mkdir -p "$work/bin"
  printf '#!/bin/sh\necho $$ > %s/hung.pid\nexec sleep 600\n' "$work" > "$work/bin/ffmpeg" && chmod +x "$work/bin/ffmpeg"
  PATH="$work/bin:$PATH" timeout --preserve-status -s INT -k 20 5 "$solrender" "${film[@]}" --width 512 --height 512 \
    --video "$work/hung.mp4" --video-only 2>/dev/null
  status=$?
  [ $status -eq 130 ] || fail "solrender with a hung ffmpeg: exit $status (137: SIGINT did not stop it)"
  hung=$(cat "$work/hung.pid")
  # Alive: ps still lists it in a state other than zombie (killed, it may stay a
  # zombie until whoever adopted it reaps it, or vanish between two looks: both
  # are dead). A signalled process may take a moment to go, so look for 5 s.
  alive() { local st; st=$(ps -o stat= -p "$hung" 2>/dev/null | cut -c1); [ -n "$st" ] && [ "$st" != "Z" ]; }
  for _ in 1 2 3 4 5 6 7 8 9 10; do alive || break; sleep 0.5; done
  if alive; then
    kill -9 "$hung" 2>/dev/null
    fail "the hung ffmpeg outlived solrender's SIGINT"
  fi
  [ -e "$work/hung.mp4" ] && fail "an interrupted --video-only left the video"
fi
echo "films: one writer a folder, whole frames, no hangs"
