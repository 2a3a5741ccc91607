#!/usr/bin/env python3
"""Draws globe.png, the gallery's equirectangular test texture (512 x 256): a blue sea, land of a fixed smooth
pattern, a yellow equator, a red prime meridian and grey graticule every 30 degrees, and a white cap on the north pole
only, so that which way a textured ball faces can be read from any image of it. Needs Pillow.

usage: make_globe.py OUT.png"""
import math
import sys

from PIL import Image


def land(lon, lat):
    # A few fixed lumps on the sphere (sums of smooth bumps): "continents".
    value = 0.0
    for (clon, clat, size) in [(0.3, 0.5, 0.6), (1.9, 0.2, 0.5), (-1.2, -0.4, 0.7), (2.8, -0.7, 0.4), (-2.4, 0.9, 0.35)]:
        # the angle between (lon, lat) and the lump's centre
        cos_angle = math.sin(lat) * math.sin(clat) + math.cos(lat) * math.cos(clat) * math.cos(lon - clon)
        value += math.exp((cos_angle - 1.0) / (size * size * 0.6))
    return value > 0.5


def main():
    if len(sys.argv) != 2:
        print(__doc__, file=sys.stderr)
        return 2
    w, h = 512, 256
    image = Image.new("RGB", (w, h))
    pixels = image.load()
    for j in range(h):
        lat = math.pi * (0.5 - (j + 0.5) / h)
        for i in range(w):
            lon = 2.0 * math.pi * ((i + 0.5) / w - 0.5)
            colour = (60, 150, 70) if land(lon, lat) else (30, 70, 170)
            if lat > math.radians(70):
                colour = (240, 240, 240)
            degrees_lon, degrees_lat = math.degrees(lon), math.degrees(lat)
            if abs(degrees_lon % 30.0) < 0.8 or abs(degrees_lat % 30.0) < 0.8:
                colour = (150, 150, 150)
            if abs(degrees_lat) < 1.2:
                colour = (240, 210, 40)
            if abs(degrees_lon) < 1.2:
                colour = (220, 40, 40)
            pixels[i, j] = colour
    image.save(sys.argv[1], optimize=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
