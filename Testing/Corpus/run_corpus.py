#!/usr/bin/env python3
"""Runs mrgi-render on every case of the bad-input corpus (make_corpus.py).

Usage: run_corpus.py MRGI_RENDER CORPUS_DIR WORK_DIR [--make-corpus] [--jobs N]
                     [--timeout S] [--wrapper CMD] [--only SUBSTRING] [--verbose]

A case passes when mrgi-render either
  - exits 1 with an error line on stderr that names the case's file, or
  - exits 0 and writes a PNG that is not empty (some pixel differs from the
    black background).
A signal, a timeout, a sanitizer report, any other exit code, an error line
without the file's name or an empty image fails the case. Prints one line per failed case and a
summary of the outcomes; exits 1 when a case failed.
"""
import argparse
import concurrent.futures
import os
import struct
import subprocess
import sys
import zlib


def png_pixels(path):
    """(width, height, channels, rows of bytes) of an 8-bit non-interlaced PNG."""
    with open(path, "rb") as f:
        data = f.read()
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        raise ValueError("not a PNG")
    pos, idat, head = 8, b"", None
    while pos + 8 <= len(data):
        length, kind = struct.unpack(">I4s", data[pos:pos + 8])
        chunk = data[pos + 8:pos + 8 + length]
        if kind == b"IHDR":
            head = struct.unpack(">IIBBBBB", chunk)
        elif kind == b"IDAT":
            idat += chunk
        pos += 12 + length
    width, height, depth, color, _, _, interlace = head
    if depth != 8 or interlace:
        raise ValueError("unsupported PNG")
    channels = {0: 1, 2: 3, 4: 2, 6: 4}[color]
    raw = zlib.decompress(idat)
    stride = width * channels
    rows, prev = [], bytearray(stride)
    for y in range(height):
        kind = raw[y * (stride + 1)]
        line = bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for i in range(stride):
            a = line[i - channels] if i >= channels else 0
            b = prev[i]
            c = prev[i - channels] if i >= channels else 0
            if kind == 1:
                line[i] = (line[i] + a) & 255
            elif kind == 2:
                line[i] = (line[i] + b) & 255
            elif kind == 3:
                line[i] = (line[i] + (a + b) // 2) & 255
            elif kind == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append(bytes(line))
        prev = line
    return width, height, channels, rows


def run_case(args, name):
    path = os.path.join(args.corpus, name)
    out = os.path.join(args.work, name.replace(os.sep, "_") + ".png")
    if os.path.exists(out):
        os.remove(out)
    command = args.wrapper + [args.render, path, "-o", out, "--size", "64x64", "-q", "--gi", "off"]
    try:
        p = subprocess.run(command, stdin=subprocess.DEVNULL, stdout=subprocess.PIPE,
                           stderr=subprocess.PIPE, timeout=args.timeout)
    except subprocess.TimeoutExpired:
        return name, "timeout", "no answer within %g s" % args.timeout
    err = p.stderr.decode("utf-8", "replace").strip()
    lines = [l for l in err.splitlines() if l.startswith("mrgi-render: error:")]
    if p.returncode < 0:
        return name, "signal", "killed by signal %d: %s" % (-p.returncode, err[-300:])
    # Under ASan/UBSan a report may end in exit status 1 like a refusal.
    if "Sanitizer" in err or "runtime error:" in err:
        return name, "sanitizer", err[-600:]
    if p.returncode == 0:
        if not os.path.exists(out):
            return name, "bad", "exit 0 without an image"
        try:
            _, _, _, rows = png_pixels(out)
        except Exception as e:  # noqa: BLE001 - any unreadable image fails the case
            return name, "bad", "exit 0, unreadable image: %s" % e
        if not any(any(r) for r in rows):
            return name, "empty", "exit 0 with an all-black image"
        return name, "rendered", ""
    if p.returncode == 1 and lines and path in lines[0]:
        return name, "refused", lines[0]
    return name, "bad", "exit %d, stderr: %s" % (p.returncode, err[-300:] or "(nothing)")


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("render")
    parser.add_argument("corpus")
    parser.add_argument("work")
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--timeout", type=float, default=60)
    parser.add_argument("--wrapper", default="", help="command (split on spaces) to run mrgi-render under")
    parser.add_argument("--only", default="")
    parser.add_argument("--make-corpus", action="store_true",
                        help="write the corpus into CORPUS_DIR first (make_corpus.py)")
    parser.add_argument("--verbose", action="store_true")
    args = parser.parse_args()
    args.wrapper = args.wrapper.split()
    if args.make_corpus:
        maker = os.path.join(os.path.dirname(os.path.abspath(__file__)), "make_corpus.py")
        subprocess.run([sys.executable, maker, args.corpus], check=True)
    os.makedirs(args.work, exist_ok=True)
    names = sorted(n for n in os.listdir(args.corpus) if args.only in n)
    if not names:
        print("no cases in %s" % args.corpus)
        return 1
    counts = {}
    failed = []
    with concurrent.futures.ThreadPoolExecutor(max_workers=args.jobs) as pool:
        for name, outcome, detail in pool.map(lambda n: run_case(args, n), names):
            counts[outcome] = counts.get(outcome, 0) + 1
            if outcome not in ("refused", "rendered"):
                failed.append(name)
                print("FAIL %s: %s: %s" % (name, outcome, detail))
            elif args.verbose:
                print("ok   %s: %s %s" % (name, outcome, detail))
    print("%d cases: %s" % (len(names), ", ".join("%d %s" % (counts[k], k) for k in sorted(counts))))
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
