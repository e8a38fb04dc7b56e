#!/usr/bin/env python3
"""Prints criterion results as Markdown tables of throughput and ratios to the first column.

Usage: python3 benches/report.py [TARGET_DIR]   (default: target, or $CARGO_TARGET_DIR)
Reads <target>/criterion/<group>/<function>/<param>/new/{estimates,benchmark}.json.
"""
import json
import os
import sys
from pathlib import Path


def main():
    target = Path(sys.argv[1] if len(sys.argv) > 1 else os.environ.get("CARGO_TARGET_DIR", "target"))
    root = target / "criterion"
    if not root.is_dir():
        sys.exit(f"no criterion results under {root}: run `cargo bench -p scratchwave-benches` first")
    for group in sorted(p for p in root.iterdir() if p.is_dir() and p.name != "report"):
        rows = {}
        cols = []
        for bench in sorted(group.glob("*/*/new/benchmark.json")):
            meta = json.loads(bench.read_text())
            est = json.loads((bench.parent / "estimates.json").read_text())
            thr = meta.get("throughput") or {}
            n = thr.get("Elements") or thr.get("Bytes") or 1
            per_s = n / (est["mean"]["point_estimate"] * 1e-9)
            fn, param = meta["function_id"], meta.get("value_str") or ""
            if fn not in cols:
                cols.append(fn)
            rows.setdefault(param, {})[fn] = per_s
        if not rows:
            continue
        print(f"\n### {group.name}\n")
        print("| input | " + " | ".join(f"{c} (/s)" for c in cols) + " | " + " | ".join(f"{c} ÷ {cols[0]}" for c in cols[1:]) + " |")
        print("|---" * (1 + 2 * len(cols) - 1) + "|")
        for param in sorted(rows, key=lambda p: (len(p), p)):
            r = rows[param]
            base = r.get(cols[0])
            vals = " | ".join(f"{r[c]:.3g}" if c in r else "–" for c in cols)
            ratios = " | ".join(f"{r[c] / base:.2f}×" if c in r and base else "–" for c in cols[1:])
            print(f"| {param} | {vals} | {ratios} |")


if __name__ == "__main__":
    main()
