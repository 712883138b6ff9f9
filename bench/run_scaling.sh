#!/bin/bash
# Whole-step scaling over the thread counts given as arguments, e.g.
#   bench/run_scaling.sh 1 2 4 8 16
# (default 1 2): out/bench/scaling.json and out/bench/scaling.md.
set -euo pipefail
MPSOLID_BENCH_THREADS="${*:-1 2}" exec "$(dirname "$0")/run_benchmarks.sh" '^step/' scaling
