#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""A hollow blade's core shifted: `compare`'s core_shift and walls against a known shift.
Numpy is not needed.

For each kind, seed and noise: at each plane (z 20, 30, 40) two channels centred on the
exact camber line at 30 % and 60 % of it (walls 0.3-0.8 mm to each side), as probe_hollow
makes them. The nominal: the blade's scan without noise and the channels where they were
designed, through the pipe. The measured: the scan with noise and the channels moved
together (one core) by a shift drawn in the plane (0-0.15 mm, any direction). `compare
MEASURED --nominal NOMINAL`: core_shift (item 20) against the shift's length, and the
deviations of the thinnest walls to the pressure and the suction side (items 18, 19)
against the exact ones (each side's least distance, over the section's channels, from the
exact section's side, parted at the mesh's LE and TE points). Prints each value off by more
than --tolerance and every flag, then a summary line.

    python3 scripts/probe_core_shift.py --seeds 1,2,3 --noise 0.002,0.005
"""
import math
import os
import random
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
from probe_hollow import (HEIGHTS, arguments, channel_points, distance_to, exact_sections, run,  # noqa: E402
                          stream_rows)

ITEMS = {18: "pressure_wall", 19: "suction_wall", 20: "core_shift"}


def scan(b, kind, seed, noise, channels, d, name, rng):
    """The blade's scan with the channels' points added, through the pipe to camber's stream."""
    subprocess.run([f"{b}/bladegen", "--kind", kind, "--points", "--noise", str(noise), "--seed", str(seed),
                    "--z-min", "15", "--z-max", "45", "-o", f"{d}/{name}.xyz"], check=True, capture_output=True)
    extra = []
    for k, z in enumerate(HEIGHTS):
        for c, r in channels.get(k, []):
            extra += channel_points(c, r, z, noise, rng)
    with open(f"{d}/{name}.xyz", "a") as out:
        out.writelines(f"{x:.5f} {y:.5f} {z:.5f}\n" for x, y, z in extra)
    at = ",".join(map(str, HEIGHTS))
    r = run(f"{b}/slice {d}/{name}.xyz --at {at} | {b}/smooth | {b}/fitspline | {b}/camber --allow-partial "
            f"-o {d}/{name}.stream")
    if r.returncode:
        raise SystemExit(f"probe_core_shift: the pipe failed on {name}: {r.stderr[-300:]}")


def side_walls(exact, channels):
    """The least wall over the channels to each side of the exact section."""
    return [min(distance_to(exact[s], c, closed=False) - r for c, r in channels) for s in ("pressure", "suction")]


def main():
    args = arguments(__doc__, "turbine,compressor,thick-root,impulse")
    b = args.bin
    values = within = flagged = missing = 0
    worst = {name: 0.0 for name in ITEMS.values()}
    ratios = {}  # noise -> core_shift's error over its standard error (compare's uncertainty / 2)
    with tempfile.TemporaryDirectory() as d:
        for kind in args.kinds.split(","):
            exact = exact_sections(b, kind, d)
            for seed in [int(s) for s in args.seeds.split(",")]:
                rng = random.Random(seed)
                designed, shifted, truth = {}, {}, {}
                for k in range(len(HEIGHTS)):
                    cam = exact[k]["camber"]
                    length, angle = rng.uniform(0, 0.15), rng.uniform(0, 2 * math.pi)
                    dx, dy = length * math.cos(angle), length * math.sin(angle)
                    for frac in (0.3, 0.6):
                        c = cam[int(frac * len(cam))]
                        r = min(distance_to(exact[k][s], c, closed=False) for s in ("pressure", "suction"))
                        r -= rng.uniform(0.3, 0.8)
                        if r < 0.3:
                            continue
                        designed.setdefault(k, []).append((c, r))
                        shifted.setdefault(k, []).append(((c[0] + dx, c[1] + dy), r))
                    if k in designed:
                        before, after = side_walls(exact[k], designed[k]), side_walls(exact[k], shifted[k])
                        truth[k] = {18: after[0] - before[0], 19: after[1] - before[1], 20: length}
                scan(b, kind, seed, 0, designed, d, "nominal", random.Random(seed + 100))
                for noise in [float(n) for n in args.noise.split(",")]:
                    scan(b, kind, seed, noise, shifted, d, "measured", random.Random(seed * 1000 + int(noise * 1e4)))
                    r = run(f"{b}/compare {d}/measured.stream --nominal {d}/nominal.stream")
                    rows = stream_rows(r.stdout, "compared")
                    for k, expected in truth.items():
                        label = f"{kind:10s} seed {seed} noise {noise} z {HEIGHTS[k]}"
                        for item, true in expected.items():
                            name = ITEMS[item]
                            row = [x for x in rows if int(float(x["section"])) == k and int(float(x["item"])) == item]
                            values += 1
                            if len(row) != 1 or row[0]["measured"] != "1":
                                missing += 1
                                print(f"{label}: {name} not measured ({r.stderr.strip()[-200:]})")
                                continue
                            got = float(row[0]["value" if item == 20 else "deviation"])
                            err = got - true
                            worst[name] = max(worst[name], abs(err))
                            sigma = float(row[0]["uncertainty"]) / 2  # compare's coverage, 2
                            if item == 20 and sigma > 0:
                                ratios.setdefault(noise, []).append(err / sigma)
                            within += abs(err) <= args.tolerance
                            flags = int(float(row[0]["flags"]))
                            flagged += flags != 0
                            if abs(err) > args.tolerance or flags:
                                print(f"{label}: {name} {true:+.4f} mm measured {got:+.4f} ({err * 1000:+.1f} um, "
                                      f"standard error {sigma * 1000:.1f} um), flags {flags}")
    print(f"core shift: {values} values, {within} within {args.tolerance * 1000:.0f} um, {flagged} flagged, "
          f"{missing} not measured; largest errors " +
          ", ".join(f"{name} {v * 1000:.1f} um" for name, v in worst.items()))
    for noise, r in sorted(ratios.items()):
        rms = math.sqrt(sum(x * x for x in r) / len(r))
        print(f"core shift at noise {noise}: error / standard error over {len(r)} values: rms {rms:.2f}, "
              f"largest {max(abs(x) for x in r):.2f}, beyond 2: {sum(abs(x) > 2 for x in r)}")


if __name__ == "__main__":
    main()
