//! Directional lobes for sampling `wi` given `wo` (local frame, both above the surface).
//!
//! Every scratch-model lobe lives in the projected disk of `d = (wi + wo)_xy = λξ`
//! (Werner Eq. 22 solved for `wi`): `wi_xy = d − wo_xy`, so the directions above the horizon
//! are the unit disk centred at `wo_xy`, and a density `p_d` in `d` is the solid-angle
//! density `p_d · cosθi` (the Nusselt analog, Werner §5).
//!
//! * [`DiskLobe`] (this crate): a product of two [`Lobe1`]s along orthonormal axes `e1`,
//!   `e2`; `d·e1` is drawn on the disk's extent along `e1`, then `d·e2` on the chord at that
//!   `d·e1`, so nothing is drawn below the horizon and the pdf integrates to 1. The base
//!   response is the Gaussian product of Werner Eq. 21, truncated; a scratch is a logistic
//!   along its tangent (the coherence window) times
//!   a Cauchy (mixture) across it (the profile's `sinc²`, Werner Eqs. 14, 26–31).
//! * [`gaussian_base_sample`]: Werner §5's base sampler verbatim: `ξ` from two normal
//!   numbers with the standard deviation `1/(√8 πσ)` of Eq. 21, `wi` from Eq. 22, evanescent
//!   samples dropped (so its pdf integrates to less than 1 at grazing `wo`).
//! * [`vmf_ring_sample`]: Werner §5's scratch sampler: the d'Eon et al. 2011 cone of
//!   directions with `wi·t = −wo·t` around the scratch tangent `t` at a uniform azimuth,
//!   perturbed by a von Mises–Fisher direction of concentration κ; directions below the
//!   surface are mirrored (density doubled). Its density is the paper's
//!   `κ/(4π sinh κ) e^{−κ cosθo cosθ} I₀(κ sinθo sinθ)` (θ measured from `t`), evaluated
//!   with the scaled Bessel function so that κ ~ 10⁴ does not overflow.

use super::lobe1d::Lobe1;
use crate::math;
use glam::{Vec2, Vec3};

/// A product lobe in the projected disk of `d = (wi + wo)_xy` (see the module docs).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DiskLobe {
    /// First axis (unit, in the tangent plane).
    pub e1: Vec2,
    /// Lobe of `d·e1`.
    pub l1: Lobe1,
    /// Lobe of `d·e2`, `e2 = (−e1.y, e1.x)`.
    pub l2: Lobe1,
}

impl DiskLobe {
    #[inline]
    fn axes(&self, wo: Vec3) -> (Vec2, Vec2, f32, f32) {
        let e1 = self.e1;
        let e2 = Vec2::new(-e1.y, e1.x);
        let c = Vec2::new(wo.x, wo.y);
        (e1, e2, c.dot(e1), c.dot(e2))
    }

    /// Draws `wi` from `u ∈ [0, 1)²`; `None` if a coordinate lands on the horizon by
    /// rounding.
    ///
    /// Both lobes are drawn in `wi`'s own coordinates `a = wi·e1 ∈ [−1, 1]`, `b = wi·e2 ∈
    /// [−h, h]` (the lobes moved by `−c`), with each sample's distances from its interval's
    /// ends ([`Lobe1::sample_ends`]): `h² = (1 + a)(1 − a)` and `wi.z² = (h + b)(h − b)` from
    /// them keep their digits at the rim, where forming `a` and `b` first (and their
    /// intervals as `c ± 1`, `c ± h`) lost them: `wi.z` 18 % off, or a sample dropped, for
    /// directions within 1e-3 of the horizon (issue #20,
    /// `kernel/tests/disk_lobe_domain_sweep.rs`).
    pub fn sample(&self, wo: Vec3, u: Vec2) -> Option<Vec3> {
        let (e1, e2, c1, c2) = self.axes(wo);
        let (a, one_plus_a, one_minus_a) = self.l1.shifted(-c1).sample_ends(u.x, -1.0, 1.0)?;
        let h2 = one_plus_a * one_minus_a;
        if !(h2 > 0.0) {
            return None;
        }
        let h = math::sqrt(h2);
        let (b, h_plus_b, h_minus_b) = self.l2.shifted(-c2).sample_ends(u.y, -h, h)?;
        let z2 = h_plus_b * h_minus_b;
        if !(z2 > 0.0) {
            return None;
        }
        let w = e1 * a + e2 * b;
        Some(Vec3::new(w.x, w.y, math::sqrt(z2)))
    }

    /// Solid-angle pdf of [`DiskLobe::sample`] at `wi`. The chord's half length
    /// `h = √(1 − a²)` is formed as `√(b² + wi.z²)` (the same for a unit `wi`), which keeps
    /// its digits where `wi` nears `±e1`.
    pub fn pdf(&self, wo: Vec3, wi: Vec3) -> f32 {
        if !(wi.z > 0.0) {
            return 0.0;
        }
        let (e1, e2, c1, c2) = self.axes(wo);
        let w = Vec2::new(wi.x, wi.y);
        let a = math::clamp(w.dot(e1), -1.0, 1.0);
        let b = w.dot(e2);
        let h = math::sqrt(b * b + wi.z * wi.z);
        let p1 = self.l1.shifted(-c1).pdf(a, -1.0, 1.0);
        let p2 = self.l2.shifted(-c2).pdf(b, -h, h);
        p1 * p2 * wi.z
    }
}

/// Werner Eq. 21: the standard deviation of the base response's angular spectrum per axis,
/// `1/(√8 πσ)` (1/µm).
#[inline]
pub fn base_xi_std(sigma: f32) -> f32 {
    1.0 / (2.0 * math::SQRT_2 * math::PI * sigma)
}

/// Werner §5 / Eqs. 21–22: `d = λξ` from two normal numbers (Box–Muller on `u`) with
/// standard deviation `std_d = λ/(√8 πσ)` in `d`, `wi_xy = d − wo_xy`; `None` for an
/// evanescent sample (dropped, as in the paper).
pub fn gaussian_base_sample(std_d: f32, wo: Vec3, u: Vec2) -> Option<Vec3> {
    let r = std_d * math::sqrt0(-2.0 * math::ln(math::max(1.0 - u.x, 1.0e-30)));
    let (s, c) = math::sin_cos(math::TAU * u.y);
    let w = Vec2::new(r * c - wo.x, r * s - wo.y);
    let z2 = 1.0 - w.length_squared();
    if !(z2 > 0.0) {
        return None;
    }
    Some(Vec3::new(w.x, w.y, math::sqrt(z2)))
}

/// Solid-angle pdf of [`gaussian_base_sample`] at `wi`.
pub fn gaussian_base_pdf(std_d: f32, wo: Vec3, wi: Vec3) -> f32 {
    if !(wi.z > 0.0) || !(std_d > 0.0) {
        return 0.0;
    }
    let d2 = (wi.x + wo.x) * (wi.x + wo.x) + (wi.y + wo.y) * (wi.y + wo.y);
    let v = std_d * std_d;
    math::exp(-0.5 * d2 / v) / (math::TAU * v) * wi.z
}

/// Werner §5 (after d'Eon et al. 2011): a direction on the cone `wi·t = −wo·t` about the
/// scratch tangent `t` (unit, in the surface plane) at azimuth `2π u_ring`, perturbed by a
/// von Mises–Fisher direction of concentration `kappa` from `u`, mirrored above the
/// surface if it points below.
pub fn vmf_ring_sample(t: Vec2, kappa: f32, wo: Vec3, u_ring: f32, u: Vec2) -> Option<Vec3> {
    if !(kappa > 0.0) {
        return None;
    }
    let t3 = Vec3::new(t.x, t.y, 0.0);
    let (a1, a2) = (Vec3::Z, t3.cross(Vec3::Z));
    let co = wo.dot(t3);
    let so = sin_from(t, wo);
    let (sp, cp) = math::sin_cos(math::TAU * u_ring);
    let mu = t3 * (-co) + (a1 * cp + a2 * sp) * so;
    // vMF about mu: w = 1 + ln(v + (1 − v) e^{−2κ})/κ, formed as 1 − w = −ln(·)/κ, the
    // logarithm's argument a sum of positives where it is below 1/2 and 1 + (1 − v)
    // expm1(−2κ) through ln1p above: `1 + ln(·)/κ` kept only ~1e-7 of 1 − w for κ ~ 10⁷ (0.65
    // of the lobe's width off), and `ln` near 1 lost the small-κ digits (issue #20,
    // `kernel/tests/vmf_ring_domain_sweep.rs`).
    let v = u.x;
    let arg = v + (1.0 - v) * math::exp(-2.0 * kappa);
    let omw = if !(arg > 0.0) {
        2.0
    } else if arg < 0.5 {
        -math::ln(arg) / kappa
    } else {
        -math::ln1p((1.0 - v) * math::expm1(-2.0 * kappa)) / kappa
    };
    let omw = math::clamp(omw, 0.0, 2.0);
    // 1 + w where w nears −1 (v → 0 at small κ): ln(v e^{2κ} + 1 − v)/κ, not 2 − (1 − w).
    let opw = if omw <= 1.0 {
        2.0 - omw
    } else if !(v > 0.0) {
        0.0
    } else if kappa <= 44.0 {
        math::ln1p(v * math::expm1(2.0 * kappa)) / kappa
    } else {
        // e^{2κ} overflows; 1 − w > 1 needs v < e^{−κ} here, so v e^{2κ} ≫ 1.
        (math::ln(v) + 2.0 * kappa) / kappa
    };
    let opw = math::clamp(opw, 0.0, 2.0);
    let w = if omw <= 1.0 { 1.0 - omw } else { opw - 1.0 };
    let sw = math::sqrt0(omw * opw);
    let (b1, b2) = orthonormal(mu);
    let (sq, cq) = math::sin_cos(math::TAU * u.y);
    let mut d = mu * w + (b1 * cq + b2 * sq) * sw;
    if d.z < 0.0 {
        d.z = -d.z;
    }
    let d = d.normalize_or_zero();
    if d.z > 0.0 { Some(d) } else { None }
}

/// Solid-angle pdf of [`vmf_ring_sample`] at `wi` (upper hemisphere): twice the paper's
/// ring density, `κ/(2π(1 − e^{−2κ})) e^{−κ(1 + cosθo cosθ − sinθo sinθ)} e^{−x}I₀(x)`
/// with `x = κ sinθo sinθ`, times 2 for the mirroring.
pub fn vmf_ring_pdf(t: Vec2, kappa: f32, wo: Vec3, wi: Vec3) -> f32 {
    if !(wi.z > 0.0) || !(kappa > 0.0) {
        return 0.0;
    }
    let t3 = Vec3::new(t.x, t.y, 0.0);
    let co = wo.dot(t3);
    let c = wi.dot(t3);
    let so = sin_from(t, wo);
    let s = sin_from(t, wi);
    let x = kappa * so * s;
    let norm = kappa / (math::TAU * -math::expm1(-2.0 * kappa));
    // 1 + cosθo cosθ − sinθo sinθ = |(cosθ, sinθ) − (−cosθo, sinθo)|²/2: no cancellation on
    // the ring, where κ ~ 10⁷ multiplies it (the difference form was 140 % off there).
    let (dc, ds) = (c + co, s - so);
    let e = 0.5 * (dc * dc + ds * ds);
    2.0 * norm * math::exp(-kappa * e) * math::bessel_i0e(x)
}

/// Sine of the angle between unit `w` and the in-plane unit tangent `t`, from `w`'s
/// components across `t` (`sqrt(1 − cos²)` loses its digits where `w` nears `±t`).
#[inline]
fn sin_from(t: Vec2, w: Vec3) -> f32 {
    let across = t.x * w.y - t.y * w.x;
    math::sqrt(across * across + w.z * w.z)
}

/// Two unit vectors completing unit `n` to an orthonormal basis (Duff et al. 2017).
#[inline]
fn orthonormal(n: Vec3) -> (Vec3, Vec3) {
    let s = math::sign(n.z);
    let a = -1.0 / (s + n.z);
    let b = n.x * n.y * a;
    (
        Vec3::new(1.0 + s * n.x * n.x * a, s * b, -s * n.x),
        Vec3::new(b, s + n.y * n.y * a, -n.y),
    )
}
