#!/usr/bin/env python3
"""Writes the fuzz seeds of Testing/Fuzz/Seeds (checked in; rerun only to
change them). Small valid inputs that reach each reader's main paths:
PLY (ASCII, both binary byte orders, lists, comments, extra elements), PNG
(every colour type, 1/2/4/8/16 bits, palette with tRNS, Adam7, all five
filters), parser texts and mrgi-render command lines. EXR seeds come from
the core's own writer: make_exr_seeds.c (see its header).

Usage: Testing/Fuzz/make_seeds.py   (from anywhere)"""
import os
import struct
import zlib

HERE = os.path.dirname(os.path.abspath(__file__))


def put(kind, name, data):
    folder = os.path.join(HERE, "Seeds", kind)
    os.makedirs(folder, exist_ok=True)
    with open(os.path.join(folder, name), "wb") as f:
        f.write(data if isinstance(data, bytes) else data.encode())


# ---- PLY ------------------------------------------------------------------
CUBE_V = [(x, y, z) for x in (0, 1) for y in (0, 1) for z in (0, 1)]
CUBE_F = [(0, 1, 3, 2), (4, 6, 7, 5), (0, 4, 5, 1), (2, 3, 7, 6), (0, 2, 6, 4), (1, 5, 7, 3)]


def ply_ascii():
    head = ("ply\nformat ascii 1.0\ncomment a unit cube\nobj_info fuzz seed\n"
            "element vertex 8\nproperty float x\nproperty float y\nproperty float z\n"
            "element face 6\nproperty list uchar int vertex_indices\nend_header\n")
    body = "".join("%g %g %g\n" % v for v in CUBE_V)
    body += "".join("4 %d %d %d %d\n" % f for f in CUBE_F)
    return head + body


def ply_binary(order):
    fmt = "binary_little_endian" if order == "<" else "binary_big_endian"
    head = ("ply\r\nformat %s 1.0\r\nelement vertex 4\r\nproperty double x\r\nproperty double y\r\n"
            "property double z\r\nproperty uchar red\r\nproperty uchar green\r\nproperty uchar blue\r\n"
            "element face 4\r\nproperty list uint8 int32 vertex_indices\r\n"
            "element edge 1\r\nproperty int vertex1\r\nproperty int vertex2\r\nend_header\r\n" % fmt)
    body = b""
    for i, v in enumerate([(0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, 1)]):
        body += struct.pack(order + "dddBBB", *v, 60 * i, 255 - 60 * i, 128)
    for f in [(0, 2, 1), (0, 1, 3), (0, 3, 2), (1, 2, 3)]:
        body += struct.pack(order + "Biii", 3, *f)
    body += struct.pack(order + "ii", 0, 1)
    return head.encode() + body


def ply_points():
    head = ("ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float32 x\n"
            "property float32 y\nproperty float32 z\nproperty float32 nx\nproperty ushort flags\n"
            "end_header\n")
    body = b"".join(struct.pack("<ffffH", i, 2 * i, 3 * i, 1.0, i) for i in range(3))
    return head.encode() + body


put("PLYCheck", "cube-ascii.ply", ply_ascii())
put("PLYCheck", "tetra-le.ply", ply_binary("<"))
put("PLYCheck", "tetra-be.ply", ply_binary(">"))
put("PLYCheck", "points.ply", ply_points())

# ---- PNG ------------------------------------------------------------------


def chunk(kind, data):
    return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))


def paeth(a, b, c):
    p = a + b - c
    pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
    return a if pa <= pb and pa <= pc else (b if pb <= pc else c)


def filter_rows(rows, bpp, filters):
    """Rows of raw bytes -> filtered scanlines, filter type per row from `filters`."""
    out, prev = b"", None
    for y, row in enumerate(rows):
        ftype = filters[y % len(filters)]
        up = prev if prev is not None else bytes(len(row))
        enc = bytearray()
        for i, x in enumerate(row):
            a = row[i - bpp] if i >= bpp else 0
            b = up[i]
            c = up[i - bpp] if i >= bpp else 0
            pred = [0, a, b, (a + b) // 2, paeth(a, b, c)][ftype]
            enc.append((x - pred) & 0xFF)
        out += bytes([ftype]) + bytes(enc)
        prev = row
    return out


def pack_row(samples, depth):
    if depth >= 8:
        return b"".join(s.to_bytes(depth // 8, "big") for s in samples)
    bits, out = "", bytearray()
    for s in samples:
        bits += format(s, "0%db" % depth)
    bits += "0" * (-len(bits) % 8)
    return bytes(int(bits[i:i + 8], 2) for i in range(0, len(bits), 8))


def png(width, height, color_type, depth, pixel, filters=(0,), interlace=0, extra=b""):
    """pixel(x, y) -> tuple of samples for the colour type."""
    channels = {0: 1, 2: 3, 3: 1, 4: 2, 6: 4}[color_type]
    bpp = max(1, channels * depth // 8)
    if interlace:
        passes = [(0, 0, 8, 8), (4, 0, 8, 8), (0, 4, 4, 8), (2, 0, 4, 4), (0, 2, 2, 4), (1, 0, 2, 2),
                  (0, 1, 1, 2)]
    else:
        passes = [(0, 0, 1, 1)]
    raw = b""
    for x0, y0, dx, dy in passes:
        xs, ys = range(x0, width, dx), range(y0, height, dy)
        if not xs or not ys:
            continue
        rows = [pack_row([s for x in xs for s in pixel(x, y)], depth) for y in ys]
        raw += filter_rows(rows, bpp, filters)
    ihdr = struct.pack(">IIBBBBB", width, height, depth, color_type, 0, 0, interlace)
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", ihdr) + extra + chunk(b"IDAT", zlib.compress(raw, 9))
            + chunk(b"IEND", b""))


put("PNG", "gray8.png", png(4, 4, 0, 8, lambda x, y: (x * 60 + y,)))
put("PNG", "gray1.png", png(9, 2, 0, 1, lambda x, y: ((x + y) & 1,)))
put("PNG", "gray2.png", png(5, 2, 0, 2, lambda x, y: ((x + y) % 4,)))
put("PNG", "gray4-trns.png", png(3, 3, 0, 4, lambda x, y: ((x * 5 + y) % 16,),
                                 extra=chunk(b"tRNS", b"\x00\x05")))
put("PNG", "gray16.png", png(2, 2, 0, 16, lambda x, y: (x * 30000 + y * 1000,)))
put("PNG", "graya8.png", png(3, 2, 4, 8, lambda x, y: (x * 80, 255 - y * 100)))
put("PNG", "rgb8-filters.png", png(5, 5, 2, 8, lambda x, y: (x * 50, y * 50, (x * y) % 256),
                                   filters=(0, 1, 2, 3, 4)))
put("PNG", "rgb16.png", png(2, 3, 2, 16, lambda x, y: (x * 20000, y * 20000, 65535)))
put("PNG", "rgba8-adam7.png", png(9, 9, 6, 8, lambda x, y: (x * 28, y * 28, 100, 200), interlace=1))
put("PNG", "palette-trns.png", png(4, 2, 3, 2, lambda x, y: ((x + y) % 3,),
                                   extra=chunk(b"PLTE", b"\xff\x00\x00\x00\xff\x00\x00\x00\xff")
                                   + chunk(b"tRNS", b"\x80\xff")))
put("PNG", "rgba16.png", png(2, 2, 6, 16, lambda x, y: (x * 60000, 1000, y * 60000, 40000),
                             filters=(4,)))

# ---- Parser texts: first byte picks the parser (see FuzzParse.c) ------------
for i, (sel, text) in enumerate([(0, "0.25"), (0, "-1.5e-3"), (0, "+12345678901234567890"),
                                 (0, "4.9406564584124654e-324"), (1, "42"), (5, "-3"),
                                 (9, "16384"), (1, "-9223372036854775808"), (2, "512x384"),
                                 (2, "1X16384"), (3, "1, 2, 3"), (3, "-0.5,\t1e2 ,3.")]):
    put("Parse", "text-%02d" % i, bytes([sel]) + text.encode())

# ---- mrgi-render command lines: NUL-separated argv (see FuzzRenderOptions.cxx)
for i, argv in enumerate([
        ["cornell", "-o", "out.png", "--size", "64x48"],
        ["cornell-area", "-o", "a.exr", "--half", "--area-light-samples", "16",
         "--area-light-visibility", "naive", "--voxel-size", "64", "--specular", "0.5:40"],
        ["cornell-spot", "-o", "b.png", "--light", "spot:1,2,3:0,0,0:30", "--light",
         "directional:0,-1,0", "--light", "positional:0,5,0", "--light", "headlight",
         "--light-intensity", "2"],
        ["cornell", "--timings", "--area-light", "278,540,280:100,0,0:0,0,-80:1,1,1:5",
         "--area-light-two-sided", "--camera-position", "0,0,5", "--camera-focal-point", "0,0,0"],
        ["scaling", "--triangles", "5000", "--objects", "4", "--seed", "7", "-o", "s.png",
         "--gi", "multires", "--depth-threshold", "8", "--normal-threshold", "inf", "--upsample",
         "mask", "--gather", "splat", "--finest-level", "2"],
        ["living-room", "-o", "r.exr", "--vpls", "64", "--rsm-size", "64", "--vpl-selection",
         "importance", "--indirect-strength", "0.5", "--tone-mapping", "--reference",
         "--reference-passes", "2", "--reference-error", "0"],
        ["--help"],
        ["--version"],
        ["cornell", "-o", "x.png", "--size", "0x64"],
        ["cornell-spot", "-o", "t.exr", "--rsm-size", "64", "--vpl-selection", "tree",
         "--tree-threshold", "0.02", "--timings"]]):
    put("RenderOptions", "argv-%02d" % i, "\0".join(argv))
print("seeds written under", os.path.join(HERE, "Seeds"))
