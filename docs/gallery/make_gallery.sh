#!/usr/bin/env bash
# The gallery (docs/gallery.md): the paper's intrinsic figures at 768x576
# with 16 samples per pixel, and the projections. Each line below is the
# command of one image; the lattice views, whose far copies do not compress,
# are made as PNG and stored as JPEG (quality 85, oiiotool) to stay under 300 KB.
#   docs/gallery/make_gallery.sh [BUILD_DIR]      (default build/ci; from the repository root)
set -euo pipefail
r=${1:-build/ci}/viewer/solrender
g=docs/gallery
a=(--width 768 --height 576 --spp 16)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
jpeg() {  # solrender's arguments with -o NAME.jpg last: rendered to PNG, stored as JPEG quality 85
  local out=${*: -1}
  "$r" "${@:1:$#-2}" -o "$tmp/x.png"
  oiiotool "$tmp/x.png" --ch R,G,B --compression jpeg:85 -o "$out"
}
$r --scene plane --position 0,0,0.5 "${a[@]}" -o $g/plane-h0.5.png
$r --scene plane --position 0,0,1.5 "${a[@]}" -o $g/plane-h1.5.png
$r --scene plane --position 0,0,3 "${a[@]}" -o $g/plane-h3.png
$r --scene plane --position 0,0,0.3 --forward 1,1,0 --up 0,0,1 "${a[@]}" -o $g/walk-above.png
$r --scene plane --position 0,0,0.02 --forward 1,1,0 --up 0,0,1 "${a[@]}" -o $g/walk-at.png
$r --scene plane --position 0,0,-0.3 --forward 1,1,0 --up 0,0,1 "${a[@]}" -o $g/walk-below.png
$r --scene $g/through-the-plane.json "${a[@]}" -o $g/through-the-plane.png
$r --scene sandwich --forward 1,0,0 "${a[@]}" -o $g/sandwich-x.png
$r --scene sandwich --forward 0,1,0 "${a[@]}" -o $g/sandwich-y.png
$r --scene sandwich "${a[@]}" -o $g/sandwich.png
jpeg --scene lattice-balls "${a[@]}" -o $g/lattice-balls-z.jpg
jpeg --scene lattice-balls --forward 1,0,0 --up 0,0,1 "${a[@]}" -o $g/lattice-balls-x.jpg
jpeg --scene lattice-balls --forward 1,1,0 --up 0,0,1 "${a[@]}" -o $g/lattice-balls-xy.jpg
jpeg --scene lattice-pillars --forward 0,0,-1 --up 0,1,0 "${a[@]}" -o $g/lattice-pillars-z.jpg
jpeg --scene lattice-pillars --forward 1,0,0 --up 0,0,1 "${a[@]}" -o $g/lattice-pillars-x.jpg
jpeg --scene lattice-pillars "${a[@]}" -o $g/lattice-pillars-xy.jpg
jpeg --scene lattice-balls --projection equirectangular --width 1024 --height 512 --spp 16 -o $g/lattice-balls-panorama.jpg
$r --scene sandwich --projection fisheye --fisheye-fov 180 --width 576 --height 576 --spp 16 -o $g/sandwich-dome.png
# Light (docs/lighting.md): the geodesic falloff beside the inverse-square law, and their ratio
# (1 + L²)/J as a map (inferno, 0 to 4: dark where the geodesics spread, bright where they focus).
for name in light-sandwich light-spheres; do
  $r --scene $g/$name.json "${a[@]}" -o $tmp/geodesic.exr
  $r --scene $g/$name-inverse-square.json "${a[@]}" -o $tmp/inverse-square.exr
  oiiotool $tmp/geodesic.exr --ch R,G,B -o $g/$name.png
  oiiotool $tmp/inverse-square.exr --ch R,G,B -o $g/$name-inverse-square.png
  oiiotool $tmp/geodesic.exr $tmp/inverse-square.exr --div --ch R --clamp:min=0:max=4 --mulc 0.25 --colormap inferno \
    -o $g/$name-ratio.png
done
ls -l $g | awk '$5 > 300000 {print "make_gallery: " $9 " is over 300 KB: " $5 " bytes"; bad = 1} END {exit bad}'
