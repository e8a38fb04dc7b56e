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

use crate::math::{self, C32};
use glam::Vec3;

/// `|a|² / |b|²`, 0 when `b` vanishes (only at η = 1 grazing, where the numerators vanish too).
#[inline]
fn ratio(num2: f32, den: C32) -> f32 {
    let d = den.norm_sqr();
    if d > 0.0 { num2 / d } else { 0.0 }
}

/// `Q(wi, wo)` for `η = n + ik`; both directions in the local frame, `z > 0`.
///
/// `sinθ = |w_xy|` comes from the components and `R² = η² − sin²θ` is formed as
/// `(η² − 1) + cos²θ` (as in [`crate::fresnel::fresnel`]): `√(1 − cos²θ)` cancels near normal
/// incidence, and its mismatch with `w_xy` made `cos²φ + sin²φ ≠ 1`: `Q` was off by up to
/// 50 % for an f32 direction 2.5e-4 rad from the normal before this form (`docs/ghs.md`).
pub fn diffraction_color(wi: Vec3, wo: Vec3, n: f32, k: f32) -> f32 {
    let ci = math::clamp(wi.z, 0.0, 1.0);
    let co = math::clamp(wo.z, 0.0, 1.0);
    let (si, so) = (
        math::sqrt(wi.x * wi.x + wi.y * wi.y),
        math::sqrt(wo.x * wo.x + wo.y * wo.y),
    );
    // φ = φo − φi − π: cosφ = −cos(φo − φi), sinφ = −sin(φo − φi). At normal incidence or
    // exit φ is undefined but Q does not depend on it there; take φ = 0.
    let sso = si * so;
    let (cos_phi, sin_phi) = if sso > 1.0e-12 {
        (
            -(wi.x * wo.x + wi.y * wo.y) / sso,
            -(wi.x * wo.y - wi.y * wo.x) / sso,
        )
    } else {
        (1.0, 0.0)
    };
    // η² − 1 = (n − 1)(n + 1) − k² + 2ink without cancellation for n ≈ 1
    let eta2m1 = C32::new((n - 1.0) * (n + 1.0) - k * k, 2.0 * n * k);
    let eta2 = eta2m1 + C32::new(1.0, 0.0);
    let e2m1 = eta2m1.norm_sqr();
    let ri = math::csqrt(eta2m1 + C32::new(ci * ci, 0.0));
    let ro = math::csqrt(eta2m1 + C32::new(co * co, 0.0));
    let s_i = C32::new(ci, 0.0) + ri; // cosθi + Ri
    let s_o = C32::new(co, 0.0) + ro;
    let p_i = math::cscale(eta2, ci) + ri; // η² cosθi + Ri
    let p_o = math::cscale(eta2, co) + ro;
    let ss = ratio(e2m1 * cos_phi * cos_phi, s_i * s_o);
    let sp = ratio(e2m1 * ro.norm_sqr() * sin_phi * sin_phi, s_i * p_o);
    let ps = ratio(e2m1 * ri.norm_sqr() * sin_phi * sin_phi, p_i * s_o);
    let pp_num = math::cscale(ri * ro, cos_phi) - math::cscale(eta2, sso);
    let pp = ratio(e2m1 * pp_num.norm_sqr(), p_i * p_o);
    ss + sp + ps + pp
}
