#!/usr/bin/env python3
"""Stability map of the area-light integral (issue #20): worst err/bound of the f32 kernel's
lights::light_integral (Velinov Eq. 27's single band, exact Si) over (angular radius, distance)
and (angular radius, height of the light's lowest point above the horizon), for spheres with
the asin and the atan cone and for convex polygons, over rectangular grooves and the same
lights and views over V grooves (light_vgroove.csv), as docs/light-stability.svg.

err is the kernel's relative error against the mpmath reference at the same f32 inputs
(reference/light_sweep.py, committed subset reference/golden/sweep/light.csv and the found
queries light_found.csv). Two bounds, one column each: the light family's
max(1e-4, 8 max(kappa, kappa_s)), which the test asserts (kappa the query's one-ulp
conditioning over its inputs, kappa_s the one-ulp resolution of a band parameter
s = sin phi kept alone; an exact 0 counts err 0 up to its 8-ulp reach), and the other
sweeps' max(1e-4, 8 kappa), which every committed query meets (asserted, on every backend)
and a further sample's not yet everywhere (docs/stability.md, Area lights; an exact 0 there
must come out below 1e-30). A cell shows the largest
err/bound of its queries (> 1 is over). Distance is the light centre's (a polygon's vertex
mean) distance from the origin in the units the query is written in (m, mm or um: the f32
magnitudes the kernel works with); the height is elev - alpha (elevation of the light's
centre minus its angular radius), at most 1e-7 drawn in the bottom row (at or below the
horizon).

  python3 docs/light_stability_map.py                      # runs the sweep test, redraws
  python3 docs/light_stability_map.py --dir DIR [--dir ..] # adds LIGHT_SWEEP_DIR samples
  python3 docs/light_stability_map.py --dump FILE [...]    # from LIGHT_SWEEP_DUMP files

With --extent, the same maps for the renderer's default rule, the extent rule (bands = 20:
the Gaussian across the band integrated over the light's own range), against the exact
integral over its own 4.5-sigma window (reference/light_extent_sweep.py,
reference/golden/sweep/light_extent.csv, kernel/tests/light_extent_sweep.rs) and
max(1e-4, 8 kappa), kappa where light_extent_kappa.csv has it (else 0), as
docs/light-extent-stability.svg (--dir adds LIGHT_EXTENT_SWEEP_DIR samples, --dump reads
LIGHT_EXTENT_SWEEP_DUMP files).

Python standard library only; the colours and drawing conventions are
docs/ghs_stability_map.py's.
"""
import argparse
import math
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
from ghs_stability_map import (bound_bar, cell, heat_cells, log_axes, read_dump, run_sweep_test,  # noqa: E402
                               svg_close, svg_open, worst_of)

# What each mode runs and draws: the sweep test, its dump and sample variables, the chart,
# its title, and the (error column, bound column, label) of each panel column.
MODES = {
    "single": dict(
        test="light_domain_sweep", dump_env="LIGHT_SWEEP_DUMP", dir_env="LIGHT_SWEEP_DIR",
        svg=os.path.join(HERE, "light-stability.svg"), flag="",
        title="Area lights (Velinov Eq. 27, exact Si) vs mpmath at the same f32 inputs: worst err / bound per cell",
        bound_text="bound = max(1e-4, K·κ): left the light family&apos;s 8·max(κ, κs) (asserted), right the inputs&apos; 8κ",
        # dumps written before `err_inputs` existed use `err`
        bounds=[("err", "bound", "8·max(κ, κs)"), ("err_inputs", "bound_inputs", "8κ")],
        source="(committed subset and found queries, rectangular and V grooves)"),
    "extent": dict(
        test="light_extent_sweep", dump_env="LIGHT_EXTENT_SWEEP_DUMP", dir_env="LIGHT_EXTENT_SWEEP_DIR",
        svg=os.path.join(HERE, "light-extent-stability.svg"), flag=" --extent",
        title="Extent rule (bands 20, exact Si) vs mpmath over its 4.5-σ window, same f32 inputs: worst err / bound per cell",
        bound_text="bound = max(1e-4, 8κ), κ the window value&apos;s one-ulp conditioning where computed, else 0",
        bounds=[("err", "bound", "8κ")],
        source="(committed subset, rectangular and V grooves)"),
}

# The kinds of `sweep_common::light_group`: rectangular grooves, then the same lights with V
# grooves (`light_vgroove.csv`, `light_extent_vgroove.csv`; "V, ..." in the titles); a kind
# with no row is not drawn.
KINDS = [("0", "sphere, asin cone"), ("1", "sphere, atan cone"), ("2", "polygon"),
         ("3", "V, sphere, asin cone"), ("4", "V, sphere, atan cone"), ("5", "V, polygon")]
# log10 axes: (lo, hi, cells)
AX = (-5.0, 0.5, 11)  # angular radius alpha (rad)
MAPS = [
    ("distance", "α × distance", (-3.0, 7.0, 10), "distance (scene units)"),
    ("height", "α × height above the horizon", (-7.0, 0.5, 15), "elev − α (rad)"),
]
HEIGHT_FLOOR = 1e-7


def y_value(r, key):
    if key == "distance":
        return float(r["distance"])
    return max(float(r["elev"]) - float(r["alpha"]), HEIGHT_FLOOR)


def err(r, column):
    return float(r.get(column, r["err"]))


def grid(rows, bounds):
    """{(kind, map, bound, ix, iy): (max err/bound, count)} from dump rows."""
    g = {}
    for r in rows:
        ix = cell(math.log10(float(r["alpha"])), *AX)
        for key, _, ya, _ in MAPS:
            iy = cell(math.log10(y_value(r, key)), *ya)
            for e, b, _ in bounds:
                k = (r["kind"], key, b, ix, iy)
                m, n = g.get(k, (0.0, 0))
                g[k] = (max(m, err(r, e) / float(r[b])), n + 1)
    return g


def kinds_of(rows):
    """The KINDS that have rows."""
    present = {r["kind"] for r in rows}
    return [(k, label) for k, label in KINDS if k in present]


def draw(g, n_rows, source, mode, kinds):
    cw, ch = 22, 14
    left, top, gapx, gapy = 70, 66, 100, 74
    pw = AX[2] * cw
    bounds = mode["bounds"]
    panels = [(kind, klabel, m) for kind, klabel in kinds for m in MAPS]
    # as wide as the two-column chart at least, for the titles
    width = max(left + len(bounds) * pw + (len(bounds) - 1) * gapx + 150, left + 2 * pw + gapx + 150)
    height = top + sum(m[2][2] * ch + gapy for _, _, m in panels) + 30
    out = svg_open(width, height) + [
           '<text x="%d" y="18" font-size="13">%s</text>' % (left, mode["title"]),
           '<text x="%d" y="34" fill="#555">python3 docs/light_stability_map.py%s %s</text>' % (left, mode["flag"], source),
           '<text x="%d" y="50" fill="#555">%d queries; %s</text>' % (left, n_rows, mode["bound_text"])]
    y0 = top
    for kind, klabel, (key, mlabel, ya, yl) in panels:
        y0 += 14
        ph = ya[2] * ch
        for col, (_, b, blabel) in enumerate(bounds):
            x0 = left + col * (pw + gapx)
            vals = [v[0] for k, v in g.items() if k[:3] == (kind, key, b)]
            status = "worst %.3g" % max(vals) if vals else "no query"
            out.append('<text x="%d" y="%d" font-size="12">%s, %s: %s</text>' % (x0, y0 - 4, klabel, blabel, status))
            out += heat_cells(lambda ix, iy: worst_of(g.get((kind, key, b, ix, iy))), AX[2], ya[2], x0, y0, cw, ch)
            out += log_axes(x0, y0, pw, ph, AX, ya, "angular radius α (rad)", yl, 48,
                            lambda e: "≤1e%d" % e if key == "height" and e == ya[0] else "1e%d" % e)
        y0 += ph + gapy - 14
    out += bound_bar(left + len(bounds) * pw + (len(bounds) - 1) * gapx + 30, top + 14, 2 * AX[2] * ch)
    svg_close(out, mode["svg"], left, height, "grey: no query in the cell; bottom row of the height maps: the light reaches the horizon or below")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--extent", action="store_true", help="the extent rule (bands = 20) instead of Eq. 27")
    ap.add_argument("--dir", action="append", default=[], help="a sweep sample directory to add (repeatable)")
    ap.add_argument("--dump", action="append", default=[], help="dump files to draw instead of running cargo")
    a = ap.parse_args()
    mode = MODES["extent" if a.extent else "single"]
    if a.dump:
        rows = [r for path in a.dump for r in read_dump(path)]
        source = "(from dumps)"
    else:
        rows = run_sweep_test(mode["test"], mode["dump_env"])
        for d in a.dir:
            os.environ[mode["dir_env"]] = d
            rows += run_sweep_test(mode["test"], mode["dump_env"])
        os.environ.pop(mode["dir_env"], None)
        source = mode["source"] if not a.dir else "%s + %d --dir sample%s)" % (mode["source"][:-1], len(a.dir), "s" * (len(a.dir) > 1))
    bounds = mode["bounds"]
    g = grid(rows, bounds)
    kinds = kinds_of(rows)
    draw(g, len(rows), source, mode, kinds)
    for kind, klabel in kinds:
        for e, b, blabel in bounds:
            vals = [v for k, v in g.items() if k[0] == kind and k[1] == MAPS[0][0] and k[2] == b]
            worst = max((v[0] for v in vals), default=0.0)
            over = sum(1 for r in rows if r["kind"] == kind and err(r, e) > float(r[b]))
            print("%s, against %s: worst err/bound %.3g, %d queries over" % (klabel, blabel, worst, over))
    print("wrote", mode["svg"])


if __name__ == "__main__":
    main()
