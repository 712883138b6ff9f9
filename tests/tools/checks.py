"""The scripts' shared check recorder: check() prints ok/FAIL and remembers
the failures; finish() prints the verdict and gives the exit code."""

failures = []


def check(condition, what, detail=""):
    if condition:
        print(f"ok: {what}")
    else:
        print(f"FAIL: {what}{': ' + detail if detail else ''}")
        failures.append(what)
    return condition
