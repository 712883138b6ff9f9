#!/usr/bin/python3
"""Markdown tables from a bench_solver JSON file (run with repetitions):
the median time per call, the spread (min-max of the repetitions, as % of
the median), particles/s and GFLOP/s; for step/ and kernel/ rows also the
speed-up of N threads over 1 thread at the same model, kernel and l0.
    /usr/bin/python3 bench/summarize.py out/bench/bench.json
"""
import json
import re
import statistics
import sys
from collections import defaultdict


def main(path):
    with open(path) as f:
        data = json.load(f)
    runs = defaultdict(list)  # name -> [iteration results]
    for b in data["benchmarks"]:
        if b.get("run_type") == "iteration":
            runs[b["run_name"]].append(b)
        elif b.get("aggregate_name") == "median":
            runs.setdefault(b["run_name"], [])
    medians = {b["run_name"]: b for b in data["benchmarks"] if b.get("aggregate_name") == "median"}
    times = {}
    for name, iters in runs.items():
        if iters:
            times[name] = [i["real_time"] for i in iters]
    print("| benchmark | median | spread | particles/s | GFLOP/s | speed-up vs 1 thread |")
    print("| --- | --- | --- | --- | --- | --- |")
    for name, med in medians.items():
        t = med["real_time"]
        unit = med["time_unit"]
        spread = ""
        if name in times and len(times[name]) > 1:
            spread = f"{100 * (max(times[name]) - min(times[name])) / t:.0f} %"
        elif "real_time" in med:
            cv = next((b for b in data["benchmarks"] if b.get("run_name") == name
                       and b.get("aggregate_name") == "cv"), None)
            if cv:
                spread = f"cv {100 * cv['real_time']:.0f} %"
        m = re.search(r"threads:(\d+)", name)
        speedup = ""
        if m and m.group(1) != "1" and (name.startswith("step/") or name.startswith("kernel/")):
            one = name.replace(f"threads:{m.group(1)}", "threads:1")
            if one in medians:
                speedup = f"{medians[one]['real_time'] / t:.2f}x"
        ps = med.get("particles/s")
        gf = med.get("GFLOP/s")
        print(f"| {name.replace('/manual_time', '')} | {t:.4g} {unit} | {spread} | "
              f"{'' if ps is None else f'{ps:.3g}'} | {'' if gf is None else f'{gf:.3g}'} | {speedup} |")


if __name__ == "__main__":
    main(sys.argv[1])
