//! The three scratch models' BRDF from the scratch terms of one wavelength: the one place
//! where `F/(πσ²λ²)` meets `|B − S|²` (Werner Eq. 15), `|S|²` (Werner §5) or
//! `Σ|S_k|² + (1 − ρc)|B|²` (Velinov Eqs. 6–7). [`crate::bsdf::eval()`] finishes every
//! wavelength with it, and the table interface reaches it through `eval`'s point values
//! (and through its SIMD batch).

use crate::lane::Real;
use crate::math;
use crate::scratch::{ScratchTerms, base_response_lanes};
use glam::Vec2;

gpu_enum! {
    /// Which scratch model a BRDF evaluates.
    pub enum Model {
        /// Coherent base + scratches (Werner Eq. 15).
        Werner = 0,
        /// Coherent scratches only, for blending with another base BRDF (Werner §5).
        WernerBlended = 1,
        /// Incoherent sum of single-scratch responses (Velinov Eq. 7).
        Velinov = 2,
    }
    fallback = Werner;
}

/// The BRDF (1/sr, no cosine) of a scratch model from the scratch terms of one wavelength:
/// `F/(πσ²λ²)` times `|B − S|²` (Werner Eq. 15), `|S|²` (Werner §5) or
/// `Σ|S_k|² + (1 − ρc)|B|²·[base_gaussian]` (Velinov Eqs. 6–7), by [`Model`]. `f` is the
/// reflectance F, `lambda` in µm; 0 unless `lambda > 0` and the result is finite and
/// positive.
#[inline]
pub fn model_value(
    model: Model,
    base_gaussian: bool,
    terms: &ScratchTerms,
    xi: Vec2,
    sigma: f32,
    f: f32,
    lambda: f32,
) -> f32 {
    model_value_lanes(model, base_gaussian, terms, [xi.x, xi.y], sigma, f, lambda)
}

/// [`model_value`] for one query per lane (the one formula).
#[inline(always)]
pub fn model_value_lanes<R: Real>(
    model: Model,
    base_gaussian: bool,
    terms: &ScratchTerms<R>,
    xi: [R; 2],
    sigma: f32,
    f: R,
    lambda: R,
) -> R {
    let c = R::splat;
    let area = math::PI * sigma * sigma;
    let norm = f / (c(area) * lambda * lambda);
    let v = match model {
        Model::Werner => terms
            .coherent
            .subtracted_from_lanes(base_response_lanes(xi, sigma))
            .norm_sqr(),
        Model::WernerBlended => terms.coherent.total_lanes().norm_sqr(),
        Model::Velinov => {
            let base = if base_gaussian {
                let b = base_response_lanes(xi, sigma);
                math::max(c(1.0) - terms.area_density, c(0.0)) * b * b
            } else {
                c(0.0)
            };
            terms.incoherent + base
        }
    };
    let r = norm * v;
    R::select(r.is_finite() & r.gt(c(0.0)) & lambda.gt(c(0.0)), r, c(0.0))
}
