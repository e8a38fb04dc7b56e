#!/usr/bin/env python3
"""Conditioning of the extent rule's exact window value (issue #20).

`light_extent_sweep.py` writes, per query, the exact integral of phi(x) L(x sd) over the
kernel's window |x| <= 4.5 (column `window`) but no conditioning: a query's kappa takes one
further quadrature per float32 input that moves the band or the light. It is needed only
where the kernel's error is above the 1e-4 floor, so this script computes it for the rows
it is given (`kernel/tests/light_extent_sweep.rs` prints them, and the test applies
#20's bound max(1e-4, 8 kappa) wherever this file has a row's kappa).

kappa is `light_sweep.py`'s: the largest relative change of the exact value when one
float32 input moves by one float32 step either way (`light_sweep.neighbours`), here of the
window value. An input that only scales a scratch (its position along and across, its half
length, the shading point, the depth) changes only that scratch's factor P_k or D2_k; one
that moves a band or the light, or sigma (which sets the band's standard deviation),
takes the scratch's window quadrature again.

A V groove's depth is inside its chord integral (`light_sweep.neighbours` moves it as an
`l` input), and its depth phase follows the light's centre and wo as the kernel's does
(`light_extent_sweep.depth_phase`), so those neighbours take the quadrature again.

Usage: python3 reference/light_extent_kappa.py [--vgroove] --rows I,J,... [--dir DIR] [--jobs N]
Reads DIR/light_extent.csv (default reference/golden/sweep/; with --vgroove
DIR/light_extent_vgroove.csv), where row 0 is the first query after the header, and writes
DIR/light_extent_kappa.csv (light_extent_vgroove_kappa.csv) (`row,kappa,window`, `window`
the recomputed exact value as a check), keeping the rows already there that were not asked
for again.
"""
import argparse
import csv
import os
import sys
import time

import mpmath as mp

import light_extent_sweep as les
import light_sweep as ls
from parallel import ordered_map

mp.mp.dps = 30

DEFAULT_DIR = os.path.join(os.path.dirname(os.path.abspath(__file__)), "golden", "sweep")


class Window:
    """The factors of a query's window value: P_k, D2_k and G_k, the window integral of
    scratch k's chord, each recomputed only where an input changes it."""

    def __init__(self, q, base=None, redo=None):
        self.q = q
        self.parts = ls.Parts.__new__(ls.Parts)
        p = self.parts
        p.q, p.wo, p.reg, p.lam = q, ls.unit(q["wo"]), ls.region(q), mp.mpf(q["lambda_nm"]) / 1000
        sig = mp.mpf(q["sigma"])
        self.sd = p.lam / (2 * mp.sqrt(2) * mp.pi * sig)
        self.ht = les.depth_phase(q, p)
        n = len(q["scratches"])
        every = set(range(n))
        redo = redo or {"p": every, "d": every, "g": every}
        p.p = [ls.along(q, s) if k in redo["p"] else base.parts.p[k] for k, s in enumerate(q["scratches"])]
        p.d2 = [ls.depth2(q, s, p.reg, p.wo) if k in redo["d"] else base.parts.d2[k]
                for k, s in enumerate(q["scratches"])]
        self.g = [self.window(s) if k in redo["g"] else base.g[k] for k, s in enumerate(q["scratches"])]

    def window(self, s):
        if self.parts.reg is None:
            return mp.mpf(0)
        _, _, win, _ = les.gaussian_integral(s, self.parts.wo, self.parts.reg[0], self.parts.lam, self.sd,
                                             x_max=les.X_KERNEL, ht=self.ht)
        return win

    def total(self):
        sig = mp.mpf(self.q["sigma"])
        p = self.parts
        return sum(a * b * c for a, b, c in zip(p.p, p.d2, self.g)) / (mp.pi * sig * sig)


def redo_of(kind, n, sigma_moved):
    """Which factors a neighbour of `light_sweep.neighbours`' `kind` changes: those of
    `light_sweep.changed_factors`, the band sum's window integral `g` for its `l`; every
    factor for 'all' and for sigma, which also sets the band's standard deviation."""
    if kind == "all" or sigma_moved:
        every = set(range(n))
        return {"p": every, "d": every, "g": every}
    changed = ls.changed_factors(kind, n)
    return {"p": changed["p"], "d": changed["d"], "g": changed["l"]}


def kappa(r):
    """(kappa, window value) of CSV row `r`."""
    q = ls.query_of(r)
    base = Window(q)
    ref = base.total()
    if ref == 0:
        return 0.0, ref
    worst = 0.0
    for kind, q2 in ls.neighbours(q):
        redo = redo_of(kind, len(q["scratches"]), q2["sigma"] != q["sigma"])
        v = Window(q2, base, redo).total()
        worst = max(worst, float(abs(v / ref - 1)))
    return worst, ref


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--rows", required=True, help="comma-separated row indices (0 = first query)")
    ap.add_argument("--dir", default=DEFAULT_DIR)
    ap.add_argument("--jobs", type=int, default=1)
    ap.add_argument("--vgroove", action="store_true", help="the V-groove table (light_extent_vgroove.csv)")
    args = ap.parse_args()
    family = "light_extent_vgroove" if args.vgroove else "light_extent"
    with open(os.path.join(args.dir, family + ".csv")) as fh:
        table = list(csv.DictReader(fh))
    wanted = sorted({int(i) for i in args.rows.split(",") if i.strip()})
    bad = [i for i in wanted if not 0 <= i < len(table)]
    if bad:
        sys.exit(f"--rows: {bad} outside 0..{len(table) - 1}")
    out = os.path.join(args.dir, family + "_kappa.csv")
    kept = {}
    if os.path.exists(out):
        with open(out) as fh:
            kept = {int(row["row"]): row for row in csv.DictReader(fh)}
    t0 = time.time()
    for i, (kap, win) in zip(wanted, ordered_map(kappa, [table[i] for i in wanted], args.jobs, chunksize=1)):
        recorded = mp.mpf(table[i]["window"])
        if recorded != 0 and abs(win / recorded - 1) > 1e-12:
            sys.exit(f"row {i}: window recomputed {mp.nstr(win, 17)}, recorded {table[i]['window']}")
        kept[i] = {"row": str(i), "kappa": "%.4g" % kap, "window": mp.nstr(win, 17, min_fixed=1, max_fixed=0)}
        print(f"row {i}: kappa {kap:.4g} ({time.time() - t0:.0f} s)", file=sys.stderr)
        # written after every row, so that an interrupted run keeps what it has
        with open(out, "w", newline="") as fh:
            w = csv.writer(fh, lineterminator="\n")
            w.writerow(["row", "kappa", "window"])
            for j in sorted(kept):
                w.writerow([kept[j]["row"], kept[j]["kappa"], kept[j]["window"]])
    print(f"wrote {out} ({len(kept)} rows)", file=sys.stderr)


if __name__ == "__main__":
    main()
