"""python3 -m mpsolid study ...: what `mpsolid study` runs (src/app/main.cpp)."""
import sys

from .study import main as study_main

if __name__ == "__main__":
    if len(sys.argv) < 2 or sys.argv[1] != "study":
        print("usage: python3 -m mpsolid study CASE --vary KEY=V1,V2,... (see --help)", file=sys.stderr)
        sys.exit(2)
    sys.exit(study_main(sys.argv[2:]))
