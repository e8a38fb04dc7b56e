#!/usr/bin/env python3
"""Stability map of the scratch models (issue #20): worst err/bound of the f32 kernel over
(groove depth, min(cos theta_i, cos theta_o)) and (sigma, groove width), for Werner's coherent
model (rect and triangle), Velinov's point model and Werner's model blended with a base
(family werner_blended), before and after the issue #20 fixes, as docs/scratch-stability.svg
(werner_blended was added to the sweep after the fixes: its "before" panels are empty).

err is the kernel's relative error against the mpmath reference at the same f32 inputs
(reference/scratch_sweep.py, committed subset reference/golden/sweep/), bound =
max(1e-4, 8 kappa) with kappa the query's one-ulp conditioning; a cell shows the largest
err/bound of its queries (> 1 is a defect). Depth and width are those of the query's first
scratch.

  python3 docs/scratch_stability_map.py                     # runs the sweep test, redraws
  python3 docs/scratch_stability_map.py --dump FILE         # from a SCRATCH_SWEEP_DUMP file
  python3 docs/scratch_stability_map.py --save-before FILE  # grid the pre-fix kernel's dump
                                                            # into docs/scratch-stability-before.csv

The "before" grid is docs/scratch-stability-before.csv, the dump of the same test on the
kernel before the fixes (commit cf41449), gridded by --save-before. Python standard library
only; the colours and drawing conventions are docs/ghs_stability_map.py's.
"""
import math
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, HERE)
from ghs_stability_map import (before_after_rows, bound_bar, cell, heat_cells, load_grid, log_axes,  # noqa: E402
                               run_sweep_test, svg_close, svg_open, worst_of)

BEFORE = os.path.join(HERE, "scratch-stability-before.csv")
# the columns of a "before" grid's key before its cell
GRID_KEY = ("group", "map")
SVG = os.path.join(HERE, "scratch-stability.svg")

# maps: (key, label, x column, x axis (log10 lo, hi, cells), x label, y column, y axis, y label)
MAPS = [
    ("depth_cos", "depth × cosθ", "depth", (-3.0, 1.0, 12), "depth D (µm)", "cos", (math.log10(0.005), 0.0, 10), "min(cosθi, cosθo)"),
    ("sigma_width", "σ × width", "sigma", (0.0, 2.0, 10), "σ (µm)", "width", (-1.0, math.log10(50), 12), "width W (µm)"),
]
GROUPS = [("werner", "Werner Eq. 15 (rect + triangle)"), ("velinov", "Velinov Eq. 7"),
          ("werner_blended", "Werner §5 |S|² + (1 − ρc) base")]


def group_of(family):
    """The map group of a sweep family (werner_rect and werner_tri share one)."""
    return family if family in ("velinov", "werner_blended") else "werner"


def grid(rows):
    """{(group, map, ix, iy): (max err/bound, count)} from dump rows."""
    g = {}
    for r in rows:
        ratio = float(r["err"]) / float(r["bound"])
        for key, _, xc, xa, _, yc, ya, _ in MAPS:
            ix = cell(math.log10(float(r[xc])), *xa)
            iy = cell(math.log10(float(r[yc])), *ya)
            k = (group_of(r["family"]), key, ix, iy)
            m, n = g.get(k, (0.0, 0))
            g[k] = (max(m, ratio), n + 1)
    return g


def run_test():
    return run_sweep_test("scratch_domain_sweep", "SCRATCH_SWEEP_DUMP")


def draw(before, after, path):
    cw, ch = 22, 16
    left, top, gapx, gapy = 70, 50, 80, 74
    pw = max(m[3][2] for m in MAPS) * cw
    ph = max(m[6][2] for m in MAPS) * ch
    panels = [(grp, glabel, m) for grp, glabel in GROUPS for m in MAPS]
    width = left + 2 * pw + gapx + 150
    height = top + len(panels) * (ph + gapy) + 30
    out = svg_open(width, height) + [
           '<text x="%d" y="18" font-size="13">Scratch models vs mpmath at the same f32 inputs: worst err / max(1e-4, 8κ) per cell</text>' % left,
           '<text x="%d" y="34" fill="#555">python3 docs/scratch_stability_map.py (queries: reference/golden/sweep/*.csv)</text>' % left]
    for row, (grp, glabel, (key, mlabel, _, xa, xl, _, ya, yl)) in enumerate(panels):
        for col, (name, g) in enumerate((("before (cf41449)", before), ("after", after))):
            x0 = left + col * (pw + gapx)
            y0 = top + row * (ph + gapy) + 14
            cells = [v[0] for k, v in g.items() if k[0] == grp and k[1] == key]
            status = "worst %.3g" % max(cells) if cells else "not swept then"
            out.append('<text x="%d" y="%d" font-size="12">%s, %s: %s</text>' % (x0, y0 - 4, glabel, name, status))
            out += heat_cells(lambda ix, iy: worst_of(g.get((grp, key, ix, iy))), xa[2], ya[2], x0, y0, cw, ch)
            out += log_axes(x0, y0, xa[2] * cw, ya[2] * ch, xa, ya, xl, yl, 44)
    out += bound_bar(left + 2 * pw + gapx + 30, top + 14, 2 * ph + gapy - 20)
    svg_close(out, path, left, height, "grey: no query in the cell; depth and width are the first scratch&apos;s")


def main():
    rows = before_after_rows(__doc__, "SCRATCH_SWEEP_DUMP", BEFORE, run_test, grid, GRID_KEY)
    if rows is None:
        return
    after = grid(rows)
    draw(load_grid(BEFORE, GRID_KEY), after, SVG)
    for grp, label in GROUPS:
        for key, mlabel, *_ in MAPS:
            w = max((v[0] for k, v in after.items() if k[0] == grp and k[1] == key), default=0)
            print("%s, %s: worst err/bound %.3g" % (label, mlabel, w))
    print("wrote", SVG)


if __name__ == "__main__":
    main()
