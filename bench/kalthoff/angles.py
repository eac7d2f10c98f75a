#!/usr/bin/env python3
"""The Kalthoff-Winkler path of one run: its angle to the notch and its speed.

Usage: angles.py RUN_DIR [mpm|pd]. MPM reads crack_growth.csv (the upper notch's tip, which starts at
(50, 25) mm); peridynamics reads crack_tips.csv (the tracker "upper", crack 0). The angle is that of
the least-squares line through the path's points within 20 mm of the notch tip (degrees from the
notch line, +x); the speed is the mean over the same 20 mm and the largest over 4 mm spans. Prints
one line: angle_deg mean_speed max_speed initiation_us points.
"""
import csv
import math
import sys

run, method = sys.argv[1], (sys.argv[2] if len(sys.argv) > 2 else "mpm")
tip = (50e-3, 25e-3)
rows = []
with open(f"{run}/crack_growth.csv" if method == "mpm" else f"{run}/crack_tips.csv") as f:
    for r in csv.DictReader(f):
        if method == "pd" and int(float(r["crack"])) != 0:
            continue
        rows.append((float(r["time_s"]), float(r["x_m"]), float(r["y_m"])))
# Peridynamics: the tracker reports a point before the crack grows; keep those past the notch tip.
path = [(t, x, y) for t, x, y in rows if math.hypot(x - tip[0], y - tip[1]) > 1e-3 and y > tip[1]]
if not path:
    print("nan nan nan nan 0")
    sys.exit(0)
near = [(t, x, y) for t, x, y in path if math.hypot(x - tip[0], y - tip[1]) <= 20e-3]
# Least-squares direction through the notch tip: the principal axis of the points about the tip.
sxx = sum((x - tip[0]) ** 2 for _, x, _ in near)
syy = sum((y - tip[1]) ** 2 for _, _, y in near)
sxy = sum((x - tip[0]) * (y - tip[1]) for _, x, y in near)
angle = 0.5 * math.degrees(math.atan2(2 * sxy, sxx - syy))
if angle < 0:
    angle += 90
s = [0.0]
for k in range(1, len(path)):
    s.append(s[-1] + math.hypot(path[k][1] - path[k - 1][1], path[k][2] - path[k - 1][2]))
t0 = path[0][0]
# Mean over the first 20 mm of path; largest over 4 mm spans.
end = max(k for k in range(len(path)) if s[k] <= 20e-3)
mean = s[end] / (path[end][0] - t0) if path[end][0] > t0 else float("nan")
vmax = 0.0
j = 0
for k in range(len(path)):
    while s[k] - s[j] > 4e-3:
        j += 1
    if j > 0 and s[k] - s[j - 1] >= 4e-3 and path[k][0] > path[j - 1][0]:
        vmax = max(vmax, (s[k] - s[j - 1]) / (path[k][0] - path[j - 1][0]))
print(f"{angle:.1f} {mean:.0f} {vmax:.0f} {t0 * 1e6:.2f} {len(path)}")
