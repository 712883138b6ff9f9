#!/usr/bin/env bash
# Regenerates the stored serial reference of tests/regression (paper model,
# cases/shock_rod.toml, 20,000 steps = 0.2 ms, 1 thread). Run only when a
# change of the results is intended, and say why in the commit.
set -euo pipefail
cd "$(dirname "$0")/../.."
bin=${1:-build/release/mpsolid}
out=$(mktemp -d)
"$bin" run cases/shock_rod.toml --threads 1 --out "$out" \
  --set time.end=2e-4 --set output.frame_interval=2e-5 --set output.history_interval=2e-5
cp "$out/history.csv" tests/regression/data/shock_rod_paper_history.csv
/usr/bin/python3 - "$out/frames.h5" tests/regression/data/shock_rod_paper_particles.csv <<'PY'
import sys, h5py
with h5py.File(sys.argv[1], "r") as f:
    last = sorted(f["frames"].keys())[-1]
    g = f["frames"][last]
    ids, pos, vel, rot = g["id"][:], g["position"][:], g["velocity"][:], g["rotation"][:]
with open(sys.argv[2], "w") as out:
    out.write("id,x,y,vx,vy,theta\n")
    for k in range(len(ids)):
        out.write("%d,%.17g,%.17g,%.17g,%.17g,%.17g\n" % (ids[k], pos[k, 0], pos[k, 1], vel[k, 0], vel[k, 1], rot[k]))
PY
python3 -c "import json;r=json.load(open('$out/run.json'));print('git', r['git_commit'], '|', r['compiler'], '|', r['flags'])"
rm -rf "$out"
