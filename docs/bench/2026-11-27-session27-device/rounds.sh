#!/bin/bash
# rounds.sh ROUNDS "THREADS" BIN... : ROUNDS rotations of every binary, scene and thread count
# (300 steps, fixed 10, error metric off); per run the median step time and its parts over steps
# 10-299 (stats.csv); then per set-up the median of the runs. Also the island stage's parts from
# an instrumented binary when one is named haif_instr.
export LD_LIBRARY_PATH=$PWD/devpack/lib:$LD_LIBRARY_PATH
R=$1; TL=$2; shift 2
nproc; lscpu | grep -E "Model name|L2|L3" | head -3
for r in $(seq $R); do for T in $TL; do for s in large_pyramid many_pyramids; do for b in "$@"; do
  o=/tmp/r_${b}_${s}_$T
  isl=$(devpack/$b run scenes/$s.json --no-render --frames 300 --threads $T --mode fixed --iterations 10 --error-every 0 --out $o 2>&1 | grep -o "islands.*")
  python3 - "$o/stats.csv" "$b $s $T $r" "$isl" >> $OUT/runs.txt <<'PY'
import csv,statistics as S,sys
r=list(csv.DictReader(open(sys.argv[1])))[10:]
m={k:S.median(float(x[k]) for x in r) for k in ['collision_ms','solve_ms','integrate_ms','total_ms']}
print(sys.argv[2], f"{m['total_ms']:.3f} {m['collision_ms']:.3f} {m['solve_ms']:.3f} {m['integrate_ms']:.3f} {m['total_ms']-m['collision_ms']-m['solve_ms']-m['integrate_ms']:.3f}", sys.argv[3])
PY
  grep -o '"state_hash[^,]*' $o/summary.json | sed "s/^/$b $s $T /" >> $OUT/hashes.txt
done; done; done; done
python3 - $OUT/runs.txt <<'PY' | tee $OUT/summary.txt
import sys,statistics as S,collections
g=collections.defaultdict(list)
for line in open(sys.argv[1]):
    f=line.split(); g[(f[0],f[1],int(f[2]))].append([float(x) for x in f[4:9]])
print("binary scene threads: median of runs (ms/step): total collision solve integrate rest | runs' totals")
for k in sorted(g, key=lambda k:(k[1],k[2],k[0])):
    v=g[k]; med=[S.median(x[i] for x in v) for i in range(5)]
    print(f"{k[0]:11s} {k[1]:14s} {k[2]:2d}T  " + " ".join(f"{x:7.3f}" for x in med) + " | " + " ".join(f"{x[0]:.2f}" for x in v))
PY
