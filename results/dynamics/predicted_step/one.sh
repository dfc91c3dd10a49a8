#!/bin/bash
# one.sh SIZE LOAD SEED VARIANT  (P: predicted 0.9 zeta_high 0.5; Q: the same at a quarter of the rate; D: the default; R: the default at a quarter of the rate)
size=$1 load=$2 seed=$3 var=$4
out=/tmp/ev/${var}_${size}_${load}_s${seed}
[ -f $out/summary.json ] && exit 0
case $var in
  P) extra="--dashpot-velocity predicted --dt-safety 0.9 --zeta-high 0.5";;
  Q) extra="--dashpot-velocity predicted --dt-safety 0.9 --zeta-high 0.5 --strain-rate 0.005";;
  D) extra="";;
  R) extra="--strain-rate 0.005";;
esac
stop="--stop-at load_loss --loss-stop-strain-ratio 0"
[ $load = triangular ] && stop="--stop-at past_peak"
[ $size = 0.96 ] && stop="$stop --tail-damping relative"
[ $size = 0.96 ] && [ $load = triangular ] && stop="$stop --stop-fraction 0.1"
start=$(date +%s)
env PYTHONPATH=/tmp/py_ev OMP_WAIT_POLICY=passive /usr/bin/python3 -m ldem cube --size $size --load $load --seed $seed --threads 1 $extra $stop --no-plots --no-progress --overwrite --out $out > $out.log 2>&1
echo "$var $size $load $seed rc $? $(( $(date +%s) - start )) s" >> /tmp/ev/times.log
