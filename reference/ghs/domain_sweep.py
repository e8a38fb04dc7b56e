#!/usr/bin/env python3
"""Domain sweep of the GHS model (H&P 2016) and Fresnel at f32 inputs (issue #20).

For every query the script draws the inputs in float64, rounds each to float32 (numpy), and
evaluates the model's *formulas* at exactly those float32 values with mpmath (dps 30; the two
quadratures G1 and sigma_rel^2 use fixed Gauss-Legendre panels at that precision, checked by
`--check` against mpmath's tanh-sinh `quad` and against the committed nested-quadrature
goldens). Nothing here comes from the kernel: the kernel's G1 table, its sigma_rel^2 rule and
its closed forms are not used; G1 is evaluated from a 1-D form of Eqs. 40-42 derived below,
sigma_rel^2 from the arc integral of Eq. 25 in the angle about the disk centre.

Each query also carries its conditioning

    kappa = max over inputs x_i, over x_i -> nextafter_f32(x_i, +-inf), of |f(x') / f(x) - 1|

(for the sampling warps, whose value is a vector v: |v(x') - v(x)| / |v(x)|), i.e. how much
the exact value moves when one input moves by one float32 ulp. The kernel test
(`kernel/tests/ghs_domain_sweep.rs`) accepts err <= max(1e-4, 8 kappa).

Directions: a query stores wi, wo (or h, w) as three float32 components that are unit only up
to float32 rounding; the reference normalises them (in mpmath) before use, i.e. the exact
value is that of the direction the float32 vector points to.

Families (files `reference/ghs/golden/sweep/<family>.csv`):
  ndf        D(h) of Eqs. 38-39 for a half vector h (3 components), beta, p
  g1         Smith G1 (Eqs. 40-42, q over R) for a direction w, beta, p
  fresnel    unpolarised Fresnel (H&P Eqs. 11-13) for cos theta, n, k
  color      the diffraction colour Q of Eq. 27 for wi, wo, n, k
  sigma_rel  sigma_rel^2 (Eq. 25, normalised K-correlation lobe inside the unit disk) for b, lambda, c, wi
  brdf       the full rho = refl + diff + layer (Eqs. 34-37, 44-49) with all parameters
  halfvec    the half-vector warp (Eq. 59 with the exponent 1/(2p)): slope vector h_xy/h_z from (u0, u1)
  diffsample the diffraction warp (Eqs. 60-63, arc centred towards the disk centre): o_p from (u0, u1)

Usage:
  python3 reference/ghs/domain_sweep.py                 # the committed subset (13 300 queries, 16 min on 2 cores)
  python3 reference/ghs/domain_sweep.py --full --out DIR  # 108 800 queries (the full sweep; 77 min on 2 busy cores)
  python3 reference/ghs/domain_sweep.py --check         # self-checks of the reference only
  GHS_SWEEP_DIR=DIR cargo test --release -p scratchwave-kernel --test ghs_domain_sweep -- --nocapture
The subset is a prefix of the full sweep (same seeds, rows drawn one after another).
"""
import argparse
import csv
import json
import math
import os
import sys
import time
from multiprocessing import Pool

import mpmath as mp
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
GOLDEN = os.path.join(HERE, "golden")
DPS = 30
mp.mp.dps = DPS

# queries per family: committed subset, and the multiplier of the full sweep
COUNTS = dict(ndf=3000, g1=1000, fresnel=3000, color=1500, sigma_rel=800, brdf=2400,
              halfvec=800, diffsample=800)
FULL_MULT = dict(ndf=10, g1=8, fresnel=10, color=8, sigma_rel=8, brdf=4, halfvec=8,
                 diffsample=8)
SEEDS = dict(ndf=2001, g1=2002, fresnel=2003, color=2004, sigma_rel=2005, brdf=2006,
             halfvec=2007, diffsample=2008)

# the documented domain (docs/ghs.md, "Valid range")
BETA = (1e-3, 0.5)
P = (0.3, 3.0)
SIGMA_S = (1e-3, 1.0)
B_UM = (0.01, 100.0)
C = (1.001, 10.0)
LAMBDA = (0.38, 0.78)
COS_MIN = 0.005


# ------------------------------------------------------------------ float32 helpers
def f32(x):
    return np.float32(x)


def s32(x):
    """Shortest decimal that reads back as the same float32 (Rust `str::parse::<f32>`)."""
    return str(np.float32(x))


def m(x):
    """The exact value of a float32 as an mpf."""
    return mp.mpf(float(np.float32(x)))


def nudge(x, up):
    return np.nextafter(np.float32(x), np.float32(np.inf if up else -np.inf), dtype=np.float32)


def mvec(v):
    x, y, z = (m(c) for c in v)
    n = mp.sqrt(x * x + y * y + z * z)
    return (x / n, y / n, z / n)


# ------------------------------------------------------------------ quadrature
def _gl_nodes(degree):
    from mpmath.calculus.quadrature import GaussLegendre
    return GaussLegendre(mp.mp).calc_nodes(degree, mp.mp.prec)


GL24 = _gl_nodes(4)  # 3 * 2^3 = 24 points on [-1, 1]


def gl(f, a, b):
    h = (b - a) / 2
    c = (a + b) / 2
    return h * mp.fsum(w * f(c + h * x) for x, w in GL24)


def panels(f, pts, rule=gl):
    return mp.fsum(rule(f, a, b) for a, b in zip(pts[:-1], pts[1:]) if b > a)


def ts(f, a, b):
    return mp.quad(f, [a, b])


# ------------------------------------------------------------------ model formulas (mpmath)
def ndf(beta, p, h):
    """Eq. 38-39: D = P22(tan^2) / cos^4, P22(x) = p/(pi beta^2 Gamma(1/p)) exp(-(x/beta^2)^p);
    h a unit vector."""
    hx, hy, hz = h
    if hz <= 0:
        return mp.mpf(0)
    t2 = (hx * hx + hy * hy) / (hz * hz)
    y = (t2 / (beta * beta)) ** p if t2 > 0 else mp.mpf(0)
    return p / (mp.pi * beta * beta * mp.gamma(1 / p)) * mp.exp(-y) / hz ** 4


def smith_lambda(u, p, rule=gl):
    """Eq. 41 with Eq. 40's q-integral over R (unit beta, u = beta tan theta).

    Lambda(u) = int_{1/u}^inf (r u - 1) P2(r) dr,  P2(r) = p/(pi Gamma(1/p)) int_R exp(-(r^2+q^2)^p) dq.
    In polar slope coordinates (x, q) = rho (cos a, sin a) the region x > 1/u has, at radius rho,
    the angles |a| < acos(1/(u rho)), over which (u x - 1) integrates to
    2 (sqrt(u^2 rho^2 - 1) - acos(1/(u rho))); so
    Lambda(u) = 2p/(pi Gamma(1/p)) int_{1/u}^inf rho e^{-rho^{2p}} (sqrt(u^2 rho^2 - 1) - acos(1/(u rho))) d rho,
    evaluated with u rho = cosh t (smooth at the lower end)."""
    if u <= 0:
        return mp.mpf(0)
    c = 2 * p / (mp.pi * mp.gamma(1 / p))
    tp, u2 = 2 * p, u * u

    def f(t):
        e = mp.exp(t)
        ch, sh = (e + 1 / e) / 2, (e - 1 / e) / 2
        return ch * sh / u2 * mp.exp(-((ch / u) ** tp)) * (sh - mp.atan(sh))

    pts = [mp.mpf(0)]
    # panel ends where the exponent (cosh t / u)^{2p} crosses these values; beyond 150 the
    # integrand is < e^-150 of its scale
    for x in (0.1, 1, 4, 16, 60, 150):
        ch = u * mp.mpf(x) ** (1 / tp)
        if ch > 1:
            t = mp.acosh(ch)
            if t > pts[-1]:
                pts.append(t)
    if len(pts) == 1:
        return mp.mpf(0)
    return c * panels(f, pts, rule)


def g1(beta, p, w, rule=gl):
    """Eq. 42: G1 = 1/(1 + Lambda(beta tan theta)), w a unit vector (w_z > 0)."""
    tan = mp.sqrt(w[0] ** 2 + w[1] ** 2) / w[2]
    return 1 / (1 + smith_lambda(beta * tan, p, rule))


def fresnel(c, n, k):
    """H&P Eqs. 11-13, unpolarised, principal square root; c clamped to [0, 1]."""
    c = min(max(c, mp.mpf(0)), mp.mpf(1))
    eta2 = mp.mpc(n, k) ** 2
    root = mp.sqrt(eta2 - 1 + c * c)
    fs = abs((c - root) / (c + root)) ** 2
    fp = abs((eta2 * c - root) / (eta2 * c + root)) ** 2
    return (fs + fp) / 2


def color_q(wi, wo, n, k):
    """Eq. 27 (Krywonos): Q = sum |Q_xy|^2 with phi = phi_o - phi_i - pi, R = sqrt(eta^2 - sin^2)."""
    eta2 = mp.mpc(n, k) ** 2
    ci, co = wi[2], wo[2]
    si, so = mp.sqrt(wi[0] ** 2 + wi[1] ** 2), mp.sqrt(wo[0] ** 2 + wo[1] ** 2)
    if si * so > 0:
        cphi = -(wi[0] * wo[0] + wi[1] * wo[1]) / (si * so)
        sphi = -(wi[0] * wo[1] - wi[1] * wo[0]) / (si * so)
    else:
        cphi, sphi = mp.mpf(1), mp.mpf(0)
    ri, ro = mp.sqrt(eta2 - si * si), mp.sqrt(eta2 - so * so)
    e = eta2 - 1
    qss = e * cphi / ((ci + ri) * (co + ro))
    qsp = e * ro * sphi / ((ci + ri) * (eta2 * co + ro))
    qps = e * ri * sphi / ((eta2 * ci + ri) * (co + ro))
    qpp = e * (ri * ro * cphi - eta2 * si * so) / ((eta2 * ci + ri) * (eta2 * co + ro))
    return abs(qss) ** 2 + abs(qsp) ** 2 + abs(qps) ** 2 + abs(qpp) ** 2


def k_density(r, B, c):
    """Eq. 22/43 in the projected-disk measure: (c-1) B^2/(2 pi) (1 + B^2 r^2)^{-(c+1)/2}."""
    return (c - 1) * B * B / (2 * mp.pi) * (1 + B * B * r * r) ** (-(c + 1) / 2)


def sigma_rel_sq(s, one_minus_s, B, c, rule=gl):
    """Eq. 25 normalised: the mass of k(|x - L|) inside the unit disk, L at distance s from the
    centre. Circles about L of radius r <= 1 - s lie inside (mass W(1 - s)); for larger r the
    inside arc has half-angle phi(r). With the angle psi at the disk centre of the arc's end,
    r^2 = 1 + s^2 + 2 s cos psi, r dr = -s sin psi dpsi and phi = atan2(sin psi, cos psi + s):
    sigma_rel^2 = W(1 - s) + int_0^pi k(r) 2 phi s sin psi dpsi  (smooth in psi)."""
    h = (c - 1) / 2
    w0 = -mp.expm1(-h * mp.log1p((B * one_minus_s) ** 2))
    if s == 0:
        return w0
    pref, ex, B2 = (c - 1) * B * B / (2 * mp.pi), -(c + 1) / 2, B * B

    def f(u):  # u = pi - psi: r^2 = (1-s)^2 + 4 s sin^2(u/2), sin psi = sin u, cos psi = -cos u
        sh, ch = mp.sin(u / 2), mp.cos(u / 2)
        sin_psi, cos_psi = 2 * sh * ch, 2 * sh * sh - 1
        k = pref * mp.exp(ex * mp.log1p(B2 * (one_minus_s ** 2 + 4 * s * sh * sh)))
        return k * 2 * mp.atan2(sin_psi, cos_psi + s) * s * sin_psi

    def u_of_r(r):
        x = (r * r - one_minus_s ** 2) / (4 * s)
        return 2 * mp.asin(mp.sqrt(min(max(x, mp.mpf(0)), mp.mpf(1))))

    # panels: geometric in r from 1 - s (where the arc opens), at the lobe's scale 1/B, and
    # four uniform in psi
    r0, r1 = one_minus_s, 1 + s
    rs = set()
    r = r0
    while r < r1:
        rs.add(r)
        r *= 3
    for x in (1, 10, 100):
        rs.add(x / B)
    pts = sorted({u_of_r(r) for r in rs if r0 <= r <= r1} | {mp.mpf(0), mp.pi}
                 | {mp.pi * j / 4 for j in range(1, 4)})
    return w0 + panels(f, pts, rule)


def fdr_fit(eta):
    """F_dr(eta) = 2 C1(1/eta), d'Eon & Irving 2011 fit (part of the model, H&P §4.4)."""
    e = min(max(eta, mp.mpf(1) / 3), mp.mpf(3))
    e = 1 / e
    if e < 1:
        c1 = (mp.mpf("0.45966") - mp.mpf("1.73965") * e + mp.mpf("3.37668") * e ** 2
              - mp.mpf("3.904945") * e ** 3 + mp.mpf("2.49277") * e ** 4 - mp.mpf("0.68441") * e ** 5)
    else:
        c1 = (mp.mpf("-4.61686") + mp.mpf("11.1136") * e - mp.mpf("10.4646") * e ** 2
              + mp.mpf("5.11455") * e ** 3 - mp.mpf("1.27198") * e ** 4 + mp.mpf("0.12746") * e ** 5)
    return min(max(2 * c1, mp.mpf(0)), mp.mpf(1))


def layer(kind, form, ci, co, n, k, albedo):
    """Eq. 49 (plastic) and Eqs. 45-48 (subsurface), T of Eq. 44; form 1 = energy-conserving."""
    if kind == 0:
        return mp.mpf(0)
    T = (1 - fresnel(ci, n, k)) * (1 - fresnel(co, n, k))
    fint = fdr_fit(1 / n)
    if kind == 1:
        if form == 0:
            return T * albedo / mp.pi / (1 - albedo / mp.pi * fint)
        return T * albedo / (mp.pi * n * n * (1 - albedo * fint))
    af = (1 - fint) / (1 + fint) if form == 0 else (1 + fint) / (1 - fint)
    st = mp.sqrt(3 * (1 - albedo))
    cti = mp.sqrt(1 - (1 - ci * ci) / (n * n))
    cto = mp.sqrt(1 - (1 - co * co) / (n * n))
    single = albedo * T / (4 * mp.pi) / (cti + cto)
    multi = T / mp.pi * albedo / 2 * mp.exp(-st) * (1 + mp.exp(-mp.mpf(4) / 3 * af * st))
    return single + multi


class Cache:
    """Memo of the two quadratures (a +-ulp change of wo leaves G1(wi) and sigma_rel^2 alone)."""

    def __init__(self):
        self.g1, self.srel = {}, {}

    def g1_of(self, beta, p, w):
        key = (beta, p, w)
        if key not in self.g1:
            self.g1[key] = g1(beta, p, w)
        return self.g1[key]

    def srel_of(self, B, c, w):
        key = (B, c, w)
        if key not in self.srel:
            s = mp.sqrt(w[0] ** 2 + w[1] ** 2)
            self.srel[key] = sigma_rel_sq(s, w[2] ** 2 / (1 + s), B, c)
        return self.srel[key]


def brdf(q, cache):
    """Eqs. 34-37 (35 with /lambda), colour per diff_color, layers; all inputs exact."""
    sig, beta, p, b, c, n, k, alb, lam = (m(q[x]) for x in
                                          ("sigma_s", "beta", "p", "b", "c", "n", "k", "albedo", "lambda"))
    wi = mvec(q["wi"])
    wo = mvec(q["wo"])
    sx, sy, sz = (wi[j] + wo[j] for j in range(3))
    sn = mp.sqrt(sx * sx + sy * sy + sz * sz)
    h = (sx / sn, sy / sn, sz / sn)
    cd = wi[0] * h[0] + wi[1] * h[1] + wi[2] * h[2]
    ci, co = wi[2], wo[2]
    G = cache.g1_of(beta, p, wi) * cache.g1_of(beta, p, wo)
    F = fresnel(cd, n, k)
    refl = mp.exp(-(4 * mp.pi * sig * cd / lam) ** 2) * F * ndf(beta, p, h) * G / (4 * ci * co)
    one_minus_a = -mp.expm1(-(2 * mp.pi * sig / lam * (ci + co)) ** 2)
    B = b / lam
    r = mp.sqrt((wi[0] + wo[0]) ** 2 + (wi[1] + wo[1]) ** 2)
    srel = cache.srel_of(B, c, wi)
    dc = q["diff_color"]
    col = {0: color_q(wi, wo, n, k) / 2, 1: color_q(wi, wo, n, k), 2: F, 3: mp.mpf(1)}[dc]
    diff = one_minus_a * k_density(r, B, c) / srel * G * col
    lay = layer(q["layer"], q["layer_form"], ci, co, n, k, alb)
    return refl + diff + lay, dict(refl=refl, diff=diff, layer=lay, srel=srel)


def gamma_q_inv(a, u):
    """y with Q(a, y) = u (upper regularized incomplete gamma), mpmath root on ln y."""
    from scipy import special
    y0 = float(special.gammainccinv(float(a), float(u)))
    if not (y0 > 0 and math.isfinite(y0)):
        y0 = 1e-300 if u > 0.5 else 1e3
    g = lambda ly: mp.gammainc(a, mp.exp(ly), mp.inf, regularized=True) - u
    return mp.exp(mp.findroot(g, mp.log(mp.mpf(y0)), tol=mp.mpf(10) ** (-2 * DPS // 3)))


def halfvec(q):
    """Eq. 59 (exponent 1/(2p)): tan = beta Q^{-1}(1/p, u1)^{1/(2p)}, phi = 2 pi u0; returns
    the slope vector tan (cos phi, sin phi)."""
    beta, p, u0, u1 = (m(q[x]) for x in ("beta", "p", "u0", "u1"))
    y = gamma_q_inv(1 / p, u1)
    tan = beta * y ** (1 / (2 * p))
    phi = 2 * mp.pi * u0
    return (tan * mp.cos(phi), tan * mp.sin(phi))


def diffsample(q):
    """Eqs. 60-63: radius from the K-correlation radial CDF truncated at 1 + s, angle uniform in
    the arc (half-angle phi(r), Eq. 62) centred on +i_p; returns o_p = d - i_p."""
    B, c, u0, u1 = (m(q[x]) for x in ("B", "c", "u0", "u1"))
    wi = mvec(q["wi"])
    s = mp.sqrt(wi[0] ** 2 + wi[1] ** 2)
    e1 = (wi[0] / s, wi[1] / s)
    e2 = (-e1[1], e1[0])
    h = (c - 1) / 2
    W = lambda r: -mp.expm1(-h * mp.log1p((B * r) ** 2))
    M = W(1 + s)
    w = M * u0
    r = mp.sqrt(mp.expm1(-mp.log1p(-w) / h)) / B
    arg = (r * r + s * s - 1) / (2 * r * s)
    ph = mp.pi if arg <= -1 else (mp.mpf(0) if arg >= 1 else mp.acos(arg))
    al = (2 * u1 - 1) * ph
    d = (r * (e1[0] * mp.cos(al) + e2[0] * mp.sin(al)), r * (e1[1] * mp.cos(al) + e2[1] * mp.sin(al)))
    return (d[0] - s * e1[0], d[1] - s * e1[1]), r


# ------------------------------------------------------------------ families: inputs, value
def loguni(rng, lo, hi):
    return math.exp(rng.uniform(math.log(lo), math.log(hi)))


def direction(rng, kind=None):
    """A float64 unit vector (rounded to float32 by the caller) stressing grazing and normal."""
    kind = rng.integers(4) if kind is None else kind
    if kind == 0:
        z = loguni(rng, COS_MIN, 1.0)
    elif kind == 1:
        z = 1 - loguni(rng, 1e-9, 1e-1)
    else:
        z = rng.uniform(COS_MIN, 1.0)
    s = math.sqrt(max(1 - z * z, 0.0))
    ph = rng.uniform(0, 2 * math.pi)
    return (s * math.cos(ph), s * math.sin(ph), z)


def v32(v):
    return tuple(np.float32(c) for c in v)


def ior(rng, kind):
    """kind 0: conductor, 1: dielectric n > 1, 2: weak absorber, 3: dielectric n < 1."""
    if kind == 0:
        return loguni(rng, 0.03, 3.0), loguni(rng, 0.5, 10.0)
    if kind == 1:
        if rng.uniform() < 0.15:
            return 1 + loguni(rng, 1e-3, 5e-2), 0.0
        return loguni(rng, 1.05, 3.0), 0.0
    if kind == 2:
        return loguni(rng, 1.05, 3.0), loguni(rng, 1e-4, 0.3)
    return loguni(rng, 0.3, 0.99), 0.0


def tan_in_lobe(rng, beta, p):
    """tan theta_h inside the NDF lobe: y = (tan/beta)^{2p} log-uniform in [1e-4, 40]."""
    y = loguni(rng, 1e-4, 40.0)
    return beta * y ** (1 / (2 * p))


def unit_from_tan(t, ph):
    c = 1 / math.sqrt(1 + t * t)
    return (t * c * math.cos(ph), t * c * math.sin(ph), c)


def gen_ndf(rng):
    beta, p = loguni(rng, *BETA), loguni(rng, *P)
    u = rng.uniform()
    ph = rng.uniform(0, 2 * math.pi)
    if u < 0.6:
        t = tan_in_lobe(rng, beta, p)
    elif u < 0.8:
        t = beta * loguni(rng, 1e-3, 1e-1)
    elif u < 0.83:
        t = 0.0
    else:
        # grazing half vectors, where D has not underflowed (y <= 60)
        tmax = beta * 60 ** (1 / (2 * p))
        zmin = max(COS_MIN, 1 / math.sqrt(1 + tmax * tmax))
        if zmin >= 0.3:
            t = tan_in_lobe(rng, beta, p)
        else:
            z = loguni(rng, zmin, 0.3)
            t = math.sqrt(1 - z * z) / z
    return dict(beta=f32(beta), p=f32(p), h=v32(unit_from_tan(t, ph)))


def val_ndf(q):
    return ndf(m(q["beta"]), m(q["p"]), mvec(q["h"]))


def gen_g1(rng):
    return dict(beta=f32(loguni(rng, *BETA)), p=f32(loguni(rng, *P)), w=v32(direction(rng)))


def val_g1(q):
    return g1(m(q["beta"]), m(q["p"]), mvec(q["w"]))


def gen_fresnel(rng):
    u = rng.uniform()
    if u < 0.3:
        c = rng.uniform(0, 1)
    elif u < 0.6:
        c = loguni(rng, 1e-6, 1.0)
    elif u < 0.8:
        c = 1 - loguni(rng, 1e-8, 1e-1)
    elif u < 0.85:
        c = float(rng.choice([0.0, 1.0, COS_MIN]))
    else:
        c = rng.uniform(0.5, 1.0)
    n, k = ior(rng, rng.integers(4))
    return dict(cos=f32(c), n=f32(n), k=f32(k))


def val_fresnel(q):
    return fresnel(m(q["cos"]), m(q["n"]), m(q["k"]))


def near_mirror(rng, wi, beta, p):
    """wo = reflect(wi, h) for h in the NDF lobe; None below cos 0.005."""
    t = tan_in_lobe(rng, beta, p)
    h = unit_from_tan(t, rng.uniform(0, 2 * math.pi))
    d = sum(a * b for a, b in zip(wi, h))
    wo = tuple(2 * d * hh - a for hh, a in zip(h, wi))
    return wo if wo[2] >= COS_MIN else None


def near_diffraction(rng, wi, B):
    """wo with o_p = -i_p + r (cos a, sin a), r = logu[1e-2, 1e2] / B (inside the disk)."""
    for _ in range(100):
        r = loguni(rng, 1e-2, 1e2) / B
        a = rng.uniform(0, 2 * math.pi)
        ox, oy = -wi[0] + r * math.cos(a), -wi[1] + r * math.sin(a)
        z2 = 1 - ox * ox - oy * oy
        if z2 >= COS_MIN ** 2:
            return (ox, oy, math.sqrt(z2))
    return None


def gen_color(rng):
    wi = direction(rng)
    n, k = ior(rng, rng.integers(3))
    u = rng.uniform()
    wo = None
    if u < 0.4:
        wo = near_mirror(rng, wi, loguni(rng, 1e-3, 0.5), 1.0)
    if wo is None:
        wo = direction(rng)
    return dict(wi=v32(wi), wo=v32(wo), n=f32(n), k=f32(k))


def val_color(q):
    return color_q(mvec(q["wi"]), mvec(q["wo"]), m(q["n"]), m(q["k"]))


def gen_sigma_rel(rng):
    return dict(b=f32(loguni(rng, *B_UM)), **{"lambda": f32(rng.uniform(*LAMBDA))},
                c=f32(1 + loguni(rng, C[0] - 1, C[1] - 1)), wi=v32(direction(rng)))


def val_sigma_rel(q):
    w = mvec(q["wi"])
    s = mp.sqrt(w[0] ** 2 + w[1] ** 2)
    return sigma_rel_sq(s, w[2] ** 2 / (1 + s), m(q["b"]) / m(q["lambda"]), m(q["c"]))


BRDF_STRATA = [  # (layer, layer_form, ior kind)
    (0, 0, 0), (0, 0, 1), (0, 0, 2), (1, 0, 1), (1, 1, 1), (2, 0, 1), (2, 1, 1), (0, 0, 0),
]


def gen_brdf(rng, i):
    lay, form, ik = BRDF_STRATA[i % len(BRDF_STRATA)]
    beta, p = loguni(rng, *BETA), loguni(rng, *P)
    b, lam = loguni(rng, *B_UM), rng.uniform(*LAMBDA)
    n, k = ior(rng, ik)
    if lay:
        n = loguni(rng, 1.05, 2.5) if rng.uniform() < 0.9 else 1 + loguni(rng, 1e-3, 5e-2)
    q = dict(sigma_s=f32(loguni(rng, *SIGMA_S)), beta=f32(beta), p=f32(p), b=f32(b),
             c=f32(1 + loguni(rng, C[0] - 1, C[1] - 1)), n=f32(n), k=f32(k),
             diff_color=int(rng.integers(4)), layer=lay, layer_form=form,
             albedo=f32(rng.uniform(0, 1)), **{"lambda": f32(lam)})
    wi = direction(rng)
    u = rng.uniform()
    wo = None
    if u < 0.5:
        wo = near_mirror(rng, wi, beta, p)
    elif u < 0.8:
        wo = near_diffraction(rng, wi, b / lam)
    if wo is None:
        wo = direction(rng)
    q["wi"], q["wo"] = v32(wi), v32(wo)
    return q


def gen_halfvec(rng):
    u = rng.uniform()
    if u < 0.5:
        u1 = rng.uniform(0, 1)
    elif u < 0.75:
        u1 = loguni(rng, 1e-7, 1e-2)
    else:
        u1 = 1 - loguni(rng, 1e-7, 1e-2)
    return dict(beta=f32(loguni(rng, *BETA)), p=f32(loguni(rng, *P)), u0=f32(rng.uniform()),
                u1=f32(u1))


def gen_diffsample(rng):
    B = loguni(rng, *B_UM) / rng.uniform(*LAMBDA)
    return dict(B=f32(B), c=f32(1 + loguni(rng, C[0] - 1, C[1] - 1)), wi=v32(direction(rng)),
                u0=f32(rng.uniform(1e-6, 1)), u1=f32(rng.uniform()))


# family: (generator, value, perturbable inputs, vector-valued?, columns)
VEC_IN = lambda name: [(name, j) for j in range(3)]
FAMILIES = {
    "ndf": (gen_ndf, val_ndf, ["beta", "p"] + VEC_IN("h")),
    "g1": (gen_g1, val_g1, ["beta", "p"] + VEC_IN("w")),
    "fresnel": (gen_fresnel, val_fresnel, ["cos", "n", "k"]),
    "color": (gen_color, val_color, ["n", "k"] + VEC_IN("wi") + VEC_IN("wo")),
    "sigma_rel": (gen_sigma_rel, val_sigma_rel, ["b", "lambda", "c"] + VEC_IN("wi")),
    "brdf": (gen_brdf, None, ["sigma_s", "beta", "p", "b", "c", "n", "k", "albedo", "lambda"]
             + VEC_IN("wi") + VEC_IN("wo")),
    "halfvec": (gen_halfvec, None, ["beta", "p", "u0", "u1"]),
    "diffsample": (gen_diffsample, None, ["B", "c", "u0", "u1"] + VEC_IN("wi")),
}


def perturbed(q, key, up):
    q2 = dict(q)
    if isinstance(key, tuple):
        name, j = key
        v = list(q[name])
        v[j] = nudge(v[j], up)
        q2[name] = tuple(v)
    else:
        q2[key] = nudge(q[key], up)
    return q2


def vdist(a, b):
    return mp.sqrt(sum((x - y) ** 2 for x, y in zip(a, b)))


def evaluate(args):
    """Reference value, kappa and extras of one query (worker process)."""
    fam, q = args
    keys = FAMILIES[fam][2]
    extra = {}
    if fam == "brdf":
        cache = Cache()
        v, parts = brdf(q, cache)
        extra = parts
        f = lambda qq: brdf(qq, cache)[0]
    elif fam in ("halfvec", "diffsample"):
        fn = halfvec if fam == "halfvec" else (lambda qq: diffsample(qq)[0])
        if fam == "diffsample":
            v, extra["r"] = diffsample(q)
        else:
            v = fn(q)
        scale = vdist(v, (0, 0)) if fam == "halfvec" else extra["r"]
        kap = mp.mpf(0)
        for key in keys:
            for up in (False, True):
                kap = max(kap, vdist(fn(perturbed(q, key, up)), v) / scale)
        return v, kap, extra
    else:
        f = FAMILIES[fam][1]
        v = f(q)
    kap = mp.mpf(0)
    if v != 0:
        for key in keys:
            for up in (False, True):
                kap = max(kap, abs(f(perturbed(q, key, up)) / v - 1))
    return v, kap, extra


def gen_queries(fam, n):
    rng = np.random.default_rng(SEEDS[fam])
    gen = FAMILIES[fam][0]
    out = []
    i = 0
    while len(out) < n:
        q = gen(rng, i) if fam == "brdf" else gen(rng)
        i += 1
        out.append(q)
    return out


def columns(fam, q):
    cols = []
    for k, v in q.items():
        if isinstance(v, tuple):
            cols += ["%s_%s" % (k, "xyz"[j]) for j in range(3)]
        else:
            cols.append(k)
    return cols


def row_values(q):
    vals = []
    for v in q.values():
        if isinstance(v, tuple):
            vals += [s32(c) for c in v]
        elif isinstance(v, int):
            vals.append(str(v))
        else:
            vals.append(s32(v))
    return vals


def fmt(x):
    return mp.nstr(x, 17, min_fixed=1, max_fixed=0) if x != 0 else "0"


def run_family(fam, n, outdir, jobs):
    qs = gen_queries(fam, n)
    t0 = time.time()
    with Pool(jobs) as pool:
        res = pool.map(evaluate, [(fam, q) for q in qs], chunksize=4)
    path = os.path.join(outdir, fam + ".csv")
    with open(path, "w", newline="") as fh:
        w = csv.writer(fh, lineterminator="\n")
        vec = fam in ("halfvec", "diffsample")
        head = columns(fam, qs[0])
        head += (["ref_x", "ref_y"] if vec else ["ref"]) + ["kappa"]
        if fam == "brdf":
            head += ["refl", "diff", "layer_lobe", "sigma_rel_sq"]
        if fam == "diffsample":
            head += ["r"]
        w.writerow(head)
        for q, (v, kap, extra) in zip(qs, res):
            row = row_values(q)
            row += ([fmt(v[0]), fmt(v[1])] if vec else [fmt(v)]) + [mp.nstr(kap, 4)]
            if fam == "brdf":
                row += [fmt(extra[x]) for x in ("refl", "diff", "layer", "srel")]
            if fam == "diffsample":
                row += [fmt(extra["r"])]
            w.writerow(row)
    kmax = max(float(r[1]) for r in res)
    print("%-10s %6d queries  %7.1f s  max kappa %.2e  -> %s" % (fam, n, time.time() - t0, kmax, path),
          flush=True)


# ------------------------------------------------------------------ self-checks
def check():
    worst = {}
    rng = np.random.default_rng(7)
    # G1: against the nested-quadrature golden (Eqs. 40-42, reference/ghs/generate.py) and
    # Beckmann's closed form at p = 1; GL panels against tanh-sinh
    rows = json.load(open(os.path.join(GOLDEN, "g1.json")))
    e = 0
    for r in rows:
        lam = smith_lambda(mp.mpf(r["beta_tan"]), mp.mpf(r["p"]))
        e = max(e, abs(1 / (1 + lam) / r["g1"] - 1))
    worst["g1 vs nested quadrature (g1.json, float64 golden)"] = e
    e = 0
    for u in (0.05, 0.2, 0.5, 1, 2, 5, 20, 100):
        a = 1 / mp.mpf(u)
        bk = (mp.exp(-a * a) / (a * mp.sqrt(mp.pi)) - mp.erfc(a)) / 2
        lam = smith_lambda(mp.mpf(u), mp.mpf(1))
        e = max(e, abs((1 + lam) / (1 + bk) - 1))
    worst["g1 p=1 vs Beckmann closed form"] = e
    e = 0
    for _ in range(25):
        u, p = m(loguni(rng, 1e-3, 250)), m(loguni(rng, *P))
        a, b = smith_lambda(u, p), smith_lambda(u, p, ts)
        e = max(e, abs((1 + a) / (1 + b) - 1))
    worst["g1 GL panels vs tanh-sinh"] = e
    # sigma_rel^2: against the 2-D disk quadrature golden, and GL vs tanh-sinh
    e = 0
    for r in json.load(open(os.path.join(GOLDEN, "sigma_rel.json"))):
        s = mp.mpf(r["s"])
        v = sigma_rel_sq(s, 1 - s, mp.mpf(r["b_over_lambda"]), mp.mpf(r["c"]))
        e = max(e, abs(v / r["sigma_rel_sq"] - 1))
    worst["sigma_rel^2 vs 2-D quadrature (sigma_rel.json, float64 golden)"] = e
    e = 0
    for _ in range(25):
        w = mvec(v32(direction(rng)))
        s = mp.sqrt(w[0] ** 2 + w[1] ** 2)
        B, c = m(loguni(rng, 0.01, 300)), m(1 + loguni(rng, 1e-3, 9))
        a = sigma_rel_sq(s, w[2] ** 2 / (1 + s), B, c)
        b = sigma_rel_sq(s, w[2] ** 2 / (1 + s), B, c, ts)
        e = max(e, abs(a / b - 1))
    worst["sigma_rel^2 GL panels vs tanh-sinh"] = e
    # Fresnel: against the committed golden/fresnel.csv
    e = 0
    with open(os.path.join(HERE, "..", "golden", "fresnel.csv")) as fh:
        for r in csv.DictReader(fh):
            v = fresnel(mp.mpf(r["cos_theta"]), mp.mpf(r["n"]), mp.mpf(r["k"]))
            want = float(r["F"])
            e = max(e, abs(v - want) / max(want, 1e-300) if want else abs(v))
    worst["fresnel vs golden/fresnel.csv"] = e
    # Q/2 = F in the specular direction
    e = 0
    for n, k in ((1.5, 0), (0.2, 3.4), (1.2, 2.5)):
        for t in (0.1, 0.7, 1.4):
            wi = (mp.sin(t), mp.mpf(0), mp.cos(t))
            wo = (-mp.sin(t), mp.mpf(0), mp.cos(t))
            e = max(e, abs(color_q(wi, wo, n, k) / 2 / fresnel(mp.cos(t), n, k) - 1))
    worst["Q/2 vs F at the mirror direction"] = e
    # Q^{-1}: forward residual
    e = 0
    for a, u in ((0.4, 1e-6), (3.3, 0.5), (1, 1 - 1e-7), (0.33, 0.9)):
        y = gamma_q_inv(mp.mpf(a), mp.mpf(u))
        e = max(e, abs(mp.gammainc(a, y, mp.inf, regularized=True) / u - 1))
    worst["Q^-1 forward residual"] = e
    # the sampling warps against the densities they claim: halfvec's tan has the CDF
    # 1 - Q(1/p, (tan/beta)^{2p}) (checked via the forward residual above); diffsample's radius
    # satisfies W(r) = M u0
    for k, v in worst.items():
        print("%-62s %.2e" % (k, float(v)))
    limits = {"g1 vs nested quadrature (g1.json, float64 golden)": 1e-12,
              "sigma_rel^2 vs 2-D quadrature (sigma_rel.json, float64 golden)": 1e-8}
    bad = [k for k, v in worst.items() if v > limits.get(k, 1e-15)]
    if bad:
        sys.exit("self-check failed: %s" % bad)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--full", action="store_true", help="the full sweep (FULL_MULT x the subset)")
    ap.add_argument("--out", default=os.path.join(GOLDEN, "sweep"))
    ap.add_argument("--only", default=",".join(FAMILIES))
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--check", action="store_true")
    ap.add_argument("--count", type=int, help="queries per family (overrides the defaults; for trials)")
    a = ap.parse_args()
    if a.check:
        check()
        return
    os.makedirs(a.out, exist_ok=True)
    for fam in a.only.split(","):
        n = a.count or COUNTS[fam] * (FULL_MULT[fam] if a.full else 1)
        run_family(fam, n, a.out, a.jobs)


if __name__ == "__main__":
    main()
