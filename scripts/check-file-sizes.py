#!/usr/bin/env python3
"""No C/C++ source file of MRGI is longer than the line limit (900).

Walks the given folders (default: Rendering and Module under the project
root) for .c/.h/.cxx/.hxx/.cpp files, counts lines as `wc -l` does, and
exits 1 listing every file over the limit that is not a known exception.
Known exceptions live in EXCEPTIONS below, each with its reason; an
exception that is no longer over the limit is reported so it gets removed,
and an exception may not grow past its own cap (its size when it was
listed), so that a file waiting for its split does not keep growing.
--self-test checks that a made-up oversize file is found and listed.

Usage: check-file-sizes.py [--limit N] [--self-test] [FOLDER ...]
"""
import os
import sys
import tempfile

LIMIT = 900
EXTENSIONS = (".c", ".h", ".cxx", ".hxx", ".cpp", ".hpp")

# Path relative to the project root -> (cap in lines, why it may stay over the
# limit for now). The cap is the file's size when it was listed: it may shrink,
# never grow.
EXCEPTIONS = {}


def count_lines(path):
    with open(path, "rb") as f:
        return f.read().count(b"\n")


def oversize(folders, root, limit):
    found = []
    for folder in folders:
        for dirpath, dirnames, names in os.walk(folder):
            dirnames[:] = sorted(d for d in dirnames if not d.startswith("."))
            for name in sorted(names):
                if name.endswith(EXTENSIONS):
                    path = os.path.join(dirpath, name)
                    n = count_lines(path)
                    if n > limit:
                        found.append((os.path.relpath(path, root).replace(os.sep, "/"), n))
    return found


def check(folders, root, limit, exceptions):
    bad, grown, stale = [], [], []
    over = dict(oversize(folders, root, limit))
    for path, n in sorted(over.items()):
        if path not in exceptions:
            bad.append((path, n))
            continue
        cap, why = exceptions[path]
        if n > cap:
            grown.append((path, n, cap))
        else:
            print("exception: %s has %d lines, cap %d (%s)" % (path, n, cap, why))
    for path in sorted(exceptions):
        if path not in over and os.path.exists(os.path.join(root, path)):
            stale.append(path)
    for path, n in bad:
        print("error: %s has %d lines, over the limit of %d" % (path, n, limit))
    for path, n, cap in grown:
        print("error: %s has %d lines, over its exception cap of %d; split it "
              "instead of growing it" % (path, n, cap))
    for path in stale:
        print("error: %s is listed as an exception but is no longer over %d lines; "
              "remove it from EXCEPTIONS" % (path, limit))
    return 1 if bad or grown or stale else 0


def self_test():
    with tempfile.TemporaryDirectory() as d:
        os.makedirs(os.path.join(d, "Rendering", "Sub"))
        def write(rel, lines):
            with open(os.path.join(d, rel), "w") as f:
                f.write("x\n" * lines)
        write("Rendering/Sub/small.cxx", 10)
        write("Rendering/Sub/edge.c", 10)
        assert check([os.path.join(d, "Rendering")], d, 10, {}) == 0, "files at the limit refused"
        write("Rendering/Sub/big.cxx", 11)
        assert check([os.path.join(d, "Rendering")], d, 10, {}) == 1, "an oversize file passed"
        assert check([os.path.join(d, "Rendering")], d, 10,
                     {"Rendering/Sub/big.cxx": (11, "test")}) == 0, "an exception was refused"
        assert check([os.path.join(d, "Rendering")], d, 10,
                     {"Rendering/Sub/big.cxx": (10, "test")}) == 1, "an exception grew past its cap"
        write("Rendering/Sub/big.cxx", 5)
        assert check([os.path.join(d, "Rendering")], d, 10,
                     {"Rendering/Sub/big.cxx": (11, "test")}) == 1, "a stale exception passed"
    print("self-test: an oversize file, an exception past its cap and a stale exception are "
          "found; files at the limit pass")
    return 0


def main(argv):
    args = list(argv[1:])
    limit = LIMIT
    if "--self-test" in args:
        return self_test()
    if "--limit" in args:
        i = args.index("--limit")
        limit = int(args[i + 1])
        del args[i:i + 2]
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    folders = args or [os.path.join(root, "Rendering"), os.path.join(root, "Module")]
    rc = check(folders, root, limit, EXCEPTIONS)
    if rc == 0:
        print("all C/C++ sources under %s are within %d lines"
              % (", ".join(os.path.relpath(f, root) for f in folders), limit))
    return rc


if __name__ == "__main__":
    sys.exit(main(sys.argv))
