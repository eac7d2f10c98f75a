#!/usr/bin/env python3
"""Writes data/scenes/pem_three_point_bend.json: a concrete three-point bend beam with aggregate,
mortar and interface (ITZ) phases (seed 004 section 4.3), for the particle equilibrium method.

Aggregates are disks placed at random (fixed seed: the scene is the same on every machine) without
overlap, each wrapped in an interface ring of width `itz`; the mortar is the beam minus the rings and
aggregates. The three bodies touch, so Gmsh meshes them conforming and their particles bond across
the boundaries; each pair follows the law of the weakest material of its elements, so every pair of
an interface element is an interface pair.

usage: concrete_beam.py [--length MM] [--depth MM] [--rmin MM] [--rmax MM] [--fraction F]
                        [--itz MM] [--size MM] [--seed N] [--out FILE]
"""
import json, math, random, sys

o = {"--length": 100.0, "--depth": 25.0, "--rmin": 2.0, "--rmax": 4.0, "--fraction": 0.3, "--itz": 0.5,
     "--size": 0.75, "--seed": 7, "--out": "data/scenes/pem_three_point_bend.json"}
it = iter(sys.argv[1:])
for a in it:
    o[a] = type(o[a])(next(it)) if not isinstance(o[a], str) else next(it)
L, H, w = o["--length"], o["--depth"], o["--itz"]
rng = random.Random(o["--seed"])
disks, area, tries = [], 0.0, 0
margin = 1.5 * w
while area < o["--fraction"] * L * H and tries < 200000:
    tries += 1
    r = rng.uniform(o["--rmin"], o["--rmax"])
    x = rng.uniform(r + w + margin, L - r - w - margin)
    y = rng.uniform(r + w + margin, H - r - w - margin)
    if all(math.hypot(x - a, y - b) > r + rb + 2 * w + margin for a, b, rb in disks):
        disks.append((x, y, r))
        area += math.pi * r * r
disk = lambda x, y, r: {"type": "disk", "center": [round(x, 4), round(y, 4), ][:2], "radius": round(r, 4)}
aggregate = {"type": "union", "shapes": [disk(x, y, r) for x, y, r in disks]}
rings = {"type": "union", "shapes": [disk(x, y, r + w) for x, y, r in disks]}
span = 0.9 * L
scene = {
    "title": "Concrete three-point bend beam with aggregate, mortar and interface phases (seed 004 section 4.3)",
    "description": (f"A {L:g} mm x {H:g} mm beam, 10 mm thick, plane stress, span {span:g} mm, loaded at mid-span by a "
                    f"prescribed velocity (0, -0.05) m/s on the top particles within 1 mm of the centre (which also holds the beam in x); the "
                    f"supports hold the bottom particles within 1 mm of x = {(L - span) / 2:g} and {(L + span) / 2:g} mm "
                    f"in y. {len(disks)} aggregates (radius {o['--rmin']:g} to {o['--rmax']:g} mm, area fraction "
                    f"{area / (L * H):.2f}, placed at random with seed {o['--seed']}) each wrapped in a {w:g} mm interface "
                    "ring (ITZ). Phases (seed 004's values were lost; typical of the literature): aggregate E 50 GPa, "
                    "tensile strength 10 MPa, G 60 J/m2; mortar E 25 GPa, 4 MPa, 40 J/m2; interface E 15 GPa, 2 MPa, "
                    "15 J/m2. The run ends when the beam separates. Written by bench/pem/concrete_beam.py."),
    "method": "pem",
    "units": {"length": "mm", "stress": "MPa", "density": "kg/m3", "time": "ms", "inverse_time": "1/ms",
              "velocity": "m/s"},
    "analysis": {"type": "plane_stress", "thickness": 10},
    "resolution": o["--size"],
    "materials": [
        {"name": "aggregate", "type": "linear_elastic", "E": 50000, "density": 2700, "tensile_strength": 10,
         "fracture_energy": 0.06},
        {"name": "mortar", "type": "linear_elastic", "E": 25000, "density": 2200, "tensile_strength": 4,
         "fracture_energy": 0.04},
        {"name": "interface", "type": "linear_elastic", "E": 15000, "density": 2000, "tensile_strength": 2,
         "fracture_energy": 0.015}],
    "bodies": [
        {"name": "mortar", "material": "mortar",
         "shape": {"type": "difference", "shapes": [{"type": "rectangle", "min": [0, 0], "max": [L, H]}, rings]}},
        {"name": "interface", "material": "interface", "shape": {"type": "difference", "shapes": [rings, aggregate]}},
        {"name": "aggregate", "material": "aggregate", "shape": aggregate}],
    "loads": [
        {"type": "velocity", "region": {"min": [L / 2 - 1, H - 0.01], "max": [L / 2 + 1, H + 0.01]}, "velocity": [0, -0.05]},
        {"type": "velocity", "region": {"min": [(L - span) / 2 - 1, -0.01], "max": [(L - span) / 2 + 1, 0.01]},
         "velocity": [None, 0]},
        {"type": "velocity", "region": {"min": [(L + span) / 2 - 1, -0.01], "max": [(L + span) / 2 + 1, 0.01]},
         "velocity": [None, 0]}],
    "damping": {"kinetic": 20},
    "time": {"end": 3, "cfl": 0.8},
    "output": {"interval": 0.05, "global_interval": 0.005}
}
json.dump(scene, open(o["--out"], "w"), indent=1)
print(f"{len(disks)} aggregates, area fraction {area / (L * H):.3f} -> {o['--out']}")
