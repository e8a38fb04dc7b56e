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
import argparse
import csv
import math
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, HERE)
from ghs_stability_map import cell, colour, colour_bar, read_dump, run_sweep_test  # noqa: E402

BEFORE = os.path.join(HERE, "scratch-stability-before.csv")
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


def save_grid(g, path):
    with open(path, "w", newline="") as fh:
        w = csv.writer(fh, lineterminator="\n")
        w.writerow(["group", "map", "ix", "iy", "max_err_over_bound", "count"])
        for (grp, key, ix, iy), (m, n) in sorted(g.items()):
            w.writerow([grp, key, ix, iy, "%.4g" % m, n])


def load_grid(path):
    g = {}
    with open(path) as fh:
        for r in csv.DictReader(fh):
            g[(r["group"], r["map"], int(r["ix"]), int(r["iy"]))] = (float(r["max_err_over_bound"]), int(r["count"]))
    return g


def draw(before, after, path):
    cw, ch = 22, 16
    left, top, gapx, gapy = 70, 50, 80, 74
    pw = max(m[3][2] for m in MAPS) * cw
    ph = max(m[6][2] for m in MAPS) * ch
    panels = [(grp, glabel, m) for grp, glabel in GROUPS for m in MAPS]
    width = left + 2 * pw + gapx + 150
    height = top + len(panels) * (ph + gapy) + 30
    out = ['<svg xmlns="http://www.w3.org/2000/svg" width="%d" height="%d" font-family="sans-serif" font-size="11">' % (width, height),
           '<rect width="100%" height="100%" fill="white"/>',
           '<text x="%d" y="18" font-size="13">Scratch models vs mpmath at the same f32 inputs: worst err / max(1e-4, 8κ) per cell</text>' % left,
           '<text x="%d" y="34" fill="#555">python3 docs/scratch_stability_map.py (queries: reference/golden/sweep/*.csv)</text>' % left]
    for row, (grp, glabel, (key, mlabel, _, xa, xl, _, ya, yl)) in enumerate(panels):
        for col, (name, g) in enumerate((("before (cf41449)", before), ("after", after))):
            x0 = left + col * (pw + gapx)
            y0 = top + row * (ph + gapy) + 14
            cells = [v[0] for k, v in g.items() if k[0] == grp and k[1] == key]
            status = "worst %.3g" % max(cells) if cells else "not swept then"
            out.append('<text x="%d" y="%d" font-size="12">%s, %s: %s</text>' % (x0, y0 - 4, glabel, name, status))
            for ix in range(xa[2]):
                for iy in range(ya[2]):
                    v = g.get((grp, key, ix, iy))
                    fill = colour(v[0]) if v else "#e6e6e6"
                    title = "<title>%.3g over %d queries</title>" % v if v else ""
                    out.append('<rect x="%d" y="%d" width="%d" height="%d" fill="%s" stroke="white" stroke-width="0.5">%s</rect>'
                               % (x0 + ix * cw, y0 + (ya[2] - 1 - iy) * ch, cw, ch, fill, title))
            xw, yh = xa[2] * cw, ya[2] * ch
            for e in range(math.ceil(xa[0]), math.floor(xa[1]) + 1):
                x = x0 + (e - xa[0]) / (xa[1] - xa[0]) * xw
                out.append('<text x="%.1f" y="%d" text-anchor="middle">1e%d</text>' % (x, y0 + yh + 13, e))
            out.append('<text x="%.1f" y="%d" text-anchor="middle">%s</text>' % (x0 + xw / 2, y0 + yh + 27, xl))
            for e in range(math.ceil(ya[0]), math.floor(ya[1]) + 1):
                y = y0 + yh - (e - ya[0]) / (ya[1] - ya[0]) * yh
                out.append('<text x="%d" y="%.1f" text-anchor="end" dominant-baseline="middle">1e%d</text>' % (x0 - 4, y, e))
            out.append('<text x="%d" y="%.1f" text-anchor="middle" transform="rotate(-90 %d %.1f)">%s</text>'
                       % (x0 - 44, y0 + yh / 2, x0 - 44, y0 + yh / 2, yl))
    bx, by, bh = left + 2 * pw + gapx + 30, top + 14, 2 * ph + gapy - 20
    out += colour_bar(bx, by, bh)
    out.append('<text x="%d" y="%d">err/bound</text>' % (bx - 4, by - 14))
    out.append('<text x="%d" y="%d" fill="#555">grey: no query in the cell; depth and width are the first scratch&apos;s</text>' % (left, height - 12))
    out.append("</svg>")
    with open(path, "w") as fh:
        fh.write("\n".join(out) + "\n")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--dump", help="a SCRATCH_SWEEP_DUMP file of the current kernel (skips cargo)")
    ap.add_argument("--save-before", metavar="DUMP", help="grid this dump into " + BEFORE + " and exit")
    a = ap.parse_args()
    if a.save_before:
        save_grid(grid(read_dump(a.save_before)), BEFORE)
        print("wrote", BEFORE)
        return
    rows = read_dump(a.dump) if a.dump else run_test()
    after = grid(rows)
    draw(load_grid(BEFORE), after, SVG)
    for grp, label in GROUPS:
        for key, mlabel, *_ in MAPS:
            w = max((v[0] for k, v in after.items() if k[0] == grp and k[1] == key), default=0)
            print("%s, %s: worst err/bound %.3g" % (label, mlabel, w))
    print("wrote", SVG)


if __name__ == "__main__":
    main()
