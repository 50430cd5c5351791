#!/usr/bin/env python3
"""Tables of an A/B call's `runtime` runs (h200_ab21.sh and its kin): per scene, camera and
width, each binary's median for a pass, the faster of its rounds, and the head against the
base. Usage, on the unpacked results folder (`tar xzf results.tar.gz`):

    python3 crates/ppr-bench/scripts/ab_table.py results [projection,frame] [base,...,head]

The runs are the folders `<binary>_r<round>_<tag>/runtime.csv`; binaries missing from a
row print as a dash. The cpu_ms column (prepare + encode on the host) is the `cpu` pass;
`frame` is the sum of a run's passes for the row (the faster run's sum).
"""
import collections
import csv
import glob
import os
import sys

root = sys.argv[1] if len(sys.argv) > 1 else "results"
passes = sys.argv[2].split(",") if len(sys.argv) > 2 else ["projection", "frame"]
bins = sys.argv[3].split(",") if len(sys.argv) > 3 else ["base", "forms", "deriv", "zinit", "nobar", "head"]

# (scene, camera, width) -> binary -> pass -> fastest median (ms)
data = collections.defaultdict(lambda: collections.defaultdict(dict))
sums = collections.defaultdict(float)  # (run, key) -> the run's passes summed
for path in glob.glob(os.path.join(root, "*_r*_*", "runtime.csv")):
    binary = os.path.basename(os.path.dirname(path)).split("_r")[0]
    with open(path, newline="") as f:
        for row in csv.DictReader(f):
            if "[" in row["scene"]:
                continue  # profile rows, not default frames
            key = (row["scene"], row["camera"][:24], row["width"])
            cell = data[key][binary]
            for name, value in ((row["pass"], row["median_ms"]), ("cpu", row.get("cpu_ms", "nan"))):
                v = float(value)
                cell[name] = min(cell.get(name, float("inf")), v)
            sums[(path, key)] += float(row["median_ms"])
        for (run, key), total in sums.items():
            if run == path:
                cell = data[key][binary]
                cell["frame"] = min(cell.get("frame", float("inf")), total)

if not data:
    sys.exit(f"no <binary>_r<round>_<tag>/runtime.csv under {root}")
for p in passes:
    print(f"\n{p} (ms, the faster round)\n")
    print("| scene | camera | width | " + " | ".join(bins) + " | head − base |")
    print("| --- | --- | ---: | " + " | ".join("---:" for _ in bins) + " | ---: |")
    for key in sorted(data):
        vals = [data[key].get(b, {}).get(p) for b in bins]
        base, head = data[key].get("base", {}).get(p), data[key].get("head", {}).get(p)
        diff = "–" if base is None or head is None else f"{head - base:+.3f}"
        cells = " | ".join("–" if v is None else f"{v:.3f}" for v in vals)
        print(f"| {' | '.join(key)} | {cells} | {diff} |")
