#!/bin/sh
# Seed 003 inclined pre-crack runs of docs/validation.md (Peridynamics, 5). Run from the repository
# root after building; outputs go to $OUT (default pd_runs/).
S=data/scenes; OUT=${OUT:-pd_runs}; mkdir -p $OUT; CLEAVE=${CLEAVE:-build/bin/cleave}
set_sigma() { echo "--set loads[0].traction=[$1,0] --set loads[1].traction=[-$1,0] --set loads[2].traction=[0,$1] --set loads[3].traction=[0,-$1]"; }
for sig in 17 23; do
  $CLEAVE run $S/pd_inclined_square.json --quiet --out $OUT/sq_0_$sig $(set_sigma $sig)
  $CLEAVE run $S/pd_inclined_square.json --quiet --out $OUT/sq_15_$sig $(set_sigma $sig) --set 'cracks[0].points=[[20.170371,23.705905],[29.829629,26.294095]]'
  $CLEAVE run $S/pd_inclined_square.json --quiet --out $OUT/sq_30_$sig $(set_sigma $sig) --set 'cracks[0].points=[[20.669873,22.5],[29.330127,27.5]]'
  $CLEAVE run $S/pd_inclined_square.json --quiet --out $OUT/sq_45_$sig $(set_sigma $sig) --set 'cracks[0].points=[[21.464466,21.464466],[28.535534,28.535534]]'
done
for sig in 15 18; do
  $CLEAVE run $S/pd_inclined_rect.json --quiet --out $OUT/rect_$sig $(set_sigma $sig)
done
