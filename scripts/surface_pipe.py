# SPDX-License-Identifier: GPL-3.0-or-later
"""The pipe on surfaces of revolution for the validation scripts: slice --axis (the x
axis) --streamline FILE... | smooth | fitspline | camber --le-direction=-1,0 (upstream in
the conformal plane), its stream written to `out` (docs/REVOLUTION.md)."""
import os, subprocess, sys


def surface_pipe(who, camber, cloud, streamlines, out, extra=()):
    tools = os.path.dirname(camber)
    files = " ".join(f"--streamline {f}" for f in streamlines)
    cmd = (f"{tools}/slice {cloud} --axis 0,0,0,1,0,0 {files} | {tools}/smooth | {tools}/fitspline"
           f" | {tools}/camber --le-direction=-1,0 {' '.join(extra)} > {out}")
    p = subprocess.run(cmd, shell=True, capture_output=True, text=True)
    if p.returncode != 0:
        sys.exit(f"{who}: the pipe on the surfaces failed: {p.stderr.strip()}")
