//! Wavelengths of the spectrum modes, the CIE 1931 2° colour-matching functions and
//! XYZ → linear sRGB.
//!
//! The colour-matching functions are the multi-lobe piecewise-Gaussian fit of C. Wyman,
//! P.-P. Sloan and P. Shirley, "Simple Analytic Approximations to the CIE XYZ Color Matching
//! Functions", JCGT 2(2), 2013 (their Eq. 2 with the coefficients of their Table 1). Spectral
//! rendering takes `N` midpoint samples `λ_k = 380 + (k + ½)·400/N` nm and normalises so that
//! a spectrum equal to 1 everywhere has `Y = 1`:
//! `XYZ = Σ_k L(λ_k) c̄(λ_k) / Σ_k ȳ(λ_k)`.

use crate::math;

gpu_enum! {
    /// How a pixel's spectrum becomes R, G, B.
    pub enum SpectrumMode {
        /// One wavelength, written to R, G and B alike.
        Single = 0,
        /// 700/520/440 nm into R/G/B (Werner 2017 §5's RGB mode).
        Rgb = 1,
        /// `N` wavelengths integrated against the CIE 1931 2° observer to linear sRGB.
        Spectral = 2,
    }
    fallback = Single;
}

/// Lower end of the spectral range (nm).
pub const SPECTRAL_MIN_NM: f32 = 380.0;
/// Width of the spectral range (nm).
pub const SPECTRAL_RANGE_NM: f32 = 400.0;
/// The RGB mode's wavelengths (nm): R, G, B.
pub const RGB_NM: [f32; 3] = [700.0, 520.0, 440.0];

/// Wavelength (nm) of sample `k` of `n` in spectral mode.
#[inline]
pub fn spectral_lambda_nm(k: u32, n: u32) -> f32 {
    SPECTRAL_MIN_NM + (k as f32 + 0.5) * SPECTRAL_RANGE_NM / n as f32
}

/// Wyman et al.'s piecewise Gaussian: `exp(−½ ((λ − μ)/σ)²)`, `σ = σ1` left of `μ`, `σ2`
/// right of it.
#[inline]
fn g(lambda: f32, mu: f32, s1: f32, s2: f32) -> f32 {
    let t = (lambda - mu) / if lambda < mu { s1 } else { s2 };
    math::exp(-0.5 * t * t)
}

/// CIE 1931 2° `(x̄, ȳ, z̄)` at λ (nm), Wyman, Sloan & Shirley 2013 multi-lobe fit.
#[inline]
pub fn cie_xyz(lambda_nm: f32) -> [f32; 3] {
    let l = lambda_nm;
    let x = 1.056 * g(l, 599.8, 37.9, 31.0) + 0.362 * g(l, 442.0, 16.0, 26.7)
        - 0.065 * g(l, 501.1, 20.4, 26.2);
    let y = 0.821 * g(l, 568.8, 46.9, 40.5) + 0.286 * g(l, 530.9, 16.3, 31.1);
    let z = 1.217 * g(l, 437.0, 11.8, 36.0) + 0.681 * g(l, 459.0, 26.0, 13.8);
    [x, y, z]
}

/// CIE XYZ → linear sRGB (IEC 61966-2-1, D65 white).
#[inline]
pub fn xyz_to_linear_srgb(c: [f32; 3]) -> [f32; 3] {
    let [x, y, z] = c;
    [
        3.240_454_2 * x - 1.537_138_5 * y - 0.498_531_4 * z,
        -0.969_266 * x + 1.876_010_8 * y + 0.041_556 * z,
        0.055_643_4 * x - 0.204_025_9 * y + 1.057_225_2 * z,
    ]
}

/// sRGB transfer function (linear → encoded, IEC 61966-2-1), input clamped to `[0, 1]`.
#[inline]
pub fn srgb_encode(x: f32) -> f32 {
    let x = math::clamp(x, 0.0, 1.0);
    if x <= 0.003_130_8 {
        12.92 * x
    } else {
        1.055 * math::pow(x, 1.0 / 2.4) - 0.055
    }
}

/// Number of wavelengths a mode evaluates per sample (`samples` is spectral mode's `N`).
#[inline]
pub fn wavelength_count(mode: SpectrumMode, samples: u32) -> u32 {
    match mode {
        SpectrumMode::Single => 1,
        SpectrumMode::Rgb => 3,
        SpectrumMode::Spectral => samples,
    }
}

/// Wavelength `k` of a mode (`single_nm` is the single mode's λ).
#[inline]
pub fn wavelength_nm(mode: SpectrumMode, k: u32, samples: u32, single_nm: f32) -> f32 {
    match mode {
        SpectrumMode::Single => single_nm,
        SpectrumMode::Rgb => match k {
            0 => RGB_NM[0],
            1 => RGB_NM[1],
            _ => RGB_NM[2],
        },
        SpectrumMode::Spectral => spectral_lambda_nm(k, samples),
    }
}

/// Adds radiance `l` at wavelength index `k` to an RGB accumulator. Spectral mode adds
/// `l·c̄(λ_k)` in XYZ; finish with [`finish`].
#[inline]
pub fn accumulate(mode: SpectrumMode, k: u32, lambda_nm: f32, l: f32, acc: &mut [f32; 3]) {
    match mode {
        SpectrumMode::Single => {
            acc[0] += l;
            acc[1] += l;
            acc[2] += l;
        }
        SpectrumMode::Rgb => match k {
            0 => acc[0] += l,
            1 => acc[1] += l,
            _ => acc[2] += l,
        },
        SpectrumMode::Spectral => {
            let c = cie_xyz(lambda_nm);
            acc[0] += l * c[0];
            acc[1] += l * c[1];
            acc[2] += l * c[2];
        }
    }
}

/// `Σ_k ȳ(λ_k)` for `n` spectral samples (the normalisation of [`finish`]).
pub fn y_normalisation(n: u32) -> f32 {
    let mut s = 0.0;
    let mut k = 0;
    while k < n {
        s += cie_xyz(spectral_lambda_nm(k, n))[1];
        k += 1;
    }
    s
}

/// The accumulator as linear RGB: unchanged for single and RGB, XYZ normalised by
/// `y_norm` ([`y_normalisation`]) and converted to linear sRGB for spectral.
#[inline]
pub fn finish(mode: SpectrumMode, acc: [f32; 3], y_norm: f32) -> [f32; 3] {
    if mode == SpectrumMode::Spectral && y_norm > 0.0 {
        xyz_to_linear_srgb([acc[0] / y_norm, acc[1] / y_norm, acc[2] / y_norm])
    } else {
        acc
    }
}
