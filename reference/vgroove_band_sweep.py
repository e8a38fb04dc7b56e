#!/usr/bin/env python3
"""Domain sweep of the V-groove band integral (issue #20): the quadrature that the area
lights run across the band for V-shaped grooves.

`kernel/src/lights/integrate.rs::across_integral` with `Profile::Triangle` returns

  I = int_{q0}^{q0 + len} |M - P|^2(q) dq      (um^2 / um)

for the inputs it receives as float32: the groove width W (um), depth D (um), the depth
phase 2 gamma / lambda in half-turns per um of depth (`ht`, 1/um), the start q0 and the
signed length len of a lit chord in xi_2 (1/um). With beta = pi W q and kappa = pi D ht
(radians), Werner's V profile (Eqs. 26, 29-31, as corrected in `kernel/src/scratch/profile.rs`)
gives

  M - P = W int_0^1 (1 - e^{i kappa (1 - u)}) cos(beta u) du,

evaluated as the mask `W sinc(beta)` less the profile's pole-free closed form
`refcore.closedform_triangle_sinc` (the reference behind the scratch goldens).

The integrand is entire in q and varies on the scale 1/W (its lobes are 1/W wide, its
peaks at W q = 0 and W q = +-D ht); here it is integrated at 30 digits by 16-point
Gauss-Legendre on pieces no wider than 1/(4 W), at exactly the float32 inputs (the upper
end q0 + len taken exactly). `--check` compares the closed form with mpmath quadrature of
the u integral, and the piecewise rule with mpmath's own quadrature in q.

Each query carries its conditioning kappa_c: the largest relative change of the exact value
when one float32 input moves to a neighbouring float32 (W, D and ht by recomputed
integrals; q0 and len through the integrand at the ends, which is the exact derivative).
The kernel test (`kernel/tests/vgroove_band_sweep.rs`) compares `across_integral` with
max(1e-4, 8 kappa_c) (`docs/stability.md` *The V-groove across the band*).

Domain: W 0.1 - 50 um and D 1 nm - 10 um (log-uniform), gamma 0.005 - 2 and lambda
360 - 830 nm (ht = 2 gamma / lambda); chords of three kinds: 35 % two ends anywhere on
the band (|q| <= 2/lambda, the lit ranges of lights up to the whole half circle), 40 %
around one of the integrand's features (q = 0 or a peak W q = +-D ht, offset by up to 10
lobes, length 1e-5 - 100 lobes, either sign), 25 % starting anywhere with a log-uniform
length 1e-6 - 4/lambda.

Usage: python3 reference/vgroove_band_sweep.py [--count N] [--seed-offset K] [--out DIR] [--jobs N] [--check]
Writes DIR/vgroove_band.csv (default reference/golden/sweep/); `--jobs N` writes the same
file as one process.
"""
import math
import random
import sys
import time

import mpmath as mp

from parallel import ordered_map
from refcore import closedform_triangle_sinc
from scratch_sweep import s32
from sweep_io import f32, gauss_legendre_mp, nudges, parse_args, progress, write_csv

mp.mp.dps = 30

FAMILY = "vgroove_band"
SEED = 20262012
# The Gauss-Legendre rule of each piece (nodes at 40 digits), and pieces per lobe 1/W.
GL_N = 16
PIECES_PER_LOBE = 4
GL = gauss_legendre_mp(GL_N)


def mask_minus_profile(w, kappa, q):
    """M - P of the V groove at xi_2 = q: the mask `W sinc(pi W q)` less the profile's
    pole-free closed form `refcore.closedform_triangle_sinc` (with 2 gamma D / lambda =
    kappa / pi, i.e. gamma = kappa / (2 pi D) at lambda = 1)."""
    beta = mp.pi * w * q
    mask = w * (mp.sin(beta) / beta if beta != 0 else 1)
    return mask - closedform_triangle_sinc(w, 1, kappa / (2 * mp.pi), 1, q)


def power(w, kappa, q):
    v = mask_minus_profile(w, kappa, q)
    return v.real ** 2 + v.imag ** 2


def band_integral(w, d, ht, q0, length, nodes=GL):
    """int_{q0}^{q0 + length} |M - P|^2 dq by Gauss-Legendre on pieces of at most 1/(4W)."""
    w, d, ht, q0, length = (mp.mpf(x) for x in (w, d, ht, q0, length))
    kappa = mp.pi * d * ht
    if length == 0:
        return mp.mpf(0)
    pieces = max(1, int(mp.ceil(abs(length) * w * PIECES_PER_LOBE)))
    h = length / pieces
    xs, ws = nodes
    total = mp.mpf(0)
    for p in range(pieces):
        mid = q0 + (p + mp.mpf(1) / 2) * h
        total += sum(wt * power(w, kappa, mid + h / 2 * x) for x, wt in zip(xs, ws))
    return total * h / 2


def conditioning(q, value):
    """Largest relative change of the exact value over one-ulp moves of each input."""
    if value == 0:
        return mp.mpf(0)
    worst = mp.mpf(0)
    for name in ("w", "d", "ht"):
        for moved in nudges(q[name]):
            other = dict(q, **{name: moved})
            v = band_integral(other["w"], other["d"], other["ht"], other["q0"], other["len"])
            worst = max(worst, abs(v - value))
    w, kappa = mp.mpf(q["w"]), mp.pi * mp.mpf(q["d"]) * mp.mpf(q["ht"])
    q0, length = mp.mpf(q["q0"]), mp.mpf(q["len"])
    f0, f1 = power(w, kappa, q0), power(w, kappa, q0 + length)
    for moved in nudges(q["q0"]):
        worst = max(worst, abs((f1 - f0) * (mp.mpf(moved) - q0)))
    for moved in nudges(q["len"]):
        worst = max(worst, abs(f1 * (mp.mpf(moved) - length)))
    return worst / abs(value)


def draw(rng):
    w = f32(10 ** rng.uniform(-1, math.log10(50)))
    d = f32(10 ** rng.uniform(-3, 1))
    gamma = 10 ** rng.uniform(math.log10(0.005), math.log10(2))
    lam = rng.uniform(0.36, 0.83)
    ht = f32(2 * gamma / lam)
    reach = 2 / lam
    kind = rng.random()
    if kind < 0.35:
        a, b = rng.uniform(-reach, reach), rng.uniform(-reach, reach)
        q0, length = f32(a), f32(b - a)
        kind_name = "anywhere"
    elif kind < 0.75:
        lobe = 1 / w
        centre = rng.choice([0.0, d * ht / w, -d * ht / w])
        offset = rng.choice([-1, 1]) * lobe * 10 ** rng.uniform(-3, 1)
        length = rng.choice([-1, 1]) * lobe * 10 ** rng.uniform(-5, 2)
        q0, length = f32(centre + offset - length / 2), f32(length)
        kind_name = "feature"
    else:
        q0 = f32(rng.uniform(-reach, reach))
        length = f32(rng.choice([-1, 1]) * 10 ** rng.uniform(-6, math.log10(4 / lam)))
        kind_name = "log-length"
    return {"kind": kind_name, "w": w, "d": d, "ht": ht, "q0": q0, "len": length}


def evaluate(q):
    value = band_integral(q["w"], q["d"], q["ht"], q["q0"], q["len"])
    return value, conditioning(q, value)


HEAD = ["kind", "w", "d", "ht", "q0", "len", "ref", "kappa"]


def row(q, value, kappa):
    return [q["kind"]] + [s32(q[k]) for k in ("w", "d", "ht", "q0", "len")] + [
        mp.nstr(value, 17, min_fixed=0, max_fixed=0),
        mp.nstr(kappa, 6, min_fixed=0, max_fixed=0),
    ]


def check(count=12):
    """The closed form against quadrature of the u integral; the piecewise rule against
    mpmath's quadrature in q (tanh-sinh, split at the lobes) and against 24 nodes."""
    rng = random.Random(SEED + 999)
    worst_form = worst_rule = worst_nodes = mp.mpf(0)
    ruled = 0
    for _ in range(count):
        q = draw(rng)
        w, kappa = mp.mpf(q["w"]), mp.pi * mp.mpf(q["d"]) * mp.mpf(q["ht"])
        for x in (q["q0"], q["q0"] + q["len"] / 3):
            beta = mp.pi * w * mp.mpf(x)
            direct = w * mp.quad(lambda u: (1 - mp.expj(kappa * (1 - u))) * mp.cos(beta * u), [0, 0.5, 1])
            got = mask_minus_profile(w, kappa, mp.mpf(x))
            worst_form = max(worst_form, abs(got - direct) / abs(direct))
        length = mp.mpf(q["len"])
        if abs(length) * w > 30:
            continue
        a = mp.mpf(q["q0"])
        pieces = max(1, int(mp.ceil(abs(length) * w * 2)))
        cuts = [a + length * k / pieces for k in range(pieces + 1)]
        want = mp.quad(lambda t: power(w, kappa, t), cuts)
        got = band_integral(q["w"], q["d"], q["ht"], q["q0"], q["len"])
        more = band_integral(q["w"], q["d"], q["ht"], q["q0"], q["len"], nodes=gauss_legendre_mp(24))
        worst_rule = max(worst_rule, abs(got - want) / abs(want))
        worst_nodes = max(worst_nodes, abs(got - more) / abs(want))
        ruled += 1
    print(f"closed form vs u quadrature: worst rel {mp.nstr(worst_form, 3)}")
    print(f"piecewise 16-point rule vs mp.quad in q ({ruled} chords of <= 30 lobes): worst rel {mp.nstr(worst_rule, 3)}")
    print(f"16 vs 24 nodes: worst rel {mp.nstr(worst_nodes, 3)}")
    assert ruled >= count // 2
    assert worst_form < 1e-20 and worst_rule < 1e-15 and worst_nodes < 1e-15


def main():
    if "--check" in sys.argv:
        check()
        return
    args = parse_args(1500, jobs=True)
    rng = random.Random(SEED + args.seed_offset)
    queries = [draw(rng) for _ in range(args.count)]
    t0 = time.time()
    rows = []
    for q, (v, k) in zip(queries, ordered_map(evaluate, queries, args.jobs)):
        rows.append(row(q, v, k))
        progress(len(rows), args.count)
    write_csv(args.out, FAMILY, HEAD, rows)
    print(f"{args.count} queries in {time.time() - t0:.0f} s", file=sys.stderr)


if __name__ == "__main__":
    main()
