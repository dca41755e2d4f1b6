#!/usr/bin/env python3
"""Generates every texture the example scenes use (standard library only).

    python3 scenes/textures/make_textures.py [OUTPUT_FOLDER]

The output is deterministic: the same PNG bytes on every run and machine, so
the committed files can be checked against a fresh run. Colours are written
as 8-bit sRGB (the scene format decodes them with the sRGB curve unless a
texture says "srgb": false).
"""

import math
import os
import struct
import sys
import zlib

# ---------------------------------------------------------------- PNG output


def write_png(path, width, height, channels, pixel):
    """pixel(x, y) -> tuple of `channels` floats in [0, 1] (already encoded)."""
    color_type = {3: 2, 4: 6}[channels]
    rows = bytearray()
    for y in range(height):
        rows.append(0)  # filter: none
        for x in range(width):
            for value in pixel(x, y):
                rows.append(max(0, min(255, int(round(value * 255.0)))))

    def chunk(tag, data):
        body = tag + data
        return struct.pack(">I", len(data)) + body + struct.pack(">I", zlib.crc32(body) & 0xFFFFFFFF)

    header = struct.pack(">IIBBBBB", width, height, 8, color_type, 0, 0, 0)
    data = (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", header) +
            chunk(b"IDAT", zlib.compress(bytes(rows), 9)) + chunk(b"IEND", b""))
    with open(path, "wb") as f:
        f.write(data)


# ------------------------------------------------------------------- helpers


def linear_to_srgb(v):
    v = max(0.0, min(1.0, v))
    return 12.92 * v if v <= 0.0031308 else 1.055 * v ** (1.0 / 2.4) - 0.055


def encode(rgb):
    return tuple(linear_to_srgb(c) for c in rgb)


def mix(a, b, t):
    return tuple(x + (y - x) * t for x, y in zip(a, b))


def smoothstep(e0, e1, x):
    t = max(0.0, min(1.0, (x - e0) / (e1 - e0)))
    return t * t * (3.0 - 2.0 * t)


def lattice(ix, iy, iz, seed):
    """Deterministic hash of a lattice point to [0, 1)."""
    h = (ix * 374761393 + iy * 668265263 + iz * 1274126177 + seed * 2246822519) & 0xFFFFFFFF
    h = ((h ^ (h >> 13)) * 1274126177) & 0xFFFFFFFF
    return ((h ^ (h >> 16)) & 0xFFFFFF) / float(0x1000000)


def value_noise(x, y, z, seed, period=None):
    """Trilinear value noise; `period` (x, y) makes it tile in x and y."""
    ix, iy, iz = math.floor(x), math.floor(y), math.floor(z)
    fx, fy, fz = x - ix, y - iy, z - iz
    sx, sy, sz = (f * f * (3 - 2 * f) for f in (fx, fy, fz))

    def at(dx, dy, dz):
        px, py = ix + dx, iy + dy
        if period:
            px, py = px % period[0], py % period[1]
        return lattice(px, py, iz + dz, seed)

    def lerp(a, b, t):
        return a + (b - a) * t

    x00 = lerp(at(0, 0, 0), at(1, 0, 0), sx)
    x10 = lerp(at(0, 1, 0), at(1, 1, 0), sx)
    x01 = lerp(at(0, 0, 1), at(1, 0, 1), sx)
    x11 = lerp(at(0, 1, 1), at(1, 1, 1), sx)
    return lerp(lerp(x00, x10, sy), lerp(x01, x11, sy), sz)


def fbm(x, y, z, seed, octaves=5, period=None):
    total, amplitude, norm = 0.0, 1.0, 0.0
    for o in range(octaves):
        scale = 2 ** o
        p = (period[0] * scale, period[1] * scale) if period else None
        total += amplitude * value_noise(x * scale, y * scale, z * scale, seed + o, p)
        norm += amplitude
        amplitude *= 0.5
    return total / norm


# ------------------------------------------------------------------ textures


def checker(x, y, size=64, cells=8):
    cell = size // cells
    light = ((x // cell) + (y // cell)) % 2 == 0
    return encode((0.78, 0.78, 0.74) if light else (0.10, 0.10, 0.12))


def planet(x, y, width=256, height=128):
    """Equirectangular planet: oceans, continents, deserts, ice caps."""
    u, v = (x + 0.5) / width, (y + 0.5) / height
    lon, lat = (u - 0.5) * 2 * math.pi, (0.5 - v) * math.pi
    # Sample the noise on the unit sphere so the map has no seam at u = 0/1.
    px, py, pz = math.cos(lat) * math.cos(lon), math.sin(lat), math.cos(lat) * math.sin(lon)
    h = fbm(px * 2.2 + 5, py * 2.2 + 5, pz * 2.2 + 5, seed=11, octaves=6)
    moisture = fbm(px * 3 + 17, py * 3 + 17, pz * 3 + 17, seed=29, octaves=3)
    sea_level = 0.55
    if h < sea_level:
        depth = smoothstep(0.30, sea_level, h)
        color = mix((0.01, 0.03, 0.16), (0.03, 0.16, 0.38), depth)
    else:
        land = smoothstep(sea_level, 0.75, h)
        green = mix((0.06, 0.20, 0.04), (0.22, 0.24, 0.10), land)
        desert = (0.50, 0.38, 0.18)
        color = mix(desert, green, smoothstep(0.25, 0.5, moisture))
    ice = smoothstep(0.88, 0.96, abs(py) + 0.08 * (h - 0.5))
    color = mix(color, (0.85, 0.88, 0.92), ice)
    return encode(color)


def marble(x, y, size=128):
    """Tileable veined marble."""
    u, v = x / size, y / size
    turbulence = fbm(u * 4, v * 4, 0.5, seed=41, octaves=5, period=(4, 4))
    vein = abs(math.sin(2 * math.pi * (u * 2 + v) + 9.0 * turbulence))
    vein = vein ** 0.35
    base = mix((0.10, 0.09, 0.08), (0.80, 0.78, 0.74), vein)
    tint = fbm(u * 2, v * 2, 3.5, seed=53, octaves=3, period=(2, 2))
    return encode(mix(base, (base[0] * 0.9, base[1] * 0.95, base[2] * 1.05), tint))


def perforated(x, y, size=128, holes=4):
    """Orange sheet with round holes (alpha 0) ringed by a half-transparent band."""
    cell = size / holes
    cx, cy = (x + 0.5) % cell - cell / 2, (y + 0.5) % cell - cell / 2
    r = math.hypot(cx, cy) / (cell / 2)
    if r < 0.55:
        alpha = 0.0
    elif r < 0.75:
        alpha = 0.5
    else:
        alpha = 1.0
    shade = 0.75 + 0.25 * fbm(x / 16, y / 16, 0.0, seed=61, octaves=3, period=(size // 16, size // 16))
    return encode((0.95 * shade, 0.45 * shade, 0.08 * shade)) + (alpha,)


# A 5x7 font for the skybox face labels.
GLYPHS = {
    "+": ["00000", "00100", "00100", "11111", "00100", "00100", "00000"],
    "-": ["00000", "00000", "00000", "11111", "00000", "00000", "00000"],
    "X": ["10001", "10001", "01010", "00100", "01010", "10001", "10001"],
    "Y": ["10001", "10001", "01010", "00100", "00100", "00100", "00100"],
    "Z": ["11111", "00001", "00010", "00100", "01000", "10000", "11111"],
}

# Face -> direction for texel (s, t) in [-1, 1]^2, inverting the cube-map table
# of the scene format (+x: sc = -dz, tc = -dy; and so on).
FACES = {
    "px": ("+X", lambda sc, tc: (1.0, -tc, -sc)),
    "nx": ("-X", lambda sc, tc: (-1.0, -tc, sc)),
    "py": ("+Y", lambda sc, tc: (sc, 1.0, tc)),
    "ny": ("-Y", lambda sc, tc: (sc, -1.0, -tc)),
    "pz": ("+Z", lambda sc, tc: (sc, -tc, 1.0)),
    "nz": ("-Z", lambda sc, tc: (-sc, -tc, -1.0)),
}

SUN = (0.55, 0.45, -0.70)  # direction toward the sun disc (normalized below)


def sky_radiance(d):
    n = math.sqrt(sum(c * c for c in d))
    dx, dy, dz = (c / n for c in d)
    if dy >= 0:
        zenith, horizon = (0.10, 0.22, 0.55), (0.62, 0.72, 0.85)
        color = mix(horizon, zenith, smoothstep(0.0, 0.7, dy) ** 0.8)
        clouds = fbm(dx / (dy + 0.15) * 1.5 + 7, dz / (dy + 0.15) * 1.5 + 7, 0.3, seed=71, octaves=5)
        color = mix(color, (0.85, 0.86, 0.88), smoothstep(0.55, 0.75, clouds) * smoothstep(0.02, 0.2, dy))
    else:
        ground_near, ground_far = (0.10, 0.09, 0.07), (0.35, 0.36, 0.34)
        color = mix(ground_far, ground_near, smoothstep(0.0, 0.3, -dy))
    s = [c / math.sqrt(sum(k * k for k in SUN)) for c in SUN]
    cos_sun = dx * s[0] + dy * s[1] + dz * s[2]
    glow = smoothstep(0.93, 1.0, cos_sun) ** 3
    return mix(color, (1.0, 0.93, 0.80), glow)


def label_mask(label, x, y, size, scale, centre):
    """1 inside the label's glyphs or its orientation mark, else 0.

    The label is centred on `centre` (pixels). A solid square above its first
    glyph's top-left corner marks the label's top-left: a swapped, mirrored or
    rotated face shows the mark in another corner (the glyphs alone are too
    symmetric: "X" looks the same upside down)."""
    width = (6 * len(label) - 1) * scale
    x0, y0 = centre[0] - width // 2, centre[1] - 7 * scale // 2
    if x0 <= x < x0 + 2 * scale and y0 - 3 * scale <= y < y0 - scale:
        return 1
    gx, gy = (x - x0) // scale, (y - y0) // scale
    if not (0 <= gy < 7 and 0 <= gx < 6 * len(label)):
        return 0
    glyph, column = GLYPHS[label[gx // 6]], gx % 6
    return 1 if column < 5 and glyph[gy][column] == "1" else 0


def sky_face(face, size=128):
    label, direction = FACES[face]
    # Side faces carry their label below the horizon (t = 0.75), where a
    # scene's floor hides it; the top and bottom faces in their centre.
    centre = (size // 2, size // 2 if face in ("py", "ny") else 3 * size // 4)

    def pixel(x, y):
        sc, tc = 2 * (x + 0.5) / size - 1, 2 * (y + 0.5) / size - 1
        color = sky_radiance(direction(sc, tc))
        # Seen from inside the cube the table mirrors each face left-right, so
        # the label is drawn mirrored in the file and reads correctly rendered.
        if label_mask(label, size - 1 - x, y, size, 2, centre):
            bright = 0.2126 * color[0] + 0.7152 * color[1] + 0.0722 * color[2] > 0.4
            color = mix(color, (0.05, 0.1, 0.3) if bright else (1.0, 1.0, 1.0), 0.35)
        return encode(color)

    return pixel


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else os.path.dirname(os.path.abspath(__file__))
    os.makedirs(out, exist_ok=True)
    jobs = [
        ("checker.png", 64, 64, 3, checker),
        ("planet.png", 256, 128, 3, planet),
        ("marble.png", 128, 128, 3, marble),
        ("perforated.png", 128, 128, 4, perforated),
    ]
    jobs += [("sky_%s.png" % face, 128, 128, 3, sky_face(face)) for face in FACES]
    for name, width, height, channels, pixel in jobs:
        write_png(os.path.join(out, name), width, height, channels, pixel)
        print("wrote", os.path.join(out, name))


if __name__ == "__main__":
    main()
