#!/usr/bin/env bash
# The paper's four films as small animated GIFs in docs/films/: each path of
# docs/paths/ rendered by solrender --path (160x120, 8 fps, 4 samples per
# pixel; the lattice, whose far copies make a GIF large, at 112x84 and 5 fps),
# the frames joined by oiiotool (OpenImageIO writes animated GIF).
#   docs/paths/make_films.sh OUT_DIR [BUILD_DIR]   (from the repository root; BUILD_DIR default
#   build/release, the README's; docs/films as OUT_DIR replaces the films the docs show)
set -euo pipefail
if [ $# -lt 1 ]; then echo "usage: docs/paths/make_films.sh OUT_DIR [BUILD_DIR]" >&2; exit 2; fi
out=$1
build=${2:-build/release}
solrender=$build/viewer/solrender
frames=$(mktemp -d)
trap 'rm -rf "$frames"' EXIT
mkdir -p "$out"
for film in balloon:plane through-the-plane:plane between-the-planes:sandwich inside-the-manifold:lattice-balls; do
  name=${film%%:*} scene=${film#*:}
  fps=8 size=(--width 160 --height 120)
  if [ "$scene" = lattice-balls ]; then fps=5 size=(--width 112 --height 84); fi
  "$solrender" --scene "$scene" --path "docs/paths/$name.json" --fps $fps "${size[@]}" --spp 4 -o "$frames/$name-%03d.png"
  oiiotool "$frames/$name"-*.png --siappendall --attrib:type=rational FramesPerSecond $fps/1 -o "$out/$name.gif"
  echo "$out/$name.gif: $(stat -c %s "$out/$name.gif") bytes"
done
