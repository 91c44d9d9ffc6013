#!/bin/bash
# ab.sh ROUNDS BIN... : ROUNDS rotations over thread counts (THREADS, default 1 2 4 8 16), the
# scenes (SCENES: paths under scenes/ without .json, default the four below) and the binaries in
# turn (300 steps, fixed 10, error metric off); per run the median step and its parts over steps
# 10-299 (stats.csv); then per set-up the median of the runs.
export LD_LIBRARY_PATH=$PWD/devpack/lib:$LD_LIBRARY_PATH
R=$1; shift
nproc; lscpu | grep -E "Model name|L2|L3" | head -3
for r in $(seq $R); do for T in ${THREADS:-1 2 4 8 16}; do for s in ${SCENES:-large_pyramid many_pyramids tumbler stress/swept_pit}; do for b in "$@"; do
  o=/tmp/r_$T
  devpack/$b run scenes/$s.json --no-render --frames 300 --threads $T --mode fixed --iterations 10 --error-every 0 --out $o > /dev/null 2>&1
  python3 - "$o/stats.csv" "$b $s $T $r" >> $OUT/runs.txt <<'PY'
import csv,statistics as S,sys
r=list(csv.DictReader(open(sys.argv[1])))[10:]
m={k:S.median(float(x[k]) for x in r) for k in ['collision_ms','solve_ms','integrate_ms','total_ms']}
print(sys.argv[2], f"{m['total_ms']:.3f} {m['collision_ms']:.3f} {m['solve_ms']:.3f} {m['integrate_ms']:.3f} {m['total_ms']-m['collision_ms']-m['solve_ms']-m['integrate_ms']:.3f}")
PY
  echo "$b $s $T $(grep -o '"state_hash[^,]*' $o/summary.json)" >> $OUT/hashes.txt
done; done; done; done
python3 - $OUT/runs.txt <<'PY' | tee $OUT/summary.txt
import sys,statistics as S,collections
g=collections.defaultdict(list)
for line in open(sys.argv[1]):
    f=line.split(); g[(f[1],int(f[2]),f[0])].append([float(x) for x in f[4:9]])
print("scene threads binary: median of runs (ms/step): total collision solve integrate rest | runs' totals")
for k in sorted(g):
    v=g[k]; med=[S.median(x[i] for x in v) for i in range(5)]
    print(f"{k[0]:18s} {k[1]:2d}T {k[2]:10s} " + " ".join(f"{x:7.3f}" for x in med) + " | " + " ".join(f"{x[0]:.2f}" for x in v))
PY
awk '{print $1, $2, $5, $6}' $OUT/hashes.txt | sort | uniq -c
