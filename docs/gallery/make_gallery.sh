#!/usr/bin/env bash
# The gallery (docs/gallery.md): the paper's intrinsic figures at 768x576
# with 16 samples per pixel, and the projections. Each line below is the
# command of one image; the lattice views, whose far copies do not compress,
# are made as PNG and stored as JPEG (quality 85, oiiotool) to stay under 300 KB.
#   docs/gallery/make_gallery.sh OUT_DIR [BUILD_DIR]   (from the repository root; BUILD_DIR default
#   build/release, the README's; docs/gallery as OUT_DIR replaces the pictures the docs show)
set -euo pipefail
if [ $# -lt 1 ]; then echo "usage: docs/gallery/make_gallery.sh OUT_DIR [BUILD_DIR]" >&2; exit 2; fi
g=$1
r=${2:-build/release}/viewer/solrender
s=docs/gallery  # the scene files the pictures are made of
mkdir -p "$g"
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
$r --scene $s/through-the-plane.json "${a[@]}" -o $g/through-the-plane.png
$r --scene sandwich --forward 1,0,0 "${a[@]}" -o $g/sandwich-x.png
$r --scene sandwich --forward 0,1,0 "${a[@]}" -o $g/sandwich-y.png
$r --scene sandwich "${a[@]}" -o $g/sandwich.png
jpeg --scene lattice-balls "${a[@]}" -o $g/lattice-balls-z.jpg
jpeg --scene lattice-balls --forward 1,0,0 --up 0,0,1 "${a[@]}" -o $g/lattice-balls-x.jpg
jpeg --scene lattice-balls --forward 1,1,0 --up 0,0,1 "${a[@]}" -o $g/lattice-balls-xy.jpg
jpeg --scene lattice-pillars --forward 0,0,-1 --up 0,1,0 "${a[@]}" -o $g/lattice-pillars-z.jpg
jpeg --scene lattice-pillars --forward 1,0,0 --up 0,0,1 "${a[@]}" -o $g/lattice-pillars-x.jpg
jpeg --scene lattice-pillars "${a[@]}" -o $g/lattice-pillars-xy.jpg
jpeg --scene trace4-balls "${a[@]}" -o $g/trace4-balls-z.jpg
jpeg --scene trace4-balls --forward 1,1,0 --up 0,0,1 "${a[@]}" -o $g/trace4-balls-xy.jpg
jpeg --scene trace4-pillars --forward 0,0,-1 --up 0,1,0 "${a[@]}" -o $g/trace4-pillars-z.jpg
jpeg --scene trace4-pillars "${a[@]}" -o $g/trace4-pillars-xy.jpg
jpeg --scene halfturn-balls "${a[@]}" -o $g/halfturn-balls-z.jpg
jpeg --scene $s/golden-two-balls.json "${a[@]}" -o $g/golden-two-balls-z.jpg
jpeg --scene $s/z-loop.json "${a[@]}" -o $g/z-loop.jpg
jpeg --scene $s/xy-loops.json "${a[@]}" -o $g/xy-loops.jpg
jpeg --scene $s/mirror-balls.json "${a[@]}" -o $g/mirror-balls.jpg
jpeg --scene $s/composites.json "${a[@]}" -o $g/composites.jpg
# Glass, glossy and a lens (scene-format.md): 32 samples, for the glossy lobe and the lens's blur.
jpeg --scene $s/lens-glass.json --width 768 --height 576 --spp 32 -o $g/lens-glass.jpg
jpeg --scene $s/globe-cut-locus.json --width 768 --height 576 --spp 4 -o $g/globe-cut-locus.jpg
jpeg --scene $s/golden-glass.json --width 768 --height 576 --spp 16 -o $g/golden-glass.jpg
jpeg --scene $s/lit-room.json --width 768 --height 576 --transport path --spp 4 --denoise -o $g/lit-room.jpg
# Path traced (docs/lighting.md, "Path tracing"; on the kernel where there is one): 64 paths a pixel.
p=(--transport path --spp 64 --width 768 --height 576)
jpeg --scene $s/glowing-sandwich.json "${p[@]}" -o $g/glowing-sandwich.jpg
jpeg --scene $s/glowing-lattice-balls.json "${p[@]}" -o $g/glowing-lattice-balls.jpg
jpeg --scene lattice-balls --projection equirectangular --width 1024 --height 512 --spp 16 -o $g/lattice-balls-panorama.jpg
$r --scene sandwich --projection fisheye --fisheye-fov 180 --width 576 --height 576 --spp 16 -o $g/sandwich-dome.png
# Light (docs/lighting.md): the geodesic falloff beside the inverse-square law. For the sandwich lit
# from the eye (no ambient light, one light: the images' ratio is (1 + L²)/J), the map of L²/J from that
# ratio and the AOV distance L, at 384x288 (inferno, 0 to 2: 1, the Euclidean spreading, is red;
# brighter where the geodesics focus, darker where they spread).
for name in light-sandwich light-spheres; do
  $r --scene $s/$name.json "${a[@]}" -o $g/$name.png
  $r --scene $s/$name-inverse-square.json "${a[@]}" -o $g/$name-inverse-square.png
done
$r --scene $s/light-sandwich.json --width 384 --height 288 -o $tmp/geodesic.exr --aov $tmp/aov.exr
$r --scene $s/light-sandwich-inverse-square.json --width 384 --height 288 -o $tmp/inverse-square.exr
oiiotool $tmp/aov.exr --ch distance --dup --mul -o $tmp/l2.exr
oiiotool $tmp/l2.exr --addc 1 -o $tmp/l2p1.exr
oiiotool $tmp/geodesic.exr --ch R $tmp/inverse-square.exr --ch R --div $tmp/l2.exr --mul $tmp/l2p1.exr --div \
  --mulc 0.5 --clamp:min=0:max=1 --colormap inferno -o $g/light-sandwich-focus.png
ls -l $g | awk '$5 > 300000 {print "make_gallery: " $9 " is over 300 KB: " $5 " bytes"; bad = 1} END {exit bad}'
