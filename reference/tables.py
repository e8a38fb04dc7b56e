"""Definitions of the BRDF-table golden cases (specs in the CLI's format).

Every query is built from plain float64 numbers, written to the JSON exactly as
used; the reference value is computed from those floats (refcore.brdf).
"""

import math

import numpy as np

import refcore as rc

DEG = math.pi / 180


def sph(theta, phi):
    st = math.sin(theta)
    return [st * math.cos(phi), st * math.sin(phi), math.cos(theta)]


def mirror(w):
    return [-w[0], -w[1], w[2]]


def wo_from_sum(wi, sxy):
    """wo with (wi + wo)_xy = sxy (None if that leaves the hemisphere)."""
    ox, oy = sxy[0] - wi[0], sxy[1] - wi[1]
    r2 = ox * ox + oy * oy
    if r2 >= 0.9999:
        return None
    return [ox, oy, math.sqrt(1 - r2)]


def f32(v):
    """The nearest float32, as a Python float (the kernel's input precision)."""
    return float(np.float32(v))


def f32_unit(w):
    """w normalised in f64 and rounded to f32: what the kernel receives (see UNIT_TOLERANCE)."""
    n = math.sqrt(sum(float(a) * float(a) for a in w))
    return [f32(float(a) / n) for a in w]


def q(wi, wo, lam, x, **kw):
    # Queries are stored at f32-representable values so that the reference is evaluated at
    # exactly the inputs the f32 kernel sees; near oscillation zeros and on narrow lobes the
    # rounding of the inputs alone would otherwise exceed the 1e-4 target.
    d = {"wi": f32_unit(wi), "wo": f32_unit(wo),
         "lambda_nm": f32(lam), "x": [f32(x[0]), f32(x[1])]}
    d.update(kw)
    return d


def seg_tb(p0, p1):
    d = np.subtract(p1, p0).astype(float)
    t = d / np.hypot(*d)
    return t, np.array([-t[1], t[0]])


# ---------------------------------------------------------------------------

def mirror_queries(rng):
    """Queries around the mirror direction, incl. grazing and invalid ones."""
    qs = []
    for lam in (380.0, 520.0, 780.0):
        for th_deg in (0.0, 10.0, 30.0, 60.0, 80.0):
            phi = rng.uniform(0, 2 * math.pi)
            wi = sph(th_deg * DEG, phi)
            for dxi in (0.0, 0.005, 0.02, 0.05, 0.1):
                ang = rng.uniform(0, 2 * math.pi)
                s = [dxi * lam / 1000 * math.cos(ang), dxi * lam / 1000 * math.sin(ang)]
                wo = wo_from_sum(wi, s)
                x = rng.uniform(-50, 50, 2)
                if wo is not None:
                    qs.append(q(wi, wo, lam, x))
    # grazing (z = 0.02): exact mirror and slightly off
    gi = [math.sqrt(1 - 0.02 ** 2), 0.0, 0.02]
    for dxi in (0.0, 0.01, 0.03):
        wo = wo_from_sum(gi, [0.0, dxi * 0.52])
        qs.append(q(gi, wo, 520.0, [0, 0]))
    # far from mirror: astronomically small
    for lam in (380.0, 780.0):
        qs.append(q(sph(30 * DEG, 0.3), sph(40 * DEG, 2.0), lam, [1, 2]))
        qs.append(q(sph(5 * DEG, 0.3), sph(5 * DEG, 0.3 + math.pi * 0.98), lam, [1, 2]))
    # unnormalised input vectors (the reference normalises)
    wi = sph(25 * DEG, 1.0)
    qs.append(q([2.5 * v for v in wi], [0.4 * v for v in mirror(wi)], 520.0, [0, 0]))
    # invalid: below the horizon -> 0
    qs.append(q(sph(30 * DEG, 0.0), [0.5, 0.0, -0.2], 520.0, [0, 0]))
    qs.append(q([1.0, 0.0, 0.0], [-1.0, 0.0, 0.0], 520.0, [0, 0]))
    return qs


def bitangent_queries(rng, scratches, xs, lams, n_per, qrange=0.7, xi1s=(0.0,),
                      th_range=(5, 60), extra_q=()):
    """Queries whose (wi+wo)_xy lies along a scratch's bitangent (+ xi1 offsets)."""
    qs = []
    for s in scratches:
        t, b = seg_tb(s["p0"], s["p1"])
        for _ in range(n_per):
            lam = float(rng.choice(lams))
            wi = sph(rng.uniform(*th_range) * DEG, rng.uniform(0, 2 * math.pi))
            x1 = float(rng.choice(xi1s))
            qq = rng.uniform(-qrange, qrange)
            sxy = qq * b + x1 * lam / 1000 * t
            wo = wo_from_sum(wi, sxy)
            if wo is None:
                continue
            x = xs[rng.integers(len(xs))]
            qs.append(q(wi, wo, lam, x))
        for qq in extra_q:
            lam = float(rng.choice(lams))
            wi = sph(rng.uniform(*th_range) * DEG, rng.uniform(0, 2 * math.pi))
            wo = wo_from_sum(wi, qq * b)
            if wo is not None:
                qs.append(q(wi, wo, lam, xs[0]))
    return qs


def sinc_zero_queries(s, lams, x, th=30 * DEG):
    """xi1 = 0 and xi2 = k/W exactly (up to float rounding): mask zeros."""
    qs = []
    t, b = seg_tb(s["p0"], s["p1"])
    phi_b = math.atan2(b[1], b[0])
    for lam in lams:
        wi = sph(th, phi_b + math.pi)  # incidence in the bitangent plane
        for k in (-2, -1, 1, 2, 3):
            qq = k * (lam / 1000) / s["width"]
            wo = wo_from_sum(wi, qq * b)
            if wo is not None:
                qs.append(q(wi, wo, lam, x))
    return qs


def triangle_pole_queries(s, lams, x, gamma_mode):
    """xi1 = 0, xi2 = +-2 D gamma / (W lambda): removable poles of the triangle formula."""
    from scipy.optimize import brentq
    qs = []
    t, b = seg_tb(s["p0"], s["p1"])
    phi_b = math.atan2(b[1], b[0])
    W, D = s["width"], s["depth"]
    for lam in lams:
        l_um = lam / 1000
        wi = sph(20 * DEG, phi_b + math.pi)
        for sgn in (1, -1):
            if gamma_mode == "small_angle":
                # gamma -> 2: xi2 = 4D/(W lambda), i.e. (wi+wo).b = 4D/W
                wo = wo_from_sum(wi, sgn * 4 * D / W * b)
            else:
                def fres(qq):
                    wo = wo_from_sum(wi, qq * b)
                    return qq - sgn * 2 * D * (wi[2] + wo[2]) / W

                grid = np.linspace(-1.3, 1.3, 2601)
                vals = [None if wo_from_sum(wi, g * b) is None else fres(g) for g in grid]
                wo = None
                for i in range(len(grid) - 1):
                    if vals[i] is not None and vals[i + 1] is not None \
                            and vals[i] * vals[i + 1] <= 0:
                        qq = brentq(fres, grid[i], grid[i + 1], xtol=1e-16, rtol=1e-15)
                        wo = wo_from_sum(wi, qq * b)
                        break
            if wo is not None:
                qs.append(q(wi, wo, lam, x))
    return qs


def near_mirror_queries(rng, n, spread):
    """Up to n queries with |(wi + wo)_xy| <= spread*sqrt(2) (wi within 40 deg of the normal,
    lambda cycling 380/520/780 nm, x in [-5, 5]^2 um); draws in a fixed order per candidate."""
    out = []
    for k in range(n):
        wi = sph(rng.uniform(0, 40) * DEG, rng.uniform(0, 2 * math.pi))
        lam = (380.0, 520.0, 780.0)[k % 3]
        wo = wo_from_sum(wi, rng.uniform(-1, 1, 2) * spread)
        if wo is not None:
            out.append(q(wi, wo, lam, [float(v) for v in rng.uniform(-5, 5, 2)]))
    return out


def cancellation(scratches, qq, sigma=10.0):
    """|B - S| / |B| of a werner query (depth exact) in float64 (numpy/scipy closed forms;
    agrees with mpmath to ~15 digits): fast enough to rank thousands of candidates, used only
    to select queries, never as a golden value."""
    wi, wo = (np.array(rc._direction(qq[k]), dtype=float) for k in ("wi", "wo"))
    B, d = base_minus_scratches(scratches, wi, wo, qq["lambda_nm"], qq["x"], sigma)
    return abs(d) / B


def base_minus_scratches(scratches, wi, wo, lambda_nm, x, sigma=10.0):
    """(B, B - S) in float64 for unit wi, wo (numpy arrays): the selection helper above."""
    from scipy.special import erf, erfc
    lam = lambda_nm / 1000.0
    gamma = wi[2] + wo[2]
    xi = (wi[:2] + wo[:2]) / lam
    x0 = np.array(x, dtype=float)
    S = 0j
    for s in scratches:
        p0, p1 = np.array(s["p0"], dtype=float), np.array(s["p1"], dtype=float)
        L = float(np.hypot(*(p1 - p0)))
        t = (p1 - p0) / L
        b = np.array([-t[1], t[0]])
        c = 0.5 * (p0 + p1) - x0
        s_t, s_b, xi1, xi2 = c @ t, c @ b, xi @ t, xi @ b
        W, D = s["width"], s["depth"]
        m = W * np.sinc(W * xi2)
        if s.get("profile", "rect") == "triangle":
            a = 2 * math.pi * gamma * D / lam
            tm, tp = a - math.pi * W * xi2, a + math.pi * W * xi2
            p = (np.exp(1j * a) * W / 2 * (np.exp(-0.5j * tm) * np.sinc(tm / (2 * math.pi))
                                            + np.exp(-0.5j * tp) * np.sinc(tp / (2 * math.pi))))
        else:
            p = np.exp(2j * math.pi * gamma * D / lam) * m
        A = 2 * math.pi * sigma ** 2 * xi1
        r2 = math.sqrt(2) * sigma
        wb, wa = (s_t + L / 2 + 1j * A) / r2, (s_t - L / 2 + 1j * A) / r2
        if wa.real > 0 and wb.real > 0:
            diff = erfc(wa) - erfc(wb)
        elif wa.real < 0 and wb.real < 0:
            diff = erfc(-wb) - erfc(-wa)
        else:
            diff = erf(wb) - erf(wa)
        eta = (math.sqrt(math.pi / 2) * sigma * diff
               * np.exp(-s_b ** 2 / (2 * sigma ** 2) - 2 * math.pi ** 2 * sigma ** 2 * xi1 ** 2
                        - 2j * math.pi * s_b * xi2))
        S += (m - p) * eta
    B = 2 * math.pi * sigma ** 2 * math.exp(-2 * math.pi ** 2 * sigma ** 2 * (xi @ xi))
    return B, B - S


def cancellation_sweep(scratches, starts, depths, sigma=10.0):
    """Queries at prescribed cancellation depths |B - S|/|B|: for each start query, the zero
    of B - S nearest to its (wi + wo)_xy (Nelder-Mead on |B - S|/B over the 2-D offset, wi,
    lambda and x fixed), then points along a fixed direction from that zero where the depth
    is each of `depths` (bisection; |B - S| grows linearly away from a simple zero). float64
    selection only: the golden values and the depths stored with them come from mpmath."""
    from scipy.optimize import minimize

    def depth(wi, sxy, lam, x):
        wo = wo_from_sum(list(wi), sxy)
        B, d = base_minus_scratches(scratches, np.array(wi), np.array(wo), lam, x, sigma)
        return abs(d) / B

    out = []
    for qq in starts:
        wi, lam, x = qq["wi"], qq["lambda_nm"], qq["x"]
        s0 = [wi[0] + qq["wo"][0], wi[1] + qq["wo"][1]]
        z = minimize(lambda v: depth(wi, v, lam, x), s0, method="Nelder-Mead",
                     options={"xatol": 1e-12, "fatol": 1e-14, "maxiter": 4000}).x
        e = np.array([math.cos(1.0), math.sin(1.0)])
        for d in depths:
            lo, hi = 0.0, 1e-3
            while depth(wi, z + hi * e, lam, x) < d:
                hi *= 2
            for _ in range(60):
                mid = 0.5 * (lo + hi)
                lo, hi = (mid, hi) if depth(wi, z + mid * e, lam, x) < d else (lo, mid)
            sxy = z + hi * e
            out.append(q(wi, wo_from_sum(list(wi), sxy), lam, x))
    return out


def random_scratches(rng, n, radius, profiles=("rect", "triangle")):
    out = []
    for i in range(n):
        r = radius * math.sqrt(rng.uniform())
        a = rng.uniform(0, 2 * math.pi)
        c = np.array([r * math.cos(a), r * math.sin(a)])
        ang = rng.uniform(0, math.pi)
        L = rng.uniform(20, 400)
        t = np.array([math.cos(ang), math.sin(ang)])
        p0 = c - L / 2 * t
        p1 = c + L / 2 * t
        out.append({"p0": [round(float(v), 6) for v in p0],
                    "p1": [round(float(v), 6) for v in p1],
                    "width": round(float(rng.uniform(0.5, 4.0)), 4),
                    "depth": round(float(rng.uniform(0.05, 1.0)), 4),
                    "profile": profiles[i % len(profiles)]})
    return out


# ---------------------------------------------------------------------------

def all_tables():
    """name -> (description, spec).  Deterministic."""
    T = {}
    rng = np.random.default_rng(20170917)

    mq = mirror_queries(rng)
    T["mirror_flat_werner"] = (
        "Flat mirror, no scratches, model werner, F = 0.9: f = F/(pi s^2 l^2) B^2 with "
        "B = 2 pi s^2 exp(-2 pi^2 s^2 |xi|^2). Near-mirror, grazing (z = 0.02), far-off-mirror "
        "(astronomically small, 0 in float64), unnormalised and below-horizon (-> 0) queries.",
        {"model": "werner", "material": {"F": 0.9}, "scratches": [], "queries": mq})
    T["mirror_flat_velinov_gaussian"] = (
        "Flat mirror for velinov with base gaussian (rho_c = 0): equals the werner mirror "
        "table with F = 1 (material omitted), sigma = 25 um.",
        {"model": "velinov", "sigma_um": 25, "scratches": [],
         "options": {"base": "gaussian"}, "queries": mirror_queries(rng)[::2]})

    # --- one centred rect scratch
    s1 = {"p0": [-300.0, 0.0], "p1": [300.0, 0.0], "width": 2.0, "depth": 0.25}
    qs = []
    qs += bitangent_queries(rng, [s1], [[0, 0], [0, 5], [0, -12], [3, 25]],
                            [380.0, 520.0, 780.0], 40, qrange=0.9,
                            xi1s=(0.0, 0.0, 0.01, 0.03, 0.1))
    qs += sinc_zero_queries(s1, [380.0, 520.0, 780.0], [0, 0])
    gi = [0.0, -math.sqrt(1 - 0.02 ** 2), 0.02]  # grazing incidence across the scratch
    for qq in (0.0, 0.005, 0.02, 0.05):
        wo = wo_from_sum(gi, [0.0, -qq])
        qs.append(q(gi, wo, 520.0, [0, 0]))
    qs += mirror_queries(rng)[:20]
    T["rect_centered_werner"] = (
        "One rect scratch (W 2, D 0.25) along x through the origin, werner, F = 0.95, "
        "depth small_angle. Queries along the bitangent (xi1 = 0) and slightly off it "
        "(xi1 = 0.01 .. 0.1), at mask sinc zeros xi2 = k/W, grazing, shading points across "
        "the scratch.",
        {"model": "werner", "material": {"F": 0.95}, "sigma_um": 10,
         "scratches": [s1], "queries": qs})

    # --- triangle, small angle and exact
    s2 = {"p0": [-40.0, -69.282032], "p1": [40.0, 69.282032], "width": 3.0, "depth": 0.4,
          "profile": "triangle"}
    xs2 = [[0, 0], [4, -2], [-6, 3]]
    qs = bitangent_queries(rng, [s2], xs2, [380.0, 520.0, 780.0], 50, qrange=0.9,
                           xi1s=(0.0, 0.0, 0.02))
    qs += sinc_zero_queries(s2, [520.0], [0, 0])
    qs += triangle_pole_queries(s2, [380.0, 520.0, 780.0], [1, 1], "small_angle")
    T["triangle_werner_small_angle"] = (
        "One triangle scratch (W 3, D 0.4) at 60 deg, werner, material omitted (F = 1), "
        "depth small_angle (gamma -> 2). Includes xi2 = +-4D/(W lambda), the removable poles "
        "of the triangle closed form.",
        {"model": "werner", "scratches": [s2], "queries": qs})
    qs = bitangent_queries(rng, [s2], xs2, [380.0, 520.0, 780.0], 50, qrange=0.9,
                           xi1s=(0.0, 0.0, 0.02))
    qs += triangle_pole_queries(s2, [380.0, 520.0, 780.0], [1, 1], "exact")
    T["triangle_werner_exact"] = (
        "Same triangle scratch, werner, depth exact (gamma = wi.z + wo.z). Includes the "
        "poles xi2 = +-2 D gamma/(W lambda) located by root finding.",
        {"model": "werner", "scratches": [s2], "options": {"depth_term": "exact"},
         "queries": qs})

    # --- coherent ensemble, all model variants
    ens = random_scratches(rng, 4, 30.0)
    xs = [[float(v) for v in rng.uniform(-8, 8, 2)] for _ in range(5)]
    eq = bitangent_queries(rng, ens, xs, [380.0, 450.0, 520.0, 650.0, 780.0], 12,
                           qrange=0.8, xi1s=(0.0, 0.0, 0.005, 0.02))
    eq += [dict(m, x=xs[i % len(xs)]) for i, m in enumerate(mirror_queries(rng)[:24:2])]
    variants = [
        ("ensemble_werner_exact", "werner", {"depth_term": "exact"}),
        ("ensemble_werner_small_angle", "werner", {}),
        ("ensemble_werner_blended", "werner_blended", {"depth_term": "exact"}),
        ("ensemble_velinov_finite", "velinov", {}),
        ("ensemble_velinov_infinite", "velinov", {"eta": "infinite"}),
        ("ensemble_velinov_finite_gaussian_exact", "velinov",
         {"base": "gaussian", "depth_term": "exact"}),
        ("ensemble_velinov_infinite_gaussian", "velinov", {"eta": "infinite", "base": "gaussian"}),
    ]
    for name, model, opts in variants:
        spec = {"model": model, "material": {"F": 0.8}, "sigma_um": 10, "scratches": ens,
                "queries": eq}
        if opts:
            spec["options"] = opts
        T[name] = ("Four scratches (rect/triangle) at random angles with centres inside 3 sigma "
                   "(coherent interference), model %s, options %s. Same scratches and queries "
                   "in every ensemble_* table. rho_c (base gaussian) always uses the finite "
                   "segment integral." % (model, opts or "default"), spec)

    # --- Fresnel with complex IOR, three angle choices
    s3 = {"p0": [-200.0, 7.0], "p1": [200.0, -3.0], "width": 1.5, "depth": 0.3}
    xs3 = [[0, 0], [2, 10]]
    iq = bitangent_queries(rng, [s3], xs3, [380.0, 520.0, 780.0], 30, qrange=0.9,
                           th_range=(0, 85))
    gi = [math.sqrt(1 - 0.02 ** 2) * 0.6, math.sqrt(1 - 0.02 ** 2) * 0.8, 0.02]
    for qq in (0.0, 0.01, 0.05):
        iq.append(q(gi, wo_from_sum(gi, [qq * 0.6, qq * 0.8]), 520.0, [0, 0]))
    iq += mirror_queries(rng)[:15]
    for ang in ("theta_d", "theta_i", "normal"):
        T["ior_silver_" + ang] = (
            "One rect scratch, werner, material ior (0.2, 3.0) with fresnel_angle %s "
            "(unpolarised H&P Eqs. 11-13 at cos = %s)." % (
                ang, {"theta_d": "wi.normalize(wi+wo)", "theta_i": "wi.z", "normal": "1"}[ang]),
            {"model": "werner", "material": {"ior": [0.2, 3.0], "fresnel_angle": ang},
             "scratches": [s3], "options": {"depth_term": "exact"}, "queries": iq})

    # --- per-query material override
    oq = bitangent_queries(rng, [s3], xs3, [450.0, 620.0], 30, qrange=0.8, th_range=(0, 80))
    mats = [None, {"F": 1.0}, {"ior": [1.5, 0.0], "fresnel_angle": "theta_i"},
            {"ior": [1.1, 6.9]}, {"ior": [0.27, 3.41], "fresnel_angle": "normal"},
            {"ior": [1.0, 0.0]}]
    for i, m in enumerate(oq):
        if mats[i % len(mats)] is not None:
            m["material"] = mats[i % len(mats)]
    T["material_override"] = (
        "Spec-level material {F: 0.5}; queries override it with F, dielectric/metal ior and "
        "every fresnel_angle (ior without fresnel_angle -> theta_d; ior (1,0) -> F = 0).",
        {"model": "velinov", "material": {"F": 0.5}, "scratches": [s3],
         "options": {"base": "gaussian"}, "queries": oq})

    # --- off-centre scratches: discriminates the depth-phase sign
    s4 = [{"p0": [-250.0, 4.0], "p1": [250.0, 4.0], "width": 1.0, "depth": 0.15},
          {"p0": [-250.0, -7.0], "p1": [250.0, -7.0], "width": 2.5, "depth": 0.08,
           "profile": "triangle"}]
    sq = bitangent_queries(rng, s4[:1], [[0, 0], [0, 2], [5, -3]], [380.0, 520.0, 780.0], 60,
                           qrange=0.15, th_range=(0, 60))
    T["offcenter_depth_sign"] = (
        "Two parallel off-centre scratches (s_b = 4 and -7 um, shallow), werner, depth exact, "
        "queries near the mirror in the bitangent plane where B and S interfere. The depth "
        "phase sign matters here: evaluating T = exp(+2 pi i gamma h/lambda) instead changes "
        "these values (see checks.json: offcenter_sign_flip_max_rel).",
        {"model": "werner", "material": {"F": 0.9}, "scratches": s4,
         "options": {"depth_term": "exact"}, "queries": sq})

    # --- short segments, large xi1: end effects only
    s5 = [{"p0": [-1.0, 0.5], "p1": [1.0, 0.5], "width": 0.8, "depth": 0.2},
          {"p0": [3.0, -4.0], "p1": [8.0, 2.0], "width": 1.2, "depth": 0.5, "profile": "triangle"}]
    fq = []
    for lam in (380.0, 520.0, 780.0):
        for xi1 in (0.0, 0.05, 0.2, 0.5, 1.0, 2.0):
            for k in range(3):
                t, b = seg_tb(s5[k % 2]["p0"], s5[k % 2]["p1"])
                wi = sph(rng.uniform(20, 70) * DEG, rng.uniform(0, 2 * math.pi))
                sxy = xi1 * lam / 1000 * t + rng.uniform(-0.3, 0.3) * b
                wo = wo_from_sum(wi, sxy)
                if wo is not None:
                    fq.append(q(wi, wo, lam, [float(v) for v in rng.uniform(-5, 5, 2)]))
    T["short_segments_far_tail"] = (
        "Two short scratches (L 2 and 7.8 um) near x0, werner_blended, large xi1 (up to 2/um): "
        "eta is dominated by the segment ends (the infinite-segment eta would be ~0).",
        {"model": "werner_blended", "scratches": s5, "queries": fq})
    T["short_segments_velinov_finite"] = (
        "Same short scratches, velinov (finite eta, base none): incoherent sum of |S_k|^2.",
        {"model": "velinov", "material": {"F": 0.7}, "scratches": s5, "queries": fq})

    # --- degenerate scratches
    s6 = [{"p0": [5.0, 5.0], "p1": [5.0, 5.0], "width": 2.0, "depth": 0.3},
          {"p0": [-100.0, 1.0], "p1": [100.0, 1.0], "width": 0.0, "depth": 0.3},
          {"p0": [-1.0, -100.0], "p1": [-1.0, 100.0], "width": 1.0, "depth": 0.0},
          {"p0": [-100.0, -100.0], "p1": [100.0, 100.0], "width": 1.0, "depth": 0.2}]
    dq = bitangent_queries(rng, s6[1:], [[0, 0], [2, -1]], [520.0], 8, qrange=0.6)
    T["degenerate_scratches"] = (
        "Zero-length (contributes nothing), zero-width (M = P = 0) and zero-depth (P = M) "
        "scratches next to a normal one, velinov with base gaussian.",
        {"model": "velinov", "scratches": s6, "options": {"base": "gaussian"}, "queries": dq})

    # --- dense coherent set, near the mirror: |B - S| cancels (own generator, so that
    # adding it leaves every table above unchanged)
    drng = np.random.default_rng(20261122)
    dense = []
    for i in range(24):
        c = drng.uniform(-10.0, 10.0, 2)
        ang = drng.uniform(0, math.pi)
        half = 10.0 * (0.05, 0.5, 3.0, 500.0)[i % 4]
        t = np.array([math.cos(ang), math.sin(ang)])
        dense.append({"p0": [round(float(v), 6) for v in c - half * t],
                      "p1": [round(float(v), 6) for v in c + half * t],
                      "width": round(float(drng.uniform(0.3, 3.3)), 4),
                      "depth": round(float(drng.uniform(0.02, 0.62)), 4),
                      "profile": ("rect", "triangle")[i % 2]})
    # Candidate queries near the mirror; keep the 18 where |B - S| cancels most (ranked
    # with the float64 closed forms: a selection, not a golden value) and 18 others.
    cands = near_mirror_queries(drng, 300, 0.004)
    ranked = sorted((cancellation(dense, c), i) for i, c in enumerate(cands))
    keep = [i for _, i in ranked[:18]]
    keep += [i for i in range(1, len(cands), 16) if i not in keep][:18]
    nq = [cands[i] for i in keep]
    T["dense_coherent_werner"] = (
        "24 scratches (0.5 to 5000 um half-lengths, rect/triangle) with centres within "
        "+-10 um, werner, depth exact, queries near the mirror: the scratches cover the "
        "coherence window several times over and |B - S| cancels (by up to ~100x in "
        "amplitude; 18 queries picked for the strongest cancellation among 300), so the f32 "
        "rounding of each term shows in the result.",
        {"model": "werner", "material": {"F": 1.0}, "sigma_um": 10, "scratches": dense,
         "options": {"depth_term": "exact"}, "queries": nq})

    # --- the same scratches, the deepest cancellation a wide search finds (own generator;
    # ranked in float64, which only selects queries and makes no golden value)
    deep = near_mirror_queries(np.random.default_rng(20261123), 6000, 0.003)
    ranked = sorted((cancellation(dense, c), i) for i, c in enumerate(deep))
    T["deep_cancellation_werner"] = (
        "The dense_coherent_werner scratches at the 12 queries, among 6000 near the mirror, "
        "where |B - S| cancels most (|B - S|/|B| down to ~1/300): the conditioning of the "
        "coherent sum at its worst, where f32 rounding of each term and of the sum is "
        "amplified most.",
        {"model": "werner", "material": {"F": 1.0}, "sigma_um": 10, "scratches": dense,
         "options": {"depth_term": "exact"}, "queries": [deep[i] for _, i in ranked[:12]]})
    return T


def sweep_tables():
    """Tables kept out of the conformance run (golden/sweeps/): each query stores the
    conditioning it was chosen for, and the test checks the error against it."""
    dd = all_tables()["deep_cancellation_werner"][1]
    depths = [1e-2, 3e-3, 1e-3, 3e-4, 1e-4]
    qs = cancellation_sweep(dd["scratches"], dd["queries"][:3], depths)
    return {"cancellation_werner": (
        "The dense_coherent_werner scratches near three zeros of B - S, at cancellation "
        "depths |B - S|/|B| of 1e-2, 3e-3, 1e-3, 3e-4 and 1e-4: how the f32 kernel's error "
        "grows as the coherent sum cancels (the amplification (|B| + sum |S_k|)/|B - S| is "
        "stored with each query).",
        dict(dd, queries=qs))}
