#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Hollow blades: generated scans with cooling channels, each channel's thinnest wall as
camber's walls table gives it against the exact one, and the profile's values against the
same scan without the channels. Numpy is not needed.

For each kind, seed and noise: `bladegen --points` over z 15-45, and at each plane (z 20,
30, 40) two channels, short cylinders (z +-1.5 mm about the plane, points every 0.08 mm, the
scan's noise along the radius), centred on the exact section's camber line at 30 % and 60 %
of it and moved across it by up to 0.3 mm, their thinnest walls drawn from 0.2-1.0 mm. The
exact walls: the least distance from the channel's centre to the exact section (the
generator's mesh, 4000 points around, cut by the plane), and to each of its sides (parted at
the mesh's LE and TE points), less its radius; each against the walls table's wall,
pressure_wall and suction_wall. Prints each wall off by more than --tolerance and every
flag, then a summary line: sections measured and refused, walls (three a channel) within the
tolerance, the largest error, walls flagged, and the largest change of the profile's values
(chord, max thickness, edge radii) that the channels make.

    python3 scripts/probe_hollow.py --seeds 1,2,3 --noise 0.002,0.005,0.01
"""
import argparse
import csv
import math
import os
import random
import subprocess
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
HEIGHTS = [20, 30, 40]


def rows(path):
    with open(path) as f:
        return list(csv.DictReader(f))


def run(cmd):
    return subprocess.run(cmd, shell=True, capture_output=True, text=True)


def exact_sections(b, kind, d):
    """Per height: the exact section's points (a polyline) and its camber line (the pipe on
    the generator's fine mesh)."""
    subprocess.run([f"{b}/bladegen", "--kind", kind, "--mesh", "--profile-points", "4000", "--layers", "241",
                    "-o", f"{d}/m.stl"], check=True, capture_output=True)
    at = ",".join(map(str, HEIGHTS))
    r = run(f"{b}/slice {d}/m.stl --at {at} > {d}/m.slice && {b}/smooth {d}/m.slice | {b}/fitspline | "
            f"{b}/camber -o {d}/m.stream")
    if r.returncode:
        raise SystemExit(f"probe_hollow: the exact mesh's pipe failed: {r.stderr[-300:]}")
    out = {}
    for name, path in (("points", f"{d}/m.slice"), ("camber", f"{d}/m.stream"), ("sides", f"{d}/m.stream")):
        for row in stream_rows(open(path).read(), name):
            r = {k: float(v) for k, v in row.items()}
            if name == "points" and r["loop"] != 0:
                continue
            key = f"side{int(r['side'])}" if name == "sides" else name
            out.setdefault(int(r["section"]), {}).setdefault(key, []).append((r["u"], r["v"]))
    for sec in out.values():
        sec["pressure"], sec["suction"] = split_sides(sec["points"], sec["side0"], sec["side1"])
    return out


def stream_rows(text, name):
    """The rows of table `name` in a stream's text, as dicts of its columns' cells."""
    out, on, head = [], False, None
    for line in text.split("\n"):
        if line.startswith("# table"):
            on, head = line.split()[2] == name, None
            continue
        if not on or not line or line.startswith("#"):
            continue
        if head is None:
            head = line.split(",")
            continue
        out.append(dict(zip(head, line.split(","))))
    return out


def arguments(doc, kinds):
    """The probes' command line: --bin, --kinds, --seeds, --noise, --tolerance."""
    ap = argparse.ArgumentParser(description=doc.split("\n")[0])
    ap.add_argument("--bin", default=os.path.join(HERE, "..", "build", "tools"))
    ap.add_argument("--kinds", default=kinds)
    ap.add_argument("--seeds", default="1,2")
    ap.add_argument("--noise", default="0.002,0.005")
    ap.add_argument("--tolerance", type=float, default=0.005, help="mm")
    return ap.parse_args()


def split_sides(poly, pressure, suction):
    """The exact profile's points parted at the mesh's LE and TE points (the ends of camber's
    sampled sides), each part the side whose samples it lies nearer."""
    def nearest(p):
        return min(range(len(poly)), key=lambda i: math.hypot(poly[i][0] - p[0], poly[i][1] - p[1]))
    a, b = sorted((nearest(pressure[0]), nearest(pressure[-1])))
    one, other = poly[a:b + 1], poly[b:] + poly[:a + 1]
    mid = one[len(one) // 2]
    if distance_to(suction, mid, closed=False) < distance_to(pressure, mid, closed=False):
        one, other = other, one
    return one, other


def distance_to(poly, c, closed=True):
    best = math.inf
    for i in range(len(poly) if closed else len(poly) - 1):
        ax, ay = poly[i]
        bx, by = poly[(i + 1) % len(poly)]
        dx, dy = bx - ax, by - ay
        t = max(0.0, min(1.0, ((c[0] - ax) * dx + (c[1] - ay) * dy) / (dx * dx + dy * dy)))
        best = min(best, math.hypot(ax + t * dx - c[0], ay + t * dy - c[1]))
    return best


def channel_points(c, r, z, noise, rng, spacing=0.08):
    n = max(8, int(math.ceil(2 * math.pi * r / spacing)))
    out = []
    zz = z - 1.5
    while zz <= z + 1.5:
        phase = rng.random()
        for i in range(n):
            t = 2 * math.pi * (i + phase) / n
            rr = r + rng.gauss(0, noise)
            out.append((c[0] + rr * math.cos(t), c[1] + rr * math.sin(t), zz + rng.uniform(-0.02, 0.02)))
        zz += spacing
    return out


def main():
    args = arguments(__doc__, "turbine,compressor,thick-root,sharp-te")
    b = args.bin
    measured = refused = walls = within = flagged = 0
    worst = 0.0
    scores = []  # each wall's error over its wall_sigma
    stations = []  # (error, flagged) of every 5th station of each wall map: its wall against the exact section
    moved = {"chord": 0.0, "max_thickness": 0.0, "le_radius": 0.0, "te_radius": 0.0}
    at = ",".join(map(str, HEIGHTS))
    with tempfile.TemporaryDirectory() as d:
        for kind in args.kinds.split(","):
            exact = exact_sections(b, kind, d)
            for seed in [int(s) for s in args.seeds.split(",")]:
                for noise in [float(n) for n in args.noise.split(",")]:
                    subprocess.run([f"{b}/bladegen", "--kind", kind, "--points", "--noise", str(noise), "--seed",
                                    str(seed), "--z-min", "15", "--z-max", "45", "-o", f"{d}/s.xyz"],
                                   check=True, capture_output=True)
                    rng = random.Random(seed * 1000 + int(noise * 1e4))
                    truth = {}  # section -> [(centre, radius, wall)]
                    extra = []
                    for k, z in enumerate(HEIGHTS):
                        cam, poly = exact[k]["camber"], exact[k]["points"]
                        for frac in (0.3, 0.6):
                            # Off the camber line by up to 0.3 mm across it (a shifted core):
                            # each side's wall its own.
                            i = int(frac * len(cam))
                            tx, ty = cam[i + 1][0] - cam[i - 1][0], cam[i + 1][1] - cam[i - 1][1]
                            shift = rng.uniform(-0.3, 0.3) / math.hypot(tx, ty)
                            c = (cam[i][0] - ty * shift, cam[i][1] + tx * shift)
                            wall = rng.uniform(0.2, 1.0)
                            sides = [distance_to(exact[k][s], c, closed=False) for s in ("pressure", "suction")]
                            r = min(sides) - wall
                            if r < 0.2:
                                continue
                            truth.setdefault(k, []).append((c, r, wall, sides[0] - r, sides[1] - r))
                            extra += channel_points(c, r, z, noise, rng)
                    with open(f"{d}/s.xyz") as f, open(f"{d}/h.xyz", "w") as out:
                        out.write(f.read())
                        out.writelines(f"{x:.5f} {y:.5f} {z:.5f}\n" for x, y, z in extra)
                    tail = f"| {b}/smooth | {b}/fitspline | {b}/camber --format csv --allow-partial"
                    solid = run(f"{b}/slice {d}/s.xyz --at {at} {tail}")
                    hollow = run(f"{b}/slice {d}/h.xyz --at {at} {tail} --walls {d}/w.csv --wall-map {d}/m.csv")
                    s_rows = {int(r["section"]): r for r in csv.DictReader(solid.stdout.splitlines())}
                    h_rows = {int(r["section"]): r for r in csv.DictReader(hollow.stdout.splitlines())}
                    w_rows = rows(f"{d}/w.csv") if os.path.exists(f"{d}/w.csv") else []
                    for m in rows(f"{d}/m.csv") if os.path.exists(f"{d}/m.csv") else []:
                        if int(float(m["station"])) % 5 == 0:
                            at_station = (float(m["cavity_u"]), float(m["cavity_v"]))
                            exact_wall = distance_to(exact[int(float(m["section"]))]["points"], at_station)
                            stations.append((float(m["wall"]) - exact_wall, int(float(m["flags"])) != 0))
                    for k, z in enumerate(HEIGHTS):
                        label = f"{kind:10s} seed {seed} noise {noise} z {z}"
                        if k not in h_rows:
                            refused += 1
                            print(f"{label}: refused: {hollow.stderr.strip()[-300:]}")
                            continue
                        measured += 1
                        if k in s_rows:
                            for c in moved:
                                change = abs(float(h_rows[k][c]) - float(s_rows[k][c]))
                                moved[c] = max(moved[c], change)
                                if change > args.tolerance:
                                    print(f"{label}: the channels move {c} by {change * 1000:.1f} um (flags "
                                          f"{int(float(s_rows[k]['flags']))} without, "
                                          f"{int(float(h_rows[k]['flags']))} with)")
                        mine = [w for w in w_rows if int(float(w["section"])) == k]
                        for c, r, wall, pressure, suction in truth.get(k, []):
                            near = [w for w in mine if math.hypot(float(w["cavity_u"]) - c[0],
                                                                  float(w["cavity_v"]) - c[1]) < r + 0.05]
                            if len(near) != 1:
                                walls += 3
                                print(f"{label}: channel of wall {wall:.3f} mm not in the walls table")
                                continue
                            w = near[0]
                            for name, true, flag in (("wall", wall, "flags"),
                                                     ("pressure_wall", pressure, "pressure_flags"),
                                                     ("suction_wall", suction, "suction_flags")):
                                walls += 1
                                err = float(w[name]) - true
                                worst = max(worst, abs(err))
                                sigma = float(w["wall_sigma"])
                                if sigma > 0:
                                    scores.append(err / sigma)
                                within += abs(err) <= args.tolerance
                                flags = int(float(w[flag]))
                                flagged += flags != 0
                                if abs(err) > args.tolerance or flags:
                                    print(f"{label}: {name} {true:.4f} mm measured {float(w[name]):.4f} "
                                          f"({err * 1000:+.1f} um, wall_sigma "
                                          f"{float(w['wall_sigma']) * 1000:.1f} um), flags {flags}")
    print(f"hollow: {measured} sections measured, {refused} refused; {within} of {walls} walls within "
          f"{args.tolerance * 1000:.0f} um (largest error {worst * 1000:.1f} um), {flagged} flagged; the channels "
          f"move the profile's values by at most " +
          ", ".join(f"{c} {v * 1000:.1f} um" for c, v in moved.items()))
    if stations:
        within_map = sum(abs(e) <= args.tolerance for e, _ in stations)
        print(f"wall maps: {len(stations)} stations (every 5th), {within_map} within "
              f"{args.tolerance * 1000:.0f} um of the exact section's distance, largest "
              f"{max(abs(e) for e, _ in stations) * 1000:.1f} um, {sum(f for _, f in stations)} flagged, "
              f"beyond {args.tolerance * 1000:.0f} um unflagged: "
              f"{sum(abs(e) > args.tolerance and not f for e, f in stations)}")
    if scores:
        rms = math.sqrt(sum(z * z for z in scores) / len(scores))
        print(f"errors over wall_sigma: rms {rms:.2f}, largest {max(abs(z) for z in scores):.2f}, beyond 3: "
              f"{sum(abs(z) > 3 for z in scores)} of {len(scores)}")


if __name__ == "__main__":
    main()
