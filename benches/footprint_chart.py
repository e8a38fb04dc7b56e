#!/usr/bin/env python3
"""Speed vs accuracy of the pixel-footprint methods (Velinov 2018 §3.2): writes
docs/footprint-accuracy.svg and prints a Markdown summary.

Accuracy: the 200 cases of reference/golden/footprint.json (exact values by mpmath) are fed
through `scratchwave footprint`; the relative error of Eq. 15, Eq. 16 (π restored) and the
accurate quadrature is plotted against A_P/A_C. Cost: criterion's estimates from
`cargo bench -p scratchwave-benches --bench footprint` (if present).

Usage: python3 benches/footprint_chart.py [SCRATCHWAVE_BIN] [TARGET_DIR]
"""
import json
import math
import os
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
BIN = sys.argv[1] if len(sys.argv) > 1 else str(ROOT / "target/release/scratchwave")
TARGET = Path(sys.argv[2] if len(sys.argv) > 2 else os.environ.get("CARGO_TARGET_DIR", ROOT / "target"))
METHODS = [("eq15", "Velinov Eq. 15", "#d62728"), ("eq16", "Eq. 16, π restored", "#ff7f0e"),
           ("accurate", "accurate quadrature", "#1f77b4")]


def kernel_values(cases):
    by_sigma = {}
    for i, c in enumerate(cases):
        by_sigma.setdefault(c["sigma"], []).append(i)
    out = [None] * len(cases)
    for sigma, idx in by_sigma.items():
        spec = {"sigma_um": sigma,
                "scratches": [{k: cases[i]["scratch"][k] for k in ("p0", "p1", "width", "depth")} for i in idx],
                "queries": [{"scratch": j, "ellipse": cases[i]["ellipse"]} for j, i in enumerate(idx)]}
        with tempfile.NamedTemporaryFile("w", suffix=".json", delete=False) as f:
            json.dump(spec, f)
        rows = subprocess.run([BIN, "footprint", f.name], check=True, capture_output=True, text=True).stdout
        os.unlink(f.name)
        lines = rows.strip().splitlines()[1:]
        for i, line in zip(idx, lines):
            out[i] = dict(zip(["eq15", "eq16", "accurate", "rho_p"], map(float, line.split(","))))
    return out


def cost_ns():
    res = {}
    for m, _, _ in METHODS:
        p = TARGET / "criterion" / "footprint" / m / "new" / "estimates.json"
        b = TARGET / "criterion" / "footprint" / m / "new" / "benchmark.json"
        if p.exists() and b.exists():
            n = json.loads(b.read_text())["throughput"]["Elements"]
            res[m] = json.loads(p.read_text())["mean"]["point_estimate"] / n
    return res


def svg(points, costs, path):
    w, h, ml, mr, mt, mb = 760, 440, 70, 230, 30, 50
    xmin, xmax, ymin, ymax = -2.2, 2.2, -8, 4

    def X(r):
        return ml + (math.log10(r) - xmin) / (xmax - xmin) * (w - ml - mr)

    def Y(e):
        le = max(ymin, min(ymax, math.log10(max(e, 1e-12))))
        return mt + (ymax - le) / (ymax - ymin) * (h - mt - mb)

    s = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{h}" font-family="sans-serif" font-size="12">',
         f'<rect width="{w}" height="{h}" fill="white"/>']
    for d in range(ymin, ymax + 1):
        y = Y(10 ** d)
        s.append(f'<line x1="{ml}" y1="{y:.1f}" x2="{w - mr}" y2="{y:.1f}" stroke="#ddd"/>')
        s.append(f'<text x="{ml - 6}" y="{y + 4:.1f}" text-anchor="end">1e{d}</text>')
    for d in (-2, -1, 0, 1, 2):
        x = X(10 ** d)
        s.append(f'<line x1="{x:.1f}" y1="{mt}" x2="{x:.1f}" y2="{h - mb}" stroke="#ddd"/>')
        s.append(f'<text x="{x:.1f}" y="{h - mb + 16}" text-anchor="middle">{10 ** d:g}</text>')
    y4 = Y(1e-4)
    s.append(f'<line x1="{ml}" y1="{y4:.1f}" x2="{w - mr}" y2="{y4:.1f}" stroke="#2ca02c" stroke-dasharray="5,4"/>')
    s.append(f'<text x="{w - mr - 4}" y="{y4 - 4:.1f}" text-anchor="end" fill="#2ca02c">1e-4 target</text>')
    s.append(f'<text x="{(ml + w - mr) / 2}" y="{h - 10}" text-anchor="middle">footprint area / coherence area  A_P/A_C</text>')
    s.append(f'<text x="16" y="{(mt + h - mb) / 2}" transform="rotate(-90 16 {(mt + h - mb) / 2})" text-anchor="middle">|relative error| vs mpmath (clipped to [1e-8, 1e4])</text>')
    for m, label, col in METHODS:
        for r, e in points[m]:
            s.append(f'<circle cx="{X(r):.1f}" cy="{Y(e):.1f}" r="2.6" fill="{col}" fill-opacity="0.65"/>')
    for k, (m, label, col) in enumerate(METHODS):
        y = mt + 20 + 42 * k
        c = f"{costs[m]:.0f} ns/eval" if m in costs else "cost: run the bench"
        s.append(f'<circle cx="{w - mr + 16}" cy="{y}" r="5" fill="{col}"/>')
        s.append(f'<text x="{w - mr + 28}" y="{y + 4}">{label}</text>')
        s.append(f'<text x="{w - mr + 28}" y="{y + 20}" fill="#555">{c}</text>')
    s.append("</svg>")
    path.write_text("\n".join(s) + "\n")


def main():
    cases = json.loads((ROOT / "reference/golden/footprint.json").read_text())["cases"]
    vals = kernel_values(cases)
    points = {m: [] for m, _, _ in METHODS}
    for c, v in zip(cases, vals):
        for m, _, _ in METHODS:
            ex = c["exact_eta_p"]
            points[m].append((c["A_P_over_A_C"], abs(v[m] - ex) / abs(ex) if ex else abs(v[m])))
    costs = cost_ns()
    out = ROOT / "docs/footprint-accuracy.svg"
    svg(points, costs, out)
    print(f"wrote {out.relative_to(ROOT)}\n")
    print("| method | cost (ns/eval) | worst rel. error, A_P/A_C < 1 | 1 ≤ A_P/A_C < 10 | A_P/A_C ≥ 10 |")
    print("|---|---|---|---|---|")
    for m, label, _ in METHODS:
        band = lambda lo, hi: max((e for r, e in points[m] if lo <= r < hi), default=float("nan"))
        c = f"{costs[m]:.0f}" if m in costs else "–"
        print(f"| {label} | {c} | {band(0, 1):.2g} | {band(1, 10):.2g} | {band(10, 1e9):.2g} |")


if __name__ == "__main__":
    main()
