#!/usr/bin/env python3
"""Domain sweep of the area-light integral (Velinov 2018 §3.4, Eq. 27; issue #20).

`kernel/src/lights/integrate.rs::light_integral` with the single-band rule (`bands = 1`,
Velinov's Eq. 27) and the exact Si returns, for a constant reflectance F = 1,

  I = 1/(pi sigma^2) sum_k P_k D2_k sum_lit [A(q1) - A(q0)]

* P_k = e^(-s_b^2/sigma^2) sqrt(pi) sigma (infinite eta), or e^(-s_b^2/sigma^2)
  int_{s_t-h}^{s_t+h} e^(-u^2/sigma^2) du (finite eta), (s_t, s_b) = (c - x0).(t, b);
* D2_k = |1 - e^(i pi kappa)|^2 = 4 sin^2(pi kappa/2), kappa = D 2000 gamma/lambda_nm,
  gamma = 2 (small angle) or wc.z + wo.z (exact), wc the light's centre direction (sphere:
  centre/|centre|; polygon: the normalised sum of the unit vertex directions) with its z
  raised to at least 1e-3 (f32) and normalised again;
* the lit intervals: the band xi_1 = 0 is the circle of directions
  w(phi) = c t3 + rho (sin phi b3 + cos phi z), c = -wo_xy.t, rho = sqrt(1 - c^2),
  phi in [-pi/2, pi/2] (the upper half: the horizon clips); an interval is lit where w lies
  inside the light (a sphere's cone of half-angle asin(r/d) or atan(r/d), the whole sphere
  when d <= r with the asin cone; a convex spherical polygon: inside every edge plane);
  q = (rho sin phi + wo_xy.b)/lambda (1/um), lambda = lambda_nm/1000;
* A(q) = W (Si(2 pi W q) - pi W q sinc^2(pi W q))/pi.

Nothing is taken from the kernel's crossing code: here the crossings of the circle with a
plane m.w = h (an edge's great circle, h = 0; the cone, m = axis, h = cos alpha) are the
angles phi = psi +- acos(g/R), psi = atan2(m.b3, m.z), R = |(m.b3, m.z)|,
g = (h - c m.t3)/rho, and each arc between consecutive crossings is classified by testing
its midpoint against the light's own definition (`--check` compares that with a dense
sampling of the half circle, and A(q1) - A(q0) with quadrature of W^2 sinc^2).
Everything is mpmath at 40 digits, at exactly the float32 inputs (wo and the tangent
normalised exactly; the tangents are unit to ~1e-9, as in `scratch_sweep.py`).

Each query also carries its conditioning kappa: the largest relative change of the exact
value when one float32 input (wo, lambda, x, sigma, every light coordinate, every scratch
field) moves to a neighbouring float32. A query whose exact value is 0 while a neighbour's
is not (a band exactly grazing a light) is redrawn. Beside it, kappa_s: the largest
relative change when one end of a lit arc moves by one float32 ulp of s = sin(phi), the
parameter the kernel keeps for it (`kernel/src/lights/band_circle.rs`): not an input's
conditioning but the resolution of that representation, which near the horizon
(|s| -> 1) and for chords much shorter than |s| is far coarser than the inputs. The
kernel test accepts err <= max(1e-4, 8 max(kappa, kappa_s)) and, for the committed
queries, the inputs' rule max(1e-4, 8 kappa) (`kernel/tests/light_domain_sweep.rs`,
`docs/stability.md` *Area lights*). Where the exact value is 0, a relative bound says
nothing: such a query carries `reach`, the largest exact value when one input moves by 8
float32 ulps either way (the bound's 8 steps taken literally rather than linearly;
`--rereach FILE...` rewrites that column of committed tables alone), and the test accepts
anything up to it (below 1e-30 where it is 0). The extent rule (bands = 20) is not swept.

Domain: sphere lights with the asin cone (35 %, 3 % of them around the shading point) and
the atan cone (15 %), convex polygons of 3-8 vertices (50 %, a circle or ellipse of
vertices in a plane tilted up to 50 degrees from facing the point); angular radius
1e-5 - 1.4 rad log-uniform; distance 1 mm - 10 m, written in m, mm or um; the light's centre
placed on the first scratch's band circle and moved off it by up to 1.3 angular radii
(0.9 for polygons)
(so most lights meet the band, some graze or miss it); 30 % near the horizon (the band
point at elevation 1e-6 - 0.1 rad, the light then lowered by -0.5 to 1 angular radius,
partly below); sigma 1-100 um, lambda 360-830 nm, W 0.1-50 um, D 1 nm - 10 um (log),
1-3 rectangular scratches of half length 0.1 sigma - 1e3 sigma, the shading point on
(40 %, |s_b| < 0.3 sigma) or off them (up to 4 sigma across, 3 sigma beyond an end), at
|x| 1 - 1e4 um; finite and infinite eta; small-angle and exact depth term; wo with
cos(theta) 0.005 - 1 (`sweep_io.draw_wo`).

`--vgroove` draws the same queries (same seed, same sequence) with every scratch a V
groove (profile 1) and writes DIR/light_vgroove.csv (the committed subset: 1 500 queries,
~10 min with --jobs 2 on a 2-core machine, the quadrature across each chord included): there the
kernel integrates |M - P|^2 across each lit chord by quadrature (`across_integral`), so
L_k is sum_lit int_{q0}^{q1} |M - P|^2 dq with the depth inside it (D2_k = 1), evaluated by
`vgroove_band_sweep.band_integral` (16-point Gauss-Legendre on quarter-lobe pieces) at the
depth phase 2 gamma / lambda of the same gamma; kappa and kappa_s as above (a depth
nudge now changes L_k).

Usage: python3 reference/light_sweep.py [--vgroove] [--count N] [--seed-offset K] [--out DIR] [--jobs N] [--check]
       python3 reference/light_sweep.py --rereach FILE... [--jobs N]
Writes DIR/light.csv (default reference/golden/sweep/). The queries are drawn in order and
kept in order, so `--jobs N` (N worker processes) writes the same file as one process.
`--found [--out DIR]` writes DIR/light_found.csv instead: the queries larger samples found
over the bound (FOUND), regenerated from their seed and draw index.
"""
import math
import sys
import time

import mpmath as mp
import numpy as np

from parallel import ordered_map
from scratch_sweep import s32, unit_tangent
import vgroove_band_sweep
from sweep_io import draw_wo, f32, nudges, parse_args, progress, write_csv

mp.mp.dps = 40

MAX_V = 8
MAX_S = 3
# The steps of `zero_reach`: the kernel test's K_LIGHT (`kernel/tests/sweep_common`).
REACH_ULPS = 8
# Queries found over the bound in larger samples, kept in `light_found.csv` (`--found`):
# (seed offset, index of the draw in that seed's sequence, redrawn ones included).
FOUND = [(2, 28870), (3, 32729), (3, 43601)]
F32_1E3 = f32(1.0e-3)


# ------------------------------------------------------------------ exact geometry (mpmath)
def unit(v):
    v = [mp.mpf(c) for c in v]
    n = mp.sqrt(sum(c * c for c in v))
    return [c / n for c in v]


def dot(a, b):
    return sum(x * y for x, y in zip(a, b))


def cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def region(q):
    """The light as ('cone', axis, alpha) or ('poly', [edge normals, inward]), its centre
    direction, or None (degenerate or entirely below the horizon)."""
    if q["kind"] == 0:
        c = [mp.mpf(v) for v in q["sphere"][:3]]
        r = mp.mpf(q["sphere"][3])
        d = mp.sqrt(dot(c, c))
        if not r > 0 or d == 0 or c[2] <= -r:
            return None
        if q["cone"] == 0:
            alpha = mp.pi if d <= r else mp.asin(r / d)
        else:
            alpha = mp.atan2(r, d)
        axis = [v / d for v in c]
        return ("cone", axis, alpha), axis
    u = [unit(v) for v in q["verts"]]
    if max(v[2] for v in u) <= 0:
        return None
    center = unit([sum(v[i] for v in u) for i in range(3)])
    n = len(u)
    normals = [cross(u[m], u[(m + 1) % n]) for m in range(n)]
    sign = 1 if dot(normals[0], center) > 0 else -1
    return ("poly", [[sign * c for c in nm] for nm in normals]), center


def inside(reg, w):
    if reg[0] == "cone":
        return reg[2] >= mp.pi or dot(w, reg[1]) >= mp.cos(reg[2])
    return all(dot(nm, w) >= 0 for nm in reg[1])


def planes(reg):
    """The boundary planes (m, h): the light's boundary lies on m.w = h."""
    if reg[0] == "cone":
        return [] if reg[2] >= mp.pi else [(reg[1], mp.cos(reg[2]))]
    return [(nm, mp.mpf(0)) for nm in reg[1]]


class Band:
    """The band xi_1 = 0 of one scratch for one view: w(phi) on the upper half circle."""

    def __init__(self, s, wo):
        t = unit([s["tx"], s["ty"]])
        self.t3 = [t[0], t[1], mp.mpf(0)]
        self.b3 = [-t[1], t[0], mp.mpf(0)]
        self.c = -(wo[0] * t[0] + wo[1] * t[1])
        self.rho = mp.sqrt(1 - self.c * self.c)
        self.wo_b = wo[0] * self.b3[0] + wo[1] * self.b3[1]

    def point(self, phi):
        sp, cp = mp.sin(phi), mp.cos(phi)
        return [self.c * self.t3[i] + self.rho * (sp * self.b3[i] + (cp if i == 2 else 0)) for i in range(3)]

    def crossings(self, m, h):
        mt, mb, mz = dot(m, self.t3), dot(m, self.b3), m[2]
        r = mp.sqrt(mb * mb + mz * mz)
        if r == 0:
            return []
        g = (h - self.c * mt) / self.rho
        if abs(g) > r:
            return []
        psi, delta = mp.atan2(mb, mz), mp.acos(g / r)
        out = []
        for phi in (psi + delta, psi - delta):
            phi = (phi + mp.pi) % (2 * mp.pi) - mp.pi
            if abs(phi) <= mp.pi / 2:
                out.append(phi)
        return out

    def lit(self, reg):
        """Lit arcs [(phi0, phi1)], merged, in increasing phi."""
        cuts = [-mp.pi / 2, mp.pi / 2]
        for m, h in planes(reg):
            cuts += self.crossings(m, h)
        cuts.sort()
        arcs = []
        for a, b in zip(cuts, cuts[1:]):
            if b > a and inside(reg, self.point((a + b) / 2)):
                if arcs and arcs[-1][1] == a:
                    arcs[-1] = (arcs[-1][0], b)
                else:
                    arcs.append((a, b))
        return arcs


def antiderivative(w, q):
    """A(q) = W (Si(2 pi W q) - pi W q sinc^2(pi W q)) / pi."""
    x = mp.pi * w * q
    s2 = mp.sin(x) ** 2 / x if x != 0 else mp.mpf(0)
    return w * (mp.si(2 * x) - s2) / mp.pi


def lit_chords(band, shape, lam_um):
    """(q0, q1) in xi_2 (1/um) of each lit arc of `band` inside the light `shape`."""
    for a, b in band.lit(shape):
        yield ((band.rho * mp.sin(a) + band.wo_b) / lam_um,
               (band.rho * mp.sin(b) + band.wo_b) / lam_um)


def lit_sum(band, shape, w, lam_um):
    """sum_lit A(q1) - A(q0) along `band` inside the light `shape` (groove width w)."""
    total = mp.mpf(0)
    for q0, q1 in lit_chords(band, shape, lam_um):
        total += antiderivative(w, q1) - antiderivative(w, q0)
    return total


def band_sum(s, wo, reg, lam_um):
    """sum_lit A(q1) - A(q0) for scratch s."""
    if reg is None:
        return mp.mpf(0)
    return lit_sum(Band(s, wo), reg[0], mp.mpf(s["w"]), lam_um)


def lit_integral_sum(band, shape, lam_um, integral):
    """sum_lit integral(q0, q1) along `band` inside the light `shape`: a V groove's
    int_{q0}^{q1} |M - P|^2 dq over each lit chord (`vgroove_sum`,
    `light_extent_sweep.chord`)."""
    total = mp.mpf(0)
    for q0, q1 in lit_chords(band, shape, lam_um):
        total += integral(q0, q1)
    return total


def depth_phase(q, reg, wo, lam_um):
    """A V groove's depth phase 2 gamma / lambda (half-turns per um of depth), `gamma` at
    the light's centre direction."""
    return 2 * gamma(q, reg, wo) / lam_um


def vgroove_sum(q, s, wo, reg, lam_um):
    """The V groove's L_k (`--vgroove`): sum_lit int_{q0}^{q1} |M - P|^2 dq, the depth
    inside (D2_k = 1), with `vgroove_band_sweep.band_integral` (16-point Gauss-Legendre on
    quarter-lobe pieces, at the working precision) at the depth phase of `depth_phase`."""
    if reg is None:
        return mp.mpf(0)
    ht = depth_phase(q, reg, wo, lam_um)
    return lit_integral_sum(
        Band(s, wo), reg[0], lam_um,
        lambda q0, q1: vgroove_band_sweep.band_integral(s["w"], s["d"], ht, q0, q1 - q0))


def chord_sum(q, s, wo, reg, lam_um):
    """L_k of scratch s: the rectangular groove's `band_sum` or the V groove's `vgroove_sum`
    (`q["profile"]`)."""
    if q.get("profile", 0) == 1:
        return vgroove_sum(q, s, wo, reg, lam_um)
    return band_sum(s, wo, reg, lam_um)


def along(q, s):
    """P_k = int |eta|^2 dxi_1 (um)."""
    t = unit([s["tx"], s["ty"]])
    r0 = [mp.mpf(s["cx"]) - mp.mpf(q["x"][0]), mp.mpf(s["cy"]) - mp.mpf(q["x"][1])]
    st = r0[0] * t[0] + r0[1] * t[1]
    sb = -r0[0] * t[1] + r0[1] * t[0]
    sig = mp.mpf(q["sigma"])
    across = mp.exp(-sb * sb / (sig * sig))
    if q["eta"] == 1:
        return across * mp.sqrt(mp.pi) * sig
    h = mp.mpf(s["h"])
    a, b = (st - h) / sig, (st + h) / sig
    if a > 0:
        diff = mp.erfc(a) - mp.erfc(b)
    elif b < 0:
        diff = mp.erfc(-b) - mp.erfc(-a)
    else:
        diff = mp.erf(b) - mp.erf(a)
    return across * mp.sqrt(mp.pi) * sig / 2 * diff


def gamma(q, reg, wo):
    """The depth term's gamma: 2 (small angle) or wc.z + wo.z (exact); 0 without a light."""
    if q["depth_term"] == 0:
        return mp.mpf(2)
    if reg is None:
        return mp.mpf(0)
    c = reg[1]
    wc = unit([c[0], c[1], max(c[2], mp.mpf(F32_1E3))])
    return wc[2] + wo[2]


def depth2(q, s, reg, wo):
    """D2_k of a rectangular groove; 1 for a V groove, whose depth is inside L_k."""
    if q.get("profile", 0) == 1:
        return mp.mpf(1)
    if q["depth_term"] == 1 and reg is None:
        return mp.mpf(0)
    kappa = mp.mpf(s["d"]) * 2000 * gamma(q, reg, wo) / mp.mpf(q["lambda_nm"])
    return 4 * mp.sin(mp.pi * kappa / 2) ** 2


class Parts:
    """Per-scratch factors (P_k, D2_k, L_k) of a query, recomputed selectively."""

    def __init__(self, q):
        self.q = q
        self.wo = unit(q["wo"])
        self.reg = region(q)
        self.lam = mp.mpf(q["lambda_nm"]) / 1000
        self.p = [along(q, s) for s in q["scratches"]]
        self.d2 = [depth2(q, s, self.reg, self.wo) for s in q["scratches"]]
        self.l = [chord_sum(q, s, self.wo, self.reg, self.lam) for s in q["scratches"]]

    def total(self):
        sig = mp.mpf(self.q["sigma"])
        return sum(p * d * l for p, d, l in zip(self.p, self.d2, self.l)) / (mp.pi * sig * sig)


def value(q):
    return Parts(q).total()


def ulp_s(s):
    """The spacing of float32 values at `s` (|s| <= 1)."""
    a = abs(float(s))
    if a == 0:
        return 2.0 ** -149
    return 2.0 ** (math.floor(math.log2(a)) - 23)


def band_parameter_conditioning(parts):
    """kappa_s: the largest relative change of the value when one lit arc's end moves by
    one float32 ulp of s = sin(phi), the kernel's parameter along the band (the horizon
    ends s = +-1 are exact there). Not an input's conditioning: the resolution of that
    representation, reported beside kappa."""
    ref = parts.total()
    if ref == 0 or parts.reg is None:
        return 0.0
    sig = mp.mpf(parts.q["sigma"])
    worst = mp.mpf(0)
    vgroove = parts.q.get("profile", 0) == 1
    ht = depth_phase(parts.q, parts.reg, parts.wo, parts.lam)
    for k, s in enumerate(parts.q["scratches"]):
        band = Band(s, parts.wo)
        w = mp.mpf(s["w"])
        for arc in band.lit(parts.reg[0]):
            for end, sign in ((arc[0], -1), (arc[1], 1)):
                if abs(end) == mp.pi / 2:
                    continue
                se = mp.sin(end)
                for d in (-1, 1):
                    s2 = min(mp.mpf(1), max(mp.mpf(-1), se + d * ulp_s(se)))
                    qa = (band.rho * se + band.wo_b) / parts.lam
                    qb = (band.rho * s2 + band.wo_b) / parts.lam
                    if vgroove:
                        dl = sign * vgroove_band_sweep.band_integral(w, s["d"], ht, qa, qb - qa)
                    else:
                        dl = sign * (antiderivative(w, qb) - antiderivative(w, qa))
                    change = parts.p[k] * parts.d2[k] * dl / (mp.pi * sig * sig)
                    worst = max(worst, abs(change / ref))
    return float(worst)


def copy_query(q):
    q2 = dict(q)
    q2["wo"] = list(q["wo"])
    q2["x"] = list(q["x"])
    q2["sphere"] = list(q["sphere"])
    q2["verts"] = [list(v) for v in q["verts"]]
    q2["scratches"] = [dict(s) for s in q["scratches"]]
    return q2


def neighbours(q, ulps=1):
    """(kind, query) for every change of one float32 input by `ulps` float32 steps either
    way; kind says which factors change: 'all', 'p' (P_k of every scratch), or
    (k, 'p'/'l'/'pl'/'d')."""
    def each(get, put, kind):
        for y in nudges(get(q), ulps):
            q2 = copy_query(q)
            put(q2, y)
            yield kind, q2

    for i in range(3):
        yield from each(lambda q, i=i: q["wo"][i], lambda q, y, i=i: q["wo"].__setitem__(i, y), "all")
    yield from each(lambda q: q["lambda_nm"], lambda q, y: q.__setitem__("lambda_nm", y), "all")
    if q["kind"] == 0:
        for i in range(4):
            yield from each(lambda q, i=i: q["sphere"][i], lambda q, y, i=i: q["sphere"].__setitem__(i, y), "all")
    else:
        for j in range(len(q["verts"])):
            for i in range(3):
                yield from each(
                    lambda q, i=i, j=j: q["verts"][j][i],
                    lambda q, y, i=i, j=j: q["verts"][j].__setitem__(i, y),
                    "all",
                )
    for i in range(2):
        yield from each(lambda q, i=i: q["x"][i], lambda q, y, i=i: q["x"].__setitem__(i, y), "p")
    yield from each(lambda q: q["sigma"], lambda q, y: q.__setitem__("sigma", y), "p")
    # A V groove's depth is inside its L_k.
    depth_kind = "l" if q.get("profile", 0) == 1 else "d"
    for k in range(len(q["scratches"])):
        for key, kind in (("cx", "p"), ("cy", "p"), ("h", "p"), ("tx", "pl"), ("ty", "pl"), ("w", "l"), ("d", depth_kind)):
            if key == "h" and q["eta"] == 1:
                continue
            yield from each(
                lambda q, k=k, key=key: q["scratches"][k][key],
                lambda q, y, k=k, key=key: q["scratches"][k].__setitem__(key, y),
                (k, kind),
            )


def changed_factors(kind, n):
    """The scratches whose factors a neighbour of `neighbours`' `kind` (not 'all') changes,
    by factor: {'p': P_k, 'l': the band sum L_k, 'd': D2_k}, each a set of indices < n."""
    if kind == "p":
        return {"p": set(range(n)), "l": set(), "d": set()}
    k, what = kind
    return {"p": {k} if "p" in what else set(), "l": {k} if "l" in what else set(),
            "d": {k} if what == "d" else set()}


def conditioning(q, base):
    """kappa, and whether a neighbour is nonzero where the value is 0."""
    ref = base.total()
    kap, flip = 0.0, False
    for kind, q2 in neighbours(q):
        if kind == "all":
            v = value(q2)
        else:
            p2 = Parts.__new__(Parts)
            p2.q, p2.wo, p2.reg, p2.lam = q2, base.wo, base.reg, base.lam
            p2.p, p2.d2, p2.l = list(base.p), list(base.d2), list(base.l)
            changed = changed_factors(kind, len(q2["scratches"]))
            for k in changed["p"]:
                p2.p[k] = along(q2, q2["scratches"][k])
            for k in changed["l"]:
                p2.l[k] = chord_sum(q2, q2["scratches"][k], p2.wo, p2.reg, p2.lam)
            for k in changed["d"]:
                p2.d2[k] = depth2(q2, q2["scratches"][k], p2.reg, p2.wo)
            v = p2.total()
        if ref == 0:
            flip = flip or v != 0
        else:
            kap = max(kap, float(abs(v / ref - 1)))
    return kap, flip


def zero_reach(q):
    """For a query whose exact value is 0 (and every one-ulp neighbour's too): the largest
    exact value when one float32 input moves by REACH_ULPS float32 steps either way. The
    test's rule for an exact 0: the kernel may return up to this, i.e. what the exact
    function gives at inputs as far off as the bound `8 max(kappa, kappa_s)` lets a
    nonzero value be (its linear analogue); 0 where no such move lights anything."""
    return max((value(q2) for _, q2 in neighbours(q, REACH_ULPS)), default=mp.mpf(0))


# ------------------------------------------------------------------ drawing (float64)
def rot(v, axis, ang):
    """`v` turned by `ang` about the unit `axis` (Rodrigues)."""
    v, axis = np.array(v), np.array(axis)
    return v * math.cos(ang) + np.cross(axis, v) * math.sin(ang) + axis * np.dot(axis, v) * (1 - math.cos(ang))


def normalise(v):
    v = np.array(v, dtype=float)
    return v / np.linalg.norm(v)


def draw(rng):
    u = rng.random()
    kind, cone = (0, 0) if u < 0.35 else (0, 1) if u < 0.5 else (1, 0)
    wo = draw_wo(rng)
    sigma = f32(10 ** rng.uniform(0, 2))
    lam = f32(rng.uniform(360, 830))
    eta = int(rng.integers(0, 2))
    depth_term = int(rng.integers(0, 2))
    x0 = [f32((1 if rng.random() < 0.5 else -1) * 10 ** rng.uniform(0, 4)) for _ in range(2)]
    scratches = []
    for _ in range(int(rng.integers(1, MAX_S + 1))):
        a = rng.integers(0, 4) * math.pi / 2 if rng.random() < 0.1 else rng.uniform(0, 2 * math.pi)
        tx, ty = unit_tangent(a)
        h = f32(sigma * 10 ** rng.uniform(-1, 3))
        sb = sigma * (rng.uniform(-0.3, 0.3) if rng.random() < 0.4 else rng.choice([-1, 1]) * rng.uniform(0.3, 4))
        st = rng.uniform(-1, 1) * (h + 3 * sigma)
        scratches.append(dict(
            cx=f32(x0[0] + st * tx - sb * ty), cy=f32(x0[1] + st * ty + sb * tx), tx=tx, ty=ty, h=h,
            w=f32(10 ** rng.uniform(-1, math.log10(50))), d=f32(10 ** rng.uniform(-3, 1)),
        ))
    # a point on the first scratch's band circle
    s0 = scratches[0]
    t3 = np.array([s0["tx"], s0["ty"], 0.0])
    b3 = np.array([-s0["ty"], s0["tx"], 0.0])
    won = normalise(wo)
    c = -(won[0] * t3[0] + won[1] * t3[1])
    rho = math.sqrt(max(0.0, 1 - c * c))
    horizon = rng.random() < 0.3
    if horizon:
        phi = (1 if rng.random() < 0.5 else -1) * math.acos(10 ** rng.uniform(-6, -1))
    else:
        phi = rng.uniform(-0.98, 0.98) * math.pi / 2
    p = c * t3 + rho * (math.sin(phi) * b3 + math.cos(phi) * np.array([0.0, 0.0, 1.0]))
    alpha = 10 ** rng.uniform(-5, math.log10(1.4))
    e = normalise(t3 - np.dot(p, t3) * p)  # across the band at p
    axis = normalise(np.cross(p, e))
    centre = rot(p, axis, rng.uniform(-1.3, 1.3) * alpha * (1 if kind == 0 else 0.7))
    if horizon:
        down = np.cross(centre, [0.0, 0.0, 1.0])
        if np.linalg.norm(down) > 1e-12:
            centre = rot(centre, normalise(down), -rng.uniform(-0.5, 1.0) * alpha)
    centre = normalise(centre)
    dist = 10 ** rng.uniform(-3, 1) * [1.0, 1e3, 1e6][int(rng.integers(0, 3))]
    sphere, verts = [0.0] * 4, []
    if kind == 0:
        if cone == 0 and rng.random() < 0.03:
            r = dist * rng.uniform(1.01, 3)
            alpha = math.pi
        else:
            r = dist * (math.sin(alpha) if cone == 0 else math.tan(alpha))
        sphere = [f32(v) for v in centre * dist] + [f32(r)]
    else:
        n = int(rng.integers(3, MAX_V + 1))
        tilt_axis = normalise(np.cross(centre, rng.normal(size=3)))
        normal = rot(centre, tilt_axis, rng.uniform(0, 50) * math.pi / 180)
        e1 = normalise(np.cross(normal, rng.normal(size=3)))
        e2 = np.cross(normal, e1)
        gaps = rng.uniform(0.5, 1.5, n)
        ang = np.cumsum(gaps / gaps.sum() * 2 * math.pi) + rng.uniform(0, 2 * math.pi)
        stretch = rng.uniform(0.5, 1)
        radius = dist * math.tan(alpha)
        for a in ang:
            v = dist * centre + radius * (math.cos(a) * e1 + stretch * math.sin(a) * e2)
            verts.append([f32(c_) for c_ in v])
        cu = normalise(np.sum([normalise(v) for v in verts], axis=0))
        alpha = max(math.acos(min(1.0, float(np.dot(cu, normalise(v))))) for v in verts)
    elev = math.asin(max(-1.0, min(1.0, centre[2])))
    return dict(kind=kind, cone=cone, sphere=sphere, verts=verts, wo=wo, lambda_nm=lam, x=x0, sigma=sigma,
                eta=eta, depth_term=depth_term, scratches=scratches, alpha=alpha, elev=elev)


# ------------------------------------------------------------------ output
def header():
    h = ["kind", "cone", "count"] + ["l_x", "l_y", "l_z", "l_r"]
    h += ["v%d_%s" % (i, c) for i in range(MAX_V) for c in "xyz"]
    h += ["wo_x", "wo_y", "wo_z", "lambda_nm", "x_x", "x_y", "sigma", "eta", "depth_term", "n"]
    h += ["s%d_%s" % (i, k) for i in range(MAX_S) for k in ("cx", "cy", "tx", "ty", "h", "w", "d", "profile")]
    return h + ["alpha", "elev", "lit", "ref", "kappa", "kappa_s", "reach"]


def row(q, ref, kappa, lit, kappa_s, reach):
    r = [str(q["kind"]), str(q["cone"]), str(len(q["verts"]))] + [s32(v) for v in q["sphere"]]
    for i in range(MAX_V):
        r += [s32(c) for c in q["verts"][i]] if i < len(q["verts"]) else ["0"] * 3
    r += [s32(v) for v in q["wo"]] + [s32(q["lambda_nm"])] + [s32(v) for v in q["x"]] + [s32(q["sigma"])]
    r += [str(q["eta"]), str(q["depth_term"]), str(len(q["scratches"]))]
    for i in range(MAX_S):
        if i < len(q["scratches"]):
            s = q["scratches"][i]
            r += [s32(s[k]) for k in ("cx", "cy", "tx", "ty", "h", "w", "d")] + [str(q.get("profile", 0))]
        else:
            r += ["0"] * 8
    r += ["%.6g" % q["alpha"], "%.6g" % q["elev"], str(lit)]
    r += [mp.nstr(ref, 17, min_fixed=1, max_fixed=0), "%.4g" % kappa, "%.4g" % kappa_s]
    return r + [reach_text(reach)]


def reach_text(reach):
    """The `reach` column as written."""
    return mp.nstr(reach, 6, min_fixed=1, max_fixed=0)


def reach_of_query(q, ref):
    """The `reach` of query `q` of exact value `ref`: `zero_reach` where `ref` is 0, else 0."""
    return zero_reach(q) if ref == 0 else mp.mpf(0)


def query_of(r):
    """The query (as `draw` makes it) whose inputs are CSV row `r` (a dict by column), the
    inverse of `row`: each input read back as the float32 it was written from."""
    def f(v):
        return f32(float(v))

    count = int(r["count"])
    return dict(
        kind=int(r["kind"]),
        cone=int(r["cone"]),
        sphere=[f(r["l_" + c]) for c in "xyzr"],
        verts=[[f(r["v%d_%s" % (i, c)]) for c in "xyz"] for i in range(count)],
        wo=[f(r["wo_" + c]) for c in "xyz"],
        lambda_nm=f(r["lambda_nm"]),
        x=[f(r["x_x"]), f(r["x_y"])],
        sigma=f(r["sigma"]),
        eta=int(r["eta"]),
        depth_term=int(r["depth_term"]),
        profile=int(r["s0_profile"]),
        scratches=[
            {k: f(r["s%d_%s" % (i, k)]) for k in ("cx", "cy", "tx", "ty", "h", "w", "d")}
            for i in range(int(r["n"]))
        ],
    )


# ------------------------------------------------------------------ self-check
def check(count=40):
    """Lit arcs against a dense sampling of the half circle, and A(q1) - A(q0) against
    quadrature of W^2 sinc^2, on the first `count` queries of the default seed."""
    rng = np.random.default_rng(20_020)
    worst_a, bad, arcs_seen = mp.mpf(0), 0, 0
    for _ in range(count):
        q = draw(rng)
        reg = region(q)
        if reg is None:
            continue
        wo = unit(q["wo"])
        for s in q["scratches"]:
            band = Band(s, wo)
            arcs = band.lit(reg[0])
            arcs_seen += len(arcs)
            n = 4000
            for j in range(n + 1):
                phi = -mp.pi / 2 + mp.pi * j / n
                got = inside(reg[0], band.point(phi))
                want = any(a <= phi <= b for a, b in arcs)
                near = any(min(abs(phi - a), abs(phi - b)) < mp.mpf(10) ** -25 for a, b in arcs)
                if got != want and not near:
                    bad += 1
            lam = mp.mpf(q["lambda_nm"]) / 1000
            w = mp.mpf(s["w"])
            for a, b in arcs[:1]:
                q0 = (band.rho * mp.sin(a) + band.wo_b) / lam
                q1 = (band.rho * mp.sin(b) + band.wo_b) / lam
                if abs(q1 - q0) * w > 200:
                    continue
                closed = antiderivative(w, q1) - antiderivative(w, q0)
                step = 1 / w
                pts = [q0 + k * step for k in range(int((q1 - q0) / step) + 1)] + [q1]
                quad = w * w * mp.quad(lambda t: mp.sinc(mp.pi * w * t) ** 2, pts)
                worst_a = max(worst_a, abs(closed / quad - 1))
    print(f"check: {arcs_seen} lit arcs, {bad} samples misclassified, A vs quadrature worst rel {mp.nstr(worst_a, 3)}")
    return bad == 0 and worst_a < 1e-20


def evaluate(q):
    """The CSV row of query `q`, or None when it is redrawn (exact 0 beside a nonzero
    neighbour)."""
    base = Parts(q)
    ref = base.total()
    kappa, flip = conditioning(q, base)
    if flip:
        return None
    lit = 0
    if base.reg is not None:
        lit = sum(len(Band(s, base.wo).lit(base.reg[0])) for s in q["scratches"])
    return row(q, ref, kappa, lit, band_parameter_conditioning(base), reach_of_query(q, ref))


def found(out):
    """`out/light_found.csv`: the FOUND draws, evaluated (none of them is redrawn)."""
    rows = []
    for offset, index in FOUND:
        rng = np.random.default_rng(20_020 + offset)
        for _ in range(index):
            draw(rng)
        r = evaluate(draw(rng))
        if r is None:
            sys.exit(f"draw {index} of seed offset {offset} is redrawn")
        rows.append(r)
    write_csv(out, "light_found", header(), rows)


def reach_of(r):
    """Row `r`'s `reach` column as `row` writes it (`reach_of_query` of its query)."""
    return reach_text(reach_of_query(query_of(r), mp.mpf(r["ref"])))


def rereach(paths, jobs):
    """Rewrite the `reach` column of each CSV in `paths` (light.csv, light_found.csv,
    light_vgroove.csv: rows as `row` writes them) at the present REACH_ULPS, every other
    column left as it is; what `evaluate` would write, since no other column depends on
    REACH_ULPS, at the cost of the exact zeros' neighbours alone."""
    import csv
    from pathlib import Path

    for path in paths:
        lines = Path(path).read_text().splitlines()
        rows = list(csv.DictReader(lines))
        if not rows or list(rows[0])[-1] != "reach":
            sys.exit(f"{path}: not a light-sweep table (its last column is not reach)")
        t0 = time.time()
        reaches = list(ordered_map(reach_of, rows, jobs))
        out = [lines[0]] + [line.rsplit(",", 1)[0] + "," + reach for line, reach in zip(lines[1:], reaches)]
        changed = sum(a != b for a, b in zip(lines[1:], out[1:]))
        Path(path).write_text("\n".join(out) + "\n")
        print(f"{path}: reach at {REACH_ULPS} ulps, {changed} of {len(rows)} rows changed, "
              f"{time.time() - t0:.0f} s", file=sys.stderr)


def main():
    if "--rereach" in sys.argv:
        i = sys.argv.index("--rereach")
        rest = sys.argv[i + 1:]
        jobs = 1
        if "--jobs" in rest:
            j = rest.index("--jobs")
            jobs = int(rest[j + 1])
            rest = rest[:j] + rest[j + 2:]
        rereach(rest, jobs)
        return
    if "--check" in sys.argv:
        sys.argv.remove("--check")
        sys.exit(0 if check() else 1)
    if "--found" in sys.argv:
        sys.argv.remove("--found")
        found(parse_args(0).out)
        return
    vgroove = "--vgroove" in sys.argv
    if vgroove:
        sys.argv.remove("--vgroove")
    args = parse_args(1500, jobs=True)
    rng = np.random.default_rng(20_020 + args.seed_offset)
    rows, redrawn, t0 = [], 0, time.time()
    while len(rows) < args.count:
        # as many draws as rows still wanted: the ones a one-at-a-time loop would make next
        batch = [draw(rng) for _ in range(args.count - len(rows))]
        for q in batch:
            q["profile"] = 1 if vgroove else 0
        for r in ordered_map(evaluate, batch, args.jobs):
            if r is None:
                redrawn += 1
                continue
            rows.append(r)
            progress(len(rows), args.count, 100)
    print(f"{len(rows)} queries ({redrawn} redrawn: exact 0 beside a nonzero neighbour), "
          f"{time.time() - t0:.0f} s", file=sys.stderr)
    write_csv(args.out, "light_vgroove" if vgroove else "light", header(), rows)


if __name__ == "__main__":
    main()
