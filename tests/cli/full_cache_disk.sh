#!/usr/bin/env bash
# A cache folder on a full disk never stops a render: Mesa's shader cache
# (written through a memory map: a full disk was SIGBUS, exit 135, no
# message) is turned off with a note, and the pipeline cache that cannot be
# written is a warning. Needs a small tmpfs: skipped (77) where this test
# cannot mount one (not root, or no mount rights in a container).
#   full_cache_disk.sh SOLRENDER WORK_DIR
set -u
solrender=$1 work=$2/full-cache
mkdir -p "$work/cache" || exit 1
mount -t tmpfs -o size=256k tmpfs "$work/cache" 2>/dev/null || { echo "cannot mount a tmpfs here: skipped"; exit 77; }
trap 'umount "$work/cache"' EXIT
dd if=/dev/zero of="$work/cache/fill" bs=4k count=1000 2>/dev/null  # fills it: dd stops at "No space left"
err=$(XDG_CACHE_HOME="$work/cache" "$solrender" --device vulkan --scene plane --width 16 --height 12 -o "$work/out.png" 2>&1)
status=$?
echo "$err"
[ "$status" -eq 0 ] || { echo "FAIL: exit status $status with the cache folder on a full disk"; exit 1; }
[ -s "$work/out.png" ] || { echo "FAIL: no image"; exit 1; }
grep -q "the driver's shader cache is off" <<<"$err" || { echo "FAIL: no note that the driver's cache is off"; exit 1; }
grep -q "cannot write the pipeline cache" <<<"$err" || { echo "FAIL: no warning about the pipeline cache"; exit 1; }
echo "rendered with the cache folder on a full disk"
