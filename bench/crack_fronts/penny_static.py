#!/usr/bin/env python3
"""Penny crack in a block under remote tension, damped to static (issue 17, validation 1).

A quarter model (symmetry planes x = 0 and y = 0) of a block of half-width W and half-height H
around a penny crack of radius a on the node plane z = 0, pulled by sigma on its z faces (ramped),
kinetic damping to the static state. Prints, per run, K_I / (2 sigma sqrt(a / pi)) over the front
nodes whose contours are complete (the two on the symmetry planes are flagged and left out), the
largest |K_II|, |K_III| / reference, and the wall time.

Usage: bench/crack_fronts/penny_static.py [--cleave build/bin/cleave] [--out DIR]
          [--cells 8] [--blocks 2,3,4] [--radii 2,4] [--volume-term] [--end-us 150] [--threads N]
          [--shape-function linear|ugimp] [--tip-cut CELLS]
"""
import argparse, math, pathlib

from fronts_run import run_scene

root = pathlib.Path(__file__).resolve().parents[2]
ap = argparse.ArgumentParser()
ap.add_argument("--cleave", default=str(root / "build/bin/cleave"))
ap.add_argument("--out", default="/tmp/cleave_penny")
ap.add_argument("--cells", type=int, default=8, help="crack radius in cells")
ap.add_argument("--blocks", default="3", help="block half-widths (and half-heights) in crack radii")
ap.add_argument("--radii", default="2", help="contour radii in cells")
ap.add_argument("--volume-term", action="store_true")
ap.add_argument("--end-us", type=float, default=150.0)
ap.add_argument("--damping", type=float, default=0.1, help="kinetic damping, 1/us")
ap.add_argument("--ppc", type=int, default=2)
ap.add_argument("--shape-function", default="linear", help="linear or ugimp")
ap.add_argument("--threads", default="")
ap.add_argument("--tip-cut", type=float, help="cracks[0].tip_cut, cells (default: the scene default)")
ap.add_argument("--integral", default="contour", help="contour (eqs. 32-33) or domain (J1 by the domain integral)")
ap.add_argument("--along", type=float, help="domain integral: the weight's half-length along the front, cells")
ap.add_argument("--inner", type=float, help="domain integral: the part of the radius where the weight is 1")
args = ap.parse_args()
domain_keys = {"integral": args.integral, **({"along": args.along} if args.along is not None else {}),
               **({"inner": args.inner} if args.inner is not None else {})}

a, sigma = 8.0, 10.0  # mm, MPa
h = a / args.cells


def scene(block, radius):
    W = block * a
    return {
        "title": f"penny crack a = {args.cells} cells, block {block}a, contour {radius} cells",
        "units": {"length": "mm", "stress": "MPa", "density": "g/cm3", "time": "us", "inverse_time": "1/us"},
        "analysis": {"type": "3d"},
        "resolution": h,
        "grid": {"min": [-2 * h, -2 * h, -W - 2 * h], "max": [W + 2 * h, W + 2 * h, W + 2 * h]},
        "mpm": {"shape_function": args.shape_function, "stress_update": "USAVG"},
        "materials": [{"name": "m", "type": "linear_elastic", "E": 3000, "nu": 0.3, "density": 1.19}],
        "bodies": [{"name": "block", "material": "m", "particles_per_cell": args.ppc,
                    "shape": {"type": "box", "min": [0, 0, -W], "max": [W, W, W]}}],
        "cracks": [{"name": "penny", "ellipse": {"center": [0, 0, 0], "normal": [0, 0, 1], "radius": a},
                    "contact": {"law": "frictionless"},
                    **({"tip_cut": args.tip_cut} if args.tip_cut is not None else {})}],
        "loads": [{"type": "symmetry", "axis": "x", "position": 0},
                  {"type": "symmetry", "axis": "y", "position": 0},
                  {"type": "traction", "face": "+z", "traction": [0, 0, sigma], "rise_time": 20},
                  {"type": "traction", "face": "-z", "traction": [0, 0, -sigma], "rise_time": 20}],
        "damping": {"kinetic": args.damping},
        "time": {"end": args.end_us, "cfl": 0.5},
        "crack_tips": {"radius": radius, "volume_term": args.volume_term, **domain_keys,
                       "reference": {"type": "embedded_crack", "crack": "penny", "stress": sigma}},
        "output": {"interval": args.end_us, "tip_interval": args.end_us / 10, "precision": "float32",
                   "fields": ["displacement"]},
    }


print(f"a = {args.cells} cells ({h:g} mm), reference K_I = 2 sigma sqrt(a/pi) = "
      f"{2 * sigma * 1e6 * math.sqrt(a * 1e-3 / math.pi):.6g} Pa m^1/2")
print("block | contour | t (us) | K_I/ref min..max (mean) | max |K_II|/ref | max |K_III|/ref | nodes | wall (s)")
for block in [float(b) for b in args.blocks.split(",")]:
    for radius in [float(r) for r in args.radii.split(",")]:
        tag = (f"c{args.cells}_b{block:g}_r{radius:g}{'_v' if args.volume_term else ''}_{args.shape_function}"
               f"{'' if args.tip_cut is None else f'_cut{args.tip_cut:g}'}_{args.integral}{args.along or ''}{args.inner or ''}")
        rows, times, wall = run_scene(args.cleave, scene(block, radius), pathlib.Path(args.out) / tag, args.threads)
        for t in times[-3:]:
            good = [r for r in rows if float(r["time_s"]) == t and int(float(r["flag"])) == 0]
            ki = [float(r["KI_Pa_sqrt_m"]) / float(r["KI_ref_Pa_sqrt_m"]) for r in good]
            k2 = max(abs(float(r["KII_Pa_sqrt_m"])) / float(r["KI_ref_Pa_sqrt_m"]) for r in good)
            k3 = max(abs(float(r["KIII_Pa_sqrt_m"])) / float(r["KI_ref_Pa_sqrt_m"]) for r in good)
            print(f"{block:g}a | {radius:g} | {t * 1e6:.0f} | {min(ki):.4f}..{max(ki):.4f} ({sum(ki) / len(ki):.4f}) | "
                  f"{k2:.4f} | {k3:.4f} | {len(good)} | {wall:.0f}", flush=True)
