#!/usr/bin/env python3
"""The grip through a window of a bench trace: per trace CSV (`bench --trace`), the mean
commanded force, its standard deviation, and the object's turn at the window's ends.

    python3 scripts/hold-stats.py OUT/trace/lift-hold/SEED 0.8 1.2 [PATTERN]

PATTERN (a substring of the file name, e.g. `safety1.2.`) picks the traces; the rest of
the name says the trial, the controller and its setting.
"""
import csv
import statistics
import sys
from pathlib import Path


def main() -> None:
    folder, t0, t1 = Path(sys.argv[1]), float(sys.argv[2]), float(sys.argv[3])
    pattern = sys.argv[4] if len(sys.argv) > 4 else ""
    print("trace, mean N_cmd [N], sd [N], turn at start -> end [mrad]")
    for path in sorted(folder.glob("*.csv")):
        if pattern not in path.name:
            continue
        with path.open() as f:
            rows = [r for r in csv.DictReader(f) if t0 <= float(r["t_s"]) <= t1]
        if not rows:
            continue
        n = [float(r["n_cmd_n"]) for r in rows]
        turn = [1000 * float(r["slip_rotation_rad"]) for r in (rows[0], rows[-1])]
        print(
            f"{path.stem}, {statistics.mean(n):.3f}, {statistics.pstdev(n):.3f}, "
            f"{turn[0]:.0f} -> {turn[1]:.0f}"
        )


if __name__ == "__main__":
    main()
