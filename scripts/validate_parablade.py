#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Runs the four parablade geometries (../shared/data/real/parablade, not part of the
repository; README there) through the whole pipe with default options, as a new user
would, and checks every value camber prints against a reference: each value is within its
target, or flagged in its row (`flags`, the bits of section/checks.h), or a SILENT WRONG.

- 2D cases (Aachen_2D, Impulse_2D, STD10_2D: `id x y`, metres, unordered CFD points): the
  id column is stripped and the x y columns given as a plain profile (`slice FILE`, no
  planes: one profile at z = 0; the tools take an input under 1 across for metres and
  convert it to mm), then `smooth | fitspline | camber --params`.
- Angles against parablade's fitted blade (matched_camber_thickness.cfg; the
  connecting-arcs fit is printed beside it, its spread is the reference's own), to 1 deg.
  The mapping, once for all: parablade builds a section in (x, y) = (meridional, tangential)
  with its leading edge at the smaller x and measures stagger, theta_in and theta_out from
  +x (the axial direction), counter-clockwise positive, along the chord and the camber
  line pointing from the LE to the TE; for a linear cascade it scales that section
  uniformly into the file's x y (blade_3D.py), so the angles hold in the file's frame.
  camber measures stagger, inlet_angle and outlet_angle from +u of the section's frame,
  along the chord and the camber tangent pointing toward the TE. So our angles are taken
  into the file's (x, y) frame through the map u,v -> x,y that the params row itself
  gives (its LE, TE and centroid in both) and compared as they are: stagger = stagger,
  inlet_angle = theta_in, outlet_angle = theta_out, camber_angle = theta_in - theta_out.
  An LE taken at the wrong end shows as about 180 deg off.
- Lengths against checks computed here from the raw points alone (mm), to 2 %: the points
  ordered into a loop (nearest-neighbour chain, then 2-opt); chord = their extent along our
  chord line; caliper chord = their extent along the convex hull's edge that bridges the
  concave side, caliper stagger its angle; max thickness = the largest inscribed diameter
  (shrinking balls: at each point, the largest circle tangent there holding no other
  point); edge radii = a circle fitted to the points within +-60 deg of the extreme point
  along the chord line, only where they are a circular arc (fit rms < 1 % of R, >= 7 points,
  else "n/a": the radius depends on the arc taken). Also printed, not judged: the points'
  axial extent against the cfg's x_trailing - x_leading (a check of the frame).
- APU_rotor (3D radial rotor, sections on surfaces of revolution: no reference for planar
  sections): `slice FILE` (no planes) and `slice FILE --count 5` (default normal 0,0,1, the
  machine axis here), through the pipe; what comes out is printed as it is, and each
  section's chord is judged against the raw points within the band of its plane (a loop
  closed on part of an open cut shows as a chord far short of them; slice now refuses
  such a section: "the loop holds only part of the section").

Usage: scripts/validate_parablade.py [--bin DIR] [--data DIR] [--keep DIR] [-- camber options]
Exit 1 when any value is a silent wrong, 0 otherwise; 0 with a message when the data are
missing (the test suite does not need them); 2 when the tools are missing.
"""
import argparse, math, os, re, subprocess, sys, tempfile

import numpy as np

from check_bits import check_bits, flagged_by
from stream_tables import table

here = os.path.dirname(os.path.abspath(__file__))
root = os.path.join(here, "..")
MM_PER = {"mm": 1.0, "m": 1000.0, "cm": 10.0, "um": 1e-3, "in": 25.4}
ANGLE_TARGET, LENGTH_TARGET = 1.0, 0.02


# ----- the tools ------------------------------------------------------------------------

def run_pipe(bin_dir, inp, tmp, slice_args=(), camber_args=()):
    """slice INP ARGS | smooth | fitspline | camber --params, each stage's output in a file
    (as a shell pipe would pass it on); returns what each stage said and wrote."""
    params = os.path.join(tmp, "params.csv")  # the stages run in tmp, on names relative to it
    if os.path.exists(params):
        os.remove(params)
    stages = [("slice", [os.path.basename(inp)] + list(slice_args)), ("smooth", []), ("fitspline", []),
              ("camber", ["--params", "params.csv"] + list(camber_args))]
    run, prev = {"stages": [], "params": params}, None
    for name, a in stages:
        out = os.path.join(tmp, name + ".txt")
        cmd = [os.path.abspath(os.path.join(bin_dir, name))] + ([os.path.basename(prev)] if prev else []) + a
        with open(out, "w") as f:
            p = subprocess.run(cmd, stdout=f, stderr=subprocess.PIPE, text=True, cwd=tmp)
        run["stages"].append((name, p.returncode, p.stderr.strip()))
        prev = out
    run["stream"] = prev
    run["rows"] = read_csv(params) if os.path.exists(params) else []
    run["slice_stream"] = os.path.join(tmp, "slice.txt")
    return run


def read_csv(path):
    lines = [l.strip() for l in open(path) if l.strip() and not l.startswith("#")]
    if not lines:
        return []
    head = lines[0].split(",")
    return [dict(zip(head, map(float, l.split(",")))) for l in lines[1:]]


def stream_notes(path):
    """The unit the input was converted from (mm per input unit), the sampling lines and
    the issues of a stream."""
    scale, sampling, issues = 1.0, [], []
    if not os.path.exists(path):
        return scale, sampling, issues
    for line in open(path):
        if line.startswith("# units_from "):
            scale = MM_PER.get(line.split()[2], scale)
        elif line.startswith("# sampling "):
            sampling.append(line[2:].strip())
        elif line.startswith("# issue "):
            issues.append(line[8:].strip())
    return scale, sampling, issues


# ----- independent geometry from the raw points (mm) ---------------------------------------

def order_loop(p):
    """The points as a closed loop: a nearest-neighbour chain, untangled by 2-opt; None
    when the loop still has a long step or crosses itself."""
    n = len(p)
    d = np.linalg.norm(p[:, None] - p[None], axis=2)
    np.fill_diagonal(d, np.inf)
    nearest = d.min(1)
    seen, o = np.zeros(n, bool), [0]
    seen[0] = True
    for _ in range(n - 1):
        r = np.where(seen, np.inf, d[o[-1]])
        o.append(int(np.argmin(r)))
        seen[o[-1]] = True
    o = np.array(o)
    np.fill_diagonal(d, 0)
    for _ in range(100):
        improved = False
        for i in range(n - 2):
            a, b = o[i], o[i + 1]
            c = o[i + 2:n - (1 if i == 0 else 0)]
            nxt = o[(np.arange(i + 2, i + 2 + len(c)) + 1) % n]
            gain = d[a, b] + d[c, nxt] - d[a, c] - d[b, nxt]
            if len(gain) and gain.max() > 1e-12:
                j = i + 2 + int(np.argmax(gain))
                o[i + 1:j + 1] = o[i + 1:j + 1][::-1].copy()
                improved = True
        if not improved:
            break
    q = p[o]
    step = np.linalg.norm(np.roll(q, -1, 0) - q, axis=1)
    if step.max() > 3 * np.percentile(nearest, 99) or crosses(q):
        return None
    return q


def crosses(q):
    a, b = q, np.roll(q, -1, 0)
    n = len(q)
    cr = lambda o, p, r: (p[..., 0] - o[..., 0]) * (r[..., 1] - o[..., 1]) - (p[..., 1] - o[..., 1]) * (r[..., 0] - o[..., 0])
    for i in range(n):
        j = np.arange(i + 2, n if i > 0 else n - 1)
        if not len(j):
            continue
        d1, d2 = cr(a[i], b[i], a[j]), cr(a[i], b[i], b[j])
        d3, d4 = cr(a[j], b[j], a[i][None]), cr(a[j], b[j], b[i][None])
        if np.any((d1 * d2 < 0) & (d3 * d4 < 0)):
            return True
    return False


def max_inscribed(q):
    """The largest inscribed diameter of loop q: at each point, the largest circle tangent
    there (inward normal from its neighbours) that holds no other point."""
    t = np.roll(q, -1, 0) - np.roll(q, 1, 0)
    area = 0.5 * np.sum(q[:, 0] * np.roll(q[:, 1], -1) - np.roll(q[:, 0], -1) * q[:, 1])
    nrm = np.c_[-t[:, 1], t[:, 0]] * (1 if area > 0 else -1)  # inward: left of a CCW loop
    nrm /= np.linalg.norm(nrm, axis=1)[:, None]
    best = 0.0
    for i in range(len(q)):
        v = q - q[i]
        dot = v @ nrm[i]
        ok = dot > 1e-12
        r = np.min((v[ok] ** 2).sum(1) / (2 * dot[ok]))
        best = max(best, r)
    return 2 * best


def caliper(q, forward):
    """Extent along the hull edge bridging the deepest concavity, and that edge's angle
    (pointing along `forward`); None when no side is concave (pocket under 1 % of the size)."""
    n = len(q)
    idx = sorted(range(n), key=lambda i: (q[i, 0], q[i, 1]))
    cross = lambda o, a, b: (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])
    hull = []
    for seq in (idx, idx[::-1]):
        part = []
        for i in seq:
            while len(part) >= 2 and cross(q[part[-2]], q[part[-1]], q[i]) <= 0:
                part.pop()
            part.append(i)
        hull += part[:-1]
    size, hull_set = np.ptp(q, axis=0).max(), set(hull)
    best = (0.0, None)
    for k in range(len(hull)):
        i, j = hull[k], hull[(k + 1) % len(hull)]
        between = np.arange(i, j + (n if j < i else 0) + 1) % n
        if hull_set.intersection(between[1:-1].tolist()):  # the other way round the loop
            between = np.arange(j, i + (n if i < j else 0) + 1) % n
        e = (q[j] - q[i]) / np.linalg.norm(q[j] - q[i])
        depth = np.abs((q[between] - q[i]) @ np.array([-e[1], e[0]])).max()
        if depth > best[0]:
            best = (depth, e)
    if best[0] < 0.01 * size:
        return None
    e = best[1] if best[1] @ forward > 0 else -best[1]
    return np.ptp(q @ e), math.degrees(math.atan2(e[1], e[0]))


def fit_circle(p):
    """Least-squares circle (algebraic start, Gauss-Newton): centre, radius, rms."""
    A = np.c_[2 * p, np.ones(len(p))]
    sol = np.linalg.lstsq(A, (p ** 2).sum(1), rcond=None)[0]
    c = sol[:2]
    r = math.sqrt(max(sol[2] + c @ c, 1e-30))
    for _ in range(20):
        v = p - c
        dist = np.linalg.norm(v, axis=1)
        J = np.c_[-v / dist[:, None], -np.ones(len(p))]
        step = np.linalg.lstsq(J, -(dist - r), rcond=None)[0]
        c, r = c + step[:2], r + step[2]
    return c, r, float(np.sqrt(np.mean((np.linalg.norm(p - c, axis=1) - r) ** 2)))


def edge_arc_circle(q, direction, half_angle):
    """Circle fitted to the points within +-half_angle (seen from its centre) of the loop's
    extreme point along `direction`: (radius, rms, points) or None."""
    tip = int(np.argmax(q @ direction))
    n, chord = len(q), np.ptp(q @ direction)
    s = np.r_[0, np.cumsum(np.linalg.norm(np.diff(q, axis=0), axis=1))]
    along = np.abs(s - s[tip])
    along = np.minimum(along, s[-1] - along)
    steps = np.minimum(np.abs(np.arange(n) - tip), n - np.abs(np.arange(n) - tip))
    pick = (along < 0.01 * chord) | (steps <= 4)
    for _ in range(10):
        if pick.sum() < 4:
            return None
        c, r, rms = fit_circle(q[pick])
        v = q - c
        dist = np.linalg.norm(v, axis=1)
        new = (v @ direction > math.cos(math.radians(half_angle)) * dist) & (np.abs(dist - r) < 0.5 * r)
        if np.array_equal(new, pick):
            break
        pick = new
    return (r, rms, int(pick.sum())) if pick.sum() >= 4 else None


def edge_radius(q, direction):
    """The edge's radius from the raw points: a circle fitted to its +-60 deg arc where that
    is a circular arc (>= 7 points, rms < 0.5 % of R, the +-45 and +-75 deg arcs' radii
    within 2 % of it): (R, R, why); else the range of the
    radii fitted to its +-30 .. +-90 deg arcs (the radius depends on the arc taken):
    (lo, hi, why); (None, None, why) when no arc holds 4 points."""
    fits = {h: edge_arc_circle(q, direction, h) for h in (30, 45, 60, 75, 90)}
    f60 = fits[60]
    steady = all(f and abs(f[0] - f60[0]) <= 0.02 * f60[0] for f in (fits[45], fits[75])) if f60 else False
    if f60 and f60[2] >= 7 and f60[1] < 0.005 * f60[0] and steady:
        return f60[0], f60[0], f"circle on +-60 deg: {f60[2]} points, rms {f60[1] / f60[0]:.2%} of R"
    radii = [f[0] for f in fits.values() if f]
    if not radii:
        return None, None, "no edge arc holds 4 points"
    why = (f"+-60 deg arc: {f60[2]} points, rms {f60[1] / f60[0]:.1%} of R{'' if steady else ', R varies with the arc'}"
           if f60 else "+-60 deg arc: under 4 points")
    return min(radii), max(radii), why + f"; range over +-30..90 deg arcs ({len(radii)} fits)"


# ----- one 2D geometry ---------------------------------------------------------------------

def read_cfg(path):
    cfg = {}
    for line in open(path):
        if "=" in line:
            k, v = line.split("=", 1)
            try:
                cfg[k.strip()] = [float(x) for x in v.split(",")]
            except ValueError:
                pass
    return cfg


def uv_to_xy(row):
    """The linear map of the section's frame into the file's x y (from the LE, TE and
    centroid in both; the identity when they are collinear) and its determinant's sign."""
    uv = np.array([[row[f"{k}_u"], row[f"{k}_v"]] for k in ("le", "te", "centroid")])
    xy = np.array([[row[f"{k}_x"], row[f"{k}_y"]] for k in ("le", "te", "centroid")])
    U, X = (uv[1:] - uv[0]).T, (xy[1:] - xy[0]).T
    if abs(np.linalg.det(U)) < 1e-9 * np.abs(U).max() ** 2:
        return np.eye(2)
    return X @ np.linalg.inv(U)


def angle_xy(a_deg, A):
    v = A @ np.array([math.cos(math.radians(a_deg)), math.sin(math.radians(a_deg))])
    return math.degrees(math.atan2(v[1], v[0]))


def ref_text(ref):
    return "-" if ref is None else f"{ref[0]:.3f}-{ref[1]:.3f}" if isinstance(ref, tuple) else f"{ref:.3f}"


def wrap(d):
    return (d + 180.0) % 360.0 - 180.0


def compare_2d(name, folder, args, bits, tmp):
    pts_file = [os.path.join(folder, f) for f in sorted(os.listdir(folder)) if f.startswith("MoveSurface")][0]
    raw = np.loadtxt(pts_file)[:, 1:3]
    xy_file = os.path.join(tmp, name + ".xy")
    np.savetxt(xy_file, raw, fmt="%.9g")  # the id column stripped
    ct = read_cfg(os.path.join(folder, "matched_camber_thickness.cfg"))
    ca = read_cfg(os.path.join(folder, "matched_connecting_arcs.cfg"))
    run = run_pipe(args.bin, xy_file, tmp, camber_args=args.extra)
    scale, sampling, issues = stream_notes(run["slice_stream"])
    _, _, all_issues = stream_notes(run["stream"])
    print(f"== {name}: {len(raw)} points ({os.path.relpath(pts_file, args.data)}), metres")
    print(f"   slice {name}.xy | smooth | fitspline | camber --params params.csv {' '.join(args.extra)}".rstrip())
    for stage, rc, err in run["stages"]:
        said = "; ".join(l.split(": ", 1)[-1] for l in err.splitlines() if l)[:300]
        print(f"   {stage}: exit {rc}{': ' + said if said else ''}")
    for s in sampling:
        print(f"   {s}")
    for s in all_issues:
        print(f"   issue: {s}")
    if not run["rows"]:
        print("   NO PARAMS: the pipe gave no section; nothing to compare\n")
        return [], [], [(name, "pipe", "no params row")]
    row = run["rows"][0]
    p = np.unique(raw, axis=0) * 1000.0  # mm: the stream's unit
    q = order_loop(p)
    A = uv_to_xy(row)
    le = np.array([row["le_x"], row["le_y"]])
    te = np.array([row["te_x"], row["te_y"]])
    d = (te - le) / np.linalg.norm(te - le)
    forward = np.array([1.0, 0.0]) if ct["x_trailing"][0] > ct["x_leading"][0] else np.array([-1.0, 0.0])
    print(f"   input unit: {'converted to mm, x%g' % scale if scale != 1 else 'read as mm (not converted)'};"
          f" flags {int(row['flags'])} ({', '.join(flagged_by(row['flags'], '', {b: (n, None) for b, (n, _) in bits.items()})) or 'none'})")
    print(f"   frame check (not judged): axial extent of the points {np.ptp(p[:, 0]):.3f} mm,"
          f" cfg x_trailing - x_leading {1000 * (ct['x_trailing'][0] - ct['x_leading'][0]):.3f} mm;"
          f" loop ordered here: {'yes' if q is not None else 'NO (lengths not checked)'}")
    rows = []  # (column, ours, reference, ref note, diff text, within, flags)

    def add_angle(col, ours, ref, alt):
        diff = wrap(ours - ref)
        rows.append((col, ours, ref, f"cfg CT (CA {alt:.2f})", f"{diff:+.2f} deg", abs(diff) <= ANGLE_TARGET))

    def add_length(col, ours, ref, note):
        """ref: a value, a (lo, hi) range, or None (nothing to compare with)."""
        if ref is None:
            rows.append((col, ours, None, note, "", None))
            return
        lo, hi = ref if isinstance(ref, tuple) else (ref, ref)
        nearest = min(max(ours, lo), hi)
        rel = (ours - nearest) / nearest
        rows.append((col, ours, ref, note, f"{100 * rel:+.2f} %", abs(rel) <= LENGTH_TARGET))

    add_angle("stagger", angle_xy(row["stagger"], A), ct["stagger"][0], ca["stagger"][0])
    add_angle("inlet_angle", angle_xy(row["inlet_angle"], A), ct["theta_in"][0], ca["theta_in"][0])
    add_angle("outlet_angle", angle_xy(row["outlet_angle"], A), ct["theta_out"][0], ca["theta_out"][0])
    sign = 1 if np.linalg.det(A) > 0 else -1
    add_angle("camber_angle", sign * row["camber_angle"], ct["theta_in"][0] - ct["theta_out"][0],
              ca["theta_in"][0] - ca["theta_out"][0])
    if q is not None:
        add_length("chord", row["chord"], float(np.ptp(q @ d)), "extent along our chord line")
        cal = caliper(q, forward)
        if cal and row.get("caliper_found", 1):
            add_length("caliper_chord", row["caliper_chord"], cal[0], "extent along the hull's bridge")
            add_angle("caliper_stagger", angle_xy(row["caliper_stagger"], A), cal[1], float("nan"))
            rows[-1] = rows[-1][:3] + ("hull's bridge",) + rows[-1][4:]
        add_length("max_thickness", row["max_thickness"], max_inscribed(q), "largest inscribed circle")
        unit = lambda deg: np.array([math.cos(math.radians(deg)), math.sin(math.radians(deg))])
        # the edges point along the reference's camber line out of the blade
        for col, end in (("le_radius", -unit(ct["theta_in"][0])), ("te_radius", unit(ct["theta_out"][0]))):
            lo, hi, why = edge_radius(q, end)
            shape = int(row[col[:2] + "_shape"])
            note = f"{why}; ours {['round', 'blunt', 'sharp'][shape] if 0 <= shape <= 2 else shape}"
            add_length(col, row[col], None if lo is None else (lo if lo == hi else (lo, hi)), note)
    print(f"   {'column':15s} {'ours':>10s} {'reference':>10s} {'diff':>11s} {'target':>7s}  {'flagged by':22s} verdict   reference")
    silent, off_flagged = [], []
    for col, ours, ref, note, diff, within in rows:
        fl = flagged_by(row["flags"], col, bits)
        if within is None:
            verdict = "n/a"
        elif within:
            verdict = "ok" if not fl else "ok, flagged"
        else:
            verdict = "FLAGGED" if fl else "SILENT WRONG"
            (off_flagged if fl else silent).append((name, col, ours, ref, diff, note, fl))
        target = "1 deg" if col.endswith(("stagger", "angle")) else "2 %"
        ref_txt = ref_text(ref).rjust(10)
        print(f"   {col:15s} {ours:10.3f} {ref_txt} {diff:>11s} {target:>7s}  {','.join(fl) or '-':22s} {verdict:9s} {note}")
    print()
    return silent, off_flagged, []


# ----- APU rotor: what comes out, recorded --------------------------------------------------

def apu(folder, args, bits, tmp):
    """APU_rotor through the pipe as a user would try it; per section with params, its chord
    against the extent along its chord line of the raw points within the section's band
    (the `# band` half width slice used; a lower bound of the section's length)."""
    raw = np.loadtxt(os.path.join(folder, "MoveSurface.txt"))[:, 1:4]
    xyz = os.path.join(tmp, "APU_rotor.xyz")
    np.savetxt(xyz, raw, fmt="%.9g")
    refused, silent, off_flagged = [], [], []
    r = np.hypot(raw[:, 0], raw[:, 1]) * 1000
    print(f"== APU_rotor: {len(raw)} points, metres, 3D (radial rotor; axis z here: z {raw[:, 2].min() * 1000:.1f}.."
          f"{raw[:, 2].max() * 1000:.1f} mm, radius {r.min():.1f}..{r.max():.1f} mm)")
    print("   no reference for planar sections (parablade's values are on surfaces of revolution);"
          " only the chord against the raw points in the section's band")
    for slice_args in ([], ["--count", "5"]):
        run = run_pipe(args.bin, xyz, tmp, slice_args, args.extra)
        scale, sampling, _ = stream_notes(run["slice_stream"])
        _, _, issues = stream_notes(run["stream"])
        frames = {int(f["section"]): f for f in table(run["slice_stream"], "frames")} if os.path.exists(run["slice_stream"]) else {}
        band = {}
        for line in open(run["slice_stream"]):
            m = re.match(r"# band section=(\d+) half_width=([\d.eE+-]+)", line)
            if m:
                band[int(m[1])] = float(m[2])
        label = "APU_rotor " + (" ".join(slice_args) or "(no planes)")
        print(f"   slice APU_rotor.xyz {' '.join(slice_args)} | smooth | fitspline | camber --params params.csv")
        for stage, rc, err in run["stages"]:
            said = "; ".join(l.split(": ", 1)[-1] for l in err.splitlines() if l)
            print(f"   {stage}: exit {rc}{': ' + said[:400] if said else ''}")
            if rc != 0 and not any(x[0] == label for x in refused):  # the first stage that failed
                last = [l for l in err.splitlines() if "error" in l or "incomplete" in l] or [said]
                refused.append((label, stage, f"exit {rc}: {last[-1][:200]}"))
        for s in sampling:
            print(f"   {s}")
        print(f"   sections sliced: {len(frames)}, with params: {len(run['rows'])}")
        for s in issues:
            print(f"   issue: {s[:160]}")
        if run["rows"]:
            print(f"   {'sec':>3s} {'chord':>8s} {'in band':>8s} {'diff':>9s} {'t_max':>7s} {'stagger':>8s} {'inlet':>8s}"
                  f" {'outlet':>8s} {'LE r':>6s} {'TE r':>6s}  flags; chord verdict")
        for row in run["rows"]:
            sec = int(row["section"])
            f = frames[sec]
            le, te = (np.array([row[f"{k}_{c}"] for c in "xyz"]) for k in ("le", "te"))
            d, nrm = (te - le) / np.linalg.norm(te - le), np.array([f["n_x"], f["n_y"], f["n_z"]])
            origin = np.array([f["origin_x"], f["origin_y"], f["origin_z"]])
            pts = raw * scale
            near = pts[np.abs((pts - origin) @ nrm) <= band.get(sec, 0.0)]
            ext = float(np.ptp(near @ d)) if len(near) > 1 else None
            rel = (row["chord"] - ext) / ext if ext else None
            fl = flagged_by(row["flags"], "chord", bits)
            verdict = "n/a" if rel is None else "ok" if abs(rel) <= LENGTH_TARGET else "FLAGGED" if fl else "SILENT WRONG"
            if verdict in ("FLAGGED", "SILENT WRONG"):
                item = (label + f" section {sec}", "chord", row["chord"], ext, f"{100 * rel:+.1f} %",
                        f"raw points within +-{band.get(sec, 0):.2f} mm of the plane reach {ext:.2f} mm along the chord line", fl)
                (off_flagged if fl else silent).append(item)
            every = flagged_by(row["flags"], "", {b: (n, None) for b, (n, _) in bits.items()})
            print(f"   {sec:3d} {row['chord']:8.3f} {ref_text(ext):>8s} {'' if rel is None else f'{100 * rel:+.1f} %':>9s}"
                  f" {row['max_thickness']:7.3f} {row['stagger']:8.2f} {row['inlet_angle']:8.2f} {row['outlet_angle']:8.2f}"
                  f" {row['le_radius']:6.3f} {row['te_radius']:6.3f}  {int(row['flags'])} {','.join(every) or '-'}; {verdict}")
        print()
    return silent, off_flagged, refused


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--bin", default=os.environ.get("SECTION_BIN", os.path.join(root, "build", "tools")))
    ap.add_argument("--data", default=os.path.join(root, "..", "shared", "data", "real"))
    ap.add_argument("--keep", help="keep the streams and params here")
    ap.add_argument("extra", nargs="*", help="options for camber (the defaults when none)")
    args = ap.parse_args()
    args.data = os.path.abspath(args.data)
    folder = os.path.join(args.data, "parablade")
    if not os.path.isdir(folder):
        print(f"validate_parablade: skipped: no {folder} (the real data are not part of the repository)")
        return 0
    if not all(os.access(os.path.join(args.bin, t), os.X_OK) for t in ("slice", "smooth", "fitspline", "camber")):
        print(f"validate_parablade: need the tools in {args.bin}", file=sys.stderr)
        return 2
    bits = check_bits()
    silent, off_flagged, refused = [], [], []
    with tempfile.TemporaryDirectory() as scratch:
        for name in ("Aachen_2D", "Impulse_2D", "STD10_2D"):
            tmp = os.path.join(args.keep or scratch, name)
            os.makedirs(tmp, exist_ok=True)
            s, f, r = compare_2d(name, os.path.join(folder, name), args, bits, tmp)
            silent, off_flagged, refused = silent + s, off_flagged + f, refused + r
        tmp = os.path.join(args.keep or scratch, "APU_rotor")
        os.makedirs(tmp, exist_ok=True)
        s, f, r = apu(os.path.join(folder, "APU_rotor"), args, bits, tmp)
        silent, off_flagged, refused = silent + s, off_flagged + f, refused + r
    print("Summary")
    for g, col, ours, ref, diff, note, _ in silent:
        print(f"  SILENT WRONG  {g} {col}: {ours:.3f} against {ref_text(ref)} ({diff}; {note})")
    for g, col, ours, ref, diff, note, fl in off_flagged:
        print(f"  flagged, off  {g} {col}: {ours:.3f} against {ref_text(ref)} ({diff}; flagged by {','.join(fl)})")
    for g, stage, what in refused:
        print(f"  refused       {g} {stage}: {what}")
    print(f"  {len(silent)} silent wrong, {len(off_flagged)} flagged and off, {len(refused)} refused or failed")
    return 1 if silent else 0


if __name__ == "__main__":
    sys.exit(main())
