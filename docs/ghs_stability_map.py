#!/usr/bin/env python3
"""Stability map of the GHS kernel: worst err/bound over (beta, tan theta_h) for D (Eq. 38) and
the full BRDF, before and after the issue #20 fixes, as docs/ghs-stability.svg.

err is the f32 kernel's relative error against the mpmath reference at the same f32 inputs
(reference/ghs/domain_sweep.py), bound = max(1e-4, 8 kappa) with kappa the query's
conditioning; a cell shows the largest err/bound of its queries (> 1 is a defect).

  python3 docs/ghs_stability_map.py                     # runs the sweep test, redraws the chart
  python3 docs/ghs_stability_map.py --dump FILE         # from a GHS_SWEEP_DUMP file instead
  python3 docs/ghs_stability_map.py --save-before FILE  # grid the dump of the pre-fix kernel
                                                        # into docs/ghs-stability-before.csv

The "before" column is docs/ghs-stability-before.csv: the dump of the same test run on the
kernel before the fixes (commit 969f23e, with D called as d(h.z)), gridded by --save-before.
Python standard library only.
"""
import argparse
import csv
import math
import os
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
BEFORE = os.path.join(HERE, "ghs-stability-before.csv")
SVG = os.path.join(HERE, "ghs-stability.svg")

# grid: log10 beta x log10 tan theta_h
BX = (-3.0, math.log10(0.5), 11)
TY = (-6.0, 2.5, 17)
FAMILIES = [("ndf", "D (Eq. 38)"), ("brdf", "full ρ")]


def cell(v, lo, hi, n):
    i = int((v - lo) / (hi - lo) * n)
    return min(max(i, 0), n - 1)


def grid(rows):
    """{(family, ix, iy): (max err/bound, count)} from dump rows."""
    g = {}
    for r in rows:
        beta, tan_h = float(r["beta"]), float(r["tan_h"])
        ratio = float(r["err"]) / float(r["bound"])
        ix = cell(math.log10(beta), *BX)
        iy = cell(math.log10(tan_h) if tan_h > 0 else TY[0], *TY)
        key = (r["family"], ix, iy)
        m, n = g.get(key, (0.0, 0))
        g[key] = (max(m, ratio), n + 1)
    return g


def read_dump(path):
    with open(path) as fh:
        return list(csv.DictReader(fh))


def run_sweep_test(test, dump_env):
    """Runs the kernel's sweep test `test` with `dump_env` naming a temporary dump file;
    prints its table lines and returns the dump's rows (the other maps use this too)."""
    fd, path = tempfile.mkstemp(suffix=".csv")
    os.close(fd)
    env = dict(os.environ, **{dump_env: path})
    cmd = ["cargo", "test", "--release", "-p", "scratchwave-kernel", "--test", test,
           "--", "--nocapture"]
    r = subprocess.run(cmd, cwd=ROOT, env=env, capture_output=True, text=True)
    sys.stdout.write("\n".join(l for l in r.stdout.splitlines() if l.startswith("|") or "queries" in l) + "\n")
    if r.returncode != 0:
        print("note: the sweep test failed (the map shows where)", file=sys.stderr)
    rows = read_dump(path)
    os.unlink(path)
    return rows


def run_test():
    return run_sweep_test("ghs_domain_sweep", "GHS_SWEEP_DUMP")


def save_grid(g, path, names=("family",)):
    """Writes a grid `{(*names, ix, iy): (worst err/bound, count)}` as CSV (a "before" grid;
    `names` the columns of the key before the cell)."""
    with open(path, "w", newline="") as fh:
        w = csv.writer(fh, lineterminator="\n")
        w.writerow(list(names) + ["ix", "iy", "max_err_over_bound", "count"])
        for key, (m, n) in sorted(g.items()):
            w.writerow(list(key) + ["%.4g" % m, n])


def load_grid(path, names=("family",)):
    """The grid `save_grid` wrote."""
    g = {}
    with open(path) as fh:
        for r in csv.DictReader(fh):
            key = tuple(r[c] for c in names) + (int(r["ix"]), int(r["iy"]))
            g[key] = (float(r["max_err_over_bound"]), int(r["count"]))
    return g


# colour: log10(err/bound) from -3 to +4; <= 0 greens/blues, > 0 oranges/reds
STOPS = [(-3.0, (33, 102, 172)), (-1.5, (103, 169, 207)), (-0.5, (209, 229, 240)),
         (0.0, (247, 247, 247)), (0.0001, (253, 219, 199)), (1.0, (244, 165, 130)),
         (2.0, (214, 96, 77)), (4.0, (103, 0, 31))]


def colour(ratio):
    x = math.log10(max(ratio, 1e-30))
    x = min(max(x, STOPS[0][0]), STOPS[-1][0])
    for (x0, c0), (x1, c1) in zip(STOPS[:-1], STOPS[1:]):
        if x0 <= x <= x1:
            t = (x - x0) / (x1 - x0) if x1 > x0 else 0
            return "rgb(%d,%d,%d)" % tuple(round(a + t * (b - a)) for a, b in zip(c0, c1))
    return "rgb(0,0,0)"


def bound_label(e):
    """The colour bar's label at 10^e of err/bound."""
    return "1 (bound)" if e == 0 else "1e%d" % e


def colour_bar(bx, by, bh, label=bound_label):
    """SVG lines of the vertical colour bar at (bx, by), bh tall, labelled at each decade
    (every map uses it)."""
    out = []
    n = 70
    for i in range(n):
        x = STOPS[0][0] + (STOPS[-1][0] - STOPS[0][0]) * (i + 0.5) / n
        out.append('<rect x="%d" y="%.2f" width="16" height="%.2f" fill="%s"/>' % (bx, by + bh - (i + 1) * bh / n, bh / n + 0.3, colour(10 ** x)))
    for e in range(-3, 5):
        y = by + bh - (e - STOPS[0][0]) / (STOPS[-1][0] - STOPS[0][0]) * bh
        out.append('<text x="%d" y="%.1f" dominant-baseline="middle">%s</text>' % (bx + 20, y, label(e)))
    return out



def svg_open(width, height):
    """The first lines of every map: the svg element and a white ground."""
    return ['<svg xmlns="http://www.w3.org/2000/svg" width="%d" height="%d" font-family="sans-serif" font-size="11">' % (width, height),
            '<rect width="100%" height="100%" fill="white"/>']


def svg_close(out, path, left, height, note):
    """Appends the grey footnote `note` and the closing tag to `out` and writes it to `path`."""
    out.append('<text x="%d" y="%d" fill="#555">%s</text>' % (left, height - 12, note))
    out.append("</svg>")
    with open(path, "w") as fh:
        fh.write("\n".join(out) + "\n")


def bound_bar(bx, by, bh):
    """The colour bar of err/bound with its title."""
    return colour_bar(bx, by, bh) + ['<text x="%d" y="%d">err/bound</text>' % (bx - 4, by - 14)]


def worst_of(v):
    """`heat_cells`' cell of a grid value `(worst err/bound, count)`, None for no value."""
    return (v[0], "%.3g over %d queries" % v) if v else None


def heat_cells(cell_of, nx, ny, x0, y0, cw, ch):
    """The rects of one map's nx × ny cells, (0, 0) at the bottom left: `cell_of(ix, iy)` gives
    (the value to colour, its tooltip), or None for a grey cell (no query)."""
    out = []
    for ix in range(nx):
        for iy in range(ny):
            c = cell_of(ix, iy)
            fill = colour(c[0]) if c else "#e6e6e6"
            title = "<title>%s</title>" % c[1] if c else ""
            out.append('<rect x="%d" y="%d" width="%d" height="%d" fill="%s" stroke="white" stroke-width="0.5">%s</rect>'
                       % (x0 + ix * cw, y0 + (ny - 1 - iy) * ch, cw, ch, fill, title))
    return out


def decades(axis):
    """The decades to label on a log axis `(lo, hi, cells)`: every second one where it spans
    more than 7."""
    return range(math.ceil(axis[0]), math.floor(axis[1]) + 1, 2 if axis[1] - axis[0] > 7 else 1)


def log_axes(x0, y0, w, h, xa, ya, xlabel, ylabel, ylabel_dx, ytick=lambda e: "1e%d" % e):
    """Tick labels and titles of a map's two log axes (the map `w` × `h` at (x0, y0); the
    y title `ylabel_dx` left of it; `ytick(e)` labels the y decade e)."""
    out = []
    for e in decades(xa):
        x = x0 + (e - xa[0]) / (xa[1] - xa[0]) * w
        out.append('<text x="%.1f" y="%d" text-anchor="middle">1e%d</text>' % (x, y0 + h + 13, e))
    out.append('<text x="%.1f" y="%d" text-anchor="middle">%s</text>' % (x0 + w / 2, y0 + h + 27, xlabel))
    for e in decades(ya):
        y = y0 + h - (e - ya[0]) / (ya[1] - ya[0]) * h
        out.append('<text x="%d" y="%.1f" text-anchor="end" dominant-baseline="middle">%s</text>' % (x0 - 4, y, ytick(e)))
    out.append('<text x="%d" y="%.1f" text-anchor="middle" transform="rotate(-90 %d %.1f)">%s</text>'
               % (x0 - ylabel_dx, y0 + h / 2, x0 - ylabel_dx, y0 + h / 2, ylabel))
    return out


def before_after_rows(doc, dump_env, before, run, grid, names=("family",)):
    """The command line of a map beside a "before" grid: `--dump FILE` (a `dump_env` file of
    the current kernel, instead of running cargo) or `--save-before DUMP` (grid that dump
    into `before` and stop). Returns the current kernel's rows, or None after --save-before."""
    ap = argparse.ArgumentParser(description=doc, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--dump", help="a %s file of the current kernel (skips cargo)" % dump_env)
    ap.add_argument("--save-before", metavar="DUMP", help="grid this dump into " + before + " and exit")
    a = ap.parse_args()
    if a.save_before:
        save_grid(grid(read_dump(a.save_before)), before, names)
        print("wrote", before)
        return None
    return read_dump(a.dump) if a.dump else run()


def draw(before, after, path):
    cw, ch = 26, 14
    pw, ph = BX[2] * cw, TY[2] * ch
    left, top, gapx, gapy = 70, 50, 80, 70
    width = left + 2 * pw + gapx + 150
    height = top + 2 * ph + gapy + 70
    out = svg_open(width, height) + [
           '<text x="%d" y="18" font-size="13">GHS kernel vs mpmath at the same f32 inputs: worst err / max(1e-4, 8κ) per cell</text>' % left,
           '<text x="%d" y="34" fill="#555">python3 docs/ghs_stability_map.py (queries: reference/ghs/golden/sweep/{ndf,brdf}.csv)</text>' % left]
    for row, (fam, label) in enumerate(FAMILIES):
        for col, (name, g) in enumerate((("before (969f23e)", before), ("after", after))):
            x0 = left + col * (pw + gapx)
            y0 = top + row * (ph + gapy) + 14
            worst = max((v[0] for k, v in g.items() if k[0] == fam), default=0)
            out.append('<text x="%d" y="%d" font-size="12">%s, %s: worst %.3g</text>' % (x0, y0 - 4, label, name, worst))
            out += heat_cells(lambda ix, iy: worst_of(g.get((fam, ix, iy))), BX[2], TY[2], x0, y0, cw, ch)
            out += log_axes(x0, y0, pw, ph, BX, TY, "β", "tan θh", 40)
    out += bound_bar(left + 2 * pw + gapx + 30, top + 14, 2 * ph + gapy - 20)
    svg_close(out, path, left, height, "grey: no query in the cell; tan θh = 0 is drawn in the lowest row")


def main():
    rows = before_after_rows(__doc__, "GHS_SWEEP_DUMP", BEFORE, run_test, grid)
    if rows is None:
        return
    after = grid(rows)
    draw(load_grid(BEFORE), after, SVG)
    for fam, label in FAMILIES:
        w = max((v[0] for k, v in after.items() if k[0] == fam), default=0)
        print("%s: worst err/bound %.3g" % (label, w))
    print("wrote", SVG)


if __name__ == "__main__":
    main()
