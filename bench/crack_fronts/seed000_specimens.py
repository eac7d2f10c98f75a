#!/usr/bin/env python3
"""The three specimens of seed 000 section 4 with crack-front parameters (issue 17, validations 2-4).

  rod       section 4.1, data/scenes/rod_elliptical_crack.json, damped to static: K_I at the deepest
            point A (x = 0, y = 20 mm) against 83.6 MPa m^1/2 (finite rod; 3 % at 3 mm cells), and
            K_I along the front against Irwin's infinite body (79.7 at A: about 5 % below).
  cylinder  section 4.2, data/scenes/cylinder_surface_crack.json (damped): K_I at the deepest point
            (x = 201 mm, y = 0) against 24.1 MPa m^1/2 (5 %).
  bar       section 4.3, data/scenes/bar_inclined_penny.json (damped) at t = 600 us: K_I, K_II, K_III
            at A, B, C (theta = 0, 45, 90 degrees from the direction of shear) against Tada's static
            values (5 % of K0).

Usage: bench/crack_fronts/seed000_specimens.py CASE [--resolution MM] [--radius MM] [--end US]
          [--damping PER_US] [--threads N] [--cleave build/bin/cleave] [--out DIR] [--no-oop]
          [--tip-cut CELLS]
Prints the figures and the wall time of the run.
"""
import argparse, json, math, pathlib

from fronts_run import run_scene

root = pathlib.Path(__file__).resolve().parents[2]
ap = argparse.ArgumentParser()
ap.add_argument("case", choices=["rod", "cylinder", "bar"])
ap.add_argument("--resolution", type=float)
ap.add_argument("--radius", type=float, help="contour radius in mm (default: 2 cells)")
ap.add_argument("--end", type=float, help="end time, us")
ap.add_argument("--damping", type=float, help="kinetic damping, 1/us")
ap.add_argument("--threads", default="")
ap.add_argument("--cleave", default=str(root / "build/bin/cleave"))
ap.add_argument("--out", default="/tmp/cleave_seed000")
ap.add_argument("--no-oop", action="store_true", help="seed 000's plain contour (out_of_plane_term false)")
ap.add_argument("--volume-term", action="store_true")
ap.add_argument("--detection", choices=["volume", "displacement", "none"],
                help="the crack's contact detection (none: no contact law); default: the scene's")
ap.add_argument("--tip-cut", type=float, help="cracks[0].tip_cut, cells (default: the scene's)")
ap.add_argument("--integral", default="contour", help="contour (eqs. 32-33) or domain (J1 by the domain integral)")
ap.add_argument("--along", type=float, help="domain integral: the weight's half-length along the front, cells")
ap.add_argument("--inner", type=float, help="domain integral: the part of the radius where the weight is 1")
args = ap.parse_args()

files = {"rod": "rod_elliptical_crack.json", "cylinder": "cylinder_surface_crack.json", "bar": "bar_inclined_penny.json"}
s = json.loads((root / "data/scenes" / files[args.case]).read_text())
if args.resolution:
    s["resolution"] = args.resolution
h = s["resolution"]
# A grid of whole cells at this resolution: each axis grown outwards to whole cells counted from 0, so that
# the planes through 0 (the scenes' symmetry planes and crack centres) stay node planes (a scene whose grid
# is already whole at this resolution is left as it is).
g = s["grid"]
for d in range(3):
    if abs((g["max"][d] - g["min"][d]) / h - round((g["max"][d] - g["min"][d]) / h)) > 1e-9:
        g["min"][d] = -math.ceil(-g["min"][d] / h - 1e-9) * h
        g["max"][d] = math.ceil(g["max"][d] / h - 1e-9) * h
defaults = {"rod": (400, 0.05), "cylinder": (500, 0.04), "bar": (600, 0.02)}
s["time"]["end"] = args.end or defaults[args.case][0]
s.setdefault("units", {})["inverse_time"] = "1/us"
s["damping"] = {"kinetic": args.damping if args.damping is not None else defaults[args.case][1]}
ct = {"radius": (args.radius / h) if args.radius else 2, "out_of_plane_term": not args.no_oop,
      "volume_term": args.volume_term, "integral": args.integral}
if args.along is not None:
    ct["along"] = args.along
if args.inner is not None:
    ct["inner"] = args.inner
if args.case == "rod":
    ct["reference"] = {"type": "embedded_crack", "crack": "ellipse", "stress": 400}
if args.case == "bar":
    ct["reference"] = {"type": "embedded_crack", "crack": "penny", "stress": 40, "load_axis": [0, 0, 1]}
s["crack_tips"] = ct
if args.detection == "none":
    s["cracks"][0]["contact"] = {"law": "none"}
elif args.detection:
    s["cracks"][0]["contact"]["detection"] = args.detection
if args.tip_cut is not None:
    s["cracks"][0]["tip_cut"] = args.tip_cut
end = s["time"]["end"]
s["output"] = {"interval": end, "tip_interval": end / 20, "precision": "float32", "fields": ["displacement"]}

tag = (f"{args.case}_h{h:g}_r{ct['radius']:g}{'_plain' if args.no_oop else ''}{'_v' if args.volume_term else ''}"
       f"{'_' + args.detection if args.detection else ''}{'' if args.tip_cut is None else f'_cut{args.tip_cut:g}'}"
       f"{'' if args.integral == 'contour' else '_' + args.integral + str(args.along or '') + str(args.inner or '')}")
rows, times, wall = run_scene(args.cleave, s, pathlib.Path(args.out) / tag, args.threads)
last = [r for r in rows if float(r["time_s"]) == times[-1]]
pos = lambda r: [float(r[k]) * 1e3 for k in ("x_m", "y_m", "z_m")]  # mm
K = lambda r, k: float(r[k + "_Pa_sqrt_m"]) / 1e6
print(f"{args.case}: {h:g} mm cells, contour {ct['radius'] * h:g} mm ({ct['radius']:g} cells), "
      f"{'plain contour' if args.no_oop else 'with the out-of-plane term'}, damping {s['damping']['kinetic']}/us, "
      f"contact {s['cracks'][0]['contact']}, t = {times[-1] * 1e6:.0f} us, {len(last)} front nodes, wall {wall:.0f} s")


def nearest(target):
    return min(last, key=lambda r: sum((a - b) ** 2 for a, b in zip(pos(r), target)))


if args.case == "rod":
    A = nearest([0, 20, 0])
    for t in times[-4:]:
        rA = min((r for r in rows if float(r["time_s"]) == t), key=lambda r: sum((a - b) ** 2 for a, b in zip(pos(r), [0, 20, 0])))
        print(f"  t = {t * 1e6:5.0f} us: K_I(A) = {K(rA, 'KI'):.3f} MPa m^1/2 ({100 * (K(rA, 'KI') / 83.6 - 1):+.2f} % of 83.6)")
    print("  along the front (last time): phi (deg), K_I, Irwin infinite body, ratio, flag")
    for r in sorted(last, key=lambda r: float(r["phi_rad"])):
        print(f"    {math.degrees(float(r['phi_rad'])):6.1f}  {K(r, 'KI'):7.3f}  {K(r, 'KI_ref'):7.3f}  "
              f"{K(r, 'KI') / K(r, 'KI_ref'):.4f}  {r['flag']}")
elif args.case == "cylinder":
    D = nearest([201, 0, 0])
    for t in times[-4:]:
        rD = min((r for r in rows if float(r["time_s"]) == t), key=lambda r: sum((a - b) ** 2 for a, b in zip(pos(r), [201, 0, 0])))
        print(f"  t = {t * 1e6:5.0f} us: K_I(deepest, at {pos(rD)[0]:.1f}, {pos(rD)[1]:.1f} mm) = {K(rD, 'KI'):.3f} MPa m^1/2 "
              f"({100 * (K(rD, 'KI') / 24.1 - 1):+.2f} % of 24.1), flag {rD['flag']}")
    for r in last:
        print(f"    node {r['node']:>3} ({pos(r)[0]:7.2f}, {pos(r)[1]:7.2f}) mm: K_I {K(r, 'KI'):7.3f}, K_II {K(r, 'KII'):6.3f}, "
              f"K_III {K(r, 'KIII'):6.3f}, flag {r['flag']}")
else:
    sigma, a = 40.0, 10.0
    K0 = 2 * sigma * math.sqrt(a * 1e-3 / math.pi)
    n = [0.5, 0, math.sqrt(0.75)]
    shear = [-math.sqrt(0.75), 0, 0.5]
    other = [n[1] * shear[2] - n[2] * shear[1], n[2] * shear[0] - n[0] * shear[2], n[0] * shear[1] - n[1] * shear[0]]
    expect = {"A": (0, (0.750, 0.509, 0.0)), "B": (45, (0.750, 0.360, 0.253)), "C": (90, (0.750, 0.0, 0.357))}
    print(f"  K0 = {K0:.4f} MPa m^1/2; |K|/K0 (Tada) and the error in % of K0")
    worst = 0.0
    for name, (deg, ref) in expect.items():
        th = math.radians(deg)
        target = [a * (math.cos(th) * shear[i] + math.sin(th) * other[i]) for i in range(3)]
        r = nearest(target)
        got = [abs(K(r, k)) / K0 for k in ("KI", "KII", "KIII")]
        err = [100 * (g - e) for g, e in zip(got, ref)]
        worst = max(worst, *[abs(e) for e in err])
        print(f"  {name} (theta {deg:2d}): K_I {got[0]:.3f} ({ref[0]:.3f}, {err[0]:+.1f}), K_II {got[1]:.3f} "
              f"({ref[1]:.3f}, {err[1]:+.1f}), K_III {got[2]:.3f} ({ref[2]:.3f}, {err[2]:+.1f}), flag {r['flag']}")
    print(f"  worst error {worst:.1f} % of K0")
