#!/usr/bin/env python3
"""How the cost of seed 000's rod grows with refinement (issue 17, performance).

Runs data/scenes/rod_elliptical_crack.json to 100 us (undamped, one output frame, no crack_tips) at 7.5, 5,
3.75 and 3 mm cells, with its crack and without it, twice, alternating the order; prints the fastest wall
time of each, the crack's share, and the exponent p of time ~ f^p fitted over the refinement f = 7.5 / h
(the seed reports p = 4: three dimensions and the time step).
Usage: bench/crack_fronts/rod_refinement.py [--cleave build/bin/cleave] [--out DIR] [--threads N]
"""
import argparse, json, math, pathlib, subprocess, time

root = pathlib.Path(__file__).resolve().parents[2]
ap = argparse.ArgumentParser()
ap.add_argument("--cleave", default=str(root / "build/bin/cleave"))
ap.add_argument("--out", default="/tmp/cleave_rod_refinement")
ap.add_argument("--threads", default="2")
args = ap.parse_args()
out = pathlib.Path(args.out)
out.mkdir(parents=True, exist_ok=True)
base = json.loads((root / "data/scenes/rod_elliptical_crack.json").read_text())
cells = (7.5, 5, 3.75, 3)
for h in cells:
    for cracked in (True, False):
        s = json.loads(json.dumps(base))
        s["resolution"] = h
        s.pop("crack_tips", None)
        s["output"] = {"interval": 100}
        if not cracked:
            s.pop("cracks")
        (out / f"rod_{h}_{int(cracked)}.json").write_text(json.dumps(s))
wall = {}
for rep in range(2):
    for h in cells:
        for cracked in ((True, False) if rep % 2 == 0 else (False, True)):
            t0 = time.time()
            subprocess.run([args.cleave, "run", str(out / f"rod_{h}_{int(cracked)}.json"), "--out",
                            str(out / f"o_{h}_{int(cracked)}"), "--quiet", "--threads", args.threads],
                           check=True, stderr=subprocess.DEVNULL, stdout=subprocess.DEVNULL)
            wall.setdefault((h, cracked), []).append(time.time() - t0)
for h in cells:
    a, b = min(wall[(h, True)]), min(wall[(h, False)])
    print(f"{h:g} mm: cracked {a:.2f} s (runs {', '.join('%.2f' % x for x in wall[(h, True)])}), uncracked {b:.2f} s "
          f"(runs {', '.join('%.2f' % x for x in wall[(h, False)])}), crack share {100 * (a - b) / a:.1f} %")
x = [math.log(7.5 / h) for h in cells]
y = [math.log(min(wall[(h, True)])) for h in cells]
mx, my = sum(x) / len(x), sum(y) / len(y)
p = sum((a - mx) * (b - my) for a, b in zip(x, y)) / sum((a - mx) ** 2 for a in x)
print(f"fitted exponent of time ~ f^p (cracked, 7.5 to 3 mm): p = {p:.2f}")
