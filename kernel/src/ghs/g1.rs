//! Smith masking `G1` of the generalized Beckmann NDF (H&P Eqs. 40–42), from a `const`
//! table in `(v, p)`.
//!
//! `Λ(u) = ∫_{1/u}^∞ (r u − 1) P2(r) dr`, `u = β tanθ`, with the unit-β marginal
//! `P2(r) = p/(π Γ(1/p)) ∫_{−∞}^{∞} exp(−(r² + q²)^p) dq`. Eq. 40 prints the `q` integral
//! over `[0, ∞)`: that `P2` integrates to ½, and `p = 1` then misses Beckmann's Smith `G1`
//! — erratum, the factor 2 is restored here (checked against mpmath in `ghs_golden.rs`).
//!
//! The table stores `q = G1 · (1 + v)` with `v = u · m(p)`, `m(p) = Γ(3/(2p))/(π Γ(1/p))`
//! the mean positive slope of `P2`, so that `Λ ≈ v − ½` for large `v` and `q → 1` at both
//! ends. 4-point Lagrange interpolation in `ln v` and `ln p`; the generator measured a
//! maximum relative interpolation error of 1.5e-5 (see the table's header). Outside the
//! table: `G1 = 1` below `v_min` (Λ < 3e-13 there) and `G1 = 1/(v + ½)` above `v_max`.
//!
//! The table is read through a [`G1Table`] view: on the CPU it borrows the `const` table
//! ([`G1Table::BUILTIN`]); a GPU entry point binds the same numbers as a storage buffer
//! ([`G1Table::FLAT`] is what the host uploads). A 25 kB `const` array indexed at run time
//! would become a per-invocation private array on SPIR-V, which lavapipe cannot compile in
//! reasonable time.

use super::tables::g1_table::{G1_LNP_MAX, G1_LNP_MIN, G1_LNV_MAX, G1_LNV_MIN, G1_NP, G1_NV, G1_Q};
use crate::lane::{Real, branch};
use crate::math;

/// Smallest supported `p` (the table's first row; smaller values are clamped).
pub const P_MIN: f32 = 0.1;
/// Largest supported `p` (the table's last row; larger values are clamped).
pub const P_MAX: f32 = 4.0;

/// Read-only view of the G1 table: `q[row · G1_NV + col]`, `G1_NP` rows of `G1_NV` columns.
#[derive(Clone, Copy, Debug)]
pub struct G1Table<'a> {
    q: &'a [f32],
}

impl G1Table<'static> {
    /// The table as one flat row-major array (what a GPU host uploads).
    pub const FLAT: &'static [f32] = G1_Q.as_flattened();
    /// The compiled-in table (CPU).
    pub const BUILTIN: G1Table<'static> = G1Table { q: Self::FLAT };
}

impl<'a> G1Table<'a> {
    /// A view over a flat row-major copy of [`G1Table::FLAT`] (e.g. a GPU storage buffer).
    /// A shorter slice reads as 0 beyond its end rather than panicking.
    #[inline]
    pub fn from_flat(q: &'a [f32]) -> Self {
        G1Table { q }
    }
}

/// Mean positive slope of the unit-β marginal `P2`: `m(p) = Γ(3/(2p)) / (π Γ(1/p))`.
#[inline]
pub fn mean_slope(p: f32) -> f32 {
    math::exp(math::lgamma(1.5 / p) - math::lgamma(1.0 / p)) / math::PI
}

/// Weights of 4-point Lagrange interpolation at `t` for nodes at −1, 0, 1, 2.
#[inline(always)]
fn lagrange4<R: Real>(t: R) -> [R; 4] {
    let c = R::splat;
    let (one, two) = (c(1.0), c(2.0));
    [
        -t * (t - one) * (t - two) * c(1.0 / 6.0),
        (t + one) * (t - one) * (t - two) * c(0.5),
        -(t + one) * t * (t - two) * c(0.5),
        (t + one) * t * (t - one) * c(1.0 / 6.0),
    ]
}

/// Cell index (clamped to `[1, n − 3]`, as a float) and fractional offset of `x` on a
/// uniform grid.
#[inline(always)]
fn cell<R: Real>(x: R, lo: f32, hi: f32, n: usize) -> (R, R) {
    let c = R::splat;
    let f = (x - c(lo)) / c(hi - lo) * c((n - 1) as f32);
    let fl = math::clamp(f.floor(), c(1.0), c((n - 3) as f32));
    (fl, f - fl)
}

/// `G1` for the precomputed `v = β tanθ · m(p)` and `ln p` (clamped to the table).
pub fn g1_from_v(table: &G1Table, v: f32, ln_p: f32) -> f32 {
    g1_from_v_lanes(table, v, ln_p)
}

/// [`g1_from_v`] for any [`Real`] `v` (the one formula; each lane reads its own table
/// column, the row is shared).
#[inline(always)]
pub fn g1_from_v_lanes<R: Real>(table: &G1Table, v: R, ln_p: f32) -> R {
    let c = R::splat;
    let lnv = v.ln();
    let flat = !v.gt(c(0.0)) | lnv.le(c(G1_LNV_MIN));
    let tail = lnv.ge(c(G1_LNV_MAX));
    branch!(
        flat | tail,
        R::select(flat, c(1.0), c(1.0) / (v + c(0.5))),
        {
            let lnp = math::clamp(ln_p, G1_LNP_MIN, G1_LNP_MAX);
            let (iv, tv) = cell(lnv, G1_LNV_MIN, G1_LNV_MAX, G1_NV);
            let (ip, tp) = cell(lnp, G1_LNP_MIN, G1_LNP_MAX, G1_NP);
            let wv = lagrange4(tv);
            let wp = lagrange4(tp);
            let mut q = c(0.0);
            let mut a = 0;
            while a < 4 {
                // Row `ip + a − 1`, column `iv + b − 1`: integers far below 2²⁴, exact.
                let row_start = (ip + a as f32 - 1.0) * G1_NV as f32;
                let mut s = c(0.0);
                let mut b = 0;
                while b < 4 {
                    let i = c(row_start) + iv + c(b as f32 - 1.0);
                    s = s + wv[b] * R::gather(table.q, i);
                    b += 1;
                }
                q = q + c(wp[a]) * s;
                a += 1;
            }
            math::clamp(q / (c(1.0) + v), c(0.0), c(1.0))
        },
    )
}

/// `G1(θ)` for `tanθ = tan_theta`, width `β` and kurtosis `p` (Eq. 42), from the builtin
/// table.
pub fn smith_g1(tan_theta: f32, beta: f32, p: f32) -> f32 {
    let p = math::clamp(p, P_MIN, P_MAX);
    g1_from_v(
        &G1Table::BUILTIN,
        beta * tan_theta * mean_slope(p),
        math::ln(p),
    )
}
