#!/usr/bin/python3
"""A synthetic photoelastic experiment fitted back (docs/photoelasticity.md, issue 21).

Runs data/scenes/cracked_strip.json (0.5 mm cells by default), samples the run's own fringe orders round
the right-hand tip (cleave fit --sample), adds Gaussian noise of a tenth of a fringe to them as a user's
digitising would, and fits K_I back from the noisy points alone (cleave fit --points, no run), with the
tip given and with the tip marked 0.3 mm off and fitted. Prints each fit's K_I against the K_I the run
computed from J, over several noise seeds.

usage: bench/fit/synthetic_experiment.py [BUILD_DIR] [--resolution MM] [--seeds N]
"""
import argparse, os, re, subprocess, sys
import numpy as np

ap = argparse.ArgumentParser()
ap.add_argument("build", nargs="?", default="build")
ap.add_argument("--resolution", type=float, default=0.5)
ap.add_argument("--seeds", type=int, default=10)
ap.add_argument("--noise", type=float, default=0.1)
a = ap.parse_args()
root = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
cleave = os.path.join(a.build, "bin", "cleave")
work = os.path.join(a.build, "synthetic_experiment")
run = os.path.join(work, f"strip_{a.resolution:g}mm")
os.makedirs(work, exist_ok=True)
if not os.path.exists(os.path.join(run, "crack_tips.csv")):
    subprocess.run([cleave, "run", os.path.join(root, "data/scenes/cracked_strip.json"), "--quiet", "--set",
                    f"resolution={a.resolution}", "--out", run], check=True)
common = ["--fringe-constant", "7", "--thickness", "5.7"]
out = subprocess.run([cleave, "fit", run, "--frame", "last", "--sample", "1,9", "--tip-index", "1", "--out",
                      os.path.join(work, "sampled")] + common, check=True, capture_output=True, text=True).stdout
K_run = float(re.search(r"run: K_I ([0-9.e+-]+) MPa", out).group(1))
K_clean = float(re.search(r"K_I += ([0-9.e+-]+)", out).group(1))
tip = re.search(r"tip \(([-0-9.]+), ([-0-9.]+)\) mm", out)
tx, ty = float(tip.group(1)), float(tip.group(2))
d = np.genfromtxt(os.path.join(work, "sampled_points.csv"), delimiter=",", names=True)
print(f"run K_I from J {K_run:.5f} MPa m^0.5; fit of the run's own orders (no noise) {K_clean:.5f} ({K_clean / K_run - 1:+.2%})")
for label, extra in (("tip given", ["--tip", f"{tx},{ty}"]),
                     ("tip 0.3 mm off, fitted", ["--tip", f"{tx + 0.3},{ty - 0.2}", "--fit-tip"])):
    ratios, covered = [], 0
    for seed in range(1, a.seeds + 1):
        rng = np.random.default_rng(seed)
        pts = os.path.join(work, f"points_{seed}.txt")
        N = d["N_measured"] + rng.normal(0, a.noise, d.size)
        np.savetxt(pts, np.c_[d["x_m"] * 1e3, d["y_m"] * 1e3, N], fmt="%.6f", header="x_mm y_mm N")
        o = subprocess.run([cleave, "fit", "--points", pts, "--crack-angle", "0"] + extra + common,
                           capture_output=True, text=True)
        if o.returncode != 0:
            print(f"  seed {seed}: exit {o.returncode}: {o.stderr.strip()}")
            continue
        m = re.search(r"K_I += ([0-9.e+-]+) \+- ([0-9.e+-]+)", o.stdout)
        K, se = float(m.group(1)), float(m.group(2))
        ratios.append(K / K_run)
        covered += abs(K - K_clean) <= 1.96 * se
    r = np.array(ratios)
    print(f"{label}: noise {a.noise} fringe, {len(r)} seeds: K_I / K_run mean {r.mean():.4f}, "
          f"min {r.min():.4f}, max {r.max():.4f}; 95 % interval covers the noise-free fit in {covered} of {len(r)}")
