"""Prints the tables of a scaling run (bench/scaling/run.sh OUT_DIR): the median wall
time of each command at each thread count with its speed-up over one thread, then,
per command, each stage's wall and CPU seconds at the fewest and the most threads."""

import csv
import json
import os
import statistics
import sys
from collections import defaultdict


def main(out):
    walls = defaultdict(list)
    stages = {}
    with open(os.path.join(out, "runs.tsv")) as f, open(os.path.join(out, "reports.jsonl")) as r:
        for row, line in zip(csv.DictReader(f, delimiter="\t"), r):
            key = (row["command"], int(row["threads"]))
            walls[key].append(float(row["wall_s"]))
            try:
                stages.setdefault(key, (json.loads(line) or {}).get("timings", []))
            except json.JSONDecodeError:
                stages.setdefault(key, [])
    commands = list(dict.fromkeys(c for c, _ in walls))
    threads = sorted({t for _, t in walls})
    machine = open(os.path.join(out, "machine.txt")).read().strip()
    print(f"{machine}\n")
    print("| command | " + " | ".join(f"{t} thread{'s' if t > 1 else ''}" for t in threads) + " |")
    print("|---|" + "---|" * len(threads))
    for c in commands:
        base = statistics.median(walls[(c, threads[0])])
        cells = []
        for t in threads:
            m = statistics.median(walls[(c, t)])
            cells.append(f"{m:.3f} s" + (f" ({base / m:.1f}×)" if t != threads[0] else ""))
        print(f"| `{c}` | " + " | ".join(cells) + " |")
    for c in commands:
        print(f"\nstages of `{c}` (wall s / cpu s):")
        for t in (threads[0], threads[-1]):
            listed = stages.get((c, t), [])
            parts = ", ".join(f"{s['stage']} {s['wall_s']:.3f}/{s['cpu_s']:.3f}" for s in listed)
            print(f"  {t:>2} threads: {parts}")


if __name__ == "__main__":
    main(sys.argv[1])
