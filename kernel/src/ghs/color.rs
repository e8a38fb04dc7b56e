//! The diffraction colour term `Q` (H&P Eq. 27, after Krywonos 2006), unpolarised.
//!
//! With `φ = φo − φi − π`, `R(θ) = √(η² − sin²θ)`:
//! `Q_ss = (η²−1) cosφ / ((cosθi + Ri)(cosθo + Ro))`,
//! `Q_sp = (η²−1) Ro sinφ / ((cosθi + Ri)(η² cosθo + Ro))`,
//! `Q_ps = (η²−1) Ri sinφ / ((η² cosθi + Ri)(cosθo + Ro))`,
//! `Q_pp = (η²−1)(Ri Ro cosφ − η² sinθi sinθo) / ((η² cosθi + Ri)(η² cosθo + Ro))`,
//! `Q = Σ|Q_xy|²`. In the specular direction `Q_sp = Q_ps = 0`, `Q_ss`/`Q_pp` are the
//! Fresnel amplitudes and `Q = 2F` (so the lobe colour `Q/2` equals `F` there; tested).
//! Only squared magnitudes are needed, so no complex division is formed.

use crate::fresnel::eta2_minus_1;
use crate::lane::{Cx, Real, V3};
use crate::math;
use glam::Vec3;

/// `|a|² / |b|²`, 0 when `b` vanishes (only at η = 1 grazing, where the numerators vanish too).
#[inline(always)]
fn ratio<R: Real>(num2: R, den: Cx<R>) -> R {
    let d = den.norm_sqr();
    R::select(d.gt(R::splat(0.0)), num2 / d, R::splat(0.0))
}

/// `Q(wi, wo)` for `η = n + ik`; both directions in the local frame, `z > 0`.
///
/// `sinθ = |w_xy|` comes from the components and `R² = η² − sin²θ` is formed as
/// `(η² − 1) + cos²θ` (as in [`crate::fresnel::fresnel`]): `√(1 − cos²θ)` cancels near normal
/// incidence, and its mismatch with `w_xy` made `cos²φ + sin²φ ≠ 1`: `Q` was off by up to
/// 50 % for an f32 direction 2.5e-4 rad from the normal before this form (`docs/ghs.md`).
pub fn diffraction_color(wi: Vec3, wo: Vec3, n: f32, k: f32) -> f32 {
    diffraction_color_lanes(wi.into(), wo.into(), n, k)
}

/// [`diffraction_color`] for any [`Real`] (the one formula).
#[inline(always)]
pub fn diffraction_color_lanes<R: Real>(wi: V3<R>, wo: V3<R>, n: R, k: R) -> R {
    let c = R::splat;
    let ci = math::clamp(wi.z, c(0.0), c(1.0));
    let co = math::clamp(wo.z, c(0.0), c(1.0));
    let (si, so) = (
        (wi.x * wi.x + wi.y * wi.y).sqrt(),
        (wo.x * wo.x + wo.y * wo.y).sqrt(),
    );
    let sso = si * so;
    let apart = sso.gt(c(1.0e-12));
    let cos_phi = R::select(apart, -(wi.x * wo.x + wi.y * wo.y) / sso, c(1.0));
    let sin_phi = R::select(apart, -(wi.x * wo.y - wi.y * wo.x) / sso, c(0.0));
    let eta2m1 = eta2_minus_1(n, k);
    let eta2 = Cx::new(eta2m1.re + c(1.0), eta2m1.im + c(0.0));
    let e2m1 = eta2m1.re * eta2m1.re + eta2m1.im * eta2m1.im;
    let ri = math::csqrt_cx(eta2m1 + Cx::real(ci * ci));
    let ro = math::csqrt_cx(eta2m1 + Cx::real(co * co));
    let s_i = Cx::real(ci) + ri; // cosθi + Ri
    let s_o = Cx::real(co) + ro;
    let p_i = eta2.scale(ci) + ri; // η² cosθi + Ri
    let p_o = eta2.scale(co) + ro;
    let ss = ratio(e2m1 * cos_phi * cos_phi, s_i * s_o);
    let sp = ratio(e2m1 * ro.norm_sqr() * sin_phi * sin_phi, s_i * p_o);
    let ps = ratio(e2m1 * ri.norm_sqr() * sin_phi * sin_phi, p_i * s_o);
    let pp_num = (ri * ro).scale(cos_phi) - eta2.scale(sso);
    let pp = ratio(e2m1 * pp_num.norm_sqr(), p_i * p_o);
    ss + sp + ps + pp
}
