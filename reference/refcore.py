"""High-precision reference definitions for scratchwave (mpmath).

Every quantity here is computed from its *defining integral* by numerical
quadrature (mpmath.quad), never from the closed forms the Rust kernel uses.
The closed forms appear only in ``closedform_*`` helpers, which exist so the
self-checks can compare the two.

Units: lengths in micrometres, wavelength in micrometres (lambda_nm / 1000),
spatial frequencies in 1/um.  Conventions follow ARCHITECTURE.md (*Conventions*):

    xi      = (wi + wo)_xy / lambda                      (1/um)
    G(x)    = exp(-|x - x0|^2 / (2 sigma^2))
    FT      F{g}(xi) = integral g(x) exp(-2 pi i x.xi) dx
    T(b)    = exp(-2 pi i gamma h(b) / lambda),  grooves h < 0
"""

import mpmath as mp
from mpmath import mpf, mpc

DPS = 30  # decimal digits of the reported results (work precision is higher)
TABLE_ETA_DPS = 24  # eta inside BRDF tables (outputs are float64)

# Every eta used in a table is also evaluated with the App. A closed form
# (mpmath complex erf); the largest relative disagreement seen is kept here.
ETA_CHECK = {"max_rel": 0.0}
# Memo of (eta, M, P) inside one table job: several tables share scratches and
# queries and differ only in model/options/material.  Cleared per job.
MEMO = {}


def M(x):
    """Exact conversion of a float (or int / str) to mpf at current precision."""
    return mp.mpf(x)


# ---------------------------------------------------------------------------
# Segment geometry
# ---------------------------------------------------------------------------

class Segment:
    """Scratch segment frame: centre c, tangent t, bitangent b = n x t."""

    def __init__(self, p0, p1):
        p0 = [M(v) for v in p0]
        p1 = [M(v) for v in p1]
        dx, dy = p1[0] - p0[0], p1[1] - p0[1]
        self.L = mp.sqrt(dx * dx + dy * dy)
        self.c = [(p0[0] + p1[0]) / 2, (p0[1] + p1[1]) / 2]
        if self.L == 0:
            self.t = [mpf(1), mpf(0)]
        else:
            self.t = [dx / self.L, dy / self.L]
        self.b = [-self.t[1], self.t[0]]

    def frame(self, x0, xi):
        """Return (s_t, s_b, xi1, xi2) for shading point x0 and frequency xi."""
        r0 = [self.c[0] - M(x0[0]), self.c[1] - M(x0[1])]
        s_t = r0[0] * self.t[0] + r0[1] * self.t[1]
        s_b = r0[0] * self.b[0] + r0[1] * self.b[1]
        xi = [M(xi[0]), M(xi[1])]
        xi1 = xi[0] * self.t[0] + xi[1] * self.t[1]
        xi2 = xi[0] * self.b[0] + xi[1] * self.b[1]
        return s_t, s_b, xi1, xi2


# ---------------------------------------------------------------------------
# Spatial phase eta (Werner Eq. 12 / App. A) by contour quadrature
# ---------------------------------------------------------------------------

_GL_CACHE = {}


def _gl_nodes(degree):
    """Gauss-Legendre nodes/weights on [-1, 1] (3*2^(degree-1) points) at current precision."""
    key = (degree, mp.mp.prec)
    if key not in _GL_CACHE:
        _GL_CACHE[key] = mp.calculus.quadrature.GaussLegendre(mp.mp).calc_nodes(degree, mp.mp.prec)
    return _GL_CACHE[key]


def glquad(f, pts, degree=4):
    """Composite Gauss-Legendre: a fixed 3*2^(degree-1)-point rule on every piece.

    Pieces are chosen by the callers so that the integrand's exponent changes
    by |c|h <~ 9 on each (<= 6 nepers and <= one oscillation), where the 24-point
    rule errs by ~ (|c|h/2)^48/48! ~ 1e-31 of the piece and the 48-point rule
    (used when an estimate is requested, and then returned) by ~1e-89.
    The ``degree+1`` rule is used as the error estimate where one is needed.
    Unlike mp.quad's adaptive test (absolute tolerance), this is scale-free.
    """
    nodes = _gl_nodes(degree)
    tot = mpc(0)
    for a, b in zip(pts[:-1], pts[1:]):
        mid = (a + b) / 2
        hw = (b - a) / 2
        acc = mpc(0)
        for x, w in nodes:
            acc += w * f(mid + hw * x)
        tot += acc * hw
    return tot


def glquad_err(f, pts, degree=4):
    """(value, error estimate) from the degree and degree+1 composite rules."""
    lo = glquad(f, pts, degree)
    hi = glquad(f, pts, degree + 1)
    return hi, abs(hi - lo)


def quad_exp_quadratic(E, s0, d, pts, degree=4, estimate=False):
    """int exp(E(s)) ds along s = s0 + d*u, u over the pieces pts.

    E is the *literal* exponent of an integrand (a function of complex s).  On
    a straight path it is a quadratic polynomial in u for every integrand used
    here; its coefficients are taken from E at u = -1, 0, 1 and the fit is
    verified against E at two further points (so a non-quadratic E is caught).
    Evaluating exp(P(u)) * (cos Q(u) + i sin Q(u)) with real P, Q is what makes
    the quadrature fast enough in pure-Python mpmath.
    """
    ua, ub = pts[0], pts[-1]
    um = (ua + ub) / 2
    h = (ub - ua) / 2
    e0 = E(s0 + d * um)
    ea = E(s0 + d * ua)
    eb = E(s0 + d * ub)
    c1 = (eb - ea) / (2 * h)
    c2 = (eb + ea - 2 * e0) / (2 * h * h)
    for v in (-h / 2, h / 3):
        ref = E(s0 + d * (um + v))
        fit = e0 + v * (c1 + v * c2)
        tol = mpf(10) ** (-(mp.mp.dps - 8)) * (1 + abs(e0) + abs(h * c1) + abs(h * h * c2))
        if abs(fit - ref) > tol:
            raise AssertionError("exponent is not quadratic along the path")
    p0, p1, p2 = mp.re(e0), mp.re(c1), mp.re(c2)
    q0, q1, q2 = mp.im(e0), mp.im(c1), mp.im(c2)

    def run(deg):
        nodes = _gl_nodes(deg)
        re_parts = []
        im_parts = []
        for a, b in zip(pts[:-1], pts[1:]):
            mid = (a + b) / 2
            hw = (b - a) / 2
            for x, w in nodes:
                u = mid + hw * x - um
                P = p0 + u * (p1 + u * p2)
                Q = q0 + u * (q1 + u * q2)
                c, sn = mp.cos_sin(Q)
                m = w * hw * mp.exp(P)
                re_parts.append(m * c)
                im_parts.append(m * sn)
        return mpc(mp.fsum(re_parts), mp.fsum(im_parts)) * d

    if estimate:
        lo = run(degree)
        hi = run(degree + 1)
        return hi, abs(hi - lo)
    return run(degree), mpf(0)


def _pieces(a, b, h):
    """Breakpoints from a to b (a < b) with spacing <= h."""
    n = max(1, int(mp.ceil((b - a) / h)))
    return [a + (b - a) * k / n for k in range(n + 1)]


def eta_quad(sigma, p0, p1, x0, xi, dps=DPS, return_info=False, estimate=False):
    """eta = int_{-L/2}^{L/2} ds G(c + s t) exp(-2 pi i xi.(c + s t - x0)).

    The integrand is entire in s, so by Cauchy's theorem the real segment
    [-L/2, L/2] may be replaced by the three legs
        -L/2 -> -L/2 + iY -> L/2 + iY -> L/2,
    with Y = -2 pi sigma^2 xi1 (the height of the saddle point).  On the
    horizontal leg the integrand no longer oscillates; on the vertical legs it
    decays exponentially away from the real axis.  This turns a cancellation-
    dominated oscillatory integral (|eta| can be ~exp(-50000)) into integrals
    that are computed to full relative precision.  The integrand is the
    literal one above, evaluated at complex s; only the choice of contour and
    of the breakpoints uses the frame quantities (s_t, s_b, xi1).  Parts of a
    leg where the integrand is below 10^-(dps+12) of that leg's peak are not
    integrated; a vertical leg whose bound |f|max * length is below
    10^-(dps+8) |horizontal leg| is skipped.

    Returns mpc (and an info dict with an error estimate if return_info).
    """
    extra = 15
    with mp.workdps(dps + extra):
        sigma = M(sigma)
        seg = Segment(p0, p1)
        if seg.L == 0:
            return (mpc(0), {"err": mpf(0), "legs": []}) if return_info else mpc(0)
        x0m = [M(x0[0]), M(x0[1])]
        xim = [M(xi[0]), M(xi[1])]
        s_t, s_b, xi1, xi2 = seg.frame(x0, xi)
        L = seg.L
        two_s2 = 2 * sigma * sigma
        tpi = 2 * mp.pi
        r0 = [seg.c[0] - x0m[0], seg.c[1] - x0m[1]]
        tx, ty = seg.t

        def E(s):  # literal exponent of G(c + s t) exp(-2 pi i xi.(c + s t - x0))
            X = r0[0] + s * tx
            Y = r0[1] + s * ty
            return (-(X * X + Y * Y) / two_s2
                    - 1j * tpi * (xim[0] * X + xim[1] * Y))

        K = (dps + 12) * mp.log(10)  # neper range kept inside each leg
        Yc = -tpi * sigma * sigma * xi1
        legs = []
        err = mpf(0)

        # --- horizontal leg  s = x + i Yc,  x in [-L/2, L/2]
        # log|f| = const - (x + s_t)^2 / (2 sigma^2): Gaussian in x, peak at -s_t
        xp = min(max(-s_t, -L / 2), L / 2)
        half = mp.sqrt((xp + s_t) ** 2 + two_s2 * K)
        lo = max(-L / 2, -s_t - half)
        hi = min(L / 2, -s_t + half)
        pts = _pieces(lo, hi, 2 * sigma)
        if lo < xp < hi:
            pts = sorted(set(pts + [xp]))
        H, e = quad_exp_quadratic(E, mpc(0, Yc), mpf(1), pts, estimate=estimate)
        legs.append(("H", H))
        err += e

        # --- vertical legs  s = x_end + i y,  y from 0 to Yc (and back)
        if Yc != 0:
            sg = 1 if Yc > 0 else -1
            Ymag = abs(Yc)
            a1 = tpi * abs(xi1)
            log_H = mp.log(abs(H)) + s_b * s_b / two_s2
            for x_end, orient in ((-L / 2, 1), (L / 2, -1)):
                xu = x_end + s_t
                # log|f| relative to the common factor exp(-s_b^2/2s^2):
                # -xu^2/2s^2 - a1 tau + tau^2/2s^2,  tau = |y| in [0, |Yc|]
                ub = -xu * xu / two_s2 + mp.log(Ymag)
                if ub < log_H - (dps + 8) * mp.log(10):
                    continue  # provably negligible against the horizontal leg
                drop_full = a1 * Ymag - Ymag * Ymag / two_s2  # = 2 pi^2 s^2 xi1^2
                if drop_full <= K:
                    tend = Ymag
                else:
                    tend = Ymag - mp.sqrt(Ymag * Ymag - two_s2 * K)
                # pieces: <= one oscillation and <= 6 nepers of decay
                h = min(tend, 6 / a1)
                if xu != 0:
                    h = min(h, 2 * mp.pi * sigma * sigma / abs(xu))
                if tend / h > 20000:
                    raise RuntimeError("vertical leg needs %d pieces" % int(tend / h))
                pts = _pieces(mpf(0), tend, h)
                V, e = quad_exp_quadratic(E, mpc(x_end, 0), mpc(0, sg), pts,
                                          estimate=estimate)
                V *= orient
                legs.append(("V%+d" % orient, V))
                err += e

        total = mp.fsum([v for _, v in legs])
        mx = max(abs(v) for _, v in legs)
        err += mx * mpf(10) ** (-(dps + extra - 3))
        if return_info:
            return +total, {"err": err, "legs": legs}
        return +total


def eta_inf(sigma, p0, p1, x0, xi):
    """Velinov Eq. 8 (infinite segment), in this library's units."""
    sigma = M(sigma)
    seg = Segment(p0, p1)
    _, s_b, xi1, xi2 = seg.frame(x0, xi)
    return (mp.sqrt(2 * mp.pi) * sigma
            * mp.exp(-s_b ** 2 / (2 * sigma ** 2)
                     - 2 * mp.pi ** 2 * sigma ** 2 * xi1 ** 2
                     - 2j * mp.pi * s_b * xi2))


def eta_realaxis(sigma, p0, p1, x0, xi, target_rel=mpf("1e-25"), est=None,
                 max_osc=4000):
    """Check only: the same integral taken straight along the real axis.

    Working precision is raised by the cancellation ratio; returns None when
    that is impractical (too many oscillations or too much cancellation).
    """
    sigma = M(sigma)
    seg = Segment(p0, p1)
    if seg.L == 0:
        return mpc(0)
    s_t, s_b, xi1, xi2 = seg.frame(x0, xi)
    L = seg.L
    if est is None:
        est = eta_quad(sigma, p0, p1, x0, xi)
    if est == 0:
        return None
    # integrand magnitude peak (relative to common factor)
    xp = min(max(-s_t, -L / 2), L / 2)
    gmax = mp.exp(-(xp + s_t) ** 2 / (2 * sigma ** 2) - s_b ** 2 / (2 * sigma ** 2))
    cancel = mp.log10(gmax * sigma / abs(est))
    if cancel > 80:
        return None
    need = -mp.log10(target_rel) + max(0, cancel) + 10
    with mp.workdps(int(need) + 10):
        K = (need + 5) * mp.log(10)
        half = mp.sqrt((xp + s_t) ** 2 + 2 * sigma ** 2 * K)
        lo = max(-L / 2, -s_t - half)
        hi = min(L / 2, -s_t + half)
        if lo >= hi:
            return None
        period = 1 / abs(xi1) if xi1 != 0 else hi - lo
        if (hi - lo) / period > max_osc:
            return None
        h = min(period / 4, sigma / 2)
        pts = _pieces(lo, hi, h)
        r0 = [seg.c[0] - M(x0[0]), seg.c[1] - M(x0[1])]
        tx, ty = seg.t
        xim = [M(xi[0]), M(xi[1])]

        def f(s):
            X = r0[0] + s * tx
            Y = r0[1] + s * ty
            return mp.exp(-(X * X + Y * Y) / (2 * sigma * sigma)
                          - 2j * mp.pi * (xim[0] * X + xim[1] * Y))

        sc = gmax
        v = glquad(lambda s: f(s) / sc, pts, degree=5) * sc
    return v


def closedform_eta(sigma, p0, p1, x0, xi):
    """Check only: App. A closed form with complex erf (mpmath, high precision)."""
    with mp.workdps(mp.mp.dps + 25):
        sigma = M(sigma)
        seg = Segment(p0, p1)
        if seg.L == 0:
            return mpc(0)
        s_t, s_b, xi1, xi2 = seg.frame(x0, xi)
        L = seg.L
        A = 2 * mp.pi * sigma ** 2 * xi1
        r2 = mp.sqrt(2) * sigma
        wb = (s_t + L / 2 + 1j * A) / r2
        wa = (s_t - L / 2 + 1j * A) / r2
        # erf(wb) - erf(wa) without cancellation when both ends lie on one side
        if mp.re(wa) > 0 and mp.re(wb) > 0:
            diff = mp.erfc(wa) - mp.erfc(wb)
        elif mp.re(wa) < 0 and mp.re(wb) < 0:
            diff = mp.erfc(-wb) - mp.erfc(-wa)
        else:
            diff = mp.erf(wb) - mp.erf(wa)
        v = (mp.sqrt(mp.pi / 2) * sigma * diff
             * mp.exp(-s_b ** 2 / (2 * sigma ** 2)
                      - 2 * mp.pi ** 2 * sigma ** 2 * xi1 ** 2
                      - 2j * mp.pi * s_b * xi2))
    return +v


# ---------------------------------------------------------------------------
# Profile transforms (Werner Eqs. 14, 26-31) by quadrature
# ---------------------------------------------------------------------------

def height(profile, W, D, b):
    if profile == "rect":
        return -D
    if profile == "triangle":
        return -D * (1 - abs(b) / (W / 2))
    raise ValueError(profile)


def profile_quad(profile, W, D, gamma, lam, xi2, dps=DPS):
    """(M, P): mask transform and scratch-profile transform.

    M(xi2) = int_{-W/2}^{W/2} exp(-2 pi i b xi2) db
    P(xi2) = int_{-W/2}^{W/2} T(b) exp(-2 pi i b xi2) db,
    T(b)   = exp(-2 pi i gamma h(b) / lambda).
    Both halves b<0, b>0 are integrated separately (the triangle has a kink at
    0), each split into pieces of at most one oscillation, Gauss-Legendre.
    """
    with mp.workdps(dps + 10):
        W, D, gamma, lam, xi2 = (M(W), M(D), M(gamma), M(lam), M(xi2))
        if W == 0:
            return mpc(0), mpc(0)
        tpi = 2 * mp.pi

        def Em(b):  # literal exponent of the mask integrand
            return -1j * tpi * b * xi2

        def Ep(b):  # literal exponent of T(b) exp(-2 pi i b xi2)
            return -1j * tpi * (gamma * height(profile, W, D, b) / lam + b * xi2)

        # phase slope per half (rad/um): mask 2 pi xi2; triangle adds 2 gamma D/(W/2 lam)
        slope_tri = tpi * gamma * D / (W / 2) / lam
        res = []
        for E, extra in ((Em, 0), (Ep, slope_tri if profile == "triangle" else 0)):
            tot = mpc(0)
            for a, b, sgn in ((-W / 2, mpf(0), -1), (mpf(0), W / 2, 1)):
                rate = max(abs(tpi * xi2 + sgn * extra), abs(tpi * xi2), mpf(1e-30))
                h = min(W / 2, mp.pi / rate)
                # path s = mid + u, u in [a-mid, b-mid]: keeps the fit inside one half
                mid = (a + b) / 2
                v, _ = quad_exp_quadratic(E, mid, mpf(1),
                                          [p - mid for p in _pieces(a, b, h)])
                tot += v
            res.append(+tot)
        return res[0], res[1]


def closedform_rect(W, D, gamma, lam, xi2):
    """Check only: W sinc(pi W xi2), and Phi_D W sinc(pi W xi2), Phi_D = e^{+2 pi i gamma D/lam}."""
    W, D, gamma, lam, xi2 = (M(W), M(D), M(gamma), M(lam), M(xi2))
    x = mp.pi * W * xi2
    s = W * (mp.sin(x) / x if x != 0 else 1)
    return s, mp.exp(2j * mp.pi * gamma * D / lam) * s


def closedform_triangle_corrected(W, D, gamma, lam, xi2):
    """Check only: the corrected Werner Eq. 29 (derived in README)."""
    W, D, gamma, lam, xi2 = (M(W), M(D), M(gamma), M(lam), M(xi2))
    q = 2 * gamma * D / (W * lam)
    phi = mp.exp(2j * mp.pi * gamma * D / lam)
    Bc = 1j * phi / (2 * mp.pi * (xi2 - q))
    Cc = 1j * phi / (2 * mp.pi * (xi2 + q))
    return (Bc * (1 - mp.exp(1j * mp.pi * (W * xi2 - 2 * D * gamma / lam)))
            + Cc * (mp.exp(-1j * mp.pi * (W * xi2 + 2 * D * gamma / lam)) - 1))


def closedform_triangle_sinc(W, D, gamma, lam, xi2):
    """Check only: pole-free form of the triangle transform (README).

    P = Phi_D (W/2) [e^{-i th-/2} sinc(th-/2) + e^{-i th+/2} sinc(th+/2)],
    th+- = pi (2 gamma D / lambda +- W xi2),  Phi_D = e^{+2 pi i gamma D / lambda}."""
    W, D, gamma, lam, xi2 = (M(W), M(D), M(gamma), M(lam), M(xi2))

    def sinc(x):
        return mp.sin(x) / x if x != 0 else mpf(1)
    a = 2 * mp.pi * gamma * D / lam
    tm = a - mp.pi * W * xi2
    tp = a + mp.pi * W * xi2
    return (mp.exp(1j * a) * W / 2
            * (mp.exp(-1j * tm / 2) * sinc(tm / 2) + mp.exp(-1j * tp / 2) * sinc(tp / 2)))


def closedform_triangle_printed(W, D, gamma, lam, xi2, phi_sign=-1, fix_W=False):
    """Check only: Werner Eqs. 29-31 as printed (Phi_D of Eq. 28 when phi_sign = -1).

    fix_W=True applies the two typo fixes (W xi2 in the first exponent of Eq. 29,
    W lambda instead of W^2 in Eq. 30) but keeps the requested Phi_D sign."""
    W, D, gamma, lam, xi2 = (M(W), M(D), M(gamma), M(lam), M(xi2))
    phi = mp.exp(phi_sign * 2j * mp.pi * gamma * D / lam)
    qB = 2 * D * gamma / (W * lam) if fix_W else 2 * D * gamma / W ** 2
    e1 = W * xi2 if fix_W else xi2
    Bc = 1j * phi / (2 * mp.pi * (xi2 - qB))
    Cc = 1j * phi / (2 * mp.pi * (xi2 + 2 * D * gamma / (W * lam)))
    return (Bc * (1 - mp.exp(1j * mp.pi * (e1 - 2 * D * gamma / lam)))
            + Cc * (mp.exp(-1j * mp.pi * (W * xi2 + 2 * D * gamma / lam)) - 1))


# ---------------------------------------------------------------------------
# Base response, Fresnel, rho_c
# ---------------------------------------------------------------------------

def base_response(sigma, xi):
    """Werner Eq. 16 (checked once against 2-D quadrature in checks.py)."""
    sigma = M(sigma)
    x2 = M(xi[0]) ** 2 + M(xi[1]) ** 2
    return 2 * mp.pi * sigma ** 2 * mp.exp(-2 * mp.pi ** 2 * sigma ** 2 * x2)


def fresnel(cos_t, n, k):
    """Unpolarised Fresnel reflectance, H&P Eqs. 11-13, complex eta = n + ik."""
    with mp.workdps(mp.mp.dps + 10):
        c = M(cos_t)
        eta = mpc(M(n), M(k))
        e2 = eta * eta
        r = mp.sqrt(e2 - (1 - c * c))  # principal branch
        Fs = abs((c - r) / (c + r)) ** 2
        Fp = abs((e2 * c - r) / (e2 * c + r)) ** 2
        return +((Fs + Fp) / 2)


def rho_c(sigma, scratches, x0):
    """Corrected Velinov Eq. 17: (1/(2 pi s^2)) sum_k W_k int G(c_k + s t_k) ds."""
    sigma = M(sigma)
    tot = mpf(0)
    for s in scratches:
        e = eta_quad(sigma, s["p0"], s["p1"], x0, (0, 0), dps=TABLE_ETA_DPS)
        tot += M(s["width"]) * mp.re(e)
    return tot / (2 * mp.pi * sigma ** 2)


# ---------------------------------------------------------------------------
# Table BRDF
# ---------------------------------------------------------------------------

def _unit(v):
    v = [M(a) for a in v]
    n = mp.sqrt(v[0] ** 2 + v[1] ** 2 + v[2] ** 2)
    return [a / n for a in v]


# Mirrors scratchwave_kernel::table::UNIT_TOLERANCE: a direction whose squared length is
# within this of 1 is used as given (the tables store f32-rounded unit vectors, and the
# kernel and CLI reader apply the same rule), so reference and kernel see identical inputs.
UNIT_TOLERANCE = 4.0e-7


def _direction(v):
    v = [M(a) for a in v]
    l2 = v[0] ** 2 + v[1] ** 2 + v[2] ** 2
    return v if abs(l2 - 1) <= UNIT_TOLERANCE else _unit(v)


def material_F(mat, wi, wo):
    if mat is None:
        return mpf(1)
    if "F" in mat:
        return M(mat["F"])
    n, k = mat["ior"]
    ang = mat.get("fresnel_angle", "theta_d")
    if ang == "theta_d":
        h = _unit([wi[0] + wo[0], wi[1] + wo[1], wi[2] + wo[2]])
        c = wi[0] * h[0] + wi[1] * h[1] + wi[2] * h[2]
    elif ang == "theta_i":
        c = wi[2]
    elif ang == "normal":
        c = mpf(1)
    else:
        raise ValueError(ang)
    return fresnel(c, n, k)


def brdf(spec, q, flip_depth_sign=False, return_parts=False):
    """The table BRDF (1/sr, no cosine) for one query of a spec.

    flip_depth_sign=True evaluates the *wrong* convention T = exp(+2 pi i gamma h/lambda)
    (used only to show that a case discriminates the sign).
    """
    with mp.workdps(DPS + 10):
        wi = _direction(q["wi"])
        wo = _direction(q["wo"])
        if wi[2] <= 0 or wo[2] <= 0:
            return mpf(0)
        model = spec["model"]
        opts = spec.get("options", {}) or {}
        eta_mode = opts.get("eta", "finite")
        depth = opts.get("depth_term", "small_angle")
        base = opts.get("base", "none")
        sigma = M(spec.get("sigma_um", 10))
        lam = M(q["lambda_nm"]) / 1000
        gamma = wi[2] + wo[2]
        gT = gamma if depth == "exact" else mpf(2)
        xi = [(wi[0] + wo[0]) / lam, (wi[1] + wo[1]) / lam]
        x0 = q["x"]
        mat = q.get("material", spec.get("material"))
        F = material_F(mat, wi, wo)
        B = base_response(sigma, xi)
        Sk = []
        for s in spec.get("scratches", []):
            seg = Segment(s["p0"], s["p1"])
            if seg.L == 0:
                continue
            _, _, xi1, xi2 = seg.frame(x0, xi)
            prof = s.get("profile", "rect")
            Dd = M(s["depth"])
            if flip_depth_sign:
                Dd = -Dd  # h is linear in D, so exp(+2 pi i g h/l) == T with D -> -D
            pkey = ("P", prof, M(s["width"]), Dd, gT, lam, xi2)
            if pkey not in MEMO:
                MEMO[pkey] = profile_quad(prof, s["width"], Dd, gT, lam, xi2)
            Mk, Pk = MEMO[pkey]
            if model == "velinov" and eta_mode == "infinite":
                ek = eta_inf(sigma, s["p0"], s["p1"], x0, xi)
            else:
                ekey = ("eta", sigma, tuple(M(v) for v in s["p0"]), tuple(M(v) for v in s["p1"]),
                        tuple(M(v) for v in x0), xi[0], xi[1])
                if ekey not in MEMO:
                    ek = eta_quad(sigma, s["p0"], s["p1"], x0, xi, dps=TABLE_ETA_DPS)
                    cf = closedform_eta(sigma, s["p0"], s["p1"], x0, xi)
                    rel = float(abs(cf - ek) / abs(ek)) if ek != 0 else 0.0
                    ETA_CHECK["max_rel"] = max(ETA_CHECK["max_rel"], rel)
                    MEMO[ekey] = ek
                ek = MEMO[ekey]
            Sk.append((Mk - Pk) * ek)
        S = mp.fsum(Sk) if Sk else mpc(0)
        pref = F / (mp.pi * sigma ** 2 * lam ** 2)
        if model == "werner":
            val = pref * abs(B - S) ** 2
        elif model == "werner_blended":
            val = pref * abs(S) ** 2
        elif model == "velinov":
            val = mp.fsum([abs(v) ** 2 for v in Sk]) if Sk else mpf(0)
            if base == "gaussian":
                rc = rho_c(sigma, spec.get("scratches", []), x0)
                val += (1 - rc) * B ** 2
            val = pref * val
        else:
            raise ValueError(model)
        if return_parts:
            return +val, {"B": B, "S": S, "F": F, "Sk": Sk}
        return +val
