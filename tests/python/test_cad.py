# SPDX-License-Identifier: GPL-3.0-or-later
"""tocad's DXF and IGES read back by readers that share no code with the writers (ezdxf; an
IGES parser written here), and their curves checked against the stream's spline within 0.1 um
at the 400 parameters of the stream's samples table (docs/EXPORT.md)."""
import subprocess

import ezdxf
import numpy as np
import pytest

import libsection as ls
from conftest import tool

TOLERANCE = 1e-4  # mm: 0.1 um


def samples_by_curve(stream_path):
    s = ls.read_tables(stream_path)["samples"]
    return {(int(sec), int(loop)): g for (sec, loop), g in s.groupby(["section", "loop"])}


def run_tocad(stream, out, *flags):
    r = subprocess.run([tool("tocad"), str(stream), "-o", str(out), *flags], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    return out


def test_dxf_splines_match_the_stream(example_splines, tmp_path):
    dxf = run_tocad(example_splines, tmp_path / "blade.dxf")
    doc = ezdxf.readfile(dxf)
    auditor = doc.audit()
    assert not auditor.errors, [str(e) for e in auditor.errors]
    assert doc.dxfversion == "AC1015"
    assert doc.header["$INSUNITS"] == 4  # mm
    samples = samples_by_curve(example_splines)
    splines = [e for e in doc.modelspace() if e.dxftype() == "SPLINE"]
    assert len(splines) == len(samples) == 3
    worst = 0.0
    for e in splines:
        section = int(e.dxf.layer.split("_")[1])
        curve = e.construction_tool()
        assert e.dxf.degree == 3 and e.closed
        g = samples[(section, 0)]
        got = np.array([curve.point(t) for t in g["t"]])
        worst = max(worst, np.abs(got - g[["x", "y", "z"]].to_numpy()).max())
        # the section's plane: z constant on every control point
        assert np.ptp(np.array(e.control_points)[:, 2]) < 1e-9
    assert worst < TOLERANCE, f"DXF curve off the stream's by {worst} mm"


def test_dxf_polylines_lie_on_the_curve(example_splines, tmp_path):
    dxf = run_tocad(example_splines, tmp_path / "blade.dxf", "--polyline-tolerance", "0.002")
    doc = ezdxf.readfile(dxf)
    samples = samples_by_curve(example_splines)
    polylines = [e for e in doc.modelspace() if e.dxftype() == "POLYLINE"]
    assert len(polylines) == 3
    for p in polylines:
        assert p.is_3d_polyline and p.is_closed
        section = int(p.dxf.layer.split("_")[1])
        vertices = np.array([v.dxf.location for v in p.vertices])
        ring = samples[(section, 0)][["x", "y", "z"]].to_numpy()
        # every sample of the curve lies within the tolerance (plus a little) of the polyline
        a, b = vertices, np.roll(vertices, -1, axis=0)
        d = b - a
        for q in ring:
            s = np.clip(((q - a) * d).sum(1) / (d * d).sum(1), 0, 1)
            assert np.min(np.linalg.norm(q - (a + s[:, None] * d), axis=1)) < 0.002 + 1e-9


def parse_iges(path):
    """Fixed-column IGES: global parameters, and per entity its directory fields and parameters."""
    lines = open(path).read().split("\n")
    by = {}
    for line in lines:
        if line:
            assert len(line) == 80, repr(line)
            by.setdefault(line[72], []).append(line)
    glob = "".join(l[:72] for l in by["G"])
    globals_ = []
    i, token = 0, ""
    while i < len(glob) and glob[i] != ";":  # Hollerith strings (nH...) may hold delimiters
        j = i
        while j < len(glob) and glob[j].isdigit():
            j += 1
        if j < len(glob) and glob[j] == "H" and j > i:
            n = int(glob[i:j])
            globals_.append(glob[j + 1:j + 1 + n])
            i = j + 1 + n
        else:
            k = i
            while glob[k] not in ",;":
                k += 1
            globals_.append(glob[i:k].strip())
            i = k
        if glob[i] == ",":
            i += 1
    entities = []
    d = by["D"]
    for k in range(0, len(d), 2):
        f1 = [d[k][c:c + 8] for c in range(0, 72, 8)]
        f2 = [d[k + 1][c:c + 8] for c in range(0, 72, 8)]
        first, count = int(f1[1]), int(f2[3])
        data = "".join(l[:64] for l in by["P"][first - 1:first - 1 + count])
        assert all(int(l[64:72]) == k + 1 for l in by["P"][first - 1:first - 1 + count])
        params = [t.strip() for t in data.replace(";", ",").split(",")][:-1]
        entities.append({"type": int(f1[0]), "label": f2[7].strip(), "subscript": int(f2[8]), "params": params})
    assert by["T"][0][:32] == "S%7dG%7dD%7dP%7d" % (len(by["S"]), len(by["G"]), len(by["D"]), len(by["P"]))
    return globals_, entities


def real(s):
    return float(s.replace("D", "E"))


def de_boor(knots, control, degree, t):
    """A point of a B-spline (knots, control points) at t, by de Boor's algorithm."""
    k = np.searchsorted(knots, t, side="right") - 1
    k = min(max(k, degree), len(control) - 1)
    d = [control[j + k - degree].copy() for j in range(degree + 1)]
    for r in range(1, degree + 1):
        for j in range(degree, r - 1, -1):
            i = j + k - degree
            a = (t - knots[i]) / (knots[i + degree - r + 1] - knots[i])
            d[j] = (1 - a) * d[j - 1] + a * d[j]
    return d[degree]


def test_iges_curves_match_the_stream(example_splines, tmp_path):
    glob, entities = parse_iges(run_tocad(example_splines, tmp_path / "blade.igs"))
    assert glob[0] == "," and glob[1] == ";"
    assert glob[13] == "2" and glob[14] == "MM"  # units flag, units name
    assert glob[22] == "11"  # IGES 5.3
    samples = samples_by_curve(example_splines)
    assert [e["type"] for e in entities] == [126, 126, 126]
    worst = 0.0
    for e in entities:
        p = e["params"]
        k, m = int(p[1]), int(p[2])
        assert p[3:7] == ["1", "1", "1", "0"]  # planar, closed, polynomial, not periodic
        knots = np.array([real(x) for x in p[7:7 + k + m + 2]])
        w0 = 7 + k + m + 2
        assert all(real(x) == 1.0 for x in p[w0:w0 + k + 1])
        c0 = w0 + k + 1
        control = np.array([real(x) for x in p[c0:c0 + 3 * (k + 1)]]).reshape(-1, 3)
        v0, v1 = real(p[c0 + 3 * (k + 1)]), real(p[c0 + 3 * (k + 1) + 1])
        normal = np.array([real(x) for x in p[c0 + 3 * (k + 1) + 2:]])
        assert len(normal) == 3 and abs(np.linalg.norm(normal) - 1) < 1e-12
        assert e["label"] == f"S{e['subscript']}L0"
        g = samples[(e["subscript"], 0)]
        assert v0 == knots[m] and v1 == knots[k + 1]
        for t, x in zip(g["t"], g[["x", "y", "z"]].to_numpy()):
            worst = max(worst, np.abs(de_boor(knots, control, m, t) - x).max())
        assert np.abs((control - control[0]) @ normal).max() < 1e-9  # planar, normal as stated
    assert worst < TOLERANCE, f"IGES curve off the stream's by {worst} mm"
