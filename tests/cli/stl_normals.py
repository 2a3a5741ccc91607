"""solshape's binary STL: every facet's stored normal is its own, the unit
cross product of its edges in the order of its vertices, and the facets'
order makes the closed surface face outwards (its signed volume, the sum of
a . (b x c) / 6 over the facets, is positive). Slicers may trust the stored
normals; Assimp once wrote means of smoothed vertex normals, up to 167
degrees off.
  stl_normals.py SOLSHAPE WORK_DIR
"""
import math
import os
import struct
import subprocess
import sys

solshape, work = sys.argv[1], sys.argv[2]
os.makedirs(work, exist_ok=True)
worst_angle, facets, inside_out = 0.0, 0, []
for radius in (1.0, 5.0):
    path = os.path.join(work, "normals-%g.stl" % radius)
    subprocess.run([solshape, "sphere", "--radius", str(radius), "--resolution", "32", "-o", path], check=True,
                   stderr=subprocess.DEVNULL)
    data = open(path, "rb").read()
    count = struct.unpack("<I", data[80:84])[0]
    assert len(data) == 84 + 50 * count, "not a binary STL of %d facets" % count
    volume = 0.0
    for i in range(count):
        f = struct.unpack("<12fH", data[84 + 50 * i:84 + 50 * (i + 1)])
        n, a, b, c = f[0:3], f[3:6], f[6:9], f[9:12]
        volume += (a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) +
                   a[2] * (b[0] * c[1] - b[1] * c[0])) / 6.0
        u = [b[k] - a[k] for k in range(3)]
        v = [c[k] - a[k] for k in range(3)]
        cross = [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]]
        length = math.sqrt(sum(x * x for x in cross))
        if length == 0.0:
            continue  # a degenerate facet has no normal to check
        expected = [x / length for x in cross]
        dot = max(-1.0, min(1.0, sum(n[k] * expected[k] for k in range(3))))
        worst_angle = max(worst_angle, math.degrees(math.acos(dot)))
        facets += 1
    if not volume > 0.0:
        inside_out.append(radius)
print("%d facets: worst angle between a stored normal and its facet's %.4f degrees; inside out at radii %s"
      % (facets, worst_angle, inside_out))
# Within 0.1 degrees (measured 0.023, at the smallest facets of radius 5,
# whose edges are a few float roundings of their vertices long): a slicer
# needs the side, and 167 degrees was the defect.
if worst_angle > 0.1 or inside_out:
    sys.exit(1)
