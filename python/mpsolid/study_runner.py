"""A study's runner: each point of the grid run with the mpsolid executable
as a child process (`mpsolid run`, or `mpsolid resume` where a signal left a
checkpoint), at most `jobs` at a time; SIGINT or SIGTERM stops them in order.
What a point's folder already holds decides whether it runs at all."""
import json
import os
import signal
import subprocess
import threading

from . import run_data
from .study_grid import StudyError

EXIT_BAD_INPUT, EXIT_STOPPED = 2, 4


def executable():
    """The mpsolid executable: $MPSOLID_EXECUTABLE, else the one this package
    was built or installed with."""
    exe = os.environ.get("MPSOLID_EXECUTABLE")
    if not exe:
        from ._build_paths import MPSOLID_EXECUTABLE as exe
    if not os.access(exe, os.X_OK):
        raise StudyError(f"the mpsolid executable '{exe}' is missing (build it, or set MPSOLID_EXECUTABLE)")
    return exe


def point_state(folder, overrides):
    """'done' (completed or stopped by a blow-up check), 'resume' (stopped by
    a signal, checkpoint there), 'fresh' (nothing usable), or raises when the
    folder holds a run of other settings."""
    info = run_data.read_info(folder, default=None)
    if info is None:
        return "fresh"
    if info.get("overrides") != overrides:
        raise StudyError(f"{folder} holds a run with other settings ({info.get('overrides')}); "
                         f"remove it or choose another --out")
    outcome = info.get("outcome", "")
    if outcome in ("completed", "unstable"):
        return "done"
    if os.path.isfile(os.path.join(folder, run_data.CHECKPOINT_H5)):
        return "resume"
    return "fresh"


def write_provenance(out, case_path, base, vary, measures, references, jobs, threads, exe):
    """study.json: what the study was asked, and the executable and package
    that ran it."""
    tmp = os.path.join(out, "study.json.tmp")
    with open(tmp, "w") as f:
        json.dump({"case": os.path.abspath(case_path), "sets": base, "vary": vary,
                   "measures": [f"{k}:{c}" for k, c in measures],
                   "references": {name: value for _, name, value in references},
                   "jobs": jobs, "threads": threads,
                   "executable": exe, "package": os.path.dirname(os.path.abspath(__file__))}, f,
                  indent=2)
    os.replace(tmp, os.path.join(out, "study.json"))


class PointRunner:
    """Runs points as child processes; stop() asks every running child to
    stop (SIGINT: each writes its checkpoint) and starts no more."""

    def __init__(self, exe, threads, fixed_threads):
        self.exe, self.threads, self.fixed_threads = exe, threads, fixed_threads
        self.children = set()
        self.stopping = False
        self.lock = threading.Lock()

    def run(self, case_path, overrides, folder):
        state = point_state(folder, overrides)
        if state == "done":
            return "skipped"
        if state == "resume":
            cmd = [self.exe, "resume", folder]
        else:
            cmd = [self.exe, "run", case_path, "--out", folder, "--force"]
            for o in overrides:
                cmd += ["--set", o]
        cmd += ["--threads", str(self.threads)] + (["--fixed-threads"] if self.fixed_threads else [])
        os.makedirs(folder, exist_ok=True)
        with self.lock:
            if self.stopping:
                return "not started"
            with open(os.path.join(folder, "mpsolid.log"), "a") as log:
                log.write(f"$ {' '.join(cmd)}\n")
                log.flush()
                # Own process group: a Ctrl-C reaches the study, which stops its runs in order.
                child = subprocess.Popen(cmd, stdout=log, stderr=subprocess.STDOUT, start_new_session=True)
            self.children.add(child)
        code = child.wait()
        with self.lock:
            self.children.discard(child)
        if code == EXIT_BAD_INPUT:
            with open(os.path.join(folder, "mpsolid.log")) as log:
                raise StudyError(f"{folder}: mpsolid refused the point:\n{log.read()[-2000:]}")
        return {0: "ran", 3: "ran", EXIT_STOPPED: "stopped"}.get(code, f"failed (exit {code})")

    def stop(self):
        with self.lock:
            self.stopping = True
            for child in self.children:
                child.send_signal(signal.SIGINT)


def run_all(points, one, jobs, runner, failures):
    """Runs one(k, point) for every point on `jobs` threads. SIGINT or SIGTERM
    stops the runs (checkpoints) and returns 4."""
    from concurrent.futures import ThreadPoolExecutor, wait

    stop = threading.Event()

    def guarded(k, point):
        if stop.is_set():
            return
        try:
            one(k, point)
        except Exception as e:  # noqa: BLE001: the first failure stops the study
            failures.append(e)
            stop.set()
            runner.stop()

    previous = {}

    def on_signal(signum, frame):
        stop.set()
        runner.stop()

    in_main = threading.current_thread() is threading.main_thread()
    if in_main:
        for s in (signal.SIGINT, signal.SIGTERM):
            previous[s] = signal.signal(s, on_signal)
    try:
        with ThreadPoolExecutor(max_workers=jobs) as pool:
            futures = [pool.submit(guarded, k, p) for k, p in enumerate(points)]
            wait(futures)
    finally:
        for s, h in previous.items():
            signal.signal(s, h)
    if failures:
        return EXIT_BAD_INPUT
    return EXIT_STOPPED if stop.is_set() else 0
