#!/bin/bash
# Builds Release and runs the benchmarks: 5 repetitions, medians and spread,
# JSON to out/bench/NAME.json and a Markdown table to out/bench/NAME.md.
#   bench/run_benchmarks.sh                      # everything, 1 and 2 threads (NAME = bench)
#   bench/run_benchmarks.sh '^step/'             # a filter (Google Benchmark regex)
#   bench/run_benchmarks.sh '^step/' step        # ... written as out/bench/step.*
#   bench/run_benchmarks.sh '^step/' step --benchmark_repetitions=9   # more flags after NAME
#   MPSOLID_BENCH_THREADS="1 2 4" bench/run_benchmarks.sh
set -euo pipefail
cd "$(dirname "$0")/.."
filter="${1:-.}"
name="${2:-bench}"
cmake --preset release > /dev/null
cmake --build --preset release -j"$(nproc)" --target bench_solver > /dev/null
mkdir -p out/bench
build/release/bench/bench_solver --benchmark_filter="$filter" \
  --benchmark_repetitions=5 --benchmark_report_aggregates_only=true \
  --benchmark_out="out/bench/$name.json" --benchmark_out_format=json "${@:3}"
/usr/bin/python3 bench/summarize.py "out/bench/$name.json" > "out/bench/$name.md"
echo "bench/run_benchmarks.sh: out/bench/$name.json, out/bench/$name.md"
