#!/bin/sh
# Tip deflection of seed 004's cantilever (data/scenes/pem_cantilever.json) against Timoshenko
# (2.0821 mm) and Euler-Bernoulli (2.0480 mm) at four element sizes; docs/validation.md, "PEM".
# usage: bench/pem/cantilever_convergence.sh [OUT_DIR]   (from the repository root, after the build)
set -e
out=${1:-build/pem_cantilever_convergence}
mkdir -p "$out"
for h in 0.2 0.1 0.05 0.025; do
  build/bin/cleave run data/scenes/pem_cantilever.json --set resolution=$h --set output.interval=0.5 \
      --out "$out/h$h" > "$out/h$h.log" 2>&1
  python3 - "$out/h$h" "$h" <<'PY'
import csv, glob, json, sys
import meshio
out, h = sys.argv[1], sys.argv[2]
f = sorted(glob.glob(out + "/particles_*.vtu"))[-1]
m = meshio.read(f)
u = m.point_data["displacement"]
x0 = m.points - u
tip = abs(x0[:, 0] - 8) < 1e-9
w = -u[tip, 1].mean()
run = json.load(open(out + "/run.json"))
print(f"h = {h} m: {len(x0)} particles, tip deflection {w*1e3:.4f} mm, vs Timoshenko {100*(w/2.0821e-3-1):+.2f} %, "
      f"vs Euler-Bernoulli {100*(w/2.0480e-3-1):+.2f} %; {run['end']} at {run['ended_at_s']} s, "
      f"{run['step']} steps, {run['costs']['wall_s']:.1f} s wall")
PY
done
