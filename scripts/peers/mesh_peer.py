#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""The Python a user would write to cut a mesh by parallel planes: trimesh
section_multiplane. Planes as `slice --count N --normal 0,0,1`: spread evenly over the
mesh's z extent, offsets min + (max - min) (k + 1) / (N + 1).

Usage: mesh_peer.py MESH --count N
Prints one line: triangles, sections cut, closed loops, and the wall times.
"""
import argparse
import time

import numpy as np
import trimesh


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("mesh")
    ap.add_argument("--count", type=int, default=20)
    a = ap.parse_args()
    t0 = time.perf_counter()
    mesh = trimesh.load(a.mesh, force="mesh")
    t1 = time.perf_counter()
    lo, hi = mesh.bounds[0][2], mesh.bounds[1][2]
    heights = lo + (hi - lo) * (np.arange(a.count) + 1) / (a.count + 1)
    # section_multiplane takes heights along the normal relative to plane_origin.
    paths = mesh.section_multiplane(plane_origin=[0, 0, 0], plane_normal=[0, 0, 1], heights=heights)
    # discrete: the ordered polylines (closed loops repeat their first vertex), like slice's loops.
    loops = sum(len(p.discrete) for p in paths if p is not None)
    t2 = time.perf_counter()
    print(f"triangles={len(mesh.faces)} sections={sum(p is not None for p in paths)} loops={loops} "
          f"read_s={t1 - t0:.3f} section_s={t2 - t1:.3f} total_s={t2 - t0:.3f}")


if __name__ == "__main__":
    main()
