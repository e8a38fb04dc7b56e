//! The wavelengths one BSDF call serves (like pbrt-v4's `SampledWavelengths`): up to four,
//! in nm, each with the pdf it was drawn with.
//!
//! * [`Wavelengths::rgb`]: Werner 2017 §5's reduced RGB mode, 700/520/440 nm (fixed, not
//!   sampled: pdf 1 by convention);
//! * [`Wavelengths::sample_uniform`]: `count` stratified wavelengths over `[min, max]` nm
//!   from one uniform number, `λ_j = min + (j + u)/count · (max − min)`, each with pdf
//!   `1/(max − min)` (the marginal density of every entry is uniform).

use crate::scratch::MAX_SPECTRAL;
use bytemuck::{Pod, Zeroable};

/// Up to [`MAX_SPECTRAL`] wavelengths. GPU-visible: 48 bytes.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct Wavelengths {
    /// Wavelengths (nm); entries past `count` are unused.
    pub nm: [f32; MAX_SPECTRAL],
    /// The pdf (1/nm) each wavelength was drawn with; 1 for fixed sets.
    pub pdf: [f32; MAX_SPECTRAL],
    /// Number of wavelengths in use, 1 to 4 (0 or more than 4 is read as 1 or 4).
    pub count: u32,
    /// Explicit padding.
    pub pad: [u32; 3],
}

const _: () = assert!(core::mem::size_of::<Wavelengths>() == 48);

/// Werner 2017 §5's RGB wavelengths (nm): red, green, blue (the renderer's RGB mode).
pub use crate::render::spectrum::RGB_NM;

/// The visible range used by [`Wavelengths::sample_visible`] (nm).
pub const VISIBLE_NM: [f32; 2] = [360.0, 830.0];

impl Wavelengths {
    /// One wavelength (nm), pdf 1.
    pub const fn single(nm: f32) -> Wavelengths {
        Wavelengths {
            nm: [nm, 0.0, 0.0, 0.0],
            pdf: [1.0, 0.0, 0.0, 0.0],
            count: 1,
            pad: [0; 3],
        }
    }

    /// 700, 520 and 440 nm (Werner 2017 §5), pdf 1.
    pub const fn rgb() -> Wavelengths {
        Wavelengths {
            nm: [RGB_NM[0], RGB_NM[1], RGB_NM[2], 0.0],
            pdf: [1.0, 1.0, 1.0, 0.0],
            count: 3,
            pad: [0; 3],
        }
    }

    /// `count` (1–4) stratified wavelengths in `[min_nm, max_nm]` from `u ∈ [0, 1)`.
    pub fn sample_uniform(u: f32, min_nm: f32, max_nm: f32, count: u32) -> Wavelengths {
        let n = if count == 0 {
            1
        } else if count > MAX_SPECTRAL as u32 {
            MAX_SPECTRAL as u32
        } else {
            count
        };
        let range = max_nm - min_nm;
        let pdf = if range > 0.0 { 1.0 / range } else { 0.0 };
        let mut w = Wavelengths {
            count: n,
            ..Wavelengths::default()
        };
        let mut j = 0;
        while j < MAX_SPECTRAL && j < n as usize {
            w.nm[j] = min_nm + (j as f32 + u) / n as f32 * range;
            w.pdf[j] = pdf;
            j += 1;
        }
        w
    }

    /// [`Wavelengths::sample_uniform`] over [`VISIBLE_NM`] with four wavelengths.
    pub fn sample_visible(u: f32) -> Wavelengths {
        Wavelengths::sample_uniform(u, VISIBLE_NM[0], VISIBLE_NM[1], MAX_SPECTRAL as u32)
    }

    /// The number of wavelengths in use, clamped to 1..=4.
    #[inline]
    pub fn len(&self) -> usize {
        if self.count == 0 {
            1
        } else if self.count as usize > MAX_SPECTRAL {
            MAX_SPECTRAL
        } else {
            self.count as usize
        }
    }

    /// Never empty ([`Wavelengths::len`] is at least 1).
    #[inline]
    pub fn is_empty(&self) -> bool {
        false
    }
}
