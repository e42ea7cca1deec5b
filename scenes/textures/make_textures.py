#!/usr/bin/env python3
"""Writes the example scenes' textures (scenes/earth.json), so that they are reproducible
and need no download: earth.png, an equirectangular map of an invented planet (oceans,
land by height, ice caps) from 3-D value noise sampled on the sphere (so the map has no
seam at longitude 180 and no pinch at the poles), tiles.png, a floor of tiles, and uv_grid.png, the (u, v) convention's test card.
Pure Python (zlib for the PNG). Usage: make_textures.py [FOLDER]"""
import math
import os
import struct
import sys
import zlib


def write_png(path, width, height, rows):
    """rows: height lists of width (r, g, b) tuples, 0..255, row 0 the top."""
    raw = b"".join(b"\x00" + bytes(c for px in row for c in px) for row in rows)

    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)

    png = b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0))
    png += chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b"")
    with open(path, "wb") as f:
        f.write(png)


def lattice(x, y, z, seed):
    h = (x * 73856093) ^ (y * 19349663) ^ (z * 83492791) ^ (seed * 2654435761)
    h = (h ^ (h >> 13)) * 1274126177 & 0xFFFFFFFF
    return (h ^ (h >> 16)) / 4294967295.0


def value_noise(x, y, z, seed):
    xi, yi, zi = math.floor(x), math.floor(y), math.floor(z)
    fx, fy, fz = x - xi, y - yi, z - zi
    sx, sy, sz = fx * fx * (3 - 2 * fx), fy * fy * (3 - 2 * fy), fz * fz * (3 - 2 * fz)
    v = 0.0
    for dx in (0, 1):
        for dy in (0, 1):
            for dz in (0, 1):
                w = (sx if dx else 1 - sx) * (sy if dy else 1 - sy) * (sz if dz else 1 - sz)
                v += w * lattice(xi + dx, yi + dy, zi + dz, seed)
    return v


def fbm(p, seed, octaves=6):
    total, amp, freq, norm = 0.0, 1.0, 1.5, 0.0
    for o in range(octaves):
        total += amp * value_noise(p[0] * freq, p[1] * freq, p[2] * freq, seed + o)
        norm += amp
        amp *= 0.5
        freq *= 2.0
    return total / norm


def mix(a, b, t):
    return tuple(x + (y - x) * t for x, y in zip(a, b))


# 256 x 128: 32,768 texels, so that the example scenes fit the Vulkan minimum device's
# 65,536 texels a buffer (tests/portability/test_minimum_device.sh).
def earth(width=256, height=128):
    rows = []
    for j in range(height):
        lat = math.pi * (0.5 - (j + 0.5) / height)  # row 0 the north pole (v = 1, +y)
        row = []
        for i in range(width):
            # The scene format's convention: u = 1/2 + atan2(x, z) / 2 pi.
            lon = 2 * math.pi * ((i + 0.5) / width - 0.5)
            p = (math.cos(lat) * math.sin(lon), math.sin(lat), math.cos(lat) * math.cos(lon))
            h = fbm(p, 7)
            ice = abs(lat) > math.radians(68) + 0.25 * (fbm(p, 31, 3) - 0.5)
            if ice:
                c = (235, 240, 245)
            elif h < 0.52:
                c = mix((8, 24, 82), (30, 90, 160), max(0.0, (h - 0.3) / 0.22))
            else:
                dry = fbm(p, 19, 4)
                land = mix((40, 110, 40), (150, 120, 70), min(1.0, max(0.0, (dry - 0.35) * 2.5)))
                c = mix(land, (120, 110, 100), min(1.0, max(0.0, (h - 0.66) * 5)))
            row.append(tuple(int(round(min(255, max(0, x)))) for x in c))
        rows.append(row)
    return width, height, rows


def tiles(size=64, tile=32, grout=2):
    rows = []
    for j in range(size):
        row = []
        for i in range(size):
            if i % tile < grout or j % tile < grout:
                row.append((70, 66, 60))
            else:
                dark = ((i // tile) + (j // tile)) % 2
                row.append((180, 170, 150) if dark else (225, 220, 205))
        rows.append(row)
    return size, size, rows


def uv_grid(width=256, height=128):
    """The convention's picture (docs/images/uv_sphere.png): red grows with u, green with v
    (row 0 is v = 1), lines every 1/8, and a white disc at (u, v) = (0.5, 0.5)."""
    rows = []
    for j in range(height):
        v = 1 - (j + 0.5) / height
        row = []
        for i in range(width):
            u = (i + 0.5) / width
            line = (i % (width // 8) == 0) or (j % (height // 8) == 0)
            marker = (u - 0.5) ** 2 * 4 + (v - 0.5) ** 2 < 0.0025
            row.append((255, 255, 255) if marker else (20, 20, 20) if line else (int(255 * u), int(255 * v), 60))
        rows.append(row)
    return width, height, rows


def main():
    folder = sys.argv[1] if len(sys.argv) > 1 else os.path.dirname(os.path.abspath(__file__))
    write_png(os.path.join(folder, "earth.png"), *earth())
    write_png(os.path.join(folder, "tiles.png"), *tiles())
    write_png(os.path.join(folder, "uv_grid.png"), *uv_grid())


if __name__ == "__main__":
    main()
