#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""When each part of a pipe stream comes out of a shell pipeline: the seconds from the
pipeline's start to its first byte, to each `# part` line, and to its end, read 1 MiB at a
time (a line-by-line reader in Python is slower than the tools and would time itself).

Usage: scripts/pipe_timeline.py 'build/tools/slice scan.ply --count 20 | build/tools/smooth'
"""
import os
import subprocess
import sys
import time


def main() -> int:
    if len(sys.argv) != 2:
        print(__doc__.strip(), file=sys.stderr)
        return 2
    start = time.monotonic()
    proc = subprocess.Popen(["bash", "-c", sys.argv[1]], stdout=subprocess.PIPE, bufsize=0)
    first = None
    parts = []
    fd = proc.stdout.fileno()
    while True:
        chunk = os.read(fd, 1 << 20)
        if not chunk:
            break
        now = time.monotonic() - start
        if first is None:
            first = now
        parts += [now] * chunk.count(b"# part")
    code = proc.wait()
    end = time.monotonic() - start
    if first is None:
        print(f"no output; exit {code} after {end:.3f} s")
        return 1
    print(f"first byte {first:.3f} s, end {end:.3f} s, exit {code}")
    print("parts at " + " ".join(f"{t:.3f}" for t in parts))
    return 0 if code == 0 else 1


if __name__ == "__main__":
    sys.exit(main())
