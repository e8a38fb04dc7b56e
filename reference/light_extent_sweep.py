#!/usr/bin/env python3
"""Domain sweep of the area-light integral with the Gaussian across the band (issue #20).

`reference/light_sweep.py` checks Velinov's single band (Eq. 27, `bands = 1`): the band
xi_1 = 0 alone. The renderer's default is the extent rule (`bands = 20`,
`kernel/src/lights/integrate.rs::extent_power`), which weights the parallel bands
(wi + wo)_xy . t = o by the normalised Gaussian of the infinite scratch across xi_1 = o/lambda,
e^(-4 pi^2 sigma^2 xi_1^2), i.e. o ~ N(0, sd^2) with sd = lambda/(2 sqrt(2) pi sigma):

  I = 1/(pi sigma^2) sum_k P_k D2_k int phi(x) L_k(x sd) dx,

phi the standard normal density, L_k(o) = sum_lit [A(q1) - A(q0)] along the band at offset
o (the band circle w(phi) = c t3 + rho (sin phi b3 + cos phi z) with c = o - wo_xy.t,
rho = sqrt(1 - c^2)), P_k, D2_k and A as in `light_sweep.py` (whose exact geometry, lit
arcs, antiderivative, spatial and depth factors, domain and CSV columns this script reuses).

The integral over x is mpmath's tanh-sinh quadrature over the whole line cut where L_k has
kinks, found here by their own equations (nothing from the kernel's kink code):
* the band tangent to a boundary plane m.w = h (an edge's great circle, h = 0, or the cone,
  h = cos alpha): (h - c m_t)^2 = (m_b^2 + m_z^2)(1 - c^2), a quadratic in c;
* a band end on the horizon (phi = +-pi/2, w = c t3 +- rho b3) on a boundary plane:
  (h - c m_t)^2 = m_b^2 (1 - c^2);
* a polygon vertex on the band: c = t3 . v;
* c = +-1, where the band shrinks to a point.
Each piece is halved until mpmath's error estimate is below 1e-12 of the whole; a
query whose summed estimate exceeds 1e-10 of its value is redrawn (counted on stderr). 30
digits. Beyond |x| = 8 nothing: the Gaussian holds 1.2e-15 of its mass there (the kernel
stops at 4.5, 6.8e-6), so a light that the bands reach only that far out has the exact
value 0 here.

The kernel's window is part of its model, as Werner's 6-sigma window is of the coherent
sum: the extent rule integrates |x| <= 4.5 only. So each query also carries `window`, the
same integral over |x| <= 4.5 alone (its pieces are cut there and refined against their own
sum), which is what the kernel's arithmetic and quadrature are measured against; `tail`,
the share of the whole value from beyond, is the model's error from the window.

No conditioning is computed: one query's kappa would need ~50 further quadratures
(`kernel/tests/light_extent_sweep.rs`, `docs/stability.md` *Area lights*).

`--vgroove` draws the same queries (same seed and sequence) with every scratch a V groove
(profile 1) and writes DIR/light_extent_vgroove.csv (default 200 queries). The chord at
offset o is then sum_lit int_{q0}^{q1} |M - P|^2 dq (`light_sweep.vgroove_sum` on the
offset band, `vgroove_band_sweep.band_integral`), with the depth inside it (D2_k = 1), at
the depth phase 2 gamma / lambda of the one gamma the kernel takes for every band, at the
light's centre direction (`light_integrals_in`). |M - P|^2 is entire in q, so L(o) kinks
only where the lit chords' ends do, at the rectangular groove's geometric kinks above; its
peaks (W q = 0, +-D ht) are smooth and left to the halving. A chord's whole quarter-lobe
cells are cached (`VgrooveChord`). The committed subset: 200 queries, 808 s on one core.

Usage: python3 reference/light_extent_sweep.py [--vgroove] [--count N] [--seed-offset K] [--out DIR]
Writes DIR/light_extent.csv (default reference/golden/sweep/): `light_sweep.py`'s columns
without kappa, kappa_s and reach, plus `single`, the same query's exact single-band value,
`tail`, the share of the exact value that comes from bands beyond 4.5 standard deviations
(the kernel's window, `EXTENT_SDS`), and `window`, the exact value of the bands within it.
"""
import sys
import time

import mpmath as mp
import numpy as np

import light_sweep as ls
import vgroove_band_sweep
from sweep_io import parse_args, progress, write_csv

mp.mp.dps = 30

# Beyond this many standard deviations the Gaussian holds 1.2e-15 of its mass.
X_MAX = 8
# The kernel's window (`EXTENT_SDS`): the part of the value from beyond it is reported.
X_KERNEL = 4.5
# light_sweep.py's columns this sweep leaves out (no conditioning is computed here).
NOT_COMPUTED = ("kappa", "kappa_s", "reach")


class OffsetBand(ls.Band):
    """The band at offset `o` (direction cosines) from xi_1 = 0; `None`-like (rho = 0)
    where |c| >= 1."""

    def __init__(self, s, wo, o):
        super().__init__(s, wo)
        self.c = o - (wo[0] * self.t3[0] + wo[1] * self.t3[1])
        self.rho = mp.sqrt(1 - self.c * self.c) if abs(self.c) < 1 else mp.mpf(0)


# A V-groove chord over fewer whole cells than this is integrated as it stands.
SHORT_CELLS = 4


class VgrooveChord:
    """int_{q0}^{q1} |M - P|^2 dq of one V groove (W, D, depth phase ht) by
    `vgroove_band_sweep.band_integral` on the grid of its own piece width, q = k/(4W): the
    whole cells a chord covers come from a cache, its two ends are integrated anew, so a
    band costs two pieces however many lobes its chord covers. Called at one precision (the
    chord's), which the cells keep."""

    def __init__(self, w, d, ht):
        self.w, self.d, self.ht = w, d, ht
        self.cells = {}

    def piece(self, a, b):
        return vgroove_band_sweep.band_integral(self.w, self.d, self.ht, a, b - a)

    def cell(self, k, h):
        if k not in self.cells:
            self.cells[k] = self.piece(k * h, (k + 1) * h)
        return self.cells[k]

    def __call__(self, q0, q1):
        sign = 1
        if q1 < q0:
            q0, q1, sign = q1, q0, -1
        h = 1 / (vgroove_band_sweep.PIECES_PER_LOBE * mp.mpf(self.w))
        k0, k1 = int(mp.floor(q0 / h)) + 1, int(mp.floor(q1 / h))
        if k1 - k0 < SHORT_CELLS:
            return sign * self.piece(q0, q1)
        total = self.piece(q0, k0 * h) + self.piece(k1 * h, q1)
        for k in range(k0, k1):
            total += self.cell(k, h)
        return sign * total


def chord(s, wo, reg, lam_um, o, vg=None):
    """L(o) = sum_lit A(q1) - A(q0) along the band at offset o, at twice the working
    precision: the quadrature's nodes crowd within ~10^-dps of a kink, where a lit chord
    is that short and A(q1) - A(q0) cancels that many digits. With `vg` (a V groove's
    `VgrooveChord`), sum_lit int_{q0}^{q1} |M - P|^2 dq, as `light_sweep.vgroove_sum` on
    the offset band."""
    with mp.workdps(2 * mp.mp.dps):
        band = OffsetBand(s, wo, o)
        if band.rho == 0:
            return mp.mpf(0)
        if vg is None:
            total = ls.lit_sum(band, reg, mp.mpf(s["w"]), lam_um)
        else:
            total = ls.lit_integral_sum(band, reg, lam_um, vg)
    return +total


def depth_phase(q, parts):
    """The V groove's depth phase 2 gamma / lambda (half-turns per um of depth), None for a
    rectangular groove. The kernel takes gamma once, at the light's centre direction
    (`light_integrals_in`), for every band of the extent rule: so does this."""
    if q.get("profile", 0) != 1 or parts.reg is None:
        return None
    return ls.depth_phase(q, parts.reg, parts.wo, parts.lam)


def quadratic_roots(a, b, c):
    """Real roots of a x^2 + b x + c = 0."""
    if a == 0:
        return [] if b == 0 else [-c / b]
    disc = b * b - 4 * a * c
    if disc < 0:
        return []
    r = mp.sqrt(disc)
    return [(-b + r) / (2 * a), (-b - r) / (2 * a)]


def kinks_c(s, reg):
    """Values of c where L has a kink or a square-root end (see the module doc)."""
    band = ls.Band(s, [mp.mpf(0), mp.mpf(0), mp.mpf(1)])
    t3, b3 = band.t3, band.b3
    out = [mp.mpf(-1), mp.mpf(1)]
    for m, h in ls.planes(reg):
        mt, mb, mz = ls.dot(m, t3), ls.dot(m, b3), m[2]
        # tangency: (h - c mt)^2 = (mb^2 + mz^2)(1 - c^2)
        r2 = mb * mb + mz * mz
        out += quadratic_roots(mt * mt + r2, -2 * h * mt, h * h - r2)
        # a horizon end on the plane: (h - c mt)^2 = mb^2 (1 - c^2)
        out += quadratic_roots(mt * mt + mb * mb, -2 * h * mt, h * h - mb * mb)
    if reg[0] == "poly":
        # vertices: the corners of the spherical polygon, where consecutive planes meet
        normals = reg[1]
        for k in range(len(normals)):
            v = ls.cross(normals[k - 1], normals[k])
            n = mp.sqrt(ls.dot(v, v))
            if n > 0:
                for sign in (1, -1):
                    out.append(sign * ls.dot(v, t3) / n)
    return [c for c in out if -1 <= c <= 1]


def gaussian_integral(s, wo, reg, lam_um, sd, x_max=X_MAX, ht=None):
    """int phi(x) L(x sd) dx over |x| <= x_max, the sum of the pieces' error estimates, the
    part of the integral from |x| <= X_KERNEL and its error estimate.
    A piece is halved until its estimate is below 1e-12 of the sum of |pieces| between the
    kinks on its side of X_KERNEL, or it is narrower than 1e-6: the part within the window
    is refined against its own size, however small a share of the whole it is."""
    t = ls.unit([s["tx"], s["ty"]])
    wo_t = wo[0] * t[0] + wo[1] * t[1]
    ends = {-mp.mpf(x_max), mp.mpf(x_max), -mp.mpf(X_KERNEL), mp.mpf(X_KERNEL)}
    cuts = sorted({(c + wo_t) / sd for c in kinks_c(s, reg)} | ends)
    cuts = [x for x in cuts if -x_max <= x <= x_max]

    vg = None if ht is None else VgrooveChord(s["w"], s["d"], ht)

    def f(x):
        return mp.npdf(x) * chord(s, wo, reg, lam_um, x * sd, vg)

    def inside(a, b):
        return abs(a + b) / 2 <= X_KERNEL

    first = [(a, b, *mp.quad(f, [a, b], error=True)) for a, b in zip(cuts, cuts[1:]) if b > a]
    scale = sum(abs(v) for _, _, v, _ in first)
    scale_in = sum(abs(v) for a, b, v, _ in first if inside(a, b))
    tol, tol_in = mp.mpf(10) ** -12 * scale, mp.mpf(10) ** -12 * scale_in
    total, err, win, err_in = mp.mpf(0), mp.mpf(0), mp.mpf(0), mp.mpf(0)
    stack = first
    while stack:
        a, b, v, e = stack.pop()
        if e > (tol_in if inside(a, b) else tol) and b - a > mp.mpf(10) ** -6:
            mid = (a + b) / 2
            stack += [(a, mid, *mp.quad(f, [a, mid], error=True)), (mid, b, *mp.quad(f, [mid, b], error=True))]
            continue
        total += v
        err += e
        if inside(a, b):
            win += v
            err_in += e
    return total, err, win, err_in


def value(q):
    """The exact Gaussian-weighted value of query `q`, its single-band value, the
    quadrature's estimated relative error, the share of the value from beyond the kernel's
    window, the exact value within the window and its estimated relative error."""
    parts = ls.Parts(q)
    single = parts.total()
    if parts.reg is None:
        return mp.mpf(0), single, 0.0, 0.0, mp.mpf(0), 0.0
    sig = mp.mpf(q["sigma"])
    sd = parts.lam / (2 * mp.sqrt(2) * mp.pi * sig)
    ht = depth_phase(q, parts)
    total, err, win, err_in = mp.mpf(0), mp.mpf(0), mp.mpf(0), mp.mpf(0)
    for k, s in enumerate(q["scratches"]):
        weight = parts.p[k] * parts.d2[k] / (mp.pi * sig * sig)
        if weight == 0:
            continue
        g, e, w, e_in = gaussian_integral(s, parts.wo, parts.reg[0], parts.lam, sd, ht=ht)
        total += weight * g
        err += abs(weight) * e
        win += weight * w
        err_in += abs(weight) * e_in
    rel = float(err / abs(total)) if total != 0 else 0.0
    share = float((total - win) / total) if total != 0 else 0.0
    rel_in = float(err_in / abs(win)) if win != 0 else 0.0
    return total, single, rel, share, win, rel_in


def main():
    vgroove = "--vgroove" in sys.argv
    if vgroove:
        sys.argv.remove("--vgroove")
    args = parse_args(200 if vgroove else 400)
    rng = np.random.default_rng(20_020 + 7919 + args.seed_offset)
    # light_sweep's columns by name, less those this sweep does not compute
    head = ls.header()
    keep = [i for i, h in enumerate(head) if h not in NOT_COMPUTED]
    rows, t0 = [], time.time()
    while len(rows) < args.count:
        q = ls.draw(rng)
        q["profile"] = 1 if vgroove else 0
        ref, single, quad_err, tail, win, win_err = value(q)
        if quad_err > 1e-10:
            print(f"quadrature error estimate {quad_err:.1e}: redrawn", file=sys.stderr)
            continue
        if win_err > 1e-10:
            print(f"query {len(rows)}: the window's error estimate is {win_err:.1e}", file=sys.stderr)
        lit = 0
        reg = ls.region(q)
        if reg is not None:
            wo = ls.unit(q["wo"])
            lit = sum(len(ls.Band(s, wo).lit(reg[0])) for s in q["scratches"])
        full = ls.row(q, ref, 0.0, lit, 0.0, 0.0)
        r = [full[i] for i in keep]
        exact = [mp.nstr(v, 17, min_fixed=1, max_fixed=0) for v in (single, win)]
        rows.append(r + [exact[0], "%.4g" % tail, exact[1]])
        progress(len(rows), args.count, 20)
    print(f"{len(rows)} queries, {time.time() - t0:.0f} s", file=sys.stderr)
    write_csv(args.out, "light_extent_vgroove" if vgroove else "light_extent", [head[i] for i in keep] + ["single", "tail", "window"], rows)


if __name__ == "__main__":
    main()
