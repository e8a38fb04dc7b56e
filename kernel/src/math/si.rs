//! The sine integral `Si(x) = ∫_0^x sin(t)/t dt`, exact to `f32`, and Velinov's
//! approximation (Velinov 2018 Eq. 29).

/// Auxiliary-function fit for |x| > 6: `x f(x) = Σ SI_F[k] t^k`, `x² g(x) = Σ SI_G[k] t^k`,
/// `t = (6/x)²`, least squares against mpmath (`kernel/gen/math_consts.py`, max relative
/// error of the fit 1.1e-9, far below `f32` resolution).
const SI_F: [f32; 9] = [
    0.9999999849454331,
    -0.055552821139542234,
    0.01843301655883019,
    -0.014323104956903608,
    0.01578603907468461,
    -0.016464103814148933,
    0.012539796198580148,
    -0.005748820891817791,
    0.001163343338344256,
];
/// See [`SI_F`].
const SI_G: [f32; 9] = [
    0.9999998471736421,
    -0.16663862428070503,
    0.09170216957587946,
    -0.0961880983763514,
    0.1246159102867556,
    -0.140756744073892,
    0.11166484416934416,
    -0.0523735179291162,
    0.010747824629239826,
];

/// Horner evaluation of a 9-term polynomial.
#[inline]
fn poly9(c: &[f32; 9], t: f32) -> f32 {
    let mut acc = c[8];
    let mut k = 8;
    while k > 0 {
        k -= 1;
        acc = acc * t + c[k];
    }
    acc
}

/// `Si(x)`, accurate to a few `f32` ulps on the whole real line.
///
/// |x| ≤ 6: the power series `Σ (−1)^n x^{2n+1} / ((2n+1)(2n+1)!)` (terms shrink
/// monotonically after n = 3; 13 terms reach `f32` resolution at |x| = 6).
/// |x| > 6: `π/2 − f(x) cos x − g(x) sin x` with fitted auxiliary functions.
#[inline]
pub fn si(x: f32) -> f32 {
    let (asymptote, rest) = si_split(x);
    asymptote - rest
}

/// `Si(x) = asymptote − rest`: for |x| > 6, `asymptote = ±π/2` and `rest = ±(f cos x +
/// g sin x)` is the small tail (so differences of `Si` far out on one side can be taken
/// without cancelling against π/2); for |x| ≤ 6, `(0, −Si(x))`.
pub fn si_split(x: f32) -> (f32, f32) {
    let ax = super::abs(x);
    let s = super::sign(x);
    if ax <= 6.0 {
        let x2 = ax * ax;
        let mut term = ax; // x^{2n+1}/(2n+1)!
        let mut sum = ax;
        let mut n = 1;
        while n < 16 {
            let k = (2 * n) as f32;
            term *= -x2 / (k * (k + 1.0));
            sum += term / (k + 1.0);
            n += 1;
        }
        (0.0, -s * sum)
    } else {
        let t = 36.0 / (ax * ax);
        let f = poly9(&SI_F, t) / ax;
        let g = poly9(&SI_G, t) / (ax * ax);
        (
            s * 0.5 * super::PI,
            s * (f * super::cos(ax) + g * super::sin(ax)),
        )
    }
}

/// Velinov 2018 Eq. 29, as printed:
/// `Si(x) ≈ (π/2) tanh(x) − a0 x / (1 + (x − sgn(x) b0)²) + sgn(x) (1 − cos x)/(1 + |x|)`,
/// `a0 = 0.66142739`, `b0 = 0.38272292`. Its error is charted against [`si`] in the README.
#[inline]
pub fn si_velinov(x: f32) -> f32 {
    let (asymptote, rest) = si_velinov_split(x);
    asymptote - rest
}

/// [`si_velinov`] as `asymptote − rest`, like [`si_split`]: for |x| > 2, `(±π/2, ±((π/2)
/// (1 − tanh|x|) + a0|x|/(1 + (|x| − b0)²) − (1 − cos x)/(1 + |x|)))` with `1 − tanh|x| =
/// 2/(e^{2|x|} + 1)`; for |x| ≤ 2, `(0, −Si(x))`.
pub fn si_velinov_split(x: f32) -> (f32, f32) {
    const A0: f32 = 0.661_427_39;
    const B0: f32 = 0.382_722_92;
    let s = super::sign(x);
    let ax = super::abs(x);
    let d = ax - B0;
    let rational = A0 * ax / (1.0 + d * d);
    let oscillating = (1.0 - super::cos(ax)) / (1.0 + ax);
    if ax > 2.0 {
        let one_minus_tanh = 2.0 / (super::exp(2.0 * ax) + 1.0);
        let rest = 0.5 * super::PI * one_minus_tanh + rational - oscillating;
        (s * 0.5 * super::PI, s * rest)
    } else {
        (
            0.0,
            -s * (0.5 * super::PI * super::tanh(ax) - rational + oscillating),
        )
    }
}
