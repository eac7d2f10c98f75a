#!/usr/bin/env python3
"""Initiation angle of the wing cracks of a PEM run of data/scenes/pem_brazilian_cracked.json.

Reads the run's crack frames (cracks_*.vtu: pieces of the crack traced through broken pairs, point
array "initial" = 1 for the pre-crack's pieces) and, for each tip of the pre-crack, takes the first
frame in which pieces broken during the run reach `reach` from the tip: the initiation direction is
the mean direction from the tip to those pieces lying between `inner` and `reach` from it. Prints the
angle between the pre-crack's outward direction and that direction (degrees, positive
counterclockwise), and the maximum hoop stress prediction from Atkinson et al.'s leading-order K_I,
K_II (validation.md section 6).

usage: brazilian_angle.py OUT [SCENE] [--inner MM] [--reach MM]
"""
import glob, json, math, sys
import numpy as np
import meshio

args, opts, it = [], {}, iter(sys.argv[1:])
for a in it:
    if a.startswith("--"):
        opts[a] = next(it)
    else:
        args.append(a)
out = args[0]
scene = json.load(open(args[1] if len(args) > 1 else "data/scenes/pem_brazilian_cracked.json"))
inner = float(opts.get("--inner", 1.5))
reach = float(opts.get("--reach", 5.0))
scale = 1e-3 if scene.get("units", {}).get("length") == "mm" else 1.0  # scene unit -> m

pts = np.array(scene["cracks"][0]["points"], float) * scale
tips = [(pts[0], pts[0] - pts[1]), (pts[-1], pts[-1] - pts[-2])]

def hoop_angle(KI, KII):
    return 2 * math.degrees(math.atan((KI - math.sqrt(KI * KI + 8 * KII * KII)) / (4 * KII)))

d = pts[-1] - pts[0]
# beta: angle between the crack and the loading (y) axis.
beta = math.atan2(abs(d[0]), abs(d[1]))
KI = 1 - 4 * math.sin(beta) ** 2
KII = 2 * math.sin(2 * beta)
theta = hoop_angle(KI, KII)
print(f"beta = {math.degrees(beta):.1f} deg; Atkinson leading order K_I/(s0 sqrt(pi a)) = {KI:.3f}, "
      f"K_II/(s0 sqrt(pi a)) = {KII:.3f}; maximum hoop stress kink {theta:.1f} deg (magnitude {abs(theta):.1f})")

frames = sorted(glob.glob(f"{out}/cracks_*.vtu"))
for k, (tip, outward) in enumerate(tips):
    outward = outward / np.linalg.norm(outward)
    found = None
    for f in frames:
        m = meshio.read(f)
        x = m.points[:, :2]
        new = np.ravel(m.point_data["initial"]) < 0.5
        r = np.linalg.norm(x - tip, axis=1)
        near = new & (r < reach * scale * 1.2)
        if near.any() and r[near].max() >= reach * scale:
            sel = near & (r > inner * scale) & (r <= reach * scale)
            v = ((x[sel] - tip) / r[sel, None]).mean(axis=0)
            found = (f, v / np.linalg.norm(v), sel.sum())
            break
    if not found:
        print(f"tip {k}: no wing crack reached {reach} mm from the tip")
        continue
    f, v, n = found
    ang = math.degrees(math.atan2(outward[0] * v[1] - outward[1] * v[0], outward @ v))
    print(f"tip {k} at ({tip[0]/scale:.2f}, {tip[1]/scale:.2f}): first reached {reach} mm in {f.split('/')[-1]} "
          f"({n} pieces): kink {ang:+.1f} deg from the crack line; |kink| - |prediction| = {abs(ang) - abs(theta):+.1f} deg")
