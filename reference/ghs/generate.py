#!/usr/bin/env python3
"""Independent golden values for the GHS kernel (H&P 2016), written to reference/ghs/golden/.

Everything here is computed from the *defining integrals* with scipy/mpmath in float64 or
better, never from the kernel's closed forms or tables:
  ndf.json        D(h) from Eqs. 38-39 and its normalisation  int D cos(theta) dw  by 2-D quadrature
  g1.json         Smith G1 from the nested integrals of Eqs. 40-42 (with the factor 2 of the
                  q-integral over R restored), and Beckmann's closed form at p = 1 as a check
  sigma_rel.json  sigma_rel^2 = visible fraction of the K-correlation lobe, by 2-D quadrature
                  over the unit disk in polar coordinates about the disk centre
  brdf.json       full rho = rho_refl + rho_diff (+ layer) assembled from the above, Fresnel
                  from Eqs. 11-13 with numpy complex128, Q from Eq. 27
  gamma.json      inverse regularized incomplete gamma (mpmath) for the sampling math
  fresnel_dr.json hemispherical Fresnel reflectance by quadrature vs the d'Eon-Irving fit
Run: python3 reference/ghs/generate.py   (about 10 minutes on one busy core; the mpmath nested G1 dominates)
"""
import json
import math
import os
import warnings

import mpmath as mp
import numpy as np
from scipy import integrate, special

warnings.simplefilter("ignore")
HERE = os.path.dirname(os.path.abspath(__file__))
OUT = os.path.join(HERE, "golden")
mp.mp.dps = 30


# ---------------------------------------------------------------- NDF (Eqs. 38-39)
def p22(x, beta, p):
    return p / (math.pi * beta ** 2 * math.gamma(1.0 / p)) * math.exp(-((x / beta ** 2) ** p))


def ndf(cos_h, beta, p):
    if cos_h <= 0:
        return 0.0
    t2 = (1 - cos_h ** 2) / cos_h ** 2
    return p22(t2, beta, p) / cos_h ** 4


def ndf_normalisation(beta, p):
    # int_0^{pi/2} D(theta) cos(theta) sin(theta) dtheta * 2 pi, integrated in theta (not in slope)
    f = lambda th: ndf(math.cos(th), beta, p) * math.cos(th) * math.sin(th)
    # the lobe sits at theta ~ atan(beta); split there
    th0 = math.atan(beta)
    pts = sorted({0.0, th0 * 0.1, th0, min(math.pi / 2, th0 * 3), math.pi / 2})
    tot = 0.0
    for a, b in zip(pts[:-1], pts[1:]):
        tot += integrate.quad(f, a, b, limit=400, epsabs=0, epsrel=1e-12)[0]
    return 2 * math.pi * tot


# ---------------------------------------------------------------- G1 (Eqs. 40-42)
def p2_marginal(r, p):
    """Eq. 40 with the q-integral over the whole real line (2 x the printed [0, inf))."""
    g = mp.gamma(1 / mp.mpf(p))
    f = lambda q: mp.exp(-((r * r + q * q) ** p))
    return 2 * p / (mp.pi * g) * mp.quad(f, [0, 1, 10, mp.inf])


def smith_lambda_nested(u, p):
    """Eq. 41: Lambda(u) = int_{1/u}^inf (r u - 1) P2(r) dr, unit beta."""
    r0 = 1 / mp.mpf(u)
    f = lambda r: (r * u - 1) * p2_marginal(r, p)
    return mp.quad(f, [r0, r0 + 0.5, r0 + 2, r0 + 8, mp.inf])


def beckmann_lambda(u):
    a = 1.0 / u
    return (math.erf(a) - 1) / 2 + math.exp(-a * a) / (2 * a * math.sqrt(math.pi))


def p2_marginal64(r, p):
    """Eq. 40 (q over R) in float64 with scipy, for the many BRDF points."""
    g = math.gamma(1 / p)
    f = lambda q: math.exp(-((r * r + q * q) ** p))
    parts = ((0, 1), (1, 10), (10, math.inf))
    return 2 * p / (math.pi * g) * sum(integrate.quad(f, a, b, epsabs=0, epsrel=1e-12, limit=200)[0] for a, b in parts)


_G1_CACHE = {}


def g1_ref(tan_theta, beta, p):
    """Eqs. 41-42 by nested scipy quadrature (agrees with the mpmath route of g1.json to 1e-15)."""
    u = beta * tan_theta
    if u <= 0:
        return 1.0
    key = (u, p)
    if key not in _G1_CACHE:
        r0 = 1 / u
        f = lambda r: (r * u - 1) * p2_marginal64(r, p)
        parts = ((r0, r0 + 0.5), (r0 + 0.5, r0 + 2), (r0 + 2, r0 + 8), (r0 + 8, math.inf))
        lam = sum(integrate.quad(f, a, b, epsabs=0, epsrel=1e-11, limit=200)[0] for a, b in parts)
        _G1_CACHE[key] = 1 / (1 + lam)
    return _G1_CACHE[key]


# ---------------------------------------------------------------- sigma_rel^2 (Eqs. 22, 25, 43)
def k_density(r, B, c):
    return (c - 1) * B * B / (2 * math.pi) * (1 + B * B * r * r) ** (-(c + 1) / 2)


def sigma_rel_sq_ref(s, B, c):
    """int over the unit disk of k(|x + i_p|), i_p = (s, 0): polar about the disk centre."""
    def inner(rho):
        f = lambda ph: k_density(math.sqrt(max(rho * rho + s * s + 2 * rho * s * math.cos(ph), 0.0)), B, c)
        # the lobe centre -i_p is at phi = pi, rho = s
        return 2 * integrate.quad(f, 0, math.pi, points=[math.pi * 0.999, math.pi * 0.99, math.pi * 0.9],
                                  limit=400, epsabs=0, epsrel=1e-11)[0] * rho
    pts = sorted({0.0, 1.0} | {x for x in (s - 10 / B, s - 1 / B, s, s + 1 / B, s + 10 / B) if 0 < x < 1})
    tot = 0.0
    for a, b in zip(pts[:-1], pts[1:]):
        tot += integrate.quad(inner, a, b, limit=400, epsabs=0, epsrel=1e-10)[0]
    return tot


# ---------------------------------------------------------------- colour terms
def fresnel_ref(cos_t, n, k):
    eta2 = complex(n, k) ** 2
    c = min(max(cos_t, 0.0), 1.0)
    s2 = 1 - c * c
    root = np.sqrt(eta2 - s2)
    fs = abs((c - root) / (c + root)) ** 2
    fp = abs((eta2 * c - root) / (eta2 * c + root)) ** 2
    return 0.5 * (fs + fp)


def q_ref(wi, wo, n, k):
    eta2 = complex(n, k) ** 2
    ti, to = math.acos(wi[2]), math.acos(wo[2])
    phi_i, phi_o = math.atan2(wi[1], wi[0]), math.atan2(wo[1], wo[0])
    phi = phi_o - phi_i - math.pi
    si, so = math.sin(ti), math.sin(to)
    ci, co = math.cos(ti), math.cos(to)
    Ri, Ro = np.sqrt(eta2 - si * si), np.sqrt(eta2 - so * so)
    qss = (eta2 - 1) * math.cos(phi) / ((ci + Ri) * (co + Ro))
    qsp = (eta2 - 1) * Ro * math.sin(phi) / ((ci + Ri) * (eta2 * co + Ro))
    qps = (eta2 - 1) * Ri * math.sin(phi) / ((eta2 * ci + Ri) * (co + Ro))
    qpp = (eta2 - 1) * (Ri * Ro * math.cos(phi) - eta2 * si * so) / ((eta2 * ci + Ri) * (eta2 * co + Ro))
    return abs(qss) ** 2 + abs(qsp) ** 2 + abs(qps) ** 2 + abs(qpp) ** 2


def fdr_fit(eta):
    """F_dr(eta) = 2 C1(1/eta), d'Eon & Irving 2011 polynomial fit (part of the model, §4.4)."""
    e = 1 / eta
    if e < 1:
        c1 = 0.45966 - 1.73965 * e + 3.37668 * e ** 2 - 3.904945 * e ** 3 + 2.49277 * e ** 4 - 0.68441 * e ** 5
    else:
        c1 = -4.61686 + 11.1136 * e - 10.4646 * e ** 2 + 5.11455 * e ** 3 - 1.27198 * e ** 4 + 0.12746 * e ** 5
    return 2 * c1


def fdr_exact(eta):
    """2 int_0^1 F(mu) mu dmu for light from outside onto relative index eta (real)."""
    def f(mu):
        if eta < 1 and 1 - mu * mu > eta * eta:
            return mu  # total internal reflection
        return fresnel_ref(mu, eta, 0.0) * mu
    pts = [0, 1]
    if eta < 1:
        pts = [0, math.sqrt(1 - eta * eta), 1]
    return 2 * sum(integrate.quad(f, a, b, epsabs=0, epsrel=1e-12, limit=200)[0] for a, b in zip(pts[:-1], pts[1:]))


def layer_ref(kind, form, ci, co, n, k, albedo):
    T = (1 - fresnel_ref(ci, n, k)) * (1 - fresnel_ref(co, n, k))
    fint = fdr_fit(1 / n)
    if kind == 1:
        if form == 0:
            return T * albedo / math.pi / (1 - albedo / math.pi * fint)
        return T * albedo / (math.pi * n * n * (1 - albedo * fint))
    if kind == 2:
        af = (1 - fint) / (1 + fint) if form == 0 else (1 + fint) / (1 - fint)
        st = math.sqrt(3 * (1 - albedo))
        cti = math.sqrt(1 - (1 - ci * ci) / n ** 2)
        cto = math.sqrt(1 - (1 - co * co) / n ** 2)
        single = albedo * T / (4 * math.pi) / (cti + cto)
        multi = albedo * T / (2 * math.pi) * math.exp(-st) * (1 + math.exp(-4 / 3 * af * st))
        return single + multi
    return 0.0


def brdf_ref(P, lam, wi, wo):
    sig, beta, p, b, c, n, k = P["sigma_s_um"], P["beta"], P["p"], P["b_um"], P["c"], P["n"], P["k"]
    wi, wo = np.array(wi, float), np.array(wo, float)
    h = wi + wo
    h /= np.linalg.norm(h)
    cd = float(wi @ h)
    ci, co = wi[2], wo[2]
    ti = math.sqrt(1 - ci * ci) / ci
    to = math.sqrt(1 - co * co) / co
    G = g1_ref(ti, beta, p) * g1_ref(to, beta, p)
    F = fresnel_ref(cd, n, k)
    D = ndf(h[2], beta, p)
    refl = math.exp(-(4 * math.pi * sig * cd / lam) ** 2) * F * D * G / (4 * ci * co)
    A = math.exp(-(2 * math.pi * sig / lam * (ci + co)) ** 2)
    B = b / lam
    r = math.hypot(wi[0] + wo[0], wi[1] + wo[1])
    srel = sigma_rel_sq_ref(math.sqrt(1 - ci * ci), B, c)
    S = k_density(r, B, c) / srel
    col = {0: 0.5 * q_ref(wi, wo, n, k), 1: q_ref(wi, wo, n, k), 2: F, 3: 1.0}[P["diff_color"]]
    diff = (1 - A) * S * G * col
    lay = layer_ref(P["layer"], P["layer_form"], ci, co, n, k, P["layer_albedo"])
    return dict(refl=refl, diff=diff, layer=lay, rho=refl + diff + lay, sigma_rel_sq=srel)


def direction(theta, phi):
    return [math.sin(theta) * math.cos(phi), math.sin(theta) * math.sin(phi), math.cos(theta)]


def main():
    os.makedirs(OUT, exist_ok=True)

    # NDF
    rows = []
    for beta in (0.05, 0.2, 0.5):
        for p in (0.3, 0.6, 1.0, 2.0, 3.5):
            pts = [dict(cos_h=ch, d=ndf(ch, beta, p)) for ch in (1.0, 0.999, 0.99, 0.95, 0.8, 0.5)]
            rows.append(dict(beta=beta, p=p, normalisation=ndf_normalisation(beta, p), values=pts))
    json.dump(rows, open(os.path.join(OUT, "ndf.json"), "w"), indent=1)
    print("ndf: max |norm-1| =", max(abs(r["normalisation"] - 1) for r in rows))

    # G1
    rows = []
    for p in (0.3, 0.5, 0.75, 1.0, 1.5, 2.5, 3.5):
        for u in (0.05, 0.2, 0.5, 1.0, 2.0, 5.0, 20.0):
            lam = float(smith_lambda_nested(mp.mpf(u), mp.mpf(p)))
            row = dict(p=p, beta_tan=u, g1=1 / (1 + lam))
            if p == 1.0:
                row["beckmann_closed_form"] = 1 / (1 + beckmann_lambda(u))
            rows.append(row)
    json.dump(rows, open(os.path.join(OUT, "g1.json"), "w"), indent=1)
    bk = [abs(r["g1"] / r["beckmann_closed_form"] - 1) for r in rows if "beckmann_closed_form" in r]
    print("g1: p=1 vs Beckmann closed form, max rel", max(bk))

    # sigma_rel^2
    rows = []
    for c in (1.01, 1.5, 2.5, 6.0):
        for B in (0.1, 1.0, 10.0, 100.0):
            for s in (0.0, 0.3, 0.7, 0.95, 0.999):
                rows.append(dict(s=s, b_over_lambda=B, c=c, sigma_rel_sq=sigma_rel_sq_ref(s, B, c)))
    json.dump(rows, open(os.path.join(OUT, "sigma_rel.json"), "w"), indent=1)
    print("sigma_rel: done", len(rows))

    # incomplete gamma inverse
    rows = []
    for a in (0.25, 0.5, 1.0, 2.0, 5.0, 10.0):
        for q in (1e-6, 1e-3, 0.05, 0.3, 0.5, 0.7, 0.95, 0.999, 1 - 1e-5):
            rows.append(dict(a=a, q=q, x=float(mp.gammaincinv(a, q, regularized=True, tail="upper")) if hasattr(mp, "gammaincinv") else None))
    # mpmath has no gammaincinv: solve Q(a, x) = q with findroot on log x
    for r in rows:
        a, q = mp.mpf(r["a"]), mp.mpf(r["q"])
        x0 = special.gammainccinv(float(a), float(q))
        g = lambda lx: mp.gammainc(a, mp.exp(lx), mp.inf, regularized=True) - q
        r["x"] = float(mp.exp(mp.findroot(g, mp.log(x0))))
        r["lgamma_a"] = float(mp.loggamma(a))
    json.dump(rows, open(os.path.join(OUT, "gamma.json"), "w"), indent=1)

    # F_dr fit vs quadrature
    rows = [dict(eta=e, fit=fdr_fit(e), exact=fdr_exact(e)) for e in (1 / 2.0, 1 / 1.5, 1 / 1.3, 1.3, 1.5, 2.0)]
    json.dump(rows, open(os.path.join(OUT, "fresnel_dr.json"), "w"), indent=1)
    print("F_dr fit max abs err", max(abs(r["fit"] - r["exact"]) for r in rows))

    # full BRDF
    base = dict(diff_color=0, layer=0, layer_form=0, layer_albedo=0.0)
    mats = [
        dict(base, name="gold-polished", sigma_s_um=0.02, beta=0.05, p=0.8, b_um=5.0, c=2.5, n=0.487844, k=2.201734),
        dict(base, name="gold-rough", sigma_s_um=0.25, beta=0.2, p=0.6, b_um=2.0, c=2.0, n=0.147988, k=3.651548),
        dict(base, name="metal-q", sigma_s_um=0.1, beta=0.3, p=1.5, b_um=1.0, c=1.5, n=1.2, k=2.5, diff_color=1),
        dict(base, name="metal-f", sigma_s_um=0.1, beta=0.3, p=1.0, b_um=1.0, c=3.5, n=1.2, k=2.5, diff_color=2),
        dict(base, name="metal-none", sigma_s_um=0.05, beta=0.1, p=2.5, b_um=10.0, c=1.2, n=0.2, k=3.0, diff_color=3),
        dict(base, name="dielectric", sigma_s_um=0.05, beta=0.15, p=0.4, b_um=0.5, c=4.0, n=1.5, k=0.0),
        dict(base, name="plastic-pub", sigma_s_um=0.05, beta=0.1, p=1.0, b_um=3.0, c=3.0, n=1.5, k=0.0, layer=1, layer_form=0, layer_albedo=0.8),
        dict(base, name="plastic-ec", sigma_s_um=0.05, beta=0.1, p=1.0, b_um=3.0, c=3.0, n=1.5, k=0.0, layer=1, layer_form=1, layer_albedo=0.8),
        dict(base, name="sss-pub", sigma_s_um=0.1, beta=0.15, p=1.0, b_um=2.0, c=2.5, n=1.4, k=0.0, layer=2, layer_form=0, layer_albedo=0.9),
        dict(base, name="sss-ec", sigma_s_um=0.1, beta=0.15, p=1.0, b_um=2.0, c=2.5, n=1.4, k=0.0, layer=2, layer_form=1, layer_albedo=0.9),
        dict(base, name="cook-torrance-limit", sigma_s_um=0.0, beta=0.3, p=1.0, b_um=2.0, c=2.5, n=1.5, k=0.0),
    ]
    dirs = [
        (direction(0.0, 0.0), direction(0.2, 1.0)),
        (direction(0.3, 0.0), direction(0.3, math.pi)),
        (direction(0.3, 0.0), direction(0.5, 2.0)),
        (direction(0.8, 0.4), direction(0.9, 3.0)),
        (direction(1.2, 0.0), direction(1.0, math.pi + 0.3)),
        (direction(0.6, 1.0), direction(1.4, 5.0)),
    ]
    rows = []
    for m in mats:
        for lam in (0.444, 0.645):
            for wi, wo in dirs:
                r = brdf_ref(m, lam, wi, wo)
                rows.append(dict(material=m, lambda_um=lam, wi=wi, wo=wo, **r))
    json.dump(rows, open(os.path.join(OUT, "brdf.json"), "w"), indent=1)
    print("brdf:", len(rows))


if __name__ == "__main__":
    main()
