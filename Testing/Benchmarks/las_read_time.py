"""Read time of vtkMRGILASReader per million points (Documentation/PointClouds-LAS.md).

Writes LAS files of 1e6 and 1e7 points (formats 0, 3 and 6; UTM-sized
offsets, millimetre scale) with numpy into DIR, reads each three times
(page cache warm: the file was just written), prints the best and the
first time, and deletes the file. Not a test: nothing is asserted.

    PYTHONPATH=build/lib/python3/dist-packages /usr/bin/python3 \\
        Testing/Benchmarks/las_read_time.py build/Testing/Temporary
"""
import os
import struct
import sys
import time

import numpy as np

import mrgi

RECORD = {0: 20, 3: 34, 6: 30}


def write(path, n, fmt):
    record = RECORD[fmt]
    minor = 4 if fmt >= 6 else 2
    size = 375 if minor == 4 else 227
    h = bytearray(size)
    h[0:4] = b"LASF"
    h[24], h[25] = 1, minor
    struct.pack_into("<HIIBHI", h, 94, size, size, 0, fmt, record, 0 if minor == 4 else n)
    if minor == 4:
        struct.pack_into("<Q", h, 247, n)
    struct.pack_into("<3d3d", h, 131, 0.001, 0.001, 0.001, 500000.0, 5400000.0, 0.0)
    rec = np.zeros((n, record), np.uint8)
    k = np.arange(n)
    xyz = np.stack([(k % 4000) * 10, (k // 4000) * 10, k % 1000], 1).astype("<i4")
    rec[:, 0:12] = xyz.view(np.uint8).reshape(n, 12)
    rec[:, 12:14] = (k % 4096).astype("<u2").view(np.uint8).reshape(n, 2)
    rec[:, 15 if fmt < 6 else 16] = np.where(k % 3 == 0, 2, 5)
    if fmt == 3:
        rec[:, 28:34] = np.stack([k % 65536] * 3, 1).astype("<u2").view(np.uint8).reshape(n, 6)
    with open(path, "wb") as f:
        f.write(bytes(h))
        f.write(rec.tobytes())


def main():
    directory = sys.argv[1] if len(sys.argv) > 1 else "/tmp"
    for n in (10**6, 10**7):
        for fmt in (0, 3, 6):
            path = os.path.join(directory, "las_read_time_%d_%d.las" % (n, fmt))
            write(path, n, fmt)
            times = []
            for _ in range(3):
                reader = mrgi.vtkMRGILASReader()
                reader.SetFileName(path)
                start = time.perf_counter()
                reader.Update()
                times.append(time.perf_counter() - start)
                assert reader.GetOutput().GetNumberOfPoints() == n, reader.GetLastErrorMessage()
                del reader
            os.remove(path)
            print("%.0e points, format %d (%d MB): best of 3 %.3f s = %.3f s per million (first %.3f s)"
                  % (n, fmt, n * RECORD[fmt] // 10**6, min(times), min(times) / (n / 1e6), times[0]))


if __name__ == "__main__":
    main()
