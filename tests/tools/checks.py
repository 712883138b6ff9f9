"""The scripts' shared check recorder: check() prints ok/FAIL and remembers
the failures; verdict() prints the verdict and gives the exit code."""

failures = []


def check(condition, what, detail=""):
    if condition:
        print(f"ok: {what}")
    else:
        print(f"FAIL: {what}{': ' + detail if detail else ''}")
        failures.append(what)
    return condition


def verdict(script):
    """Prints the script's verdict; its exit code: 1 if any check failed."""
    print()
    if failures:
        print(f"{script}: {len(failures)} check(s) FAILED")
        return 1
    print(f"{script}: all checks passed")
    return 0
