//! The Faddeeva function `w(z) = e^{−z²} erfc(−iz)` in the closed upper half plane.
//!
//! Weideman's rational approximation (J. A. C. Weideman, "Computation of the complex error
//! function", SIAM J. Numer. Anal. 31(5), 1994) with N = 32:
//! `w(z) = 2 p(Z) / (L − iz)² + 1 / (√π (L − iz))`, `Z = (L + iz)/(L − iz)`.
//! One branch-free formula for the whole half plane (GPU friendly: no divergence, no
//! recursion). The coefficients come from `kernel/gen/math_consts.py`.
//!
//! Far from the origin, `|z|² ≥ 19.7`, a caller that knows its arguments lie there may take
//! the asymptotic series `w(z) ~ (i/(√π z)) Σ_{n≥0} (2n−1)!!/(2z²)^n` instead
//! ([`faddeeva_far_lanes`]; Abramowitz & Stegun 7.1.23 through `w(z) = e^{−z²} erfc(−iz)`):
//! eleven terms, a third of Weideman's chain. There its f32 error is at the rounding floor
//! (2.3e-7 relative at worst in a float32 emulation against mpmath, on and near the real
//! axis just above the threshold, where the series converges slowest and the neglected
//! `e^{−z²}` is below 1e-8 of `|w|`; `kernel/gen/faddeeva_asymptotic.py`). A choice per
//! lane would cost both forms wherever lanes differ, so the choice is the caller's, made
//! from what it knows of its arguments (`crate::math::gauss_interval`: a narrow interval's
//! Faddeeva form). Accuracy of both against mpmath: `kernel/tests/golden.rs`.

use super::complex::C32;
use crate::lane::{Cx, Real, branch};

const L: f32 = 4.756828460010884;
const COEFFS: [f32; 32] = [
    -1.3031797863050087e-12,
    3.7408812931653625e-12,
    8.03036789996389e-12,
    -2.154363207783877e-11,
    -5.5442359481664624e-11,
    1.1658251093523774e-10,
    4.153743091833453e-10,
    -5.231020481196329e-10,
    -3.208015091723369e-09,
    8.124889456846652e-10,
    2.3797556779897417e-08,
    2.2930439065099966e-08,
    -1.4813078915120977e-07,
    -4.1840763702169776e-07,
    4.2558331375750085e-07,
    4.40153173157855e-06,
    6.821031944001985e-06,
    -2.140961920171075e-05,
    -0.00013075449254615346,
    -0.0002453298027002143,
    0.0003925913607007031,
    0.004519541105349217,
    0.019006155784845408,
    0.05730440352983722,
    0.14060716226893769,
    0.2954445107150873,
    0.5460139720639341,
    0.9019254893647999,
    1.345544169234545,
    1.8256696296324815,
    2.2635372999002676,
    2.5722534081245696,
];

/// `1/z` by Smith's algorithm (no overflow or premature underflow for large |z|).
#[inline(always)]
fn crecip<R: Real>(z: Cx<R>) -> Cx<R> {
    let one = R::splat(1.0);
    branch!(
        z.re.abs().ge(z.im.abs()),
        {
            let r = z.im / z.re;
            let d = z.re + z.im * r;
            Cx::new(one / d, -r / d)
        },
        {
            let r = z.re / z.im;
            let d = z.re * r + z.im;
            Cx::new(r / d, -one / d)
        }
    )
}

/// Faddeeva function `w(z)` for `Im z ≥ 0` (for `Im z < 0` the argument is reflected to the
/// real axis' upper side; callers in this crate only pass `Im z ≥ 0`). |w| ≤ 1 there.
#[inline]
pub fn faddeeva(z: C32) -> C32 {
    faddeeva_lanes(Cx::from(z)).into()
}

/// [`faddeeva`] for any [`Real`]. Out of line on SPIR-V (as [`faddeeva_pair`]).
#[cfg_attr(not(target_arch = "spirv"), inline(always))]
#[cfg_attr(target_arch = "spirv", inline(never))]
pub fn faddeeva_lanes<R: Real>(z: Cx<R>) -> Cx<R> {
    let mut chain = settled::<R, _>(Chain::new(z));
    horner(&mut chain);
    settled::<R, _>(chain.value())
}

/// `(w(a), w(b))`: two Horner chains advanced in the same loop, so that their latencies
/// overlap. Out of line on SPIR-V: one copy of the 31 Horner steps in the shader
/// (every walk of every entry point calls it; the CPU keeps it inline in each lane type).
#[cfg_attr(not(target_arch = "spirv"), inline(always))]
#[cfg_attr(target_arch = "spirv", inline(never))]
pub fn faddeeva_pair<R: Real>(a: Cx<R>, b: Cx<R>) -> (Cx<R>, Cx<R>) {
    let mut chains = settled::<R, _>((Chain::new(a), Chain::new(b)));
    horner(&mut chains);
    settled::<R, _>((chains.0.value(), chains.1.value()))
}

/// The `|z|²` from which [`faddeeva_far_lanes`] may be used (module docs): `|z| ≥ 4.438`.
pub const FADDEEVA_FAR: f32 = 19.7;

/// The last power of `1/(2z²)` in [`faddeeva_far_lanes`]' series: its term
/// `19!!/(2|z|²)^10` is below 8e-8 at the threshold.
const ASYMPTOTIC_ORDER: f32 = 10.0;

/// `w(z)` for `|z|² ≥` [`FADDEEVA_FAR`] only (`Im z < 0` reflected as in [`faddeeva`]): the
/// asymptotic series `(i/(√π z)) Σ_{n≤10} (2n−1)!! (2z²)^{−n}` (A&S 7.1.23), nested as
/// `1 + u(1 + 3u(1 + 5u(…)))` with `u = 1/(2z²)` formed from `1/z` (no overflow of `z²`).
/// The caller guarantees the domain (nearer the origin the series is wrong); a third of
/// Weideman's Horner chain.
#[inline(always)]
pub fn faddeeva_far_lanes<R: Real>(z: Cx<R>) -> Cx<R> {
    let r = crecip(upper(z));
    let u = (r * r).scale(R::splat(0.5));
    let one = Cx::splat(1.0, 0.0);
    let mut t = one;
    // The odd factors 2n − 1 from n = 10 down to 1, counted in f32 (exact).
    let mut odd = 2.0 * ASYMPTOTIC_ORDER - 1.0;
    while odd > 0.0 {
        t = one + (u * t).scale(R::splat(odd));
        odd -= 2.0;
    }
    (r * t).mul_i().scale(R::splat(super::FRAC_1_SQRT_PI))
}

/// `z` with its imaginary part clamped at zero (the closed upper half plane).
#[inline(always)]
fn upper<R: Real>(z: Cx<R>) -> Cx<R> {
    Cx::new(z.re, super::max(z.im, R::splat(0.0)))
}

/// `x` unchanged, passed through memory for lane types on the CPU (`core::hint::black_box`);
/// the identity for `f32` (through memory the scalar Werner table ran 40 % slower) and on
/// SPIR-V. Around the Horner loop (the chains going in, the values coming out) it keeps
/// the loop's vector code independent of the code around the call: LLVM splits each lane
/// array into scalars and its SLP vectorizer packs them again, and how it packed the loop's
/// carried values depended on the rest of the SIMD batch (a change in the crossing walk
/// re-packed them across real and imaginary parts: 55 instructions per step instead of
/// 20, the frozen, summed batch 30 % slower). Through memory they come back as whole lane
/// arrays. Costs about 32 instructions per call (`profile_brdf`, callgrind).
#[inline(always)]
fn settled<R: Real, T>(x: T) -> T {
    #[cfg(not(target_arch = "spirv"))]
    {
        if R::LANES > 1 {
            core::hint::black_box(x)
        } else {
            x
        }
    }
    #[cfg(target_arch = "spirv")]
    {
        x
    }
}

/// One argument's evaluation of `w`: `q = 1/(L − iz)`, `Z = (L + iz) q` and the Horner
/// chain `p(Z)`; the one formula behind [`faddeeva`], [`faddeeva_lanes`] and
/// [`faddeeva_pair`].
#[derive(Clone, Copy)]
struct Chain<R: Real> {
    q: Cx<R>,
    big_z: Cx<R>,
    p: Cx<R>,
}

impl<R: Real> Chain<R> {
    #[inline(always)]
    fn new(z: Cx<R>) -> Self {
        let iz = upper(z).mul_i();
        // q = 1/(L − iz); |L − iz| ≥ L so q never blows up, and q² underflows benignly.
        let q = crecip(Cx::new(R::splat(L) - iz.re, -iz.im));
        Chain {
            q,
            big_z: Cx::new(R::splat(L) + iz.re, iz.im) * q,
            p: Cx::splat(COEFFS[0], 0.0),
        }
    }

    #[inline(always)]
    fn value(self) -> Cx<R> {
        (self.p * self.q * self.q).scale(R::splat(2.0))
            + self.q.scale(R::splat(super::FRAC_1_SQRT_PI))
    }
}

/// Chains advanced together by [`horner`] (a trait, not a closure: LLVM left such a
/// closure out of line, 31 calls per pair, and the SIMD batch ran 10 % slower).
trait Horner {
    /// One Horner step of each chain: `p ← p Z + coeff`.
    fn step(&mut self, coeff: f32);
}

impl<R: Real> Horner for Chain<R> {
    #[inline(always)]
    fn step(&mut self, coeff: f32) {
        self.p = self.p * self.big_z + Cx::splat(coeff, 0.0);
    }
}

impl<R: Real> Horner for (Chain<R>, Chain<R>) {
    #[inline(always)]
    fn step(&mut self, coeff: f32) {
        self.0.step(coeff);
        self.1.step(coeff);
    }
}

/// `chains.step(COEFFS[k])` for `k = 1, …, 31` in order.
///
/// The shader's form is written out with constant indices: an index that could be out of
/// range leaves a panic path, and on SPIR-V rust-gpu inlines every function that may panic
/// at each of its call sites (so that the abort reaches the entry point), which would copy
/// the whole Faddeeva path into every caller. The CPU keeps the loop: written out there,
/// the `scratchwave-cpu` release build ran past 14 CPU-min (4.5 with the loop).
#[inline(always)]
fn horner(chains: &mut impl Horner) {
    #[cfg(target_arch = "spirv")]
    {
        macro_rules! steps {
            ($($k:literal)*) => { $( chains.step(COEFFS[$k]); )* };
        }
        steps!(1 2 3 4 5 6 7 8 9 10 11 12 13 14 15 16 17 18 19 20 21 22 23 24 25 26 27 28 29 30 31);
    }
    #[cfg(not(target_arch = "spirv"))]
    for &coeff in &COEFFS[1..] {
        chains.step(coeff);
    }
}
