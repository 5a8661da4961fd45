#!/usr/bin/env python3
"""Prints docs/hard-cases.md's measured table from a validate report (crtforge validate --matrix
full --report DIR): per hard case (a golden tag or id pattern) and target, the largest judged RMSE
over the presets it covers and how many checks passed.

    python3 tools/hard_cases_table.py DIR/report.json
"""
import json
import re
import sys

# (case, regex on the golden id)
CASES = [
    ("time 1000 s", r"\.t1000\."),
    ("time 3599.5 s (before Godot's wrap)", r"\.t3599\."),
    ("time 3600.5 s (after Godot's wrap)", r"\.t3601\."),
    ("time 1e5 s", r"\.t100000\."),
    ("time 1e7 s", r"\.t1e7\."),
    ("mediump, time 1e5 s (GL ES)", r"\.mediump-t100000\."),
    ("frames 2^24 + 1, 2^24 + 2", r"\.f1677721[78]$"),
    ("8192 x 2 row", r"\.row8k\."),
    ("2 x 8192 column", r"\.col8k\."),
    ("1 x 1", r"\.px1\."),
    ("1 x 64, 64 x 1", r"\.line\."),
    ("7 x 5", r"\.tiny\."),
    ("333 x 251 (odd)", r"\.odd\."),
    ("3840 x 2160", r"\.3840x2160\."),
]


def main(path):
    report = json.load(open(path))
    targets = []
    table = {}
    for check in report["checks"]:
        if not check["check"].startswith("render:") or "metrics" not in check:
            continue
        gid = check["check"][len("render:"):]
        t = check["target"]
        if t not in targets:
            targets.append(t)
        for name, pattern in CASES:
            if re.search(pattern, gid):
                cell = table.setdefault((name, t), [0.0, 0, 0])
                cell[0] = max(cell[0], check["metrics"]["rmse"])
                cell[1] += 1 if check["passed"] else 0
                cell[2] += 1
    print("| case | " + " | ".join(targets) + " |")
    print("|---|" + "---|" * len(targets))
    for name, _ in CASES:
        cells = []
        for t in targets:
            c = table.get((name, t))
            cells.append("–" if not c else f"{c[0]:.5f} ({c[1]}/{c[2]})")
        print(f"| {name} | " + " | ".join(cells) + " |")


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "report.json")
