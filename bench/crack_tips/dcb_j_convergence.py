#!/usr/bin/env python3
"""Mesh convergence of the static DCB J-integral (issue 4, validation 5).

Runs data/scenes/dcb_crack.json at cell sizes 4, 2, 1 and 0.5 mm (crack tip half-way between node
columns, crack on a node row, as in the scene), with crack_tips at the default 2-cell contour and at
4 cells, and prints J against beam theory with shear and root rotation (validation.md §3) with the
wall time of each run. Usage: bench/crack_tips/dcb_j_convergence.py [build/bin/cleave] [OUTDIR]
"""
import csv, json, pathlib, subprocess, sys, time

root = pathlib.Path(__file__).resolve().parents[2]
cleave = sys.argv[1] if len(sys.argv) > 1 else str(root / "build/bin/cleave")
outdir = pathlib.Path(sys.argv[2] if len(sys.argv) > 2 else "/tmp/cleave_dcb_j")
P, E, nu, b, h = 0.4e-3, 1e5, 0.33, 1e-3, 18e-3
G = E / (2 * (1 + nu))
a = 50e-3 + 0.64 * h
G_beam = 12 * P**2 * a**2 / (E * b**2 * h**3) + 6 * P**2 / (5 * G * b**2 * h)
grids = {4: ([-8, -24], [108, 24]), 2: ([-5, -22], [105, 22]), 1: ([-5.5, -22], [104.5, 22]), 0.5: ([-5.25, -22], [104.75, 22])}
print(f"beam theory with shear and root rotation: G = {G_beam:.5f} J/m^2")
print("cell (mm) | contour 2 cells: J (J/m^2), vs beam | contour 4 cells: J, vs beam | wall (s), each run")
for cell in (4, 2, 1, 0.5):
    row = [f"{cell:g}"]
    for radius in (2, 4):
        s = json.loads((root / "data/scenes/dcb_crack.json").read_text())
        s["grid"] = {"cell_size": cell, "min": grids[cell][0], "max": grids[cell][1]}
        s["cracks"][0]["segment_length"] = cell
        s["crack_tips"] = {"interval": 0.1, "radius": radius}
        out = outdir / f"h{cell}_r{radius}"
        out.mkdir(parents=True, exist_ok=True)
        (out / "scene.json").write_text(json.dumps(s))
        t0 = time.time()
        subprocess.run([cleave, "run", str(out / "scene.json"), "--out", str(out / "run")], check=True,
                       stdout=subprocess.DEVNULL)
        wall = time.time() - t0
        J = float(list(csv.DictReader(open(out / "run/crack_tips.csv")))[-1]["J1_J_per_m2"])
        row.append(f"{J:.5f}, {100 * (J / G_beam - 1):+.2f} %")
        row.append(f"{wall:.1f}")
    print(" | ".join([row[0], row[1], row[3], f"{row[2]} / {row[4]}"]))
