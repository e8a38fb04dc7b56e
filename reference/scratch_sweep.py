#!/usr/bin/env python3
"""Domain sweep of the scratch models (Werner et al. 2017, Velinov et al. 2018) at f32 inputs
(issue #20).

Every query draws its inputs in float64, rounds each to float32 and evaluates the table BRDF
`refcore.brdf` (the mpmath reference of every BRDF-table golden: eta by contour quadrature,
M and P by quadrature of their defining integrals) at exactly those float32 values. Nothing
here comes from the kernel.

A query is what `kernel::table::evaluate` receives for one table query: the coherence sigma,
lambda (nm), wi, wo (three float32 components each, used as given when their squared length
is within `refcore.UNIT_TOLERANCE` of 1, as the kernel does), the shading point x, the
options of the model, a constant reflectance F = 1 (Fresnel has its own sweep,
`reference/ghs/domain_sweep.py`), and one to three scratches in the kernel's record form:
centre c, unit tangent t, half length h, width W, depth D (all float32). The reference
segment is p0,1 = c -+ h t/|t| (the tangents are chosen with |t| = 1 to ~1e-9; the kernel
uses t as given).

Each query also carries its conditioning

    kappa = max over inputs x_i, over x_i -> nextafter_f32(x_i, +-inf), of |f(x') / f(x) - 1|,

how much the exact value moves when one input moves by one float32 ulp. The nudged values
are evaluated with the closed forms of `refcore` (App. A eta with mpmath's complex erf, the
sinc forms of M and P) at 40+ digits; `--check` and the `cf_rel` column compare those closed
forms with the quadrature at every query. The kernel test
(`kernel/tests/scratch_domain_sweep.rs`) accepts err <= max(1e-4, 8 kappa).

Families (files `reference/golden/sweep/<family>.csv`):
  velinov      Velinov Eq. 7 point model F/(pi s^2 l^2) [sum |S_k|^2 + (1 - rho_c) B^2 [base]],
               finite (Werner App. A) or infinite (Velinov Eq. 8) eta, rect and triangle
  werner_rect  Werner Eq. 15 F/(pi s^2 l^2) |B - S|^2, rectangular grooves
  werner_tri   the same with triangular grooves (Eqs. 29-31 corrected)
  werner_blended  Werner Sec. 5: F/(pi s^2 l^2) |S|^2 + max(1 - rho_c, 0) f_base, both profiles,
               base none (table::evaluate), smooth (a delta: adds nothing to the value) or
               GHS (H&P 2016, reference/ghs/domain_sweep.py's mpmath BRDF, all its inputs
               nudged too); widths scaled so that rho_c (corrected Velinov Eq. 17) at x lands
               near 0, in between, near 1 or just above 1 (where the base weight clamps to 0)

Domain (the issue's): sigma 1-100 um, W 0.1-50 um, D 0.001-10 um, lambda 360-830 nm, cosines
down to 0.005, x on top of a scratch (|s_b| < W/2), near it, and up to 5.9 sigma away
(the kernel drops scratches beyond 6 sigma: a model truncation, see docs/stability.md), inside
the segment's span and beyond its ends; half lengths 1e-3 sigma to 1e4 um; xi near the mirror
direction, along a scratch's diffraction line (xi1 ~ 0) and anywhere.

Usage:
  python3 reference/scratch_sweep.py                   # the committed subset (4 x 1 200 queries, ~16 min on one core)
  python3 reference/scratch_sweep.py --full --out DIR  # 4 x 100 000 queries (the full sweep)
  python3 reference/scratch_sweep.py --check           # self-checks of the reference only
  SCRATCH_SWEEP_DIR=DIR cargo test --release -p scratchwave-kernel --test scratch_domain_sweep -- --nocapture
The subset is a prefix of the full sweep (same seeds, rows drawn one after another).
--jobs 1 (the default) evaluates in this process; --jobs N > 1 uses a Pool of N workers.
The werner_blended family's GHS base needs numpy (reference/ghs/domain_sweep.py).
"""
import argparse
import csv
import math
import os
import random
import struct
import sys
import time

import mpmath as mp

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import refcore as rc  # noqa: E402
from parallel import ordered_map  # noqa: E402

OUT = os.path.join(HERE, "golden", "sweep")

COUNTS = dict(velinov=1200, werner_rect=1200, werner_tri=1200, werner_blended=1200)
FULL_COUNT = 100_000
SEEDS = dict(velinov=3001, werner_rect=3002, werner_tri=3003, werner_blended=3004)

SIGMA = (1.0, 100.0)
WIDTH = (0.1, 50.0)
DEPTH = (1e-3, 10.0)
LAMBDA_NM = (360.0, 830.0)
COS_MIN = 0.005
MAX_SCRATCHES = 3
# the kernel's window: scratches farther than this many sigma from x0 are not summed
REACH = 5.9


# ------------------------------------------------------------------ float32 helpers
def f32(x):
    """The nearest float32 (round to nearest even), as a Python float."""
    return struct.unpack("<f", struct.pack("<f", float(x)))[0]


def nudge(x, up):
    """The next float32 after x towards +inf (up) or -inf."""
    x = f32(x)
    if x == 0:
        b = 1
        return f32(struct.unpack("<f", struct.pack("<I", b))[0]) * (1 if up else -1)
    b = struct.unpack("<I", struct.pack("<f", x))[0]
    if (x > 0) == up:
        b += 1
    else:
        b -= 1
    return struct.unpack("<f", struct.pack("<I", b))[0]


def s32(x):
    """Shortest decimal that reads back as the same float32 (Rust `str::parse::<f32>`)."""
    x = f32(x)
    if x == 0:
        return "0"
    for p in range(1, 10):
        s = "%.*g" % (p, x)
        if f32(float(s)) == x:
            return s
    return repr(x)


def unit_tangent(a):
    """A float32 tangent (cos a, sin a) whose length is 1 to the best float32 pair nearby."""
    c, s = f32(math.cos(a)), f32(math.sin(a))
    best = (abs(math.fsum([c * c, s * s]) - 1), c, s)
    for i in range(-4, 5):
        for j in range(-4, 5):
            cc, ss = c, s
            for _ in range(abs(i)):
                cc = nudge(cc, i > 0)
            for _ in range(abs(j)):
                ss = nudge(ss, j > 0)
            e = abs(math.fsum([cc * cc, ss * ss]) - 1)
            if e < best[0]:
                best = (e, cc, ss)
    return best[1], best[2]


def loguni(rng, lo, hi):
    return math.exp(rng.uniform(math.log(lo), math.log(hi)))


def sgn(rng):
    return 1 if rng.random() < 0.5 else -1


# ------------------------------------------------------------------ query generation
def direction(rng):
    """A float64 unit vector stressing grazing and normal directions."""
    kind = rng.randrange(4)
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
    return tuple(f32(c) for c in v)


def wo_for_xi(wi, xi, lam_um):
    """wo with (wi + wo)_xy = lambda xi, or None below cos COS_MIN."""
    ox, oy = lam_um * xi[0] - wi[0], lam_um * xi[1] - wi[1]
    r2 = ox * ox + oy * oy
    if r2 > 1 - COS_MIN * COS_MIN:
        return None
    return (ox, oy, math.sqrt(1 - r2))


def scratch(rng, x0, sigma, profile):
    """One scratch near x0 (float64 values; rounded by the caller)."""
    a = 0.0 if rng.random() < 0.1 else rng.uniform(0, 2 * math.pi)
    if rng.random() < 0.05:
        a = math.pi / 2
    tx, ty = unit_tangent(a)
    u = rng.random()
    if u < 0.3:
        h = sigma * loguni(rng, 1e-3, 0.5)  # very short
    elif u < 0.6:
        h = sigma * loguni(rng, 0.5, 5.0)
    else:
        h = min(loguni(rng, 5 * sigma, 1e4), 1e4)  # long, ends often outside the window
    w = loguni(rng, *WIDTH)
    d = loguni(rng, *DEPTH)
    # centre offset from x0 in the scratch frame: across (s_b) and along (s_t)
    u = rng.random()
    if u < 0.3:
        sb = rng.uniform(-0.5, 0.5) * w  # on top of the groove
    elif u < 0.7:
        sb = sgn(rng) * sigma * loguni(rng, 1e-2, 3.0)
    else:
        sb = sgn(rng) * sigma * rng.uniform(3.0, REACH)
    u = rng.random()
    if u < 0.5:
        st = rng.uniform(-1, 1) * h  # x0 within the segment's span
    else:
        st = sgn(rng) * (h + sigma * loguni(rng, 1e-2, 4.0))  # beyond an end
    # keep the closed segment within REACH sigma of x0 (the kernel's window)
    dt = max(abs(st) - h, 0.0)
    r = math.hypot(dt, sb)
    if r > REACH * sigma:
        k = REACH * sigma / r * 0.999
        sb *= k
        st = math.copysign(h + dt * k, st) if dt > 0 else st
    bx, by = -ty, tx
    c = (x0[0] + st * tx + sb * bx, x0[1] + st * ty + sb * by)
    return dict(cx=c[0], cy=c[1], tx=tx, ty=ty, h=h, w=w, d=d, profile=profile)


def rho_approx(scr, x0, sigma):
    """rho_c at x0 in float64 (corrected Velinov Eq. 17, erf form): only to steer the draw."""
    tot = 0.0
    for s in scr:
        dx, dy = s["cx"] - x0[0], s["cy"] - x0[1]
        st = dx * s["tx"] + dy * s["ty"]
        sb = -dx * s["ty"] + dy * s["tx"]
        r2 = math.sqrt(2) * sigma
        g = math.erf((st + s["h"]) / r2) - math.erf((st - s["h"]) / r2)
        tot += s["w"] * math.exp(-sb * sb / (2 * sigma * sigma)) * sigma * math.sqrt(math.pi / 2) * g
    return tot / (2 * math.pi * sigma * sigma)


def steer_rho(rng, scr, x0, sigma):
    """werner_blended: scale every width so that rho_c at x0 lands near 0, in between, near 1
    or just above 1 (widths stay within WIDTH; a clipped width misses the target)."""
    u = rng.random()
    if u < 0.2:
        return  # as drawn
    if u < 0.4:
        target = loguni(rng, 1e-6, 1e-2)
    elif u < 0.65:
        target = rng.uniform(0.05, 0.95)
    else:
        d = loguni(rng, 1e-6, 0.1)
        target = 1 - d if rng.random() < 0.75 else 1 + d
        # x0 within 0.3 sigma across scratch 0 and inside its span (rho_c ~ 1 needs W ~ 2.5 sigma)
        s0 = scr[0]
        st, sb = rng.uniform(-1, 1) * s0["h"], rng.uniform(-0.3, 0.3) * sigma
        s0["cx"] = x0[0] + st * s0["tx"] - sb * s0["ty"]
        s0["cy"] = x0[1] + st * s0["ty"] + sb * s0["tx"]
    rho = rho_approx(scr, x0, sigma)
    if rho > 0:
        k = target / rho
        for s in scr:
            s["w"] = min(max(s["w"] * k, WIDTH[0]), WIDTH[1])


# GHS base of werner_blended: reference/ghs/domain_sweep.py's domain (docs/ghs.md)
GHS_STRATA = [  # (layer, layer_form, ior kind), as the GHS sweep's brdf family
    (0, 0, 0), (0, 0, 1), (0, 0, 2), (1, 0, 1), (1, 1, 1), (2, 0, 1), (2, 1, 1), (0, 0, 0),
]
GHS_KEYS = ("sigma_s", "beta", "p", "b", "c", "n", "k", "albedo")


def ghs_params(rng):
    """GHS parameters (float32) drawn as reference/ghs/domain_sweep.py's brdf family does."""
    lay, form, ik = GHS_STRATA[rng.randrange(len(GHS_STRATA))]
    beta, p = loguni(rng, 1e-3, 0.5), loguni(rng, 0.3, 3.0)
    b = loguni(rng, 0.01, 100.0)
    if ik == 0:
        n, k = loguni(rng, 0.03, 3.0), loguni(rng, 0.5, 10.0)
    elif ik == 1:
        n, k = (1 + loguni(rng, 1e-3, 5e-2) if rng.random() < 0.15 else loguni(rng, 1.05, 3.0)), 0.0
    else:
        n, k = loguni(rng, 1.05, 3.0), loguni(rng, 1e-4, 0.3)
    if lay:
        n = loguni(rng, 1.05, 2.5) if rng.random() < 0.9 else 1 + loguni(rng, 1e-3, 5e-2)
    g = dict(sigma_s=loguni(rng, 1e-3, 1.0), beta=beta, p=p, b=b,
             c=1 + loguni(rng, 1e-3, 9.0), n=n, k=k, albedo=rng.uniform(0, 1))
    g = {key: f32(v) for key, v in g.items()}
    g.update(diff_color=rng.randrange(4), layer=lay, layer_form=form)
    return g


_GHS = []


def ghs_module():
    """reference/ghs/domain_sweep.py (imported on first use: it needs numpy), its `m` taking
    an mpf (the exact lambda_nm / 1000) as it is."""
    if not _GHS:
        sys.path.insert(0, os.path.join(HERE, "ghs"))
        import domain_sweep as g
        m32 = g.m
        g.m = lambda x: x if isinstance(x, mp.mpf) else m32(x)
        _GHS.append(g)
    return _GHS[0]


def ghs_value(q, cache):
    """The GHS BRDF (1/sr, no cosine) of the base at the query's directions and wavelength."""
    g = ghs_module()
    gq = dict(q["ghs"], wi=q["wi"], wo=q["wo"])
    with mp.workdps(g.DPS):
        gq["lambda"] = mp.mpf(q["lambda_nm"]) / 1000
        return g.brdf(gq, cache)[0]


def gen_query(rng, fam):
    sigma = loguni(rng, *SIGMA)
    lam = rng.uniform(*LAMBDA_NM)
    x0 = (rng.uniform(-200, 200), rng.uniform(-200, 200))
    u = rng.random()
    ns = 1 if u < 0.6 else (2 if u < 0.85 else 3)
    prof = {"werner_rect": 0, "werner_tri": 1}.get(fam)
    scr = [scratch(rng, x0, sigma, rng.randrange(2) if prof is None else prof)
           for i in range(ns)]
    if fam == "werner_blended":
        steer_rho(rng, scr, x0, sigma)
    q = dict(sigma=f32(sigma), lambda_nm=f32(lam), x=v32(x0))
    q["depth_term"] = rng.randrange(2)
    q["eta"] = rng.randrange(2) if fam == "velinov" else 0
    # the Gaussian base needs rho_c < 1 (one scratch narrower than sigma: rho_c < 0.4)
    q["base"] = int(fam == "velinov" and ns == 1 and scr[0]["w"] < sigma and rng.random() < 0.4)
    if fam == "werner_blended":
        # the kernel's BaseKind: 0 none (table::evaluate), 1 smooth, 2 GHS (bsdf::eval)
        u = rng.random()
        q["base"] = 0 if u < 0.3 else (1 if u < 0.45 else 2)
        g = ghs_params(rng)
        q["ghs"] = g if q["base"] == 2 else None
    wi = direction(rng)
    lam_um = lam / 1000
    s0 = scr[0]
    t, b = (s0["tx"], s0["ty"]), (-s0["ty"], s0["tx"])
    wo = None
    u = rng.random()
    if u < 0.35:  # near the mirror direction
        r = loguni(rng, 1e-4, 1.0) / sigma
        ph = rng.uniform(0, 2 * math.pi)
        wo = wo_for_xi(wi, (r * math.cos(ph), r * math.sin(ph)), lam_um)
    elif u < 0.75:  # along scratch 0's diffraction line
        xi1 = sgn(rng) * loguni(rng, 1e-4, 0.5) / sigma
        if rng.random() < 0.2:
            xi1 = 0.0
        xi2 = sgn(rng) * loguni(rng, 1e-3, 20.0) / s0["w"]
        xi = (xi1 * t[0] + xi2 * b[0], xi1 * t[1] + xi2 * b[1])
        wo = wo_for_xi(wi, xi, lam_um)
    if wo is None:
        wo = direction(rng)
    q["wi"], q["wo"] = v32(wi), v32(wo)
    q["scratches"] = [{k: (f32(v) if k != "profile" else v) for k, v in s.items()} for s in scr]
    return q


# ------------------------------------------------------------------ reference values
def spec_of(fam, q):
    """The query as a `refcore.brdf` spec (segments from the kernel's record at 60 digits)."""
    scr = []
    with mp.workdps(60):
        for s in q["scratches"]:
            t = (mp.mpf(s["tx"]), mp.mpf(s["ty"]))
            n = mp.sqrt(t[0] ** 2 + t[1] ** 2)
            h = mp.mpf(s["h"])
            c = (mp.mpf(s["cx"]), mp.mpf(s["cy"]))
            p0 = [c[0] - h * t[0] / n, c[1] - h * t[1] / n]
            p1 = [c[0] + h * t[0] / n, c[1] + h * t[1] / n]
            scr.append(dict(p0=p0, p1=p1, width=s["w"], depth=s["d"],
                            profile=("rect", "triangle")[s["profile"]]))
    model = {"velinov": "velinov", "werner_blended": "werner_blended"}.get(fam, "werner")
    opts = {"depth_term": ("small_angle", "exact")[q["depth_term"]],
            "eta": ("finite", "infinite")[q["eta"]],
            # werner_blended's base is added outside refcore.brdf (ref_quad, ref_cf)
            "base": ("none", "gaussian")[q["base"]] if model == "velinov" else "none"}
    spec = dict(model=model, options=opts, sigma_um=q["sigma"], scratches=scr,
                material={"F": 1.0})
    query = dict(wi=list(q["wi"]), wo=list(q["wo"]), lambda_nm=q["lambda_nm"], x=list(q["x"]))
    return spec, query


def ref_quad(fam, q):
    """refcore.brdf: eta and the profile transforms by quadrature (werner_blended: plus
    max(1 - rho_c, 0) f_GHS, rho_c by refcore.rho_c's quadrature)."""
    rc.MEMO.clear()
    spec, query = spec_of(fam, q)
    v = rc.brdf(spec, query)
    if fam == "werner_blended" and q["base"] == 2:
        with mp.workdps(rc.DPS + 10):
            wi, wo = rc._direction(query["wi"]), rc._direction(query["wo"])
            if wi[2] > 0 and wo[2] > 0:
                w = 1 - rc.rho_c(spec["sigma_um"], spec["scratches"], query["x"])
                if w > 0:
                    v = +(v + w * ghs_value(q, ghs_module().Cache()))
    return v


def term_cf(spec, s, sigma, lam, gT, x0, xi, eta_mode):
    """S_k = (M_k - P_k) eta_k from refcore's closed forms."""
    seg = rc.Segment(s["p0"], s["p1"])
    _, _, xi1, xi2 = seg.frame(x0, xi)
    W, D = mp.mpf(s["width"]), mp.mpf(s["depth"])
    if s["profile"] == "rect":
        Mk, Pk = rc.closedform_rect(W, D, gT, lam, xi2)
        # M - P = (1 - Phi_D) M without cancellation
        mp_ = -2j * mp.sin(mp.pi * gT * D / lam) * mp.exp(1j * mp.pi * gT * D / lam) * Mk
    else:
        x = mp.pi * W * xi2
        Mk = W * (mp.sin(x) / x if x != 0 else 1)
        mp_ = Mk - rc.closedform_triangle_sinc(W, D, gT, lam, xi2)
    if eta_mode == "infinite":
        e = rc.eta_inf(sigma, s["p0"], s["p1"], x0, xi)
    else:
        e = rc.closedform_eta(sigma, s["p0"], s["p1"], x0, xi)
    return mp_ * e


def ref_cf(fam, q, dps=rc.DPS + 15, memo=None, parts=None):
    """The same BRDF from the closed forms (for kappa and as a cross-check). `memo` keeps
    each scratch's term by the float32 inputs it depends on, so a nudge of one scratch's
    input recomputes only that scratch (and the GHS base by its inputs). `parts`, a dict,
    receives rho_c (werner_blended)."""
    memo = {} if memo is None else memo
    blended = fam == "werner_blended"
    spec, query = spec_of(fam, q)
    glob = (q["sigma"], q["lambda_nm"], q["wi"], q["wo"], q["x"], q["depth_term"], q["eta"], dps)
    with mp.workdps(dps):
        wi, wo = rc._direction(query["wi"]), rc._direction(query["wo"])
        if wi[2] <= 0 or wo[2] <= 0:
            return mp.mpf(0)
        opts = spec["options"]
        sigma = mp.mpf(spec["sigma_um"])
        lam = mp.mpf(query["lambda_nm"]) / 1000
        gT = wi[2] + wo[2] if opts["depth_term"] == "exact" else mp.mpf(2)
        xi = [(wi[0] + wo[0]) / lam, (wi[1] + wo[1]) / lam]
        x0 = query["x"]
        B = rc.base_response(sigma, xi)
        Sk, rho = [], []
        for s, s32_ in zip(spec["scratches"], q["scratches"]):
            key = glob + tuple(sorted(s32_.items()))
            if key not in memo:
                memo[key] = term_cf(spec, s, sigma, lam, gT, x0, xi, opts["eta"])
            Sk.append(memo[key])
            # rho_c: Velinov's Gaussian base; werner_blended's GHS base (and its rho_c column)
            if opts["base"] == "gaussian" or (blended and (q["base"] == 2 or parts is not None)):
                rk = ("rho",) + key
                if rk not in memo:
                    memo[rk] = mp.mpf(s["width"]) * mp.re(rc.closedform_eta(sigma, s["p0"], s["p1"], x0, (0, 0)))
                rho.append(memo[rk])
        pref = 1 / (mp.pi * sigma ** 2 * lam ** 2)
        if spec["model"] == "werner":
            val = abs(B - mp.fsum(Sk)) ** 2
        elif blended:
            rho_c = mp.fsum(rho) / (2 * mp.pi * sigma ** 2)
            if parts is not None:
                parts["rho_c"] = rho_c
            val = pref * abs(mp.fsum(Sk)) ** 2
            if q["base"] == 2 and rho_c < 1:
                gk = ("ghs", q["wi"], q["wo"], q["lambda_nm"]) + tuple(sorted(q["ghs"].items()))
                if gk not in memo:
                    if "ghs_cache" not in memo:
                        memo["ghs_cache"] = ghs_module().Cache()
                    memo[gk] = ghs_value(q, memo["ghs_cache"])
                val += (1 - rho_c) * memo[gk]
            return +val
        else:
            val = mp.fsum([abs(v) ** 2 for v in Sk])
            if opts["base"] == "gaussian":
                val += (1 - mp.fsum(rho) / (2 * mp.pi * sigma ** 2)) * B ** 2
        return +(pref * val)


# working digits of the nudged evaluations: kappa needs a few digits of f(x')/f(x) - 1 >= ~1e-9
KAPPA_DPS = 24


def inputs_of(q):
    """(getter, setter) pairs naming every float32 input of a query."""
    keys = [("sigma",), ("lambda_nm",)] + [("wi", j) for j in range(3)] + \
        [("wo", j) for j in range(3)] + [("x", j) for j in range(2)]
    for i in range(len(q["scratches"])):
        keys += [("scratches", i, k) for k in ("cx", "cy", "tx", "ty", "h", "w", "d")]
    if q.get("ghs"):
        keys += [("ghs", k) for k in GHS_KEYS]
    return keys


def perturbed(q, key, up):
    q2 = dict(q)
    if key[0] in ("wi", "wo", "x"):
        v = list(q[key[0]])
        v[key[1]] = nudge(v[key[1]], up)
        q2[key[0]] = tuple(v)
    elif key[0] == "scratches":
        ss = [dict(s) for s in q["scratches"]]
        ss[key[1]][key[2]] = nudge(ss[key[1]][key[2]], up)
        q2["scratches"] = ss
    elif key[0] == "ghs":
        q2["ghs"] = dict(q["ghs"], **{key[1]: nudge(q["ghs"][key[1]], up)})
    else:
        q2[key[0]] = nudge(q[key[0]], up)
    return q2


def evaluate(args):
    """(reference value, kappa, closed-form vs quadrature relative difference, rho_c or None)
    of one query."""
    fam, q = args
    mp.mp.dps = rc.DPS
    v = ref_quad(fam, q)
    parts = {}
    cf = ref_cf(fam, q, parts=parts)
    with mp.workdps(60):
        cf_rel = abs(cf / v - 1) if v != 0 else abs(cf)
    kap = mp.mpf(0)
    if v != 0:
        memo = {}
        c0 = ref_cf(fam, q, KAPPA_DPS, memo)
        for key in inputs_of(q):
            for up in (False, True):
                kap = max(kap, abs(ref_cf(fam, perturbed(q, key, up), KAPPA_DPS, memo) / c0 - 1))
    return v, kap, cf_rel, parts.get("rho_c")


# ------------------------------------------------------------------ files
def header(fam=None):
    h = ["sigma", "lambda_nm", "wi_x", "wi_y", "wi_z", "wo_x", "wo_y", "wo_z", "x_x", "x_y",
         "depth_term", "eta", "base", "n"]
    for i in range(MAX_SCRATCHES):
        h += ["s%d_%s" % (i, k) for k in ("cx", "cy", "tx", "ty", "h", "w", "d", "profile")]
    if fam == "werner_blended":
        return h + ["ghs_" + k for k in GHS_KEYS + ("diff_color", "layer", "layer_form")] + \
            ["ref", "kappa", "cf_rel", "rho_c"]
    return h + ["ref", "kappa", "cf_rel"]


def row(q, fam=None):
    r = [s32(q["sigma"]), s32(q["lambda_nm"])] + [s32(c) for c in q["wi"]] + \
        [s32(c) for c in q["wo"]] + [s32(c) for c in q["x"]]
    r += [str(q["depth_term"]), str(q["eta"]), str(q["base"]), str(len(q["scratches"]))]
    for i in range(MAX_SCRATCHES):
        if i < len(q["scratches"]):
            s = q["scratches"][i]
            r += [s32(s[k]) for k in ("cx", "cy", "tx", "ty", "h", "w", "d")] + [str(s["profile"])]
        else:
            r += ["0"] * 8
    if fam == "werner_blended":
        g = q["ghs"]
        r += [s32(g[k]) for k in GHS_KEYS] + [str(g[k]) for k in ("diff_color", "layer", "layer_form")] \
            if g else ["0"] * (len(GHS_KEYS) + 3)
    return r


def fmt(x):
    return mp.nstr(x, 17, min_fixed=1, max_fixed=0) if x != 0 else "0"


def gen_queries(fam, n, seed_offset=0):
    rng = random.Random(SEEDS[fam] + 1000 * seed_offset)
    return [gen_query(rng, fam) for _ in range(n)]


def run_family(fam, n, outdir, jobs, seed_offset=0):
    qs = gen_queries(fam, n, seed_offset)
    t0 = time.time()
    res = list(ordered_map(evaluate, [(fam, q) for q in qs], jobs, chunksize=4))
    path = os.path.join(outdir, fam + ".csv")
    with open(path, "w", newline="") as fh:
        w = csv.writer(fh, lineterminator="\n")
        w.writerow(header(fam))
        for q, (v, kap, cf_rel, rho) in zip(qs, res):
            extra = [mp.nstr(rho, 9)] if fam == "werner_blended" else []
            w.writerow(row(q, fam) + [fmt(v), mp.nstr(kap, 4), mp.nstr(cf_rel, 3)] + extra)
    kmax = max(float(r[1]) for r in res)
    cmax = max(float(r[2]) for r in res)
    print("%-12s %6d queries  %7.1f s  max kappa %.2e  max |closed form/quadrature - 1| %.1e -> %s"
          % (fam, n, time.time() - t0, kmax, cmax, path), flush=True)
    if cmax > 1e-25:
        sys.exit("closed forms and quadrature disagree by %.1e" % cmax)


def check():
    """Closed forms (used for kappa) against the quadrature (the value) on fresh queries, and
    the float32 helpers."""
    assert f32(0.1) == struct.unpack("<f", struct.pack("<f", 0.1))[0]
    assert nudge(1.0, True) == 1.0 + 2 ** -23 and nudge(1.0, False) == 1.0 - 2 ** -24
    assert nudge(-1.0, True) == -1.0 + 2 ** -24
    for x in (0.1, 3.14159, 1e-7, 123456.7):
        assert f32(float(s32(x))) == f32(x)
    worst = {}
    for fam in COUNTS:
        rng = random.Random(SEEDS[fam] + 100)
        e = 0
        mp.mp.dps = rc.DPS
        for _ in range(20):
            q = gen_query(rng, fam)
            v = ref_quad(fam, q)
            c = ref_cf(fam, q)
            with mp.workdps(60):
                e = max(e, abs(c / v - 1) if v else abs(c))
        worst[fam + ": closed forms vs quadrature"] = e
    for k, v in worst.items():
        print("%-50s %.2e" % (k, float(v)))
    bad = [k for k, v in worst.items() if v > 1e-25]
    if bad:
        sys.exit("self-check failed: %s" % bad)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--full", action="store_true", help="the full sweep (%d per family)" % FULL_COUNT)
    ap.add_argument("--out", default=OUT)
    ap.add_argument("--only", default=",".join(COUNTS))
    ap.add_argument("--jobs", type=int, default=1)
    ap.add_argument("--check", action="store_true")
    ap.add_argument("--count", type=int, help="queries per family (overrides the defaults; for trials)")
    ap.add_argument("--seed-offset", type=int, default=0,
                    help="draw a different sample (spot checks beyond the committed subset)")
    a = ap.parse_args()
    if a.check:
        check()
        return
    os.makedirs(a.out, exist_ok=True)
    for fam in a.only.split(","):
        n = a.count or (FULL_COUNT if a.full else COUNTS[fam])
        run_family(fam, n, a.out, a.jobs, a.seed_offset)


if __name__ == "__main__":
    main()
