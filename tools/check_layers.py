#!/usr/bin/python3
"""Checks the include rule of docs/ARCHITECTURE.md: each folder of the product
includes only the folders it is allowed to (a lower layer), kernels/ only the
state layer, case/ and io/ no kernel, and no product file includes a test
oracle (kernels/reference/) or a test.

    /usr/bin/python3 tools/check_layers.py [ROOT]

Prints every violation as FILE:LINE: FOLDER includes TARGET, and exits 1 if
there is any; exits 0 with a one-line summary otherwise.
"""
import pathlib
import re
import sys

# The layers, bottom up, and what each may include besides itself.
ALLOWED = {
    "src/core": set(),
    "src/distributed": {"src/core"},
    "neighbor": {"src/core"},
    "kernels": {"src/core"},
    "src/gas": {"src/core"},
    "kernels/reference": {"kernels", "src/core"},
    "src/case": {"src/core"},
    "src/io": {"src/case", "src/core"},
    "src/solver": {"kernels", "src/case", "src/core", "neighbor", "src/distributed", "src/gas"},
    "src/app": {"src/solver", "src/io", "src/case", "kernels", "src/core", "neighbor",
                "src/distributed", "src/gas"},
    # The Python module: the command line's peer, on top of everything.
    "python/bindings": {"src/app", "src/solver", "src/io", "src/case", "kernels", "src/core",
                        "neighbor", "src/distributed", "src/gas"},
}
INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"')
SOURCES = ("*.hpp", "*.cpp", "*.hpp.in")


def folder_of(path):
    """The most specific layer folder a repository path lies in, or None."""
    best = None
    for folder in ALLOWED:
        if path == folder or path.startswith(folder + "/"):
            if best is None or len(folder) > len(best):
                best = folder
    return best


def main(root):
    root = pathlib.Path(root)
    problems, files, includes = [], 0, 0
    for layer in ALLOWED:
        for pattern in SOURCES:
            for path in sorted((root / layer).glob(pattern)):
                rel = path.relative_to(root).as_posix()
                if folder_of(rel) != layer:
                    continue  # a file of a nested layer: checked under that one
                files += 1
                for number, line in enumerate(path.read_text().splitlines(), 1):
                    m = INCLUDE.match(line)
                    if not m:
                        continue
                    target = m.group(1)
                    includes += 1
                    if target.startswith("tests/") or target.startswith("bench/"):
                        problems.append(f"{rel}:{number}: {layer} includes {target} (tests only)")
                        continue
                    to = folder_of(target)
                    if to is None or to == layer:
                        continue  # a generated header (build_info.hpp) or the same folder
                    if to not in ALLOWED[layer]:
                        problems.append(f"{rel}:{number}: {layer} includes {target} "
                                        f"({to}; allowed: {', '.join(sorted(ALLOWED[layer])) or 'none'})")
    for p in problems:
        print(p)
    if files == 0:
        print("check_layers: no source files found under", root)
        return 1
    print(f"check_layers: {files} files, {includes} includes, {len(problems)} violations")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1] if len(sys.argv) > 1 else pathlib.Path(__file__).resolve().parent.parent))
