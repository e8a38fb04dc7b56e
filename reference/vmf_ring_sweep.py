#!/usr/bin/env python3
"""Domain sweep of Werner §5's scratch sampler, the von Mises-Fisher ring (issue #20).

`kernel/src/bsdf/lobes.rs` draws `wi` for one scratch of tangent `t` (unit, in the surface
plane) on the cone `wi.t = -wo.t` at an azimuth `2 pi u_ring`, perturbed by a vMF direction
of concentration kappa, mirrored above the surface (`vmf_ring_sample`), and evaluates its
solid-angle density (`vmf_ring_pdf`). Nothing here comes from the kernel: every query draws
its inputs in float64, rounds each to float32 and evaluates at exactly those float32 values,
with mpmath at 40 digits (t, wo and wi normalised exactly):

  pdf     2 kappa / (4 pi sinh kappa) exp(-kappa cos(th_o) cos(th)) I0(kappa sin(th_o) sin(th)),
          th_o, th the angles of wo and wi from t (the ring density of Werner §5 after
          d'Eon et al. 2011, doubled by the mirroring: it depends on wi.t only)
  sample  the kernel's map, exactly: the cone direction
          mu = -cos(th_o) t + sin(th_o) (cos(2 pi u_ring) z + sin(2 pi u_ring) (t x z)),
          the vMF cosine w = 1 + ln(v + (1 - v) e^(-2 kappa)) / kappa (v = u_x), the
          azimuth 2 pi u_y about mu in the frame of Duff et al. 2017 (the kernel's
          `orthonormal`), d = w mu + sqrt(1 - w^2) (cos b1 + sin b2), z mirrored to >= 0

Each value carries its conditioning, the largest change of the exact value when one input
(t, kappa, wo, wi or u_ring, u_x, u_y) moves to a neighbouring float32, measured as the
error is: relative for the pdf; for the sample the angle to the exact direction divided by
the lobe's angular width min(1, 1/sqrt(kappa)) (a vMF of concentration kappa spreads about
1/sqrt(kappa) radians; an angle is only small or large against that).

Domain (log-uniform unless noted): kappa 1e-5 - 1e7 (the kernel's `ring_kappa` = 1/s^2 with
s = lambda max(1/(sqrt 8 pi sigma), 1/(2 h sqrt(2 pi))): 6e6 at sigma = 100 um,
lambda = 360 nm; 1e-5 for a 1 nm segment); t at any angle (10 % along an axis); wo with
cos(theta) from the normal 0.005 - 1 (20 % with 1 - cos(theta) 1e-9 - 0.1), any azimuth;
wi on the ring (10 %), near it (40 %: off by 1e-3 - 10 lobe widths in any direction) or
anywhere above the surface (50 %); u_ring, u_y uniform; u_x uniform (70 %) or within
1e-7 - 1e-2 of 0 (15 %) or of 1 (15 %).

Usage: python3 reference/vmf_ring_sweep.py [--count N] [--seed-offset K] [--out DIR]
Writes DIR/vmf_ring.csv (default reference/golden/sweep/).
"""
import math

import mpmath as mp
import numpy as np

from sweep_io import angle, draw_wo, f32, nudges, parse_args, progress, unit, write_csv

mp.mp.dps = 40





def dot(a, b):
    return sum(x * y for x, y in zip(a, b))


def pdf(t, kappa, wo, wi):
    if not wi[2] > 0:
        return mp.mpf(0)
    t3 = unit([t[0], t[1], 0])
    co, c = dot(unit(wo), t3), dot(unit(wi), t3)
    so, s = mp.sqrt(1 - co * co), mp.sqrt(1 - c * c)
    k = mp.mpf(kappa)
    x = k * so * s
    # log form: kappa up to 1e7 puts sinh, exp and I0 far beyond any float range
    log_p = (
        mp.log(2 * k / (4 * mp.pi))
        - (k + mp.log(-mp.expm1(-2 * k) / 2))  # log sinh(kappa)
        - k * co * c
        + (mp.log(mp.besseli(0, x) * mp.exp(-x)) + x)
    )
    return mp.exp(log_p)


def orthonormal(n):
    """Duff et al. 2017, as the kernel's `orthonormal` (sign(0) = +1)."""
    s = mp.mpf(1) if n[2] >= 0 else mp.mpf(-1)
    a = -1 / (s + n[2])
    b = n[0] * n[1] * a
    return (
        [1 + s * n[0] * n[0] * a, s * b, -s * n[0]],
        [b, s + n[1] * n[1] * a, -n[1]],
    )


def cone(t, wo, u_ring):
    """The ring's direction at azimuth 2 pi u_ring: wi.t = -wo.t."""
    t3 = unit([t[0], t[1], 0])
    co = dot(unit(wo), t3)
    so = mp.sqrt(1 - co * co)
    a2 = [t3[1], -t3[0], mp.mpf(0)]  # t x z
    phi = 2 * mp.pi * mp.mpf(u_ring)
    cp, sp = mp.cos(phi), mp.sin(phi)
    return [-co * t3[i] + (cp * (1 if i == 2 else 0) + sp * a2[i]) * so for i in range(3)]


def sample(t, kappa, wo, u_ring, ux, uy):
    mu = cone(t, wo, u_ring)
    k, v = mp.mpf(kappa), mp.mpf(ux)
    omw = -mp.log(v + (1 - v) * mp.exp(-2 * k)) / k
    w = 1 - omw
    sw = mp.sqrt(omw * (2 - omw))
    b1, b2 = orthonormal(mu)
    q = 2 * mp.pi * mp.mpf(uy)
    cq, sq = mp.cos(q), mp.sin(q)
    d = [mu[i] * w + (b1[i] * cq + b2[i] * sq) * sw for i in range(3)]
    d[2] = abs(d[2])
    return unit(d)


def width(kappa):
    return min(1.0, 1.0 / math.sqrt(kappa))



def rotate_off(v, delta, psi):
    """`v` (unit) turned by `delta` towards the direction at azimuth `psi` about it."""
    b1, b2 = orthonormal([mp.mpf(c) for c in v])
    return [
        v[i] * mp.cos(delta) + (b1[i] * mp.cos(psi) + b2[i] * mp.sin(psi)) * mp.sin(delta)
        for i in range(3)
    ]


def draw(rng):
    if rng.random() < 0.1:
        phi_t = rng.integers(0, 4) * math.pi / 2
    else:
        phi_t = rng.uniform(0, 2 * math.pi)
    t = [f32(math.cos(phi_t)), f32(math.sin(phi_t))]
    kappa = f32(10 ** rng.uniform(-5, 7))
    wo = draw_wo(rng)
    cls = rng.random()
    if cls < 0.5:  # on or near the ring
        ring = cone(t, wo, rng.random())
        delta = 0.0 if cls < 0.1 else width(kappa) * 10 ** rng.uniform(-3, 1)
        v = rotate_off(ring, mp.mpf(delta), mp.mpf(rng.uniform(0, 2 * math.pi)))
        v = [float(c) for c in v]
        v[2] = abs(v[2])
        if v[2] < 1e-3:
            v[2] = 1e-3
    else:
        cw = 10 ** rng.uniform(math.log10(0.005), 0)
        sw, pw = math.sqrt(1 - cw * cw), rng.uniform(0, 2 * math.pi)
        v = [sw * math.cos(pw), sw * math.sin(pw), cw]
    n = math.sqrt(sum(c * c for c in v))
    wi = [f32(c / n) for c in v]
    u_ring, uy = f32(rng.random()), f32(rng.random())
    r = rng.random()
    if r < 0.7:
        ux = f32(rng.random())
    elif r < 0.85:
        ux = f32(10 ** rng.uniform(-7, -2))
    else:
        ux = f32(1 - 10 ** rng.uniform(-7, -2))
    return t, kappa, wo, wi, u_ring, ux, uy


def conditioning(t, kappa, wo, wi, u_ring, ux, uy, p, d):
    kp, ks = 0.0, 0.0
    w = width(kappa)

    def vary(vec, i):
        for y in nudges(vec[i]):
            v2 = list(vec)
            v2[i] = y
            yield v2

    def upd_p(val):
        nonlocal kp
        if p != 0:
            kp = max(kp, float(abs(val / p - 1)))

    def upd_s(dir2):
        nonlocal ks
        ks = max(ks, float(angle(dir2, d)) / w)

    for i in range(2):
        for t2 in vary(t, i):
            upd_p(pdf(t2, kappa, wo, wi))
            upd_s(sample(t2, kappa, wo, u_ring, ux, uy))
    for k2 in nudges(kappa):
        upd_p(pdf(t, k2, wo, wi))
        upd_s(sample(t, k2, wo, u_ring, ux, uy))
    for i in range(3):
        for wo2 in vary(wo, i):
            upd_p(pdf(t, kappa, wo2, wi))
            upd_s(sample(t, kappa, wo2, u_ring, ux, uy))
        for wi2 in vary(wi, i):
            upd_p(pdf(t, kappa, wo, wi2))
    for ur in nudges(u_ring):
        if 0 <= ur < 1:
            upd_s(sample(t, kappa, wo, ur, ux, uy))
    for x2 in nudges(ux):
        if 0 <= x2 < 1:
            upd_s(sample(t, kappa, wo, u_ring, x2, uy))
    for y2 in nudges(uy):
        if 0 <= y2 < 1:
            upd_s(sample(t, kappa, wo, u_ring, ux, y2))
    return kp, ks


def main():
    args = parse_args(2000)
    rng = np.random.default_rng(21_000 + args.seed_offset)
    head = ["t_x", "t_y", "kappa", "wo_x", "wo_y", "wo_z", "wi_x", "wi_y", "wi_z", "u_ring", "u_x", "u_y"]
    head += ["pdf_ref", "pdf_kappa", "sample_x", "sample_y", "sample_z", "sample_kappa"]
    rows = []
    for i in range(args.count):
        t, kappa, wo, wi, u_ring, ux, uy = draw(rng)
        p = pdf(t, kappa, wo, wi)
        d = sample(t, kappa, wo, u_ring, ux, uy)
        kp, ks = conditioning(t, kappa, wo, wi, u_ring, ux, uy, p, d)
        row = [repr(np.float32(x).item()) for x in t + [kappa] + wo + wi + [u_ring, ux, uy]]
        row += [mp.nstr(p, 17, min_fixed=1, max_fixed=0), "%.4g" % kp]
        row += [mp.nstr(c, 17, min_fixed=1, max_fixed=0) for c in d]
        row += ["%.4g" % ks]
        rows.append(row)
        progress(i + 1, args.count, 200)
    write_csv(args.out, "vmf_ring", head, rows)


if __name__ == "__main__":
    main()
