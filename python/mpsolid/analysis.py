"""Measures of a run's history and the Richardson extrapolation of a
refinement series: pure Python, shared by `mpsolid study`, the examples and
bench/error_vs_cost.py (which loads this file by path)."""
import math


def first_peak(t, x):
    """Value and time of the first maximum of x(t) above half the largest
    value, refined by a parabola through the three samples around it.
    Raises ValueError when there is none (the run ended before it)."""
    if len(x) < 3:
        raise ValueError("no peak: fewer than 3 samples")
    top = max(x)
    for k in range(1, len(x) - 1):
        if x[k] >= x[k - 1] and x[k] >= x[k + 1] and x[k] > 0.5 * top:
            a, b, c = x[k - 1], x[k], x[k + 1]
            denom = a - 2 * b + c
            shift = 0.5 * (a - c) / denom if denom != 0 else 0.0
            h = t[k + 1] - t[k]
            return b - 0.25 * (a - c) * shift, t[k] + shift * h
    raise ValueError("no peak: the run ended before the first maximum")


def extreme(t, x, largest):
    """Value and time of the largest (or smallest) sample."""
    k = max(range(len(x)), key=lambda i: x[i]) if largest else min(range(len(x)), key=lambda i: x[i])
    return x[k], t[k]


def richardson(values, ratio=2.0):
    """values at h, h/r, h/r^2, ... (coarse to fine, at least 3). The observed
    order from the three finest, the extrapolated value and its error bar:
    the largest of the distance to the finest value and the distance to the
    coarser triplet's own extrapolation (or, when that triplet or the finest
    is not in the asymptotic range, the last change)."""
    if len(values) < 3:
        raise ValueError("Richardson extrapolation needs at least 3 refinements")

    def extrapolate(f1, f2, f3):
        q = (f1 - f2) / (f2 - f3) if f2 != f3 else float("inf")
        if not (q > 1 and math.isfinite(q)):
            return float("nan"), None
        order = math.log(q) / math.log(ratio)
        return order, f3 + (f3 - f2) / (ratio**order - 1)

    order, best = extrapolate(*values[-3:])
    if best is None:
        return {"order": order, "value": values[-1], "error": abs(values[-1] - values[-2])}
    bar = abs(best - values[-1])
    if len(values) >= 4:
        _, coarser = extrapolate(*values[-4:-1])
        bar = max(bar, abs(best - coarser) if coarser is not None else abs(values[-1] - values[-2]))
    return {"order": order, "value": best, "error": bar}
