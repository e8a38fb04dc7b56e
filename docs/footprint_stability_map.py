#!/usr/bin/env python3
"""Stability map of the pixel-footprint averages (issue #20): worst err/bound of the f32
kernel's accurate eta_P = (1/A_P) int_P |eta_s|^2 over (footprint size sqrt(a1 a2)/sigma,
aspect a_major/a_minor), before and after the issue #20 footprint fixes, and the model error
of Velinov's Eq. 16 (pi restored) against the exact eta_P over the same axes, as
docs/footprint-stability.svg.

err is the kernel's relative error against the mpmath reference at the same f32 inputs
(reference/footprint_sweep.py, committed subset reference/golden/sweep/footprint.csv), bound =
max(1e-4, 8 kappa) with kappa the query's one-ulp conditioning; a cell shows the largest
err/bound of its queries (> 1 is a defect). The model error is |exact Eq. 16 / exact eta_P - 1|
(both from the CSV: the approximation itself, not f32 arithmetic); its cells show the median
and the worst of their queries.

  python3 docs/footprint_stability_map.py                     # runs the sweep test, redraws
  python3 docs/footprint_stability_map.py --dump FILE         # from a FOOTPRINT_SWEEP_DUMP file
  python3 docs/footprint_stability_map.py --save-before FILE  # grid the pre-fix kernel's dump
                                                              # into docs/footprint-stability-before.csv

The "before" grid is docs/footprint-stability-before.csv, the dump of the same test on the
kernel before the footprint fixes, gridded by --save-before. Python standard library only;
the colours and drawing conventions are docs/ghs_stability_map.py's.
"""
import argparse
import csv
import math
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, HERE)
from ghs_stability_map import bound_label, cell, colour, colour_bar, read_dump, run_sweep_test  # noqa: E402

BEFORE = os.path.join(HERE, "footprint-stability-before.csv")
SVG = os.path.join(HERE, "footprint-stability.svg")

# log10 axes: (lo, hi, cells)
SX = (-3.0, 4.0, 14)  # sqrt(a1 a2)/sigma
AY = (0.0, 3.0, 6)  # aspect
# model-error colours: log10(error) shifted so that 1 % sits where err/bound = 1 does
MODEL_REF = 1e-2


def cells(r):
    size, asp = float(r["size"]), float(r["aspect"])
    return cell(math.log10(size), *SX), cell(math.log10(max(asp, 1.0)), *AY)


def grid(rows):
    """{(ix, iy): (max err/bound of eta_P, count)}."""
    g = {}
    for r in rows:
        k = cells(r)
        ratio = float(r["eta_err"]) / float(r["eta_bound"])
        m, n = g.get(k, (0.0, 0))
        g[k] = (max(m, ratio), n + 1)
    return g


def model_grid(rows):
    """{(ix, iy): (median, worst, count)} of the Eq. 16 model error."""
    acc = {}
    for r in rows:
        v = float(r["eq16_model"])
        if math.isfinite(v):
            acc.setdefault(cells(r), []).append(v)
    out = {}
    for k, v in acc.items():
        v.sort()
        out[k] = (v[len(v) // 2], v[-1], len(v))
    return out


def run_test():
    return run_sweep_test("footprint_domain_sweep", "FOOTPRINT_SWEEP_DUMP")


def save_grid(g, path):
    with open(path, "w", newline="") as fh:
        w = csv.writer(fh, lineterminator="\n")
        w.writerow(["ix", "iy", "max_err_over_bound", "count"])
        for (ix, iy), (m, n) in sorted(g.items()):
            w.writerow([ix, iy, "%.4g" % m, n])


def load_grid(path):
    g = {}
    with open(path) as fh:
        for r in csv.DictReader(fh):
            g[(int(r["ix"]), int(r["iy"]))] = (float(r["max_err_over_bound"]), int(r["count"]))
    return g


def draw(before, after, model, path):
    cw, ch = 26, 20
    left, top, gapx, gapy = 70, 50, 90, 80
    pw, ph = SX[2] * cw, AY[2] * ch
    width = left + 2 * pw + gapx + 170
    height = top + 2 * (ph + gapy) + 30
    out = ['<svg xmlns="http://www.w3.org/2000/svg" width="%d" height="%d" font-family="sans-serif" font-size="11">' % (width, height),
           '<rect width="100%" height="100%" fill="white"/>',
           '<text x="%d" y="18" font-size="13">Pixel footprint (Velinov §4) vs mpmath at the same f32 inputs</text>' % left,
           '<text x="%d" y="34" fill="#555">python3 docs/footprint_stability_map.py (queries: reference/golden/sweep/footprint.csv)</text>' % left]
    panels = [
        (0, 0, "accurate η_P, before: worst err/max(1e-4, 8κ)", {k: v[0] for k, v in before.items()}, 1.0),
        (0, 1, "accurate η_P, after: worst err/max(1e-4, 8κ)", {k: v[0] for k, v in after.items()}, 1.0),
        (1, 0, "Eq. 16 model error vs exact η_P: median", {k: v[0] for k, v in model.items()}, MODEL_REF),
        (1, 1, "Eq. 16 model error vs exact η_P: worst", {k: v[1] for k, v in model.items()}, MODEL_REF),
    ]
    for row, col, label, g, ref in panels:
        x0 = left + col * (pw + gapx)
        y0 = top + row * (ph + gapy) + 14
        worst = max(g.values(), default=0)
        out.append('<text x="%d" y="%d" font-size="12">%s (max %.3g)</text>' % (x0, y0 - 4, label, worst))
        for ix in range(SX[2]):
            for iy in range(AY[2]):
                v = g.get((ix, iy))
                fill = colour(v / ref) if v is not None else "#e6e6e6"
                title = "<title>%.3g</title>" % v if v is not None else ""
                out.append('<rect x="%d" y="%d" width="%d" height="%d" fill="%s" stroke="white" stroke-width="0.5">%s</rect>'
                           % (x0 + ix * cw, y0 + (AY[2] - 1 - iy) * ch, cw, ch, fill, title))
        xw, yh = SX[2] * cw, AY[2] * ch
        for e in range(math.ceil(SX[0]), math.floor(SX[1]) + 1):
            x = x0 + (e - SX[0]) / (SX[1] - SX[0]) * xw
            out.append('<text x="%.1f" y="%d" text-anchor="middle">1e%d</text>' % (x, y0 + yh + 13, e))
        out.append('<text x="%.1f" y="%d" text-anchor="middle">footprint size √(a1 a2)/σ</text>' % (x0 + xw / 2, y0 + yh + 27))
        for e in range(math.ceil(AY[0]), math.floor(AY[1]) + 1):
            y = y0 + yh - (e - AY[0]) / (AY[1] - AY[0]) * yh
            out.append('<text x="%d" y="%.1f" text-anchor="end" dominant-baseline="middle">1e%d</text>' % (x0 - 4, y, e))
        out.append('<text x="%d" y="%.1f" text-anchor="middle" transform="rotate(-90 %d %.1f)">aspect</text>'
                   % (x0 - 40, y0 + yh / 2, x0 - 40, y0 + yh / 2))
    # legends: err/bound (top row) and model error (bottom row), the same colours
    bx = left + 2 * pw + gapx + 30
    for row, title, fmt in ((0, "err/bound", bound_label),
                            (1, "model error", lambda e: "1e%d" % (e + round(math.log10(MODEL_REF))))):
        by, bh = top + row * (ph + gapy) + 14, ph + 30
        out += colour_bar(bx, by, bh, fmt)
        out.append('<text x="%d" y="%d">%s</text>' % (bx - 4, by - 6, title))
    out.append('<text x="%d" y="%d" fill="#555">grey: no query in the cell; aspect = a_major/a_minor; model error |Eq. 16/η_P − 1| of the exact values</text>' % (left, height - 12))
    out.append("</svg>")
    with open(path, "w") as fh:
        fh.write("\n".join(out) + "\n")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--dump", help="a FOOTPRINT_SWEEP_DUMP file of the current kernel (skips cargo)")
    ap.add_argument("--save-before", metavar="DUMP", help="grid this dump into " + BEFORE + " and exit")
    a = ap.parse_args()
    if a.save_before:
        save_grid(grid(read_dump(a.save_before)), BEFORE)
        print("wrote", BEFORE)
        return
    rows = read_dump(a.dump) if a.dump else run_test()
    after = grid(rows)
    model = model_grid(rows)
    draw(load_grid(BEFORE), after, model, SVG)
    print("accurate eta_P: worst err/bound %.3g" % max((v[0] for v in after.values()), default=0))
    for lo in range(int(SX[0]), int(SX[1])):
        sel = [v for (ix, _), v in model.items() if lo <= SX[0] + ix * (SX[1] - SX[0]) / SX[2] < lo + 1]
        if sel:
            print("Eq. 16 model error, size 1e%d-1e%d: cell medians %.2g-%.2g, worst %.2g"
                  % (lo, lo + 1, min(v[0] for v in sel), max(v[0] for v in sel), max(v[1] for v in sel)))
    print("wrote", SVG)


if __name__ == "__main__":
    main()
