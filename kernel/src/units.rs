//! Unit conversions every model shares: unit directions from f32 input, λ from nm to µm,
//! and the two phase quantities that divide by λ in nm (`ξ` and the depth phase).

use crate::lane::Real;
use crate::math;
use glam::{Vec2, Vec3};

/// Directions whose squared length is within this of 1 are used as given (an f32-rounded
/// unit vector is within 2^-23); others are normalised. Readers apply the same rule, so a
/// direction that arrives as f32 values is never rounded twice (the mpmath reference mirrors
/// it in `reference/refcore.py`).
pub const UNIT_TOLERANCE: f32 = 4.0e-7;

/// `v` as a unit vector under the [`UNIT_TOLERANCE`] rule (zero for a zero or non-finite
/// vector).
#[inline]
pub fn direction(v: [f32; 3]) -> Vec3 {
    let v = Vec3::from_array(v);
    let l2 = v.length_squared();
    if math::abs(l2 - 1.0) <= UNIT_TOLERANCE {
        v
    } else {
        v.normalize_or_zero()
    }
}

/// λ in µm from λ in nm, for the prefactors and band widths (`λ_nm · 0.001_f32`: its
/// 4.7e-8 relative error is harmless there; the phases use [`xi_of`] and
/// [`depth_half_turns_per_um`], which divide by `λ_nm` instead).
#[inline(always)]
pub fn um_from_nm<R: Real>(lambda_nm: R) -> R {
    lambda_nm * R::splat(1.0e-3)
}

/// `ξ = (wi + wo)_xy / λ` (1/µm; zero in the mirror direction) from λ in nm.
///
/// Written `1000 (wi + wo)_xy / λ_nm`: a division by the run-time `λ_nm`, which every
/// target rounds correctly. The product `λ_nm · 0.001_f32` would put `0.001_f32`'s 4.7e-8
/// relative error into every phase of a query with the same sign, an error the coherent sum
/// does not average out (and spirv-opt rewrites a division by the constant 1000 into that
/// product).
#[inline]
pub fn xi_of(wi: Vec3, wo: Vec3, lambda_nm: f32) -> Vec2 {
    Vec2::new(wi.x + wo.x, wi.y + wo.y) * 1000.0 / lambda_nm
}

/// The depth phase per µm of groove depth in half-turns, `κ/(πD) = 2γ/λ` (1/µm), from `γ`
/// and λ in nm, as `2000 γ / λ_nm` (a run-time division; see [`xi_of`]).
#[inline]
pub fn depth_half_turns_per_um(gamma: f32, lambda_nm: f32) -> f32 {
    2000.0 * gamma / lambda_nm
}
