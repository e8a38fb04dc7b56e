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
import math
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, HERE)
from ghs_stability_map import (before_after_rows, bound_label, cell, colour_bar, heat_cells, load_grid,  # noqa: E402
                               log_axes, run_sweep_test, svg_close, svg_open)

BEFORE = os.path.join(HERE, "footprint-stability-before.csv")
# the columns of a "before" grid's key before its cell
GRID_KEY = ()
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


def scaled_cells(g, ref):
    """`heat_cells`' cells of a grid of single values, coloured as value/ref."""
    def cell_of(ix, iy):
        v = g.get((ix, iy))
        return None if v is None else (v / ref, "%.3g" % v)
    return cell_of


def draw(before, after, model, path):
    cw, ch = 26, 20
    left, top, gapx, gapy = 70, 50, 90, 80
    pw, ph = SX[2] * cw, AY[2] * ch
    width = left + 2 * pw + gapx + 170
    height = top + 2 * (ph + gapy) + 30
    out = svg_open(width, height) + [
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
        out += heat_cells(scaled_cells(g, ref), SX[2], AY[2], x0, y0, cw, ch)
        out += log_axes(x0, y0, SX[2] * cw, AY[2] * ch, SX, AY, "footprint size √(a1 a2)/σ", "aspect", 40)
    # legends: err/bound (top row) and model error (bottom row), the same colours
    bx = left + 2 * pw + gapx + 30
    for row, title, fmt in ((0, "err/bound", bound_label),
                            (1, "model error", lambda e: "1e%d" % (e + round(math.log10(MODEL_REF))))):
        by, bh = top + row * (ph + gapy) + 14, ph + 30
        out += colour_bar(bx, by, bh, fmt)
        out.append('<text x="%d" y="%d">%s</text>' % (bx - 4, by - 6, title))
    svg_close(out, path, left, height, "grey: no query in the cell; aspect = a_major/a_minor; model error |Eq. 16/η_P − 1| of the exact values")


def main():
    rows = before_after_rows(__doc__, "FOOTPRINT_SWEEP_DUMP", BEFORE, run_test, grid, GRID_KEY)
    if rows is None:
        return
    after = grid(rows)
    model = model_grid(rows)
    draw(load_grid(BEFORE, GRID_KEY), after, model, SVG)
    print("accurate eta_P: worst err/bound %.3g" % max((v[0] for v in after.values()), default=0))
    for lo in range(int(SX[0]), int(SX[1])):
        sel = [v for (ix, _), v in model.items() if lo <= SX[0] + ix * (SX[1] - SX[0]) / SX[2] < lo + 1]
        if sel:
            print("Eq. 16 model error, size 1e%d-1e%d: cell medians %.2g-%.2g, worst %.2g"
                  % (lo, lo + 1, min(v[0] for v in sel), max(v[0] for v in sel), max(v[1] for v in sel)))
    print("wrote", SVG)


if __name__ == "__main__":
    main()
