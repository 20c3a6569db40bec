#!/usr/bin/env python3
"""How much of writing a set's files is the disk: each FOLDER/*.stl read into memory, then
written to a new file in the same folder from memory, once without and once with an fsync
before the close (the export's write ends with one); seconds summed over the files, two rounds."""
import glob
import os
import sys
import time

folder = sys.argv[1]
files = sorted(glob.glob(os.path.join(folder, "*.stl")))
data = [open(p, "rb").read() for p in files]
for round_ in (1, 2):
    for sync in (False, True):
        total = 0.0
        for i, blob in enumerate(data):
            out = os.path.join(folder, "rewrite_%d.bin" % i)
            start = time.perf_counter()
            fd = os.open(out, os.O_WRONLY | os.O_CREAT | os.O_TRUNC, 0o644)
            view = memoryview(blob)
            while view:
                view = view[os.write(fd, view):]
            if sync:
                os.fsync(fd)
            os.close(fd)
            total += time.perf_counter() - start
            os.unlink(out)
        print("round %d: %d files, %.1f MB, written from memory %s fsync: %.3f s" % (
            round_, len(data), sum(map(len, data)) / 1e6, "with" if sync else "without", total))
