"""Pixel-footprint integrals (Velinov 2018 Sec. 3.2-3.3), exact by 2-D quadrature.

For one scratch segment (centre c, tangent t, bitangent b, length L, width W)
and a footprint ellipse E (centre e, a1 along angle_rad, a2), with A_P = pi a1 a2:

    eta0(x)   = int_{-L/2}^{L/2} G(c + s t; x) ds           (eta at xi = 0, real)
    rho_c(x)  = W eta0(x) / (2 pi sigma^2)                  (corrected Eq. 17)
    exact_eta_p = (1/A_P) int_E eta0(x)^2 dx
    exact_rho_p = (1/A_P) int_E rho_c(x) dx

With x = c + alpha t + beta b:  eta0 = exp(-beta^2/(2 s^2)) * I(alpha) where
I(alpha) = int_{-L/2}^{L/2} exp(-(s - alpha)^2/(2 s^2)) ds is evaluated with
erf/erfc (the brief allows erf for this 1-D Gaussian integral; erfc is used
when both limits are on one side, so there is no cancellation).

The 2-D integral is done in float64 with composite Gauss-Legendre:
 * outer variable beta = beta_c + beta_max sin(theta), theta in [-pi/2, pi/2]
   (removes the square-root behaviour of the chord length at the ellipse's
   extreme beta), panels of at most sigma/4 in beta and pi/64 in theta;
 * inner variable alpha over the chord, through a cumulative table of
   int I^p dalpha on a global grid (panels <= sigma/4, refined near the
   segment ends), plus partial panels at the chord ends.
Convergence is checked by halving every panel (and raising the node count);
the relative change is stored per case (it is ~1e-15) and asserted < 1e-10.
A few cases are re-done with nested mpmath.quad (checks.py).
"""

import math

import numpy as np
from numpy.polynomial.legendre import leggauss
from scipy.special import erf, erfc

SQRT2 = math.sqrt(2.0)


def erf_diff(p, q):
    """erf(q) - erf(p) without cancellation (vectorised)."""
    p = np.asarray(p, dtype=float)
    q = np.asarray(q, dtype=float)
    out = erf(q) - erf(p)
    pos = p >= 0
    neg = q <= 0
    out = np.where(pos, erfc(p) - erfc(q), out)
    out = np.where(neg, erfc(-q) - erfc(-p), out)
    return out


def line_integral_I(alpha, L, sigma):
    """I(alpha) = int_{-L/2}^{L/2} exp(-(s-alpha)^2/(2 sigma^2)) ds."""
    r = sigma * SQRT2
    return sigma * math.sqrt(math.pi / 2) * erf_diff((-L / 2 - alpha) / r, (L / 2 - alpha) / r)


def seg_frame(p0, p1):
    p0 = np.asarray(p0, float)
    p1 = np.asarray(p1, float)
    d = p1 - p0
    L = float(np.hypot(d[0], d[1]))
    t = d / L
    b = np.array([-t[1], t[0]])
    c = (p0 + p1) / 2
    return c, t, b, L


def ellipse_in_frame(ell, c, t, b):
    """Ellipse centre (alpha_c, beta_c) and quadratic form Q in the scratch frame."""
    e = np.asarray(ell["center"], float) - c
    ac, bc = float(e @ t), float(e @ b)
    th = ell["angle_rad"]
    u1 = np.array([math.cos(th), math.sin(th)])
    u1f = np.array([u1 @ t, u1 @ b])  # a1 axis in (alpha, beta)
    u2f = np.array([-u1f[1], u1f[0]])
    a1, a2 = ell["a1"], ell["a2"]
    Q = np.outer(u1f, u1f) / a1 ** 2 + np.outer(u2f, u2f) / a2 ** 2
    return ac, bc, Q


def _panels(lo, hi, h, extra=()):
    n = max(1, int(math.ceil((hi - lo) / h)))
    pts = set(np.linspace(lo, hi, n + 1).tolist())
    for x in extra:
        if lo < x < hi:
            pts.add(float(x))
    return np.array(sorted(pts))


def _footprint_integrals(sigma, p0, p1, ell, refine=1, nodes=20):
    c, t, b, L = seg_frame(p0, p1)
    ac, bc, Q = ellipse_in_frame(ell, c, t, b)
    a1, a2 = ell["a1"], ell["a2"]
    A_P = math.pi * a1 * a2
    # extent in beta, chord in alpha for given beta:
    # Q11 da^2 + 2 Q12 da db + Q22 db^2 = 1
    Q11, Q12, Q22 = Q[0, 0], Q[0, 1], Q[1, 1]
    det = Q11 * Q22 - Q12 ** 2
    bmax = math.sqrt(Q11 / det)
    xg, wg = leggauss(nodes)

    # --- global alpha grid with cumulative integrals of I and I^2
    amax = math.sqrt(Q22 / det)  # alpha half-extent of the ellipse
    alo, ahi = ac - amax, ac + amax
    h = sigma / 4 / refine
    ends = []
    for e in (-L / 2, L / 2):
        for k in range(-24, 25):
            ends.append(e + k * sigma / 4)
    grid = _panels(alo, ahi, h, ends)
    mids = (grid[1:] + grid[:-1]) / 2
    hw = (grid[1:] - grid[:-1]) / 2
    xs = mids[:, None] + hw[:, None] * xg[None, :]
    Iv = line_integral_I(xs, L, sigma)
    cum1 = np.concatenate([[0.0], np.cumsum((Iv * wg).sum(1) * hw)])
    cum2 = np.concatenate([[0.0], np.cumsum((Iv ** 2 * wg).sum(1) * hw)])

    def chord_int(lo, hi):
        """int_lo^hi I and I^2 for arrays of chords (lo <= hi)."""
        klo = np.searchsorted(grid, lo, side="left")   # first grid pt >= lo
        khi = np.searchsorted(grid, hi, side="right") - 1  # last grid pt <= hi
        same = klo > khi
        k1 = np.clip(klo, 0, len(grid) - 1)
        k2 = np.clip(khi, 0, len(grid) - 1)
        g1 = grid[k1]
        g2 = grid[k2]
        # full panels
        full1 = np.where(same, 0.0, cum1[k2] - cum1[k1])
        full2 = np.where(same, 0.0, cum2[k2] - cum2[k1])
        # partial pieces [lo, g1] and [g2, hi], or [lo, hi] if same panel
        a_l = lo
        b_l = np.where(same, hi, g1)
        a_r = np.where(same, hi, g2)
        b_r = hi
        out1 = full1.copy()
        out2 = full2.copy()
        for a, bb in ((a_l, b_l), (a_r, b_r)):
            m = (a + bb) / 2
            hh = (bb - a) / 2
            x = m[:, None] + hh[:, None] * xg[None, :]
            v = line_integral_I(x, L, sigma)
            out1 += (v * wg).sum(1) * hh
            out2 += (v ** 2 * wg).sum(1) * hh
        return out1, out2

    # --- outer theta panels
    hb = sigma / 4 / refine
    nb = int(math.ceil(2 * bmax / hb))
    bpts = np.linspace(-bmax, bmax, nb + 1)
    th_from_b = np.arcsin(np.clip(bpts / bmax, -1, 1))
    th_uniform = np.linspace(-math.pi / 2, math.pi / 2, 64 * refine + 1)
    extra = []
    for k in range(-40, 41):  # ridge of the line beta = 0, +- k sigma/4
        bb = -bc + k * sigma / 4
        if -bmax < bb < bmax:
            extra.append(math.asin(bb / bmax))
    th = np.unique(np.concatenate([th_from_b, th_uniform, extra]))
    tm = (th[1:] + th[:-1]) / 2
    thw = (th[1:] - th[:-1]) / 2
    T = (tm[:, None] + thw[:, None] * xg[None, :]).ravel()
    W_ = (thw[:, None] * wg[None, :]).ravel()
    dbeta = bmax * np.sin(T)
    beta = bc + dbeta
    jac = bmax * np.cos(T)
    # chord for each dbeta
    disc = np.maximum(Q11 - det * dbeta ** 2, 0.0)
    half = np.sqrt(disc) / Q11
    amid = ac - Q12 * dbeta / Q11
    i1, i2 = chord_int(amid - half, amid + half)
    g1 = np.exp(-beta ** 2 / (2 * sigma ** 2))
    J1 = float(np.sum(W_ * jac * g1 * i1))            # int_E eta0
    J2 = float(np.sum(W_ * jac * g1 ** 2 * i2))       # int_E eta0^2
    return J1 / A_P, J2 / A_P, A_P


def footprint_exact(sigma, p0, p1, width, ell):
    """(exact_eta_p, exact_rho_p, rel_change_on_refinement)."""
    m1, m2, A_P = _footprint_integrals(sigma, p0, p1, ell, refine=1, nodes=20)
    n1, n2, _ = _footprint_integrals(sigma, p0, p1, ell, refine=2, nodes=24)
    eta_p = n2
    rho_p = width * n1 / (2 * math.pi * sigma ** 2)
    ch = max(abs(m2 - n2) / abs(n2) if n2 else 0.0, abs(m1 - n1) / abs(n1) if n1 else 0.0)
    return eta_p, rho_p, ch


def l_contained(p0, p1, ell):
    """Length of the segment inside the ellipse (line-ellipse intersection)."""
    th = ell["angle_rad"]
    u1 = np.array([math.cos(th), math.sin(th)])
    u2 = np.array([-u1[1], u1[0]])
    e = np.asarray(ell["center"], float)
    P0 = np.asarray(p0, float) - e
    P1 = np.asarray(p1, float) - e
    q0 = np.array([P0 @ u1 / ell["a1"], P0 @ u2 / ell["a2"]])
    q1 = np.array([P1 @ u1 / ell["a1"], P1 @ u2 / ell["a2"]])
    d = q1 - q0
    A = d @ d
    Bq = 2 * q0 @ d
    C = q0 @ q0 - 1
    disc = Bq * Bq - 4 * A * C
    L = float(np.hypot(*(np.asarray(p1, float) - np.asarray(p0, float))))
    if A == 0 or disc <= 0:
        return 0.0
    sq = math.sqrt(disc)
    t1 = (-Bq - sq) / (2 * A)
    t2 = (-Bq + sq) / (2 * A)
    lo, hi = max(t1, 0.0), min(t2, 1.0)
    return max(hi - lo, 0.0) * L


def paper_approximations(sigma, p0, p1, width, ell):
    """Velinov Eqs. 15, 16 (pi restored), 18 (factor 2 removed), and the printed ones."""
    a1, a2 = ell["a1"], ell["a2"]
    A_P = math.pi * a1 * a2
    A_C = math.pi * sigma ** 2
    l = l_contained(p0, p1, ell)
    c, t, b, L = seg_frame(p0, p1)
    s_b = abs(float((np.asarray(ell["center"], float) - c) @ b))
    alpha = min(A_P / (2 * A_C), 1.0)
    eq15 = 2 * sigma ** 3 * math.sqrt(math.pi) * l / (a1 * a2)
    eq16 = (2 * sigma ** 2 / A_P) * (alpha * sigma * math.pi ** 1.5 * l
                                     + (1 - alpha) * math.pi * A_P * math.exp(-s_b ** 2 / sigma ** 2))
    eq16_printed = (2 * sigma ** 2 / A_P) * (alpha * sigma * math.pi ** 1.5 * l
                                             + (1 - alpha) * A_P * math.exp(-s_b ** 2 / sigma ** 2))
    eq18 = width * l / A_P
    eq18_printed = 2 * width * l / A_P
    return {"l_contained": l, "eq15": eq15, "eq16": eq16, "eq18": eq18,
            "eq16_printed": eq16_printed, "eq18_printed": eq18_printed, "s_b": s_b}
