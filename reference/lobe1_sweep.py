#!/usr/bin/env python3
"""Domain sweep of the scratch models' one-dimensional sampling lobes at f32 inputs (issue #20).

`kernel/src/bsdf/lobe1d.rs` truncates a mixture of up to three logistic, Cauchy or Gaussian
components to an interval [a, b] and provides its mass, its density and its inverse CDF
(the sampler of Werner §5 / Velinov as this project implements it: the disk-product lobes of
`kernel/src/bsdf/lobes.rs`, whose intervals are chords of the unit disk). Nothing here comes
from the kernel: every query draws its inputs in float64, rounds each to float32 and
evaluates at exactly those float32 values, with mpmath at 40 digits,

  mass    sum_j w_j (F_j(b) - F_j(a)),                 F_j(x) = F((x - mu_j)/s_j)
  pdf     sum_j w_j f_j(x) / mass  at a point x in [a, b]
  sample  the kernel's mapping of u in [0, 1) to x, exactly: component j chosen by
          u * mass against the running sums of w_j m_j, then v = (u mass - below)/(w_j m_j)
          and x = F_j^-1(F_j(a) + v (F_j(b) - F_j(a))), solved to 40 digits

with F the logistic 1/(1 + e^-z), the Cauchy 1/2 + atan(z)/pi and the Gaussian
erfc(-z/sqrt 2)/2. Each value carries its conditioning

    kappa = max over inputs y, over y -> nextafter_f32(y, +-inf), of |f(y') / f(y) - 1|

over every input (mu_j, s_j, w_j, a, b and x or u), the definition of the other sweeps.

Domain (log-uniform unless noted): scales s 1e-4 - 3 (the lobes' scales in direction
cosines: the base Gaussian lambda/(sqrt 8 pi sigma) from 4e-4, the Cauchy lambda/(pi W) up
to 2.6); centres 0 (as the lobes use them) or uniform in [-1, 1], mixtures of 2 - 3 components
of one kind with weights 0.05 - 1; intervals [c - h, c + h] with h 1e-4 - 1 and the interval
either around a centre, or off it by a gap g with g/s from 1e-3 to the kind's tail limit:
60 for the logistic and 12 for the Gaussian (f32 holds F down to 1e-38 only; beyond that the
kernel's lobe has no representable mass, see docs/stability.md), 1e4 for the Cauchy.

Usage: python3 reference/lobe1_sweep.py [--count N] [--seed-offset K] [--out DIR]
Writes DIR/lobe1.csv (default reference/golden/sweep/). ~1 min per 1 000 queries.
"""
import math

import mpmath as mp
import numpy as np

from sweep_io import f32, nudges, parse_args, progress, write_csv

mp.mp.dps = 40
KINDS = ["logistic", "cauchy", "gaussian"]  # Lobe1Kind codes 0, 1, 2
TAIL_LIMIT = {"logistic": 60.0, "cauchy": 1.0e4, "gaussian": 12.0}




def cdf(kind, z):
    """F(z), accurate on the side where it is small (z <= 0)."""
    if kind == "logistic":
        return 1 / (1 + mp.exp(-z))
    if kind == "cauchy":
        return mp.mpf(1) / 2 + mp.atan(z) / mp.pi
    return mp.erfc(-z / mp.sqrt(2)) / 2


def density(kind, z):
    if kind == "logistic":
        e = mp.exp(-abs(z))
        return e / (1 + e) ** 2
    if kind == "cauchy":
        return 1 / (mp.pi * (1 + z * z))
    return mp.exp(-z * z / 2) / mp.sqrt(2 * mp.pi)


def mass_one(kind, mu, s, a, b):
    if not b > a:
        return mp.mpf(0)
    za, zb = (mp.mpf(a) - mu) / s, (mp.mpf(b) - mu) / s
    if za >= 0:  # both right of the centre: the mirrored left tail
        return cdf(kind, -za) - cdf(kind, -zb)
    return cdf(kind, zb) - cdf(kind, za)


def inverse(kind, p, lo, hi):
    """z in [lo, hi] with F(z) = p (p on the small side, p <= F(0) or solved via 1 - F)."""
    lo, hi = mp.mpf(lo), mp.mpf(hi)
    f = lambda z: mp.log(cdf(kind, z)) - mp.log(p)
    if kind == "logistic":
        z0 = mp.log(p / (1 - p))
        return z0
    if kind == "cauchy":
        return mp.tan(mp.pi * (p - mp.mpf(1) / 2))
    # Gaussian: bisection on log F (monotone), then Newton to full precision.
    for _ in range(200):
        mid = (lo + hi) / 2
        if f(mid) < 0:
            lo = mid
        else:
            hi = mid
        if hi - lo <= mp.mpf(10) ** -12 * max(1, abs(lo)):
            break
    z = (lo + hi) / 2
    for _ in range(6):
        z = z - (cdf(kind, z) - p) / density(kind, z)
    return z


def sample_one(kind, mu, s, v, a, b):
    """The truncated inverse CDF of one component, mirrored into the left tail when the
    interval lies right of the centre (the kernel's mapping, evaluated exactly)."""
    za, zb = (mp.mpf(a) - mu) / s, (mp.mpf(b) - mu) / s
    flip = za >= 0
    if flip:
        lo, hi, v = -zb, -za, 1 - v
    else:
        lo, hi = za, zb
    f_lo, f_hi = cdf(kind, lo), cdf(kind, hi)
    p = f_lo + v * (f_hi - f_lo)
    if p <= mp.mpf(1) / 2:
        z = inverse(kind, p, lo, min(hi, 0) if hi > 0 else hi)
    else:
        # 1 - p = (1 - v) width + (1 - F(hi)) with 1 - F(hi) = F(-hi)
        q = (1 - v) * (f_hi - f_lo) + cdf(kind, -hi)
        z = -inverse(kind, q, -hi, 0)
    if flip:
        z = -z
    return mu + s * z


def evaluate(kind, comps, a, b, x, u):
    masses = [w * mass_one(kind, mu, s, a, b) for (mu, s, w) in comps]
    total = sum(masses)
    dens = sum(w * density(kind, (mp.mpf(x) - mu) / s) / s for (mu, s, w) in comps)
    pdf = dens / total if total > 0 and a <= x <= b else mp.mpf(0)
    sample = mp.mpf(0)
    if total > 0:
        target = mp.mpf(u) * total
        acc, pick, pick_mass, below = mp.mpf(0), None, mp.mpf(0), mp.mpf(0)
        for j, wm in enumerate(masses):
            if wm > 0:
                pick, pick_mass, below = j, wm, acc
                if target < acc + wm:
                    break
            acc += wm
        v = min(max((target - below) / pick_mass, 0), 1)
        mu, s, _ = comps[pick]
        sample = min(max(sample_one(kind, mu, s, v, a, b), mp.mpf(a)), mp.mpf(b))
    return total, pdf, sample


def draw(rng, i, n):
    kind = KINDS[i % 3]
    count = 1 if rng.random() < 0.7 else int(rng.integers(2, 4))
    comps = []
    for j in range(count):
        mu = 0.0 if (j == 0 and rng.random() < 0.5) else rng.uniform(-1, 1)
        s = 10 ** rng.uniform(-4, math.log10(3))
        w = 10 ** rng.uniform(math.log10(0.05), 0)
        comps.append((f32(mu), f32(s), f32(w)))
    mu0, s0, _ = comps[0]
    h = 10 ** rng.uniform(-4, 0)
    cls = rng.random()
    if cls < 0.4:  # around the first centre
        c = mu0 + rng.uniform(-1, 1) * h
    else:  # off it by a gap, either side
        g = s0 * 10 ** rng.uniform(-3, math.log10(TAIL_LIMIT[kind]))
        c = mu0 + (1 if rng.random() < 0.5 else -1) * (g + h)
    a, b = f32(c - h), f32(c + h)
    if not b > a:
        b = float(np.nextafter(np.float32(a), np.float32(np.inf)))
    x = f32(a + (b - a) * rng.random())
    x = min(max(x, a), b)
    u = f32(rng.random())
    return kind, comps, a, b, x, u


def nudged_components(comps):
    """Each mixture with one centre, scale or weight moved to a neighbouring float32
    (scales and weights kept positive)."""
    for j in range(len(comps)):
        for slot in range(3):
            for y in nudges(comps[j][slot]):
                c2 = [list(c) for c in comps]
                c2[j][slot] = y
                if c2[j][1] > 0 and c2[j][2] > 0:
                    yield [tuple(c) for c in c2]


def kappa(kind, comps, a, b, x, u, exact):
    worst = [0.0, 0.0, 0.0]

    def upd(vals):
        for k in range(3):
            if exact[k] != 0:
                worst[k] = max(worst[k], float(abs(vals[k] / exact[k] - 1)))

    for c2 in nudged_components(comps):
        upd(evaluate(kind, c2, a, b, x, u))
    for y in nudges(a):
        if y < b:
            upd(evaluate(kind, comps, y, b, min(max(x, y), b), u))
    for y in nudges(b):
        if y > a:
            upd(evaluate(kind, comps, a, y, min(max(x, a), y), u))
    for y in nudges(x):
        if a <= y <= b:
            upd(evaluate(kind, comps, a, b, y, u))
    for y in nudges(u):
        if 0 <= y < 1:
            upd(evaluate(kind, comps, a, b, x, y))
    return worst


def main():
    args = parse_args(1500)
    rng = np.random.default_rng(20_000 + args.seed_offset)
    head = ["kind", "count"]
    for j in range(3):
        head += [f"mu{j}", f"s{j}", f"w{j}"]
    head += ["a", "b", "x", "u", "mass_ref", "mass_kappa", "pdf_ref", "pdf_kappa", "sample_ref", "sample_kappa"]
    rows = []
    for i in range(args.count):
        kind, comps, a, b, x, u = draw(rng, i, args.count)
        exact = evaluate(kind, comps, a, b, x, u)
        ks = kappa(kind, comps, a, b, x, u, exact)
        padded = comps + [(0.0, 1.0, 0.0)] * (3 - len(comps))
        row = [str(KINDS.index(kind)), str(len(comps))]
        for mu, s, w in padded:
            row += [repr(np.float32(mu).item()), repr(np.float32(s).item()), repr(np.float32(w).item())]
        row += [repr(a), repr(b), repr(x), repr(u)]
        for k in range(3):
            row += [mp.nstr(exact[k], 17, min_fixed=1, max_fixed=0), "%.4g" % ks[k]]
        rows.append(row)
        progress(i + 1, args.count)
    write_csv(args.out, "lobe1", head, rows)


if __name__ == "__main__":
    main()
