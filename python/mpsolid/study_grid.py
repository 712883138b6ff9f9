"""A study's grid: the points of `mpsolid study` from its spec (the --vary
keys and values, the --set overrides every point shares, the measures and
their references), each point's folder name and overrides, and the check
of every point before anything runs. Pure Python but for that check."""
import math
import re

MEASURE_KINDS = ("first_peak", "max", "min", "final")


class StudyError(ValueError):
    """Bad study input (exit 2 on the command line)."""


def split_values(text):
    """'a,b,[1,2],"x,y"' -> ['a', 'b', '[1,2]', '"x,y"']: commas inside
    brackets or quotes do not split."""
    values, depth, quote, start = [], 0, None, 0
    for k, ch in enumerate(text):
        if quote:
            if ch == quote:
                quote = None
        elif ch in "\"'":
            quote = ch
        elif ch in "[{":
            depth += 1
        elif ch in "]}":
            depth -= 1
        elif ch == "," and depth == 0:
            values.append(text[start:k].strip())
            start = k + 1
    values.append(text[start:].strip())
    return values


def parse_vary(text):
    """'KEY=V1,V2,...' -> (KEY, [V1, V2, ...]) as TOML texts."""
    key, sep, rest = text.partition("=")
    key = key.strip()
    if not sep or not key or not rest.strip():
        raise StudyError(f"--vary '{text}': expected KEY=VALUE1,VALUE2,... (e.g. l0=0.002,0.001)")
    values = split_values(rest)
    if any(v == "" for v in values):
        raise StudyError(f"--vary '{text}': an empty value")
    if len(set(values)) != len(values):
        raise StudyError(f"--vary '{text}': a value is listed twice")
    return key, values


def parse_measure(text):
    """'KIND:COLUMN' -> (KIND, COLUMN)."""
    kind, sep, column = text.partition(":")
    if not sep or kind not in MEASURE_KINDS or not column:
        raise StudyError(f"--measure '{text}': expected KIND:COLUMN with KIND one of "
                         f"{', '.join(MEASURE_KINDS)} (e.g. first_peak:plate.x)")
    return kind, column


def parse_reference(text):
    """'first_peak:plate.x=0.0116961' -> ('first_peak:plate.x', 'first_peak(plate.x)', 0.0116961):
    the option's KIND:COLUMN, the measure's name in study.csv, the value;
    'first_peak:plate.x.t=...' names the measure's time."""
    option, sep, value = text.rpartition("=")
    try:
        number = float(value)
    except ValueError:
        number = math.nan
    if not sep or not math.isfinite(number) or number == 0:
        raise StudyError(f"--reference '{text}': expected KIND:COLUMN=VALUE with a finite, nonzero "
                         f"VALUE (e.g. first_peak:plate.x=0.0116961)")
    timed = option.endswith(".t")
    kind, column = parse_measure(option.removesuffix(".t"))
    return option, f"{kind}({column})" + (".t" if timed else ""), number


def measure_names(measures):
    """The study.csv columns of the measures: KIND(COLUMN) and, but for
    final, KIND(COLUMN).t, its time."""
    names = []
    for kind, column in measures:
        names.append(f"{kind}({column})")
        if kind != "final":
            names.append(f"{kind}({column}).t")
    return names


def toml_text(value):
    """A Python value as the TOML text --set reads (strings pass as given:
    on the command line a bare word is a string)."""
    if isinstance(value, str):
        return value
    from . import toml_value
    return toml_value(value)


def vary_list(vary):
    """{key: [values]} or [(key, [values])], values as Python values or TOML
    texts -> [(key, [TOML texts])]; at least one key, none twice."""
    pairs = vary.items() if isinstance(vary, dict) else vary
    vary = [(k, [toml_text(v) for v in vs]) for k, vs in pairs]
    if not vary:
        raise StudyError("nothing to vary: give at least one --vary KEY=V1,V2,...")
    if len({k for k, _ in vary}) != len(vary):
        raise StudyError("a key is varied twice")
    return vary


def measure_list(measures):
    """Measures as "kind:column" or (kind, column) -> [(kind, column)]."""
    return [parse_measure(m) if isinstance(m, str) else tuple(m) for m in measures]


def reference_list(references, measures):
    """--reference texts -> [(option, measure name, value)], each of one of
    the measures."""
    references = [parse_reference(r) for r in references]
    for _, name, _ in references:
        if name not in measure_names(measures):
            raise StudyError(f"--reference for {name}: that is not one of the measures "
                             f"({', '.join(measure_names(measures)) or 'none given'})")
    return references


def folder_name(point):
    """'l0=0.002,model=paper': readable, unique per point, safe as a name."""
    parts = [f"{k}={v}" for k, v in point]
    name = ",".join(parts)
    return re.sub(r"[^A-Za-z0-9._=,+\-\[\]]", "_", name)


def grid(vary):
    """Every combination of the varied values, the first key slowest."""
    points = [[]]
    for key, values in vary:
        points = [p + [(key, v)] for p in points for v in values]
    return points


def point_overrides(base, point):
    """A point's --set overrides: the study's own, then its values."""
    return base + [f"{key}={value}" for key, value in point]


def check_points(case_path, base, points):
    """Loads the case with every point's overrides, so that a bad one raises
    the command line's InputError before anything runs."""
    from . import Case
    for point in points:
        case = Case.load(case_path)
        for override in point_overrides(base, point):
            key, _, value = override.partition("=")
            case.set_text(key, value)
