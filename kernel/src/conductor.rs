//! Spectral complex IORs `n(λ) + i k(λ)` of five metals, for materials rendered at more
//! wavelengths than the RGB presets of [`crate::ghs::presets`] cover.
//!
//! Each curve is tabulated every 5 nm from 360 to 830 nm (the CIE 1931 observer's range) in
//! [`crate::conductor_data`] and interpolated linearly; outside that range the end value
//! holds. The data are the measured tables behind the RGB presets (refractiveindex.info,
//! via `reference/conductors/spectral_ior.py`):
//!
//! | metal | source | samples |
//! |---|---|---|
//! | gold | Yakubovsky et al., Opt. Express 25, 25574 (2017), 117 nm film | 10 nm |
//! | silver | McPeak et al., ACS Photonics 2, 326 (2015) | 10 nm |
//! | copper | McPeak et al. (2015) | 10 nm |
//! | aluminium | McPeak et al. (2015) | 5 nm |
//! | nickel | Johnson & Christy, Phys. Rev. B 9, 5056 (1974) | 9–20 nm |
//!
//! Every sample of the 10 nm and 5 nm tables is a grid point, so there the curve is the
//! dataset's own linear interpolation (to the 6 significant digits stored); nickel's
//! samples fall between grid points, and its resampled curve is within 3.1e-3 (relative) of
//! the dataset's interpolation (`kernel/tests/conductor_ior.rs`).

use crate::conductor_data::{GRID_POINTS, K, N};
use crate::lane::Real;
use crate::math;

gpu_enum! {
    /// A metal with a spectral IOR; `None` means "the constant `n`, `k` of the record".
    pub enum Conductor {
        /// No spectral curve: the record's own constant IOR.
        None = 0,
        /// Gold (Yakubovsky et al. 2017).
        Gold = 1,
        /// Silver (McPeak et al. 2015).
        Silver = 2,
        /// Copper (McPeak et al. 2015).
        Copper = 3,
        /// Aluminium (McPeak et al. 2015).
        Aluminium = 4,
        /// Nickel (Johnson & Christy 1974).
        Nickel = 5,
    }
    fallback = None;
}

/// First wavelength of the grid (nm).
pub const GRID_START_NM: f32 = 360.0;
/// Grid spacing (nm).
pub const GRID_STEP_NM: f32 = 5.0;

impl Conductor {
    /// The lower-case names the scene and table files use, in code order from `Gold`.
    pub const NAMES: [&'static str; 5] = ["gold", "silver", "copper", "aluminium", "nickel"];
}

/// `(n, k)` at `lambda_nm`, or `(n, k)` themselves for [`Conductor::None`]. Any [`Real`]:
/// the metal is shared, the wavelength per lane. NaN wavelengths read as 360 nm.
#[inline(always)]
pub fn ior<R: Real>(metal: Conductor, lambda_nm: R, n: f32, k: f32) -> (R, R) {
    let row = metal as u32;
    if row == 0 {
        return (R::splat(n), R::splat(k));
    }
    let last = (GRID_POINTS - 1) as f32;
    let t = math::clamp(
        (lambda_nm - R::splat(GRID_START_NM)) * R::splat(1.0 / GRID_STEP_NM),
        R::splat(0.0),
        R::splat(last),
    );
    // The lower grid point (the last interval for t at the upper end) and the fraction.
    let i = math::min(t.floor(), R::splat(last - 1.0));
    let f = t - i;
    let base = R::splat(((row - 1) as usize * GRID_POINTS) as f32) + i;
    (lerp(&N, base, f), lerp(&K, base, f))
}

/// `table[base] + f·(table[base + 1] − table[base])` per lane.
#[inline(always)]
fn lerp<R: Real>(table: &[f32; 5 * GRID_POINTS], base: R, f: R) -> R {
    let a = R::gather_array(table, base);
    let b = R::gather_array(table, base + R::splat(1.0));
    a + f * (b - a)
}
