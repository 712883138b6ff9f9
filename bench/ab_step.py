#!/usr/bin/python3
"""Two (or more) builds of bench_solver against each other, interleaved:
the same benchmarks run by each binary in turn, the order alternating from
round to round, so that a busy or throttled moment hits all of them alike.
Prints the median time of each benchmark per binary and the ratio of the
last to the first (below 1: the last is faster).

  bench/ab_step.py FILTER ROUNDS THREADS BENCH_A BENCH_B [...]
  bench/ab_step.py 'step/paper/l0_um:(2000|500)/flush:0/' 5 "1 2" old/bench_solver build/release/bench/bench_solver
"""
import collections
import os
import statistics
import subprocess
import sys


def main():
    if len(sys.argv) < 6:
        sys.exit(__doc__)
    flt, rounds, threads, binaries = sys.argv[1], int(sys.argv[2]), sys.argv[3], sys.argv[4:]
    times = collections.defaultdict(list)
    for r in range(rounds):
        for b in binaries if r % 2 == 0 else binaries[::-1]:
            out = subprocess.run([b, f"--benchmark_filter={flt}", "--benchmark_min_time=0.3"],
                                 env=dict(os.environ, MPSOLID_BENCH_THREADS=threads),
                                 capture_output=True, text=True, check=True).stdout
            for line in out.splitlines():
                fields = line.split()
                if len(fields) > 2 and "/" in fields[0] and fields[2] == "ns":
                    times[(fields[0].split("/min_time")[0], b)].append(float(fields[1]))
    names = sorted({name for name, _ in times})
    if not names:
        sys.exit(f"ab_step: no benchmark matched '{flt}'")
    for name in names:
        medians = [statistics.median(times[(name, b)]) for b in binaries]
        cells = "  ".join(f"{m / 1e3:10.1f} us" for m in medians)
        print(f"{name:55s} {cells}   last/first {medians[-1] / medians[0]:.2f}")
    print(f"medians of {rounds} interleaved rounds; binaries: {' '.join(binaries)}")


if __name__ == "__main__":
    main()
