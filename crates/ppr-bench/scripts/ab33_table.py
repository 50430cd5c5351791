#!/usr/bin/env python3
"""Whole-frame table of an h200_ab33.sh call: per scene, camera and width, each binary's
`frame span` median (the faster of its runs) and, from the BOUND step, the frame with the
upload bound against copied. Usage, on the unpacked results folder:

    python3 crates/ppr-bench/scripts/ab33_table.py results e,f,h [csv-out]

With csv-out, also every row read (run, binary, scene, camera, width, variant, median, p95)
as CSV.
"""
import collections
import csv
import glob
import os
import sys

root = sys.argv[1]
bins = sys.argv[2].split(",")
out = sys.argv[3] if len(sys.argv) > 3 else None
best = collections.defaultdict(dict)  # (scene, camera, width) -> column -> ms
rows = []
for path in sorted(glob.glob(os.path.join(root, "*", "runtime.csv"))):
    run = os.path.basename(os.path.dirname(path))
    binary = run.split("_")[1] if run.startswith("ab_") else "bound"
    with open(path, newline="") as f:
        for r in csv.DictReader(f):
            if r["pass"] != "frame" or "[" not in r["scene"]:
                continue
            scene, variant = r["scene"].split(" [", 1)
            variant = variant.rstrip("]")
            key = (scene, r["camera"][:28], r["width"])
            rows.append([run, binary, scene, r["camera"], r["width"], variant, r["median_ms"], r["p95_ms"], r["adapter"]])
            if binary != "bound" and variant != "frame span":
                continue
            col = binary if binary != "bound" else variant
            v = float(r["median_ms"])
            best[key][col] = min(best[key].get(col, float("inf")), v)
cols = bins + ["frame span", "frame span, copied upload"]
print("| scene | camera | width | " + " | ".join(cols) + " |")
print("| --- | --- | --- | " + " | ".join("---:" for _ in cols) + " |")
for key in sorted(best):
    cells = [f"{best[key][c]:.4f}" if c in best[key] else "-" for c in cols]
    print("| " + " | ".join(key) + " | " + " | ".join(cells) + " |")
if out:
    with open(out, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["run", "binary", "scene", "camera", "width", "variant", "median_ms", "p95_ms", "adapter"])
        w.writerows(rows)
