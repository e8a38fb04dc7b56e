//! The Faddeeva function `w(z) = e^{−z²} erfc(−iz)` in the closed upper half plane.
//!
//! Weideman's rational approximation (J. A. C. Weideman, "Computation of the complex error
//! function", SIAM J. Numer. Anal. 31(5), 1994) with N = 32:
//! `w(z) = 2 p(Z) / (L − iz)² + 1 / (√π (L − iz))`, `Z = (L + iz)/(L − iz)`.
//! One branch-free formula for the whole half plane (GPU friendly: no divergence, no
//! recursion). The coefficients come from `kernel/gen/math_consts.py`. Accuracy against
//! mpmath is measured by `kernel/tests/faddeeva.rs`.

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
    faddeeva_chains([Cx::from(z)])[0].into()
}

/// [`faddeeva`] for any [`Real`].
#[inline(always)]
pub fn faddeeva_lanes<R: Real>(z: Cx<R>) -> Cx<R> {
    faddeeva_chains([z])[0]
}

/// `(w(a), w(b))`: two Horner chains advanced in the same loop, so that their latencies
/// overlap.
#[inline(always)]
pub fn faddeeva_pair<R: Real>(a: Cx<R>, b: Cx<R>) -> (Cx<R>, Cx<R>) {
    let w = faddeeva_chains([a, b]);
    (w[0], w[1])
}

/// `w(z)` for `N` independent arguments at once: the one formula behind [`faddeeva`],
/// [`faddeeva_lanes`] and [`faddeeva_pair`].
#[inline(always)]
fn faddeeva_chains<R: Real, const N: usize>(z: [Cx<R>; N]) -> [Cx<R>; N] {
    let c = R::splat;
    let zero = Cx::splat(0.0, 0.0);
    let mut q = [zero; N];
    let mut big_z = [zero; N];
    let mut p = [Cx::splat(COEFFS[0], 0.0); N];
    let mut l = 0;
    while l < N {
        let zl = Cx::new(z[l].re, super::max(z[l].im, c(0.0)));
        let iz = zl.mul_i();
        // q = 1/(L − iz); |L − iz| ≥ L so q never blows up, and q² underflows benignly.
        q[l] = crecip(Cx::new(c(L) - iz.re, -iz.im));
        big_z[l] = Cx::new(c(L) + iz.re, iz.im) * q[l];
        l += 1;
    }
    let mut k = 1;
    while k < 32 {
        let mut l = 0;
        while l < N {
            p[l] = p[l] * big_z[l] + Cx::splat(COEFFS[k], 0.0);
            l += 1;
        }
        k += 1;
    }
    let mut out = [zero; N];
    let mut l = 0;
    while l < N {
        out[l] = (p[l] * q[l] * q[l]).scale(c(2.0)) + q[l].scale(c(super::FRAC_1_SQRT_PI));
        l += 1;
    }
    out
}
