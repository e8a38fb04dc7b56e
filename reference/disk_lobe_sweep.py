#!/usr/bin/env python3
"""Domain sweep of the scratch models' two-dimensional sampling lobes (issue #20).

`kernel/src/bsdf/lobes.rs`'s `DiskLobe` samples `wi` given `wo` in the projected disk of
`d = (wi + wo)_xy`: `d.e1` from a one-dimensional lobe `l1` truncated to the disk's extent
`[c1 - 1, c1 + 1]` (`c = wo_xy`), then `d.e2` from `l2` truncated to the chord
`[c2 - h, c2 + h]`, `h = sqrt(1 - a^2)`, `a = d.e1 - c1`; `wi = (a e1 + b e2, sqrt(h^2 - b^2))`.
Its solid-angle density at `wi` is `p1(a + c1) p2(b + c2) wi.z`. The lobes are those the
kernel builds (`bsdf/mixture.rs`): the base response's Gaussian (Werner Eq. 21) on both
axes, and a scratch's logistic along its tangent times a Cauchy (or, for a V-groove, a
three-Cauchy mixture) across it.

Nothing here comes from the kernel: the one-dimensional masses, densities and inverse CDFs
are `lobe1_sweep.py`'s exact mpmath forms (40 digits), composed at exactly the float32
inputs (e1 and wi normalised exactly). Each value carries its conditioning, the largest
change of the exact value when one input (e1, every lobe parameter, wo, wi or u) moves to a
neighbouring float32, measured as the error is: relative for the pdf; for the sample, the
angle to the exact direction divided by the lobes' smallest scale (capped at 1), the
angular size of the lobe.

Domain: base lobes (40 %): e1 = x, Gaussian scale 4e-4 - 0.1 (lambda/(sqrt 8 pi sigma)
for sigma 1 - 100 um, lambda 360 - 830 nm); scratch lobes (60 %): e1 at any angle (10 % on
an axis), logistic scale 2e-4 - 100 along, Cauchy scale 2.3e-3 - 2.6 across (lambda/(pi W),
W 0.1 - 50 um), 30 % V-groove mixtures (centres 0, +-c with c 1e-3 - 3, weights 1/2, 1/4,
1/4, scales s, 2s, 2s). wo with cos(theta) 0.005 - 1 (20 % with 1 - cos(theta) 1e-9 - 0.1),
any azimuth. wi: near the lobe (40 %: d within 0.1 - 10 scales of 0), grazing (30 %:
wi.z 1e-6 - 1e-2, any azimuth) or anywhere (30 %). u uniform, 15 % of each coordinate
within 1e-6 of 0 or 1. Queries whose chord holds no f32-representable mass (a Gaussian
interval more than ~12 scales from its centre) are drawn again: the kernel's lobe carries
nothing there by design (docs/stability.md, Sampling lobes).

Usage: python3 reference/disk_lobe_sweep.py [--count N] [--seed-offset K] [--out DIR]
Writes DIR/disk_lobe.csv (default reference/golden/sweep/).
"""
import math

import mpmath as mp
import numpy as np

from lobe1_sweep import KINDS, evaluate, nudged_components
from sweep_io import angle, draw_wo, f32, nudges, parse_args, progress, unit, write_csv

mp.mp.dps = 40
MASS_FLOOR = mp.mpf("1e-30")



def frame(e1, wo):
    e = unit([e1[0], e1[1]])
    e2 = [-e[1], e[0]]
    c1 = mp.mpf(wo[0]) * e[0] + mp.mpf(wo[1]) * e[1]
    c2 = mp.mpf(wo[0]) * e2[0] + mp.mpf(wo[1]) * e2[1]
    return e, e2, c1, c2


def lobe_eval(lobe, a, b, x, u):
    kind, comps = lobe
    return evaluate(kind, comps, a, b, x, u)


def pdf(e1, l1, l2, wo, wi):
    """(density, smallest interval mass)."""
    e, e2, c1, c2 = frame(e1, wo)
    w = unit(wi)
    if not w[2] > 0:
        return mp.mpf(0), mp.mpf(0)
    a = w[0] * e[0] + w[1] * e[1]
    b = w[0] * e2[0] + w[1] * e2[1]
    h = mp.sqrt(1 - a * a)
    m1, p1, _ = lobe_eval(l1, c1 - 1, c1 + 1, a + c1, 0.5)
    m2, p2, _ = lobe_eval(l2, c2 - h, c2 + h, b + c2, 0.5)
    return p1 * p2 * w[2], min(m1, m2)


def sample(e1, l1, l2, wo, u):
    """(direction, smallest interval mass)."""
    e, e2, c1, c2 = frame(e1, wo)
    m1, _, d1 = lobe_eval(l1, c1 - 1, c1 + 1, c1, u[0])
    a = min(max(d1 - c1, mp.mpf(-1)), mp.mpf(1))
    h = mp.sqrt(1 - a * a)
    m2, _, d2 = lobe_eval(l2, c2 - h, c2 + h, c2, u[1])
    b = min(max(d2 - c2, -h), h)
    z = mp.sqrt(h * h - b * b)
    return [a * e[0] + b * e2[0], a * e[1] + b * e2[1], z], min(m1, m2)


def width(l1, l2):
    return min(1.0, min(s for (_, s, _) in l1[1]), min(s for (_, s, _) in l2[1]))



def lobe_text(lobe):
    kind, comps = lobe
    padded = comps + [(0.0, 1.0, 0.0)] * (3 - len(comps))
    out = [str(KINDS.index(kind)), str(len(comps))]
    for mu, s, w in padded:
        out += [repr(mu), repr(s), repr(w)]
    return out


def draw(rng):
    if rng.random() < 0.4:
        s = f32(10 ** rng.uniform(math.log10(4e-4), -1))
        e1 = [1.0, 0.0]
        l1 = l2 = ("gaussian", [(0.0, s, 1.0)])
    else:
        phi = rng.integers(0, 4) * math.pi / 2 if rng.random() < 0.1 else rng.uniform(0, 2 * math.pi)
        e1 = [f32(math.cos(phi)), f32(math.sin(phi))]
        l1 = ("logistic", [(0.0, f32(10 ** rng.uniform(math.log10(2e-4), 2)), 1.0)])
        sc = f32(10 ** rng.uniform(math.log10(2.3e-3), math.log10(2.6)))
        if rng.random() < 0.3:
            c = f32(10 ** rng.uniform(-3, math.log10(3)))
            l2 = ("cauchy", [(0.0, sc, 0.5), (c, f32(2 * sc), 0.25), (-c, f32(2 * sc), 0.25)])
        else:
            l2 = ("cauchy", [(0.0, sc, 1.0)])
    wo = draw_wo(rng)
    cls = rng.random()
    if cls < 0.4:
        scale = width(l1, l2)
        r, q = scale * 10 ** rng.uniform(-1, 1), rng.uniform(0, 2 * math.pi)
        x, y = r * math.cos(q) - wo[0], r * math.sin(q) - wo[1]
        n2 = x * x + y * y
        if n2 >= 1:
            x, y = x / math.sqrt(n2) * 0.999, y / math.sqrt(n2) * 0.999
            n2 = x * x + y * y
        v = [x, y, math.sqrt(1 - n2)]
    elif cls < 0.7:
        z, q = 10 ** rng.uniform(-6, -2), rng.uniform(0, 2 * math.pi)
        r = math.sqrt(1 - z * z)
        v = [r * math.cos(q), r * math.sin(q), z]
    else:
        z = 10 ** rng.uniform(math.log10(0.005), 0)
        r, q = math.sqrt(1 - z * z), rng.uniform(0, 2 * math.pi)
        v = [r * math.cos(q), r * math.sin(q), z]
    wi = [f32(c) for c in v]
    u = []
    for _ in range(2):
        r = rng.random()
        if r < 0.075:
            u.append(f32(10 ** rng.uniform(-6, -2) * rng.random()))
        elif r < 0.15:
            u.append(f32(1 - 10 ** rng.uniform(-6, -2)))
        else:
            u.append(f32(rng.random()))
    return e1, l1, l2, wo, wi, u


def nudged_lobes(lobe):
    kind, comps = lobe
    for c2 in nudged_components(comps):
        yield (kind, c2)


def vary(vec):
    for i in range(len(vec)):
        for y in nudges(vec[i]):
            v2 = list(vec)
            v2[i] = y
            yield v2


def conditioning(e1, l1, l2, wo, wi, u, p, d):
    kp, ks = 0.0, 0.0
    wd = width(l1, l2)

    def both(e1_, l1_, l2_, wo_, wi_=None, u_=None):
        nonlocal kp, ks
        if wi_ is not None and p != 0:
            kp = max(kp, float(abs(pdf(e1_, l1_, l2_, wo_, wi_)[0] / p - 1)))
        if u_ is not None:
            ks = max(ks, float(angle(sample(e1_, l1_, l2_, wo_, u_)[0], d)) / wd)

    for e in vary(e1):
        both(e, l1, l2, wo, wi, u)
    for l in nudged_lobes(l1):
        both(e1, l, l2, wo, wi, u)
    for l in nudged_lobes(l2):
        both(e1, l1, l, wo, wi, u)
    for w in vary(wo):
        both(e1, l1, l2, w, wi, u)
    for w in vary(wi):
        if w[2] > 0:
            both(e1, l1, l2, wo, wi_=w)
    for v in vary(u):
        if 0 <= v[0] < 1 and 0 <= v[1] < 1:
            both(e1, l1, l2, wo, u_=v)
    return kp, ks


def main():
    args = parse_args(1500)
    rng = np.random.default_rng(22_000 + args.seed_offset)
    head = ["e1_x", "e1_y"]
    for name in ["l1", "l2"]:
        head += [f"{name}_kind", f"{name}_count"]
        for j in range(3):
            head += [f"{name}_mu{j}", f"{name}_s{j}", f"{name}_w{j}"]
    head += ["wo_x", "wo_y", "wo_z", "wi_x", "wi_y", "wi_z", "u_x", "u_y"]
    head += ["pdf_ref", "pdf_kappa", "sample_x", "sample_y", "sample_z", "sample_kappa"]
    rows = []
    while len(rows) < args.count:
        e1, l1, l2, wo, wi, u = draw(rng)
        p, pm = pdf(e1, l1, l2, wo, wi)
        d, sm = sample(e1, l1, l2, wo, u)
        if pm < MASS_FLOOR or sm < MASS_FLOOR:
            continue
        kp, ks = conditioning(e1, l1, l2, wo, wi, u, p, d)
        row = [repr(x) for x in e1] + lobe_text(l1) + lobe_text(l2)
        row += [repr(x) for x in wo + wi + u]
        row += [mp.nstr(p, 17, min_fixed=1, max_fixed=0), "%.4g" % kp]
        row += [mp.nstr(c, 17, min_fixed=1, max_fixed=0) for c in unit(d)]
        row += ["%.4g" % ks]
        rows.append(row)
        progress(len(rows), args.count)
    write_csv(args.out, "disk_lobe", head, rows)


if __name__ == "__main__":
    main()
