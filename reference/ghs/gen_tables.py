#!/usr/bin/env python3
"""Generates the GHS kernel's `const` tables (std side; the GPU cannot compute them).

Writes
  kernel/src/ghs/tables/g1_table.rs        Smith G1 of the generalized Beckmann NDF
  kernel/src/ghs/tables/gauss_legendre.rs  Gauss-Legendre rule for the sigma_rel^2 quadrature

G1 route used here (the golden reference in generate.py uses a different one: the nested
integrals of Eqs. 40-41): for an isotropic slope distribution with radial density
p_rho, Smith's Lambda is the average over the slope radius rho of the azimuthal
integral (1/2pi) * int (t cos(phi) - 1)^+ dphi = (1/pi)(sqrt(t^2-1) - acos(1/t)), t = u*rho,
u = beta*tan(theta). With y = rho^(2p) ~ Gamma(1/p, 1) (unit beta):
  Lambda(u) = E_y[ h(u * y^(1/(2p))) ],  h(t) = (sqrt(t^2-1) - acos(1/t))/pi for t > 1.

Table: q(v, p) = G1 * (1 + v) with v = u * m(p), m(p) = Gamma(3/(2p)) / (pi Gamma(1/p)) the
mean positive 1-D slope (so Lambda ~ v - 1/2 for large v and q -> 1 at both ends), on a
uniform grid in ln v x ln p; the kernel interpolates with 4-point Lagrange in each axis.
The script also measures that interpolation error at cell centres and writes it in the
generated file's header.
"""
import math
import os
import sys

import numpy as np
from scipy import integrate, special

ROOT = os.path.normpath(os.path.join(os.path.dirname(__file__), "..", ".."))
OUT = os.path.join(ROOT, "kernel", "src", "ghs", "tables")

LNV_MIN, LNV_MAX, NV = -8.0, 10.0, 160
LNP_MIN, LNP_MAX, NP = math.log(0.1), math.log(4.0), 40
GL_N = 20


def mean_slope(p):
    return math.exp(special.gammaln(1.5 / p) - special.gammaln(1.0 / p)) / math.pi


def h(t):
    if t <= 1.0:
        return 0.0
    return (math.sqrt(t * t - 1.0) - math.acos(1.0 / t)) / math.pi


def smith_lambda(u, p):
    """Lambda(u) for unit beta, by quadrature over y ~ Gamma(1/p)."""
    a = 1.0 / p
    y0 = u ** (-2.0 * p)  # h vanishes below
    lg = special.gammaln(a)

    def f(ly):  # integrate in ln y for the wide spread of small p
        y = math.exp(ly)
        return h(u * y ** (0.5 / p)) * math.exp(a * ly - y - lg)

    lo = math.log(y0)
    hi = max(lo, math.log(a)) + 60.0
    # split at the mode of y^a e^-y (y = a) and a few decades around it
    pts = sorted({lo, hi} | {x for x in (math.log(a) - 3, math.log(a), math.log(a) + 1.5, lo + 0.01, lo + 0.3) if lo < x < hi})
    total = 0.0
    for x0, x1 in zip(pts[:-1], pts[1:]):
        v, _ = integrate.quad(f, x0, x1, epsabs=0.0, epsrel=1e-12, limit=400)
        total += v
    return total


def q_value(lnv, lnp):
    p = math.exp(lnp)
    v = math.exp(lnv)
    u = v / mean_slope(p)
    lam = smith_lambda(u, p)
    return (1.0 + v) / (1.0 + lam)


def lagrange4(xs, t):
    """Weights of 4-point Lagrange interpolation at fractional position t in [0,1] of the
    middle cell (nodes at -1, 0, 1, 2)."""
    return (
        -t * (t - 1) * (t - 2) / 6.0,
        (t + 1) * (t - 1) * (t - 2) / 2.0,
        -(t + 1) * t * (t - 2) / 2.0,
        (t + 1) * t * (t - 1) / 6.0,
    )


def interp(table, lnv, lnp):
    """Mirror of the kernel's interpolation (kernel/src/ghs/g1.rs)."""
    fv = (lnv - LNV_MIN) / (LNV_MAX - LNV_MIN) * (NV - 1)
    fp = (lnp - LNP_MIN) / (LNP_MAX - LNP_MIN) * (NP - 1)
    iv = min(max(int(math.floor(fv)), 1), NV - 3)
    ip = min(max(int(math.floor(fp)), 1), NP - 3)
    wv = lagrange4(None, fv - iv)
    wp = lagrange4(None, fp - ip)
    s = 0.0
    for a in range(4):
        for b in range(4):
            s += wp[a] * wv[b] * table[ip - 1 + a][iv - 1 + b]
    return s


def fmt_rows(rows, per_line=6):
    out = []
    for row in rows:
        out.append("    [")
        for i in range(0, len(row), per_line):
            out.append("        " + " ".join(f"{x:.9e}," for x in row[i:i + per_line]))
        out.append("    ],")
    return "\n".join(out)


def fmt_flat(xs, per_line=6):
    xs = list(xs)
    return "\n".join("    " + " ".join(f"{x:.9e}," for x in xs[i:i + per_line]) for i in range(0, len(xs), per_line))


def main():
    lnvs = np.linspace(LNV_MIN, LNV_MAX, NV)
    lnps = np.linspace(LNP_MIN, LNP_MAX, NP)
    table = [[q_value(lv, lp) for lv in lnvs] for lp in lnps]
    # interpolation error at cell centres (worst case for Lagrange) over the interior
    hv = (LNV_MAX - LNV_MIN) / (NV - 1)
    hp = (LNP_MAX - LNP_MIN) / (NP - 1)
    max_err = 0.0
    worst = None
    for j in range(0, NP - 1):
        for i in range(0, NV - 1, 2):
            lv = LNV_MIN + (i + 0.5) * hv
            lp = LNP_MIN + (j + 0.5) * hp
            exact = q_value(lv, lp)
            err = abs(interp(table, lv, lp) / exact - 1.0)
            if err > max_err:
                max_err, worst = err, (math.exp(lv), math.exp(lp))
    # end behaviour: at v_min Lambda must be negligible, at v_max the 1/v extrapolation holds
    lam_lo = max(1.0 / (table[j][0] / (1 + math.exp(LNV_MIN))) - 1.0 for j in range(NP))
    print(f"G1 table {NP}x{NV}: max interpolation rel err {max_err:.3e} at v={worst[0]:.3g}, p={worst[1]:.3g}; max Lambda at v_min {lam_lo:.2e}", file=sys.stderr)

    with open(os.path.join(OUT, "g1_table.rs"), "w") as f:
        f.write(f"""//! GENERATED by `reference/ghs/gen_tables.py` — do not edit.
//!
//! `q(v, p) = G1 · (1 + v)` for the generalized Beckmann NDF, `v = β tanθ · m(p)`,
//! `m(p) = Γ(3/(2p)) / (π Γ(1/p))`, on a uniform grid in `ln v ∈ [{LNV_MIN}, {LNV_MAX}]`
//! ({NV} nodes) × `ln p ∈ [ln 0.1, ln 4]` ({NP} nodes). 4-point Lagrange interpolation in
//! each axis: max relative error {max_err:.2e} at cell centres (measured by the generator
//! against direct quadrature; worst at v = {worst[0]:.3g}, p = {worst[1]:.3g}).
//! Below `v_min`, Λ < {lam_lo:.1e}.

/// `ln v` of the first column.
pub const G1_LNV_MIN: f32 = {LNV_MIN:.1f};
/// `ln v` of the last column.
pub const G1_LNV_MAX: f32 = {LNV_MAX:.1f};
/// `ln p` of the first row.
pub const G1_LNP_MIN: f32 = {LNP_MIN:.9e};
/// `ln p` of the last row.
pub const G1_LNP_MAX: f32 = {LNP_MAX:.9e};
/// Columns (`ln v`).
pub const G1_NV: usize = {NV};
/// Rows (`ln p`).
pub const G1_NP: usize = {NP};

/// `q[p_row][v_col]`. A `const`, not a `static`: rust-gpu kernels cannot use statics.
#[rustfmt::skip]
#[allow(clippy::large_const_arrays)]
pub const G1_Q: [[f32; {NV}]; {NP}] = [
{fmt_rows(table)}
];
""")

    x, w = np.polynomial.legendre.leggauss(GL_N)
    # Gauss-Legendre on t in [0, pi] composed with xi = (1 - cos t)/2: the rule for
    # int_0^1 g(xi) dxi used by sigma_rel^2 (kernel/src/ghs/spread.rs), nodes and weights
    # precomputed so the kernel does no trigonometry for them.
    t = 0.5 * np.pi * (x + 1.0)
    xi = 0.5 * (1.0 - np.cos(t))
    ws = 0.5 * np.pi * w * 0.5 * np.sin(t)
    with open(os.path.join(OUT, "gauss_legendre.rs"), "w") as f:
        f.write(f"""//! GENERATED by `reference/ghs/gen_tables.py` — do not edit.
//!
//! {GL_N}-point Gauss–Legendre rule in `t ∈ [0, π]` (numpy.polynomial.legendre.leggauss)
//! composed with `ξ = (1 − cos t)/2`: `∫₀¹ g(ξ) dξ ≈ Σ GL_WS[k] g(GL_XI[k])`. The
//! substitution makes square-root endpoint singularities of `g` smooth.

/// Number of nodes.
pub const GL_N: usize = {GL_N};
/// Nodes `ξ_k ∈ (0, 1)`.
#[rustfmt::skip]
pub const GL_XI: [f32; {GL_N}] = [
{fmt_flat(xi)}
];
/// Weights `(π/2) w_k · sin(t_k)/2` (sum 1).
#[rustfmt::skip]
pub const GL_WS: [f32; {GL_N}] = [
{fmt_flat(ws)}
];
""")


if __name__ == "__main__":
    main()
