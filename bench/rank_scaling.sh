#!/usr/bin/env bash
# Strong and weak scaling over MPI ranks (docs/mpi.md), with bench_ranks:
#  - strong: the rod at l0 = 0.25 and 0.125 mm at 1..R ranks;
#  - weak: about 18,000 and 72,000 particles per rank (l0 = 0.5 mm and
#    0.25 mm at one rank, l0 / sqrt(R) at R ranks).
# Each line is bench_ranks' summary (median of 5 rounds) and its halo lines.
#   bash bench/rank_scaling.sh [MAX_RANKS (default: the cores)] [MODEL (paper)]
set -eu
cd "$(dirname -- "${BASH_SOURCE[0]}")/.."
BENCH=build/release/bench/bench_ranks
MAX=${1:-$(nproc)}
MODEL=${2:-paper}
export OMPI_MCA_btl_vader_single_copy_mechanism=none
run() {  # run RANKS L0 STEPS
  mpirun -np "$1" --oversubscribe --allow-run-as-root --bind-to core "$BENCH" "$2" "$3" "$MODEL" |
    sed "s/^/  /"
}
echo "# strong scaling ($MODEL)"
for l0 in 0.00025 0.000125; do
  steps=$([[ $l0 == 0.00025 ]] && echo 200 || echo 50)
  for ((r = 1; r <= MAX; r *= 2)); do run "$r" "$l0" "$steps"; done
done
echo "# weak scaling ($MODEL)"
for base in 0.0005 0.00025; do
  steps=$([[ $base == 0.0005 ]] && echo 400 || echo 100)
  for ((r = 1; r <= MAX; r *= 2)); do
    l0=$(/usr/bin/python3 -c "import math, sys; print(f'{float(sys.argv[1]) / math.sqrt(int(sys.argv[2])):.6g}')" "$base" "$r")
    run "$r" "$l0" "$steps"
  done
done
