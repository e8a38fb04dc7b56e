#!/usr/bin/env python3
"""Werner's coherent BRDF from the windowed scalar integral over the heightfield (issue #21).

Nothing here comes from the kernel or from Werner's closed forms. The value is

    f_r = F / (pi sigma^2 lambda^2) |A|^2,                       (Werner Eq. 15, no cosine)
    A   = int G(p) T(p) exp(-2 pi i xi.(p - x0)) dp              (Werner Eqs. 8-9)
        = B - S,   S = int G(p) (1 - T(p)) exp(-2 pi i xi.(p - x0)) dp,

with the conventions of ARCHITECTURE.md (*Conventions*) and refcore.py:
    G(p)  = exp(-|p - x0|^2 / (2 sigma^2))                       coherence window (Werner Eq. 7)
    T(p)  = exp(-2 pi i gamma h(p) / lambda),  h = -depth < 0 in a groove, 0 elsewhere
    gamma = wi.z + wo.z (the kernel's `depth_term: exact`, DepthTerm::Exact; Werner Eq. 20
            with the corrected sign), xi = (wi + wo)_xy / lambda (1/um)
    B     = int G(p) exp(-2 pi i xi.(p - x0)) dp = 2 pi sigma^2 exp(-2 pi^2 sigma^2 |xi|^2)
            (Werner Eq. 16, the Gaussian's Fourier transform, exact; checked by 2-D
            quadrature in refcore/checks.py), so only S, where 1 - T != 0, needs quadrature.

A groove k is the rectangle {c + s t + v b : |s| <= h, |v| <= W/2} of the kernel's Scratch
record (centre c, unit tangent t, bitangent b = (-t.y, t.x), half length h), depth D (rect)
or D (1 - |v| / (W/2)) (triangle, a V whose phase is linear in |v|).

Two switches:
  window  frozen: groove k sees the window at its centre line, G(c + s t) (the separable form
                  behind Werner Eqs. 9-13: S_k = (M_k - P_k) eta_k, Eq. 17)
          exact:  G(p) at the point itself
  crossings summed:  S = sum_k S_k (Werner Eq. 9: a crossing is cut twice)
            deepest: the surface is cut once, by the deeper groove: h(p) = -max_k depth_k(p).
                     With the frozen window, a point belongs to the groove that is deepest
                     there and sees that groove's centre-line window. Implemented as
                     S_deep = S_summed - sum over overlap pieces of the shallower groove's
                     integrand there (pairwise overlaps only; a triple overlap is refused).
Velinov's incoherent sum (Eq. 7) from the same parts: sum_k |S'_k|^2, S'_k the integral over
the part of the surface groove k cuts (S_k, less with deepest the overlap pieces where k is
the shallower groove): `brdf_models`.

frozen/summed is exactly the kernel's Werner model (table::evaluate, model werner,
depth_term exact): the golden test testkit/tests/heightfield_reference.rs checks that.

Quadrature (float64, numpy):
  * Single grooves: in the groove frame the integrand of S_k is a product g_s(s) g_v(v) for
    both windows (G(c + s t + v b) = exp(-(s_t+s)^2/2s^2) exp(-(s_b+v)^2/2s^2), the Fourier
    factor likewise, T depends on v only), so the tensor-product Gauss-Legendre rule over
    the rectangle is the product of the two 1-D composite rules; it is evaluated that way
    (`check` compares it with the 2-D polygon rule below on the same rectangles).
    Panels: split at v = 0 (the V's kink), at the groove ends and where the window is
    below e^{-81/2} = 2.6e-18 of its peak (|s_t + s| > 9 sigma: the only truncation);
    panel length <= sigma and <= PHI_PANEL / (phase rate) for each direction's bucket.
  * Crossing overlaps: the overlap of the two rectangles (convex polygon clipping) is cut
    along both V centre lines and along the line where the two depths are equal (the
    depth is linear in p within each piece), so the integrand is smooth on every piece;
    each convex piece is split into slabs between its vertices' y values, each slab mapped
    to a square (x between its left and right edges), composite Gauss-Legendre in both.
  * Every value is computed with ORDER and with 2 ORDER points per panel and dimension;
    the 2 ORDER value is stored and the difference is reported (`conv`).

Usage:
  python3 reference/heightfield.py --check     # self-checks (2-D vs product rule, refcore,
                                               # mpmath 30-digit spot checks, brute-force
                                               # deepest cut, coincident grooves), written
                                               # to reference/golden/heightfield_checks.json
  python3 reference/heightfield_golden.py      # writes reference/golden/heightfield.json,
                                               # with the ORDER vs 2 ORDER convergence
"""
import math

import mpmath as mp
import numpy as np

SIGMA_TRUNC = 9.0  # window truncated where exp(-r^2/2) < e^{-40.5} = 2.6e-18
PHI_PANEL = 4.0  # largest phase change (rad) across one panel
ORDER = 12  # Gauss-Legendre points per panel and dimension (the check uses 2 * ORDER)
UNIT_TOLERANCE = 4.0e-7  # as kernel units::UNIT_TOLERANCE / refcore.UNIT_TOLERANCE
CHUNK = 4_000_000  # complex entries per evaluation block (memory bound)
NODE_BLOCK = 2_000_000  # polygon quadrature nodes per block (memory bound)

_GL = {}


def gl(n):
    """Gauss-Legendre nodes and weights on [-1, 1]."""
    if n not in _GL:
        _GL[n] = np.polynomial.legendre.leggauss(n)
    return _GL[n]


def composite_1d(a, b, breaks, hmax, n):
    """Nodes and weights of composite GL on [a, b], split at `breaks`, panels <= hmax."""
    pts = sorted({a, b} | {x for x in breaks if a < x < b})
    x0, w0 = gl(n)
    xs, ws = [], []
    for lo, hi in zip(pts[:-1], pts[1:]):
        k = max(1, int(math.ceil((hi - lo) / hmax - 1e-12)))
        e = np.linspace(lo, hi, k + 1)
        half = 0.5 * (e[1:] - e[:-1])
        mid = 0.5 * (e[1:] + e[:-1])
        xs.append((mid[:, None] + half[:, None] * x0[None, :]).ravel())
        ws.append((half[:, None] * w0[None, :]).ravel())
    return np.concatenate(xs), np.concatenate(ws)


# ---------------------------------------------------------------------------
# Inputs
# ---------------------------------------------------------------------------

def direction(v):
    """The kernel's units::direction: used as given within UNIT_TOLERANCE of unit length."""
    v = np.asarray(v, dtype=np.float64)
    l2 = np.sum(v * v, axis=-1, keepdims=True)
    return np.where(np.abs(l2 - 1.0) <= UNIT_TOLERANCE, v, v / np.sqrt(l2))


class Groove:
    """One scratch in the kernel's record form (µm; tangent normalised in float64)."""

    def __init__(self, rec):
        self.c = np.array(rec["center"], dtype=np.float64)
        t = np.array(rec["tangent"], dtype=np.float64)
        self.t = t / math.hypot(*t)
        self.b = np.array([-self.t[1], self.t[0]])
        self.h = float(rec["half_len"])
        self.W = float(rec["width"])
        self.D = float(rec["depth"])
        self.profile = rec["profile"]
        assert self.profile in ("rect", "triangle")

    def polygon(self):
        c, t, b, h, w = self.c, self.t, self.b, self.h, self.W / 2
        return [c - h * t - w * b, c + h * t - w * b, c + h * t + w * b, c - h * t + w * b]

    def depth_plane(self, sign):
        """depth(p) = a.p + a0 on the side sign = sign(v) (linear in p; Werner Eqs. 26, 29)."""
        if self.profile == "rect":
            return np.zeros(2), self.D
        # D (1 - 2 sign v / W), v = (p - c).b
        a = -self.D * 2.0 * sign / self.W * self.b
        return a, self.D - float(a @ self.c)

    def depth_at(self, p):
        v = (p - self.c) @ self.b
        if self.profile == "rect":
            return np.full(v.shape, self.D)
        return self.D * (1.0 - np.abs(v) / (self.W / 2))


class Query:
    """Directions (N of them) sharing wi, lambda, x0, sigma and the material."""

    def __init__(self, wi, wo, lambda_nm, x0, sigma, material):
        self.wi = direction(wi)
        self.wo = direction(np.atleast_2d(wo))
        assert self.wi[2] > 0 and np.all(self.wo[:, 2] > 0)
        self.lam = float(lambda_nm) / 1000.0
        self.x0 = np.array(x0, dtype=np.float64)
        self.sigma = float(sigma)
        s = self.wi[None, :] + self.wo
        self.xi = s[:, :2] / self.lam  # xi = (wi + wo)_xy / lambda
        self.gamma = s[:, 2]  # depth_term exact: gamma = wi.z + wo.z
        self.kd = 2.0 * math.pi * self.gamma / self.lam  # T = exp(i kd depth)
        self.F = reflectance(material, self.wi, self.wo)

    def base(self):
        """B (Werner Eq. 16)."""
        s2 = self.sigma ** 2
        return 2 * math.pi * s2 * np.exp(-2 * math.pi ** 2 * s2 * np.sum(self.xi ** 2, axis=1))

    def levels(self, rate):
        """Bucket directions by the phase rate (rad/um): level l has panels <= sigma / 2^l."""
        lv = np.ceil(np.log2(np.maximum(rate * self.sigma / PHI_PANEL, 1.0)))
        return lv.astype(int)


def fresnel(c, n, k):
    """Unpolarised Fresnel of n + ik at cos c, H&P Eqs. 11-13 (principal sqrt), as
    refcore.fresnel."""
    c = np.clip(c, 0.0, 1.0)
    e2 = complex(n, k) ** 2
    r = np.sqrt(e2 - (1.0 - c * c) + 0j)
    fs = np.abs((c - r) / (c + r)) ** 2
    fp = np.abs((e2 * c - r) / (e2 * c + r)) ** 2
    return 0.5 * (fs + fp)


def reflectance(material, wi, wo):
    if material is None:
        return np.ones(len(wo))
    if "F" in material:
        return np.full(len(wo), float(material["F"]))
    n, k = material["ior"]
    ang = material.get("fresnel_angle", "theta_d")
    if ang == "theta_d":
        hv = wi[None, :] + wo
        hv = hv / np.linalg.norm(hv, axis=1, keepdims=True)
        c = hv @ wi
    elif ang == "theta_i":
        c = np.full(len(wo), wi[2])
    else:
        c = np.ones(len(wo))
    return fresnel(c, n, k)


# ---------------------------------------------------------------------------
# Single groove: tensor-product rule over its rectangle (Werner Eqs. 12, 14, 17 integrands)
# ---------------------------------------------------------------------------

def _blocked(nodes_fn, q, idx, f):
    """sum_j w_j f(dirs, nodes) for the directions idx, in blocks."""
    x, w = nodes_fn
    out = np.zeros(len(idx), dtype=complex)
    step = max(1, CHUNK // max(1, len(x)))
    for i in range(0, len(idx), step):
        sel = idx[i:i + step]
        out[i:i + step] = f(sel, x) @ w
    return out


def groove_S(g, q, window, n):
    """S_k for every direction: int over the groove of window (1 - T) e^{-2 pi i xi.(p - x0)}."""
    sig = q.sigma
    r0 = g.c - q.x0
    st, sb = float(r0 @ g.t), float(r0 @ g.b)
    xi1, xi2 = q.xi @ g.t, q.xi @ g.b
    N = len(xi1)
    # along the groove, u = s_t + s (window coordinate), window factor exp(-u^2/2 sigma^2)
    lo, hi = max(st - g.h, -SIGMA_TRUNC * sig), min(st + g.h, SIGMA_TRUNC * sig)
    if lo >= hi:
        return np.zeros(N, dtype=complex)
    A_s = np.zeros(N, dtype=complex)
    lv = q.levels(2 * math.pi * np.abs(xi1))
    for L in np.unique(lv):
        idx = np.nonzero(lv == L)[0]
        nodes = composite_1d(lo, hi, [0.0], sig / 2.0 ** L, n)

        def fs(sel, u):
            return np.exp(-u[None, :] ** 2 / (2 * sig * sig)
                          - 2j * math.pi * xi1[sel, None] * u[None, :])
        A_s[idx] = _blocked(nodes, q, idx, fs)
    # across the groove, v in [-W/2, W/2] (window coordinate s_b + v), kink at v = 0
    A_v = np.zeros(N, dtype=complex)
    slope = g.D * 2.0 / g.W if g.profile == "triangle" else 0.0
    lv = q.levels(2 * math.pi * np.abs(xi2) + q.kd * slope)
    for L in np.unique(lv):
        idx = np.nonzero(lv == L)[0]
        nodes = composite_1d(-g.W / 2, g.W / 2, [0.0], sig / 2.0 ** L, n)
        depth = g.depth_at(g.c + nodes[0][:, None] * g.b[None, :])

        def fv(sel, v):
            win = (np.exp(-(sb + v) ** 2 / (2 * sig * sig)) if window == "exact"
                   else np.full(v.shape, math.exp(-sb * sb / (2 * sig * sig))))
            one_minus_T = 1.0 - np.exp(1j * q.kd[sel, None] * depth[None, :])
            return win[None, :] * one_minus_T * np.exp(-2j * math.pi * xi2[sel, None]
                                                       * (sb + v)[None, :])
        A_v[idx] = _blocked(nodes, q, idx, fv)
    return A_s * A_v


# ---------------------------------------------------------------------------
# Convex polygons: clipping and the slab rule
# ---------------------------------------------------------------------------

def clip(poly, a, a0):
    """Part of the convex polygon where a.p + a0 >= 0 (Sutherland-Hodgman, one edge)."""
    out = []
    m = len(poly)
    for i in range(m):
        P, Q = poly[i], poly[(i + 1) % m]
        fp, fq = float(a @ P) + a0, float(a @ Q) + a0
        if fp >= 0:
            out.append(P)
        if (fp >= 0) != (fq >= 0):
            out.append(P + (Q - P) * (fp / (fp - fq)))
    return _dedupe(out)


def _dedupe(poly, tol=1e-12):
    out = []
    for p in poly:
        if not out or np.linalg.norm(p - out[-1]) > tol:
            out.append(p)
    while len(out) > 1 and np.linalg.norm(out[0] - out[-1]) <= tol:
        out.pop()
    return out


def area(poly):
    if len(poly) < 3:
        return 0.0
    s = 0.0
    for i in range(len(poly)):
        P, Q = poly[i], poly[(i + 1) % len(poly)]
        s += P[0] * Q[1] - P[1] * Q[0]
    return 0.5 * s


def intersect(P1, P2):
    """Intersection of two convex polygons (counter-clockwise)."""
    out = P1
    m = len(P2)
    for i in range(m):
        A, B = P2[i], P2[(i + 1) % m]
        e = B - A
        a = np.array([-e[1], e[0]])  # left normal: inside for a CCW polygon
        out = clip(out, a, -float(a @ A))
        if len(out) < 3:
            return []
    return out if area(out) > 1e-14 else []


def _section(poly, y):
    xs = []
    m = len(poly)
    for i in range(m):
        P, Q = poly[i], poly[(i + 1) % m]
        if P[1] == Q[1]:
            if P[1] == y:
                xs += [P[0], Q[0]]
            continue
        lo, hi = min(P[1], Q[1]), max(P[1], Q[1])
        if lo <= y <= hi:
            xs.append(P[0] + (Q[0] - P[0]) * (y - P[1]) / (Q[1] - P[1]))
    return min(xs), max(xs)


def polygon_nodes(poly, hmax, n, block=NODE_BLOCK):
    """Composite GL nodes (M x 2) and weights on a convex polygon, yielded in blocks of
    about `block` nodes (a run of panel rows; memory, not accuracy): slabs between vertex
    heights, each mapped to the square (x linear between the slab's two edges)."""
    x0, w0 = gl(n)
    ys = sorted({float(p[1]) for p in poly})
    for ya, yb in zip(ys[:-1], ys[1:]):
        if yb - ya < 1e-13:
            continue
        (la, ra), (lb, rb) = _section(poly, ya), _section(poly, yb)
        width = max(ra - la, rb - lb)
        ny = max(1, int(math.ceil((yb - ya) / hmax)))
        nx = max(1, int(math.ceil(width / hmax)))
        ey = np.linspace(ya, yb, ny + 1)
        ex = np.linspace(0.0, 1.0, nx + 1)
        z = (0.5 * (ex[1:] + ex[:-1])[:, None] + 0.5 * (ex[1:] - ex[:-1])[:, None] * x0).ravel()
        wz = (0.5 * (ex[1:] - ex[:-1])[:, None] * w0).ravel()
        rows = max(1, block // (len(z) * len(x0)))
        for r in range(0, ny, rows):
            e = ey[r:r + rows + 1]
            y = (0.5 * (e[1:] + e[:-1])[:, None] + 0.5 * (e[1:] - e[:-1])[:, None] * x0).ravel()
            wy = (0.5 * (e[1:] - e[:-1])[:, None] * w0).ravel()
            f = (y - ya) / (yb - ya)
            xl, xr = la + (lb - la) * f, ra + (rb - ra) * f
            X = xl[:, None] + (xr - xl)[:, None] * z[None, :]
            Wm = (wy * (xr - xl))[:, None] * wz[None, :]
            yield np.stack([X.ravel(), np.repeat(y, len(z))], axis=1), Wm.ravel()


def window_box(q):
    r = SIGMA_TRUNC * q.sigma
    x, y = q.x0
    return [np.array(v) for v in ((x - r, y - r), (x + r, y - r), (x + r, y + r), (x - r, y + r))]


def region_S(poly, g, q, window, n):
    """int over the convex polygon of groove g's integrand: window (1 - T_g) e^{...}."""
    sig = q.sigma
    N = len(q.kd)
    out = np.zeros(N, dtype=complex)
    slope = g.D * 2.0 / g.W if g.profile == "triangle" else 0.0
    lv = q.levels(2 * math.pi * np.linalg.norm(q.xi, axis=1) + q.kd * slope)
    for L in np.unique(lv):
        idx = np.nonzero(lv == L)[0]
        for p, w in polygon_nodes(poly, sig / 2.0 ** L, n):
            d = p - q.x0
            if window == "exact":
                win = np.exp(-np.sum(d * d, axis=1) / (2 * sig * sig))
            else:  # the groove's centre line at the same s (Werner Eq. 12's G(c + s t))
                s = (p - g.c) @ g.t
                e = g.c[None, :] + s[:, None] * g.t[None, :] - q.x0
                win = np.exp(-np.sum(e * e, axis=1) / (2 * sig * sig))
            depth = g.depth_at(p)

            def f(sel, dd, win=win, depth=depth, d=d):
                return (win[None, :] * (1.0 - np.exp(1j * q.kd[sel, None] * depth[None, :]))
                        * np.exp(-2j * math.pi * (q.xi[sel] @ d.T)))
            out[idx] += _blocked((d, w), q, idx, f)
    return out


def overlap_pieces(gj, gk, q):
    """Pieces of the overlap of grooves j and k on which the integrand is smooth, each
    with the index (0: j, 1: k) of the shallower groove there (the one cut away)."""
    O = intersect(intersect(gj.polygon(), gk.polygon()), window_box(q))
    if not O:
        return []
    pieces = [O]
    for g in (gj, gk):  # the V's kink along its centre line
        if g.profile == "triangle":
            nxt = []
            for P in pieces:
                for sgn in (1.0, -1.0):
                    a = sgn * g.b
                    Q = clip(P, a, -float(a @ g.c))
                    if len(Q) >= 3 and area(Q) > 1e-14:
                        nxt.append(Q)
            pieces = nxt
    out = []
    for P in pieces:
        cen = np.mean(P, axis=0)
        sj = 1.0 if (cen - gj.c) @ gj.b >= 0 else -1.0
        sk = 1.0 if (cen - gk.c) @ gk.b >= 0 else -1.0
        aj, a0j = gj.depth_plane(sj)
        ak, a0k = gk.depth_plane(sk)
        a, a0 = aj - ak, a0j - a0k  # depth_j - depth_k, linear on the piece
        if np.linalg.norm(a) == 0.0:
            # constant difference: tie -> the later groove is the one cut away
            out.append((P, 1 if a0 >= 0 else 0))
            continue
        for sgn, shallow in ((1.0, 1), (-1.0, 0)):
            Q = clip(P, sgn * a, sgn * a0)
            if len(Q) >= 3 and area(Q) > 1e-14:
                out.append((Q, shallow))
    return out


def groove_parts(grooves, q, window, crossings, n):
    """Each groove's own part of S: S_k, less (deepest) the overlap pieces where groove k
    is the shallower one, i.e. the integral over the part of the surface groove k cuts."""
    parts = [groove_S(g, q, window, n) for g in grooves]
    if crossings == "summed":
        return parts
    m = len(grooves)
    for i in range(m):
        for j in range(i + 1, m):
            for k in range(j + 1, m):
                P = intersect(intersect(grooves[i].polygon(), grooves[j].polygon()),
                              grooves[k].polygon())
                assert not P, "triple overlap: not supported"
    for i in range(m):
        for j in range(i + 1, m):
            for P, shallow in overlap_pieces(grooves[i], grooves[j], q):
                k = (i, j)[shallow]
                parts[k] = parts[k] - region_S(P, grooves[k], q, window, n)
    return parts


def scratch_S(grooves, q, window, crossings, n):
    """S for the whole scratch set: the sum of the grooves' parts."""
    return sum(groove_parts(grooves, q, window, crossings, n),
               np.zeros(len(q.kd), dtype=complex))


VARIANTS = (("frozen", "summed"), ("frozen", "deepest"), ("exact", "summed"), ("exact", "deepest"))


def brdf_models(scratches, q, window, crossings, n=2 * ORDER):
    """Both models from one set of parts, without the cosine:
    werner  = F/(pi sigma^2 lambda^2) |B - S|^2                 (Werner Eq. 15)
    velinov = F/(pi sigma^2 lambda^2) sum_k |S'_k|^2            (Velinov Eq. 7, no base;
              S'_k = the groove's part, so with deepest each groove loses the overlap
              pieces where the other one cuts deeper: the incoherent sum's intensity form)."""
    grooves = [Groove(s) for s in scratches]
    parts = groove_parts(grooves, q, window, crossings, n)
    S = sum(parts, np.zeros(len(q.kd), dtype=complex))
    norm = q.F / (math.pi * q.sigma ** 2 * q.lam ** 2)
    werner = norm * np.abs(q.base() - S) ** 2
    velinov = norm * sum(np.abs(p) ** 2 for p in parts)
    return werner, velinov


def brdf(scratches, q, window, crossings, n=2 * ORDER, parts=False):
    """Werner Eq. 15 without the cosine: F/(pi sigma^2 lambda^2) |B - S|^2."""
    grooves = [Groove(s) for s in scratches]
    S = scratch_S(grooves, q, window, crossings, n)
    B = q.base()
    v = q.F / (math.pi * q.sigma ** 2 * q.lam ** 2) * np.abs(B - S) ** 2
    return (v, B, S) if parts else v


# ---------------------------------------------------------------------------
# mpmath spot checks (30 digits)
# ---------------------------------------------------------------------------

def mp_groove_S(g, q, d, window, dps=30):
    """S_k of direction d by mpmath.quad: the product of the two 1-D integrals (exact
    factorisation of the rectangle's integral, see the module doc)."""
    with mp.workdps(dps + 10):
        sig = mp.mpf(q.sigma)
        c = [mp.mpf(v) for v in g.c]
        t = [mp.mpf(v) for v in g.t]
        b = [-t[1], t[0]]
        x0 = [mp.mpf(v) for v in q.x0]
        r0 = [c[0] - x0[0], c[1] - x0[1]]
        st, sb = r0[0] * t[0] + r0[1] * t[1], r0[0] * b[0] + r0[1] * b[1]
        xi = [mp.mpf(v) for v in q.xi[d]]
        xi1, xi2 = xi[0] * t[0] + xi[1] * t[1], xi[0] * b[0] + xi[1] * b[1]
        kd = 2 * mp.pi * mp.mpf(q.gamma[d]) / (mp.mpf(q.lam))
        h, W, D = mp.mpf(g.h), mp.mpf(g.W), mp.mpf(g.D)
        lo = max(st - h, -mp.mpf(SIGMA_TRUNC) * sig)
        hi = min(st + h, mp.mpf(SIGMA_TRUNC) * sig)

        def split(a, bb, step):
            k = max(1, int(mp.ceil((bb - a) / step)))
            return [a + (bb - a) * i / k for i in range(k + 1)]
        rate = 2 * mp.pi * abs(xi1)
        step = min(sig / 2, 2 / rate) if rate > 0 else sig / 2
        pts = sorted(set(split(lo, hi, step)) | ({mp.mpf(0)} if lo < 0 < hi else set()))
        As = mp.quad(lambda u: mp.exp(-u * u / (2 * sig * sig) - 2j * mp.pi * xi1 * u), pts)

        def depth(v):
            return D if g.profile == "rect" else D * (1 - abs(v) / (W / 2))

        def fv(v):
            win = mp.exp(-(sb + v) ** 2 / (2 * sig * sig)) if window == "exact" \
                else mp.exp(-sb * sb / (2 * sig * sig))
            return win * (1 - mp.exp(1j * kd * depth(v))) * mp.exp(-2j * mp.pi * xi2 * (sb + v))
        rate = 2 * mp.pi * abs(xi2) + kd * 2 * D / W
        step = min(W / 2, 2 / rate)
        pts = sorted(set(split(-W / 2, mp.mpf(0), step)) | set(split(mp.mpf(0), W / 2, step)))
        Av = mp.quad(fv, pts)
        return As * Av


def mp_region_S(poly, g, q, d, window, dps=30):
    """region_S of one direction by 2-D mpmath.quad over the polygon's slabs."""
    with mp.workdps(dps + 10):
        sig = mp.mpf(q.sigma)
        x0 = [mp.mpf(v) for v in q.x0]
        xi = [mp.mpf(v) for v in q.xi[d]]
        kd = 2 * mp.pi * mp.mpf(q.gamma[d]) / mp.mpf(q.lam)
        c = [mp.mpf(v) for v in g.c]
        t = [mp.mpf(v) for v in g.t]
        b = [-t[1], t[0]]
        W, D = mp.mpf(g.W), mp.mpf(g.D)

        def f(x, y):
            dx, dy = x - x0[0], y - x0[1]
            if window == "exact":
                win = mp.exp(-(dx * dx + dy * dy) / (2 * sig * sig))
            else:
                s = (x - c[0]) * t[0] + (y - c[1]) * t[1]
                ex, ey = c[0] + s * t[0] - x0[0], c[1] + s * t[1] - x0[1]
                win = mp.exp(-(ex * ex + ey * ey) / (2 * sig * sig))
            v = (x - c[0]) * b[0] + (y - c[1]) * b[1]
            dep = D if g.profile == "rect" else D * (1 - abs(v) / (W / 2))
            return win * (1 - mp.exp(1j * kd * dep)) * mp.exp(-2j * mp.pi * (xi[0] * dx + xi[1] * dy))
        total = mp.mpc(0)
        ys = sorted({float(p[1]) for p in poly})
        for ya, yb in zip(ys[:-1], ys[1:]):
            if yb - ya < 1e-13:
                continue
            (la, ra), (lb, rb) = _section(poly, ya), _section(poly, yb)
            ya_, yb_ = mp.mpf(ya), mp.mpf(yb)
            la, ra, lb, rb = (mp.mpf(v) for v in (la, ra, lb, rb))

            def inner(y):
                fr = (y - ya_) / (yb_ - ya_)
                xl, xr = la + (lb - la) * fr, ra + (rb - ra) * fr
                return mp.quad(lambda x: f(x, y), [xl, xr])
            total += mp.quad(inner, [ya_, yb_])
        return total


# ---------------------------------------------------------------------------
# Self-checks
# ---------------------------------------------------------------------------

def check():
    """Convergence, the 2-D slab rule against the product rule, and mpmath spot checks."""
    import heightfield_golden as hg
    results = {}
    cases = hg.all_cases()
    # 1. 2-D slab rule vs the single-groove product rule, on the groove's windowed rectangle
    worst = 0.0
    for case in [c for c in cases if c["kind"] == "single"][::15]:
        q = hg.query_of(case)
        # the lobe directions only (|xi| <= 0.5/um): the 2-D rule costs (rate x size)^2
        keep = np.linalg.norm(q.xi, axis=1) <= 0.5
        q = hg.query_of(dict(case, wo=[w for w, k in zip(case["wo"], keep) if k]))
        g = Groove(case["scratches"][0])
        box = intersect(g.polygon(), window_box(q))
        # the V's kink: split along the centre line, as overlap_pieces does
        halves = [clip(box, sg * g.b, -float(sg * g.b @ g.c)) for sg in (1.0, -1.0)] \
            if g.profile == "triangle" else [box]
        for window in ("frozen", "exact"):
            a = groove_S(g, q, window, 2 * ORDER)
            b = sum(region_S(P, g, q, window, 2 * ORDER) for P in halves)
            ref = np.max(np.abs(a))
            worst = max(worst, float(np.max(np.abs(a - b)) / ref))
    results["slab_vs_product_max_abs_over_peak"] = worst
    print(f"2-D slab rule vs product rule (single grooves, every 15th case, |xi| <= 0.5/um): "
          f"max |diff| / max|S| = {worst:.2e}", flush=True)
    # 2a. frozen/summed against refcore.brdf (mpmath, Werner's closed-form factorisation
    # (M - P) eta with eta by contour quadrature): the same model reached another way
    import refcore as rc
    worst_rc = 0.0
    names = ("single_triangle_W1.0_off1_th30", "single_rect_W0.3_off2_th80",
             "finite_triangle_W1.0_off1_th60", "crossing45_unequal_triangle_th30")
    for case in [c for c in cases if c["name"] in names]:
        q = hg.query_of(case)
        v = brdf(case["scratches"], q, "frozen", "summed")
        spec = {"model": "werner", "options": {"depth_term": "exact"}, "sigma_um": q.sigma,
                "scratches": [{k: s[k] for k in ("p0", "p1", "width", "depth", "profile")}
                              for s in case["scratches"]]}
        for d in range(0, len(case["wo"]), 9):
            r = float(rc.brdf(spec, {"wi": case["wi"], "wo": case["wo"][d],
                                     "lambda_nm": case["lambda_nm"], "x": case["x"],
                                     "material": hg.MATERIAL}))
            e = abs(v[d] / r - 1) if r >= 1e-3 * v.max() else abs(v[d] - r) / v.max()
            worst_rc = max(worst_rc, e)
    results["refcore_frozen_summed_max_rel"] = worst_rc
    print(f"frozen/summed vs refcore.brdf (werner, depth_term exact; 4 cases, every 9th "
          f"direction): max rel {worst_rc:.2e} (abs/peak below 1e-3 of the peak)", flush=True)
    # 2. mpmath spot checks: single grooves (product of 1-D mp.quad) and crossing pieces (2-D)
    worst_single = 0.0
    for case in [c for c in cases if c["kind"] == "single"][::29]:
        q = hg.query_of(case)
        g = Groove(case["scratches"][0])
        for window in ("frozen", "exact"):
            S = groove_S(g, q, window, 2 * ORDER)
            for d in (0, len(q.kd) // 3, len(q.kd) // 2):
                m = complex(mp_groove_S(g, q, d, window))
                rel = abs(S[d] - m) / max(abs(m), 1e-300)
                worst_single = max(worst_single, rel)
                print(f"  mpmath single {case['name']} {window} dir {d}: |S| = {abs(m):.6e}, "
                      f"rel diff {rel:.2e}", flush=True)
    results["mpmath_single_max_rel"] = worst_single
    worst_cross = 0.0
    for case in [c for c in cases if c["kind"] == "crossing"][::7]:
        q = hg.query_of(case)
        gs = [Groove(s) for s in case["scratches"]]
        pieces = overlap_pieces(gs[0], gs[1], q)
        for window in ("frozen", "exact"):
            for P, shallow in pieces[:2]:
                g = gs[shallow]
                d = 0  # the mirror direction
                S = region_S(P, g, q, window, 2 * ORDER)[d]
                m = complex(mp_region_S(P, g, q, d, window))
                rel = abs(S - m) / max(abs(m), 1e-300)
                worst_cross = max(worst_cross, rel)
                print(f"  mpmath overlap piece {case['name']} {window}: |S| = {abs(m):.6e}, "
                      f"rel diff {rel:.2e}", flush=True)
    results["mpmath_overlap_max_rel"] = worst_cross
    print(f"mpmath (30 digits) vs float64 quadrature: single grooves max rel {worst_single:.2e}, "
          f"overlap pieces max rel {worst_cross:.2e}")
    # 3. the deepest cut, brute force: the overlap correction sum_k S_k - S_deep as a
    # midpoint sum of [sum_k win_k (1 - T_k) - win_d (1 - T_d)] e^{...} on a fine grid with
    # the depth taken pointwise (no pieces, no planes): first order in the grid step, an
    # independent check of the piece logic.
    worst_bf = 0.0
    for case in [c for c in cases if c["kind"] == "crossing"][::3]:
        q = hg.query_of(case)
        gs = [Groove(s) for s in case["scratches"]]
        O = intersect(gs[0].polygon(), gs[1].polygon())
        lo, hi = np.min(O, axis=0) - 0.01, np.max(O, axis=0) + 0.01
        step = 0.004
        xs = np.arange(lo[0], hi[0], step) + step / 2
        ys = np.arange(lo[1], hi[1], step) + step / 2
        # the mirror and the direction farthest from it with |xi| <= 1/um
        rx = np.linalg.norm(q.xi, axis=1)
        dsel = [0, int(np.argmax(np.where(rx <= 1.0, rx, -1.0)))]
        for window in ("frozen", "exact"):
            pieces = overlap_pieces(gs[0], gs[1], q)
            corr = sum(region_S(P, gs[sh], q, window, 2 * ORDER) for P, sh in pieces)
            bf = np.zeros(len(dsel), dtype=complex)
            for y in ys:
                p = np.stack([xs, np.full_like(xs, y)], axis=1)
                terms, depths = [], []
                for g in gs:
                    r = p - g.c
                    s, v = r @ g.t, r @ g.b
                    inside = (np.abs(s) <= g.h) & (np.abs(v) <= g.W / 2)
                    dep = np.where(inside, g.depth_at(p), 0.0)
                    if window == "exact":
                        win = np.exp(-np.sum((p - q.x0) ** 2, axis=1) / (2 * q.sigma ** 2))
                    else:
                        e = g.c + s[:, None] * g.t - q.x0
                        win = np.exp(-np.sum(e * e, axis=1) / (2 * q.sigma ** 2))
                    depths.append(dep)
                    terms.append(win)
                deeper = np.where(depths[0] >= depths[1], 0, 1)  # tie: the first is kept
                for j, d in enumerate(dsel):
                    ph = np.exp(-2j * math.pi * ((p - q.x0) @ q.xi[d]))
                    one = [1 - np.exp(1j * q.kd[d] * dep) for dep in depths]
                    summed = terms[0] * one[0] + terms[1] * one[1]
                    deep = np.where(deeper == 0, terms[0] * one[0], terms[1] * one[1])
                    bf[j] += np.sum((summed - deep) * ph) * step * step
            top = max(abs(corr[d]) for d in dsel)  # the correction at the mirror
            for j, d in enumerate(dsel):
                rel = abs(corr[d] - bf[j]) / abs(corr[d])
                worst_bf = max(worst_bf, abs(corr[d] - bf[j]) / top)
                print(f"  brute-force deepest correction {case['name']} {window} dir {d}: "
                      f"|xi| = {rx[d]:.3f}/um, |corr| = {abs(corr[d]):.4e}, rel diff {rel:.2e}, "
                      f"diff / |corr at the mirror| {abs(corr[d] - bf[j]) / top:.2e}", flush=True)
    results["bruteforce_deepest_max_diff_over_mirror_corr"] = worst_bf
    print(f"deepest-cut correction, pieces vs pointwise midpoint sum (step 0.004 um, first "
          f"order at the groove edges): max |diff| / |correction at the mirror| {worst_bf:.2e}")
    # 4. identical grooves: the deepest cut of two coincident grooves is one groove
    case = [c for c in cases if c["kind"] == "single"][50]
    q = hg.query_of(case)
    s = case["scratches"][0]
    shallow = dict(s, depth=s["depth"] / 2)
    worst_id = 0.0
    for window in ("frozen", "exact"):
        one = brdf([s], q, window, "summed")
        two = brdf([shallow, s], q, window, "deepest")
        worst_id = max(worst_id, float(np.max(np.abs(one - two)) / one.max()))
    results["coincident_grooves_max_abs_over_peak"] = worst_id
    print(f"coincident grooves (D/2 under D), deepest = the deeper alone: "
          f"max |diff|/peak {worst_id:.2e}")
    return results


if __name__ == "__main__":
    import argparse
    import json
    import os
    import sys
    sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--check", action="store_true")
    a = ap.parse_args()
    if a.check:
        res = check()
        out = os.path.join(os.path.dirname(os.path.abspath(__file__)), "golden",
                           "heightfield_checks.json")
        with open(out, "w") as fh:
            json.dump({k: float(f"{v:.3g}") for k, v in res.items()}, fh, indent=1)
            fh.write("\n")
        print(f"wrote {out}")
    else:
        ap.print_help()
