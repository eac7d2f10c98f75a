#!/bin/sh
# The Kalthoff-Winkler benchmark (issue 18, validations 3 and 4; docs/validation.md "Growing cracks",
# docs/performance.md "Crack growth"): MPM (data/scenes/kalthoff.json, half model, growing explicit
# crack) and peridynamics (data/scenes/kalthoff_pd.json, full plate) at 2, 1 and 0.5 mm, each with
# its path angle to the notch, tip speeds and wall time; then the cost of growth at 0.5 mm: the
# run's own crack-growth share (run.json) and the wall time against the same scene with propagation
# off, interleaved, three pairs. Run from the repository root after building (build/bin/cleave).
# Writes under ${OUT:-build/kalthoff}. About 10 minutes on 2 cores.
set -e
CLEAVE=${CLEAVE:-build/bin/cleave}
OUT=${OUT:-build/kalthoff}
mkdir -p "$OUT"
export OMP_WAIT_POLICY=PASSIVE
wall() { python3 -c "import json,sys; j=json.load(open(sys.argv[1])); print('%.1f' % j['costs']['wall_s'])" "$1/run.json"; }
share() { python3 -c "
import json,sys; c=json.load(open(sys.argv[1]))['costs']; p=c['parts']
g=p.get('crack_growth',0); s=p['step']+g+p.get('crack_fields',0)+p.get('contact',0)
print('%.2f %.2f' % (100*g/c['wall_s'], 100*g/s))" "$1/run.json"; }
echo "method cell_mm angle_deg mean_speed_m_s max_speed_4mm_m_s initiation_us points wall_s"
for h in 2 1 0.5; do
  "$CLEAVE" run data/scenes/kalthoff.json --set resolution=$h --out "$OUT/mpm_$h" > "$OUT/mpm_$h.log" 2>&1
  echo "mpm $h $(python3 bench/kalthoff/angles.py "$OUT/mpm_$h" mpm) $(wall "$OUT/mpm_$h")"
  "$CLEAVE" run data/scenes/kalthoff_pd.json --set resolution=$h --out "$OUT/pd_$h" > "$OUT/pd_$h.log" 2>&1
  echo "pd $h $(python3 bench/kalthoff/angles.py "$OUT/pd_$h" pd) $(wall "$OUT/pd_$h")"
done
echo "growth cost at 0.5 mm: crack_growth share of the wall and of the step (step + crack fields + contact + growth), %"
python3 -c "
import json; s=json.load(open('data/scenes/kalthoff.json')); del s['cracks'][0]['propagation']
json.dump(s, open('$OUT/kalthoff_static.json', 'w'))"
for k in 1 2 3; do
  "$CLEAVE" run data/scenes/kalthoff.json --set resolution=0.5 --out "$OUT/on" > /dev/null 2>&1
  "$CLEAVE" run "$OUT/kalthoff_static.json" --set resolution=0.5 --out "$OUT/off" > /dev/null 2>&1
  on=$(wall "$OUT/on"); off=$(wall "$OUT/off")
  echo "pair $k: on $on s, off $off s, ratio $(python3 -c "print('%.3f' % ($on / $off))"), growth share $(share "$OUT/on")"
done
echo "figure: docs/images/kalthoff_mpm_pd.png (0.5 mm runs at 60 us, dark-field fringes, 300 N/mm per fringe, 5 mm)"
"$CLEAVE" render "$OUT/mpm_0.5" --frames time:60e-6 --fringes dark --fringe-constant 300 --thickness 5 --size 600x600 > /dev/null
"$CLEAVE" render "$OUT/pd_0.5" --frames time:60e-6 --fringes dark --fringe-constant 300 --thickness 5 --size 600x600 \
  --roi 0,0,100,100 --length-unit mm > /dev/null
ffmpeg -y -loglevel error -i "$OUT/mpm_0.5/render/fringes_000012.png" -i "$OUT/pd_0.5/render/fringes_000012.png" \
  -filter_complex hstack docs/images/kalthoff_mpm_pd.png
