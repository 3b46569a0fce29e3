"""Converts Xvfb's screen file (XWD, from `Xvfb -fbdir DIR`) to a PNG.

    /usr/bin/python3 xwd_to_png.py SCREEN.xwd OUT.png [--crop] [--max-width W]

--crop keeps the smallest rectangle holding every non-black pixel (with no
window manager, the application's window on Xvfb's black root window);
--max-width scales the image down, averaging the pixels each output pixel
covers, so that it is at most W pixels wide. Only numpy and zlib: no
ImageMagick, no PIL. Reads the 24- and 32-bit TrueColor images Xvfb writes
(-screen 0 WxHx24); anything else is refused with a message.
"""
import argparse
import struct
import sys
import zlib

import numpy as np

XWD_HEADER = ">25I"  # 25 big-endian CARD32 fields (X11 XWDFileHeader)


def read_xwd(path):
    """Returns the image as an (height, width, 3) uint8 array."""
    with open(path, "rb") as f:
        data = f.read()
    if len(data) < 100:
        raise ValueError("%s: %d bytes, too short for an XWD header" % (path, len(data)))
    (header_size, version, pixmap_format, depth, width, height, _xoffset, byte_order, _unit,
     _bit_order, _pad, bits_per_pixel, bytes_per_line, visual_class, red_mask, green_mask,
     blue_mask, _bits_per_rgb, _colormap_entries, ncolors, *_rest) = struct.unpack(XWD_HEADER, data[:100])
    # 7: XWD file version; 2: ZPixmap; 4: TrueColor.
    if version != 7 or pixmap_format != 2 or visual_class != 4 or bits_per_pixel != 32:
        raise ValueError("%s: not a 32-bit TrueColor ZPixmap XWD (version %d, format %d, class %d, "
                         "%d bits per pixel)" % (path, version, pixmap_format, visual_class, bits_per_pixel))
    if (red_mask, green_mask, blue_mask) != (0xFF0000, 0xFF00, 0xFF):
        raise ValueError("%s: unexpected colour masks %#x %#x %#x" % (path, red_mask, green_mask, blue_mask))
    offset = header_size + ncolors * 12  # each XWDColor is 12 bytes
    if len(data) < offset + bytes_per_line * height or bytes_per_line < 4 * width:
        raise ValueError("%s: truncated (%dx%d, depth %d)" % (path, width, height, depth))
    rows = np.frombuffer(data, dtype=np.uint8, count=bytes_per_line * height, offset=offset)
    pixels = rows.reshape(height, bytes_per_line)[:, :4 * width].reshape(height, width, 4)
    # byte_order 0 (LSBFirst): B, G, R, unused; 1 (MSBFirst): unused, R, G, B.
    rgb = pixels[:, :, [2, 1, 0]] if byte_order == 0 else pixels[:, :, [1, 2, 3]]
    return np.ascontiguousarray(rgb)


def crop_to_content(image):
    """The smallest rectangle holding every non-black pixel."""
    lit = image.max(axis=2) > 0
    rows, cols = np.nonzero(lit.any(axis=1))[0], np.nonzero(lit.any(axis=0))[0]
    if rows.size == 0:
        raise ValueError("the screen is black: nothing to crop to")
    return image[rows[0]:rows[-1] + 1, cols[0]:cols[-1] + 1]


def box_weights(n_in, n_out):
    """(n_out, n_in) matrix averaging the input pixels each output pixel covers."""
    scale = n_in / n_out
    weights = np.zeros((n_out, n_in))
    for o in range(n_out):
        lo, hi = o * scale, (o + 1) * scale
        for i in range(int(lo), min(n_in, int(np.ceil(hi)))):
            weights[o, i] = min(hi, i + 1) - max(lo, i)
    return weights / weights.sum(axis=1, keepdims=True)


def shrink(image, max_width):
    height, width, _ = image.shape
    if width <= max_width:
        return image
    new_width, new_height = max_width, max(1, round(height * max_width / width))
    wy, wx = box_weights(height, new_height), box_weights(width, new_width)
    # Two matrix products (rows, then columns), not one einsum: numpy would
    # evaluate the three-operand form as one huge loop.
    rows = np.tensordot(wy, image.astype(np.float64), axes=(1, 0))  # (new_h, w, 3)
    out = np.tensordot(rows, wx, axes=(1, 1)).transpose(0, 2, 1)  # (new_h, new_w, 3)
    return np.clip(np.rint(out), 0, 255).astype(np.uint8)


def write_png(path, image):
    height, width, _ = image.shape
    raw = b"".join(b"\0" + image[y].tobytes() for y in range(height))  # filter 0 per row

    def chunk(kind, payload):
        return (struct.pack(">I", len(payload)) + kind + payload
                + struct.pack(">I", zlib.crc32(kind + payload) & 0xFFFFFFFF))

    with open(path, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n")
        f.write(chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0)))
        f.write(chunk(b"IDAT", zlib.compress(raw, 9)))
        f.write(chunk(b"IEND", b""))


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("xwd")
    parser.add_argument("png")
    parser.add_argument("--crop", action="store_true")
    parser.add_argument("--max-width", type=int, default=0)
    args = parser.parse_args()
    try:
        image = read_xwd(args.xwd)
        if args.crop:
            image = crop_to_content(image)
        if args.max_width > 0:
            image = shrink(image, args.max_width)
    except (OSError, ValueError) as error:
        sys.exit("xwd_to_png: %s" % error)
    write_png(args.png, image)
    print("xwd_to_png: wrote %s (%dx%d)" % (args.png, image.shape[1], image.shape[0]))


if __name__ == "__main__":
    main()
