#!/usr/bin/env python3
"""Hostile inputs and runs for tests/tools/test_hostile.sh (issue 26), made on the fly.

  hostile.py short-ply-binary OUT   binary PLY of 20000 vertices declaring 1000
  hostile.py short-ply-ascii OUT    ascii PLY of 20000 vertices declaring 19990
  hostile.py short-stl OUT          binary STL of 100 triangles declaring 50
  hostile.py edit IN OUT WHAT       a stream with one thing broken (WHAT, see EDITS)
  hostile.py planes N OUT           a planes CSV of N planes along z
  hostile.py shift D IN OUT         a cloud (x y z lines) moved by (D, D, D)
  hostile.py cr IN OUT              a text file with CR-only line ends
  hostile.py signal SIG OUT CMD...  runs CMD (writing OUT), sends SIG once OUT's temporary
                                    file appears; prints the exit status and any file left
                                    beside OUT but OUT itself (none is right)
"""
import glob
import os
import random
import signal
import struct
import subprocess
import sys
import time


def points(n=20000):
    rng = random.Random(1)
    return [(rng.uniform(-10, 10), rng.uniform(-10, 10), rng.uniform(0, 10)) for _ in range(n)]


def short_ply_binary(out):
    with open(out, "wb") as f:
        f.write(b"ply\nformat binary_little_endian 1.0\nelement vertex 1000\n"
                b"property double x\nproperty double y\nproperty double z\nend_header\n")
        for p in points():
            f.write(struct.pack("<3d", *p))


def short_ply_ascii(out):
    with open(out, "w") as f:
        f.write("ply\nformat ascii 1.0\nelement vertex 19990\n"
                "property float x\nproperty float y\nproperty float z\nend_header\n")
        for p in points():
            f.write("%g %g %g\n" % p)


def short_stl(out):
    with open(out, "wb") as f:
        f.write(b"\0" * 80 + struct.pack("<I", 50))
        for k in range(100):
            f.write(struct.pack("<12fH", 0, 0, 1, k, 0, 0, k + 1, 0, 0, k, 1, 0, 0))


def tables(lines):
    """(table name or None, is header, index) for each line of a stream."""
    table, header = None, False
    for i, line in enumerate(lines):
        if line.startswith("# table "):
            table, header = line[8:], True
            yield None, False, i
        elif line.startswith("#"):
            table = None
            yield None, False, i
        else:
            yield table, header, i
            header = False


def first_row(lines, name):
    return next(i for t, h, i in tables(lines) if t == name and not h)


def set_cell(lines, name, column, value):
    header = lines[first_row(lines, name) - 1].split(",")
    i = first_row(lines, name)
    cells = lines[i].split(",")
    cells[header.index(column)] = value
    lines[i] = ",".join(cells)


def edit(src, out, what):
    lines = open(src).read().split("\n")
    if what == "duplicate-params":        # two params rows for section 0
        i = first_row(lines, "params")
        lines.insert(i, lines[i])
    elif what == "duplicate-point":       # one points row twice
        i = first_row(lines, "points")
        lines.insert(i, lines[i])
    elif what == "negative-loop":
        set_cell(lines, "points", "loop", "-1")
    elif what == "negative-index":
        set_cell(lines, "points", "index", "-3")
    elif what == "negative-count":        # loops.points = -5
        set_cell(lines, "loops", "points", "-5")
    elif what == "wrong-label":           # part 0 labelled 7
        i = lines.index("# part 0")
        lines[i] = "# part 7"
    elif what == "second-part":           # part 1 labelled 0 (section 0 twice)
        i = lines.index("# part 1")
        lines[i] = "# part 0"
    elif what == "duplicate-column":      # the points header names u twice
        i = first_row(lines, "points") - 1
        lines[i] = lines[i].replace(",v,", ",u,", 1)
    elif what == "empty-points":          # part 1's points table without rows
        keep = []
        in_part = False
        for t, h, i in tables(lines):
            if lines[i].startswith("# part"):
                in_part = lines[i] == "# part 1"
            if in_part and t == "points" and not h:
                continue
            keep.append(lines[i])
        lines = keep
    elif what == "no-v":                  # the points table's v column renamed
        i = first_row(lines, "points") - 1
        lines[i] = lines[i].replace(",v,", ",w,", 1)
    else:
        sys.exit("hostile.py: unknown edit " + what)
    open(out, "w").write("\n".join(lines))


def planes(n, out):
    with open(out, "w") as f:
        f.write("origin_x,origin_y,origin_z,normal_x,normal_y,normal_z\n")
        for i in range(n):
            f.write("0,0,%g,0,0,1\n" % (i * 1e-4))


def shift(d, src, out):
    d = float(d)
    with open(src) as f, open(out, "w") as g:
        for line in f:
            x, y, z = (float(v) for v in line.split()[:3])
            g.write("%.17g %.17g %.17g\n" % (x + d, y + d, z + d))


def cr(src, out):
    open(out, "wb").write(open(src, "rb").read().replace(b"\n", b"\r"))


def signal_run(sig, out, cmd):
    def default_signals():  # a signal the caller ignores (a background job's SIGINT) is not
        for s in (signal.SIGINT, signal.SIGTERM, signal.SIGHUP):
            signal.signal(s, signal.SIG_DFL)

    proc = subprocess.Popen(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, preexec_fn=default_signals)
    pattern = glob.escape(out) + ".*.partial*"
    for _ in range(2000):  # up to 20 s for the temporary file to appear
        if glob.glob(pattern) or proc.poll() is not None:
            break
        time.sleep(0.01)
    if proc.poll() is None:
        proc.send_signal(getattr(signal, "SIG" + sig))
    code = proc.wait()
    left = [p for p in glob.glob(glob.escape(out) + "*") if p != out]
    print(code, " ".join(left) if left else "")


def main():
    a = sys.argv[1:]
    if not a:
        sys.exit(__doc__)
    {"short-ply-binary": lambda: short_ply_binary(a[1]), "short-ply-ascii": lambda: short_ply_ascii(a[1]),
     "short-stl": lambda: short_stl(a[1]), "edit": lambda: edit(a[1], a[2], a[3]),
     "planes": lambda: planes(int(a[1]), a[2]), "shift": lambda: shift(a[1], a[2], a[3]),
     "cr": lambda: cr(a[1], a[2]), "signal": lambda: signal_run(a[1], a[2], a[3:])}[a[0]]()


if __name__ == "__main__":
    main()
