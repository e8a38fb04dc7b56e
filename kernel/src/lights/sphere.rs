//! Spherical lights (Velinov 2018 §3.4.1, Eqs. 30–35).
//!
//! Seen from the shading point, a sphere of radius `r` at distance `d` fills the cone of
//! half-angle `α = asin(r/d)` around its centre direction `d̂`. Velinov's Eq. 31 normalises
//! the points of a disk of radius `r` perpendicular to `d̂` instead, which is the cone
//! `α = atan(r/d)` (an erratum: that disk is the sphere's great disk, which lies behind the
//! silhouette circle — radius `r cos α` at distance `d cos² α` — and looks smaller); both are
//! offered ([`Cone`]). The disk's solid angle `2π(1 − cos atan(r/d))` falls short of the
//! sphere's `2π(1 − cos asin(r/d))` by 1.0 % at `r/d = 0.1`, 9 % at 0.3 and 37 % at 0.7.
//!
//! Crossings of the band with the cone boundary `wi · d̂ = cos α` use the circle solution of
//! [`super::band_circle`] with the slack `R − g = (cos β − cos α)/ρ =
//! 2 sin((α+β)/2) sin((α−β)/2)/ρ`, `β` the angle from `d̂` to the band circle, formed without
//! the cancellation of `cos β − cos α` that makes the printed quadratic (Eq. 34) lose all
//! f32 digits for lights below ~1e-3 rad.

use super::band_circle::{ArcPoints, BandCircle, Breakpoints};
use crate::math;
use glam::Vec3;

gpu_enum! {
    /// Which cone a sphere subtends.
    pub enum Cone {
        /// The true sphere: `α = asin(r/d)` (`α = π`, every direction, when `d ≤ r`).
        Asin = 0,
        /// Velinov's Eq. 31 (a disk facing the point): `α = atan(r/d)`.
        Atan = 1,
    }
    fallback = Asin;
}

/// Absolute slack of [`SphereCap::dot_bound`].
const DOT_BOUND_SLACK: f32 = 1.0e-5;

/// The cone of directions a spherical light fills.
#[derive(Clone, Copy, Debug)]
pub struct SphereCap {
    /// Unit centre direction `d̂`.
    pub axis: Vec3,
    /// Half-angle α in `[0, π]`.
    pub alpha: f32,
    /// `|wi − d̂|²` on the boundary: `4 sin²(α/2)`.
    chord2: f32,
}

impl SphereCap {
    /// The empty cap (contains nothing).
    pub const EMPTY: SphereCap = SphereCap {
        axis: Vec3::Z,
        alpha: 0.0,
        chord2: -1.0,
    };

    /// The cap of a sphere (centre relative to the shading point, radius, same units).
    /// `None` when the sphere is degenerate (`r ≤ 0`, centre at the point for `Atan`, or
    /// not finite) or lies entirely below the horizon.
    pub fn new(center: Vec3, radius: f32, cone: Cone) -> Option<SphereCap> {
        let d = center.length();
        if !(radius > 0.0) || !d.is_finite() || !radius.is_finite() {
            return None;
        }
        if super::horizon::sphere_below(center.z, radius) {
            return None;
        }
        let axis = center.normalize_or_zero();
        let alpha = match cone {
            Cone::Asin if d <= radius => math::PI,
            Cone::Asin => math::asin(radius / d),
            Cone::Atan => math::atan2(radius, d),
        };
        if !(alpha > 0.0) || (axis == Vec3::ZERO && alpha < math::PI) {
            return None;
        }
        let h = math::sin(0.5 * alpha);
        Some(SphereCap {
            axis,
            alpha,
            chord2: 4.0 * h * h,
        })
    }

    /// Whether the direction `w` (unit) is inside the cone.
    #[inline]
    pub fn contains(&self, w: Vec3) -> bool {
        self.alpha >= math::PI || (w - self.axis).length_squared() <= self.chord2
    }

    /// `[min, max]` of `u · w` (unit `u`) over the cone's directions `w`: the angle to `u`
    /// ranges over `θ ∓ α` clamped to `[0, π]`.
    pub fn dot_range(&self, u: Vec3) -> (f32, f32) {
        if self.alpha >= math::PI {
            return (-1.0, 1.0);
        }
        let theta = math::angle_between(u, self.axis);
        let near = math::max(theta - self.alpha, 0.0);
        let far = math::min(theta + self.alpha, math::PI);
        (math::cos(far), math::cos(near))
    }

    /// A cheap superset of [`SphereCap::dot_range`]: `u · d̂ ± (|w − d̂| + 1e-5)`, since
    /// `|u · w − u · d̂| ≤ |w − d̂|` for unit `u`; the slack covers the rounding of both
    /// (~1e-7), so a band test that fails on this fails on the exact range too.
    #[inline]
    pub fn dot_bound(&self, u: Vec3) -> (f32, f32) {
        let c = u.dot(self.axis);
        let r = math::sqrt0(self.chord2) + DOT_BOUND_SLACK;
        (c - r, c + r)
    }

    /// Adds the values of `u · w` where the lit chord of the circle `u · w = const` has a
    /// kink: where the circle is tangent to the cone's boundary from inside (the cone holds
    /// `−u` or `u`, so that the circles around it lie wholly inside up to `cos(θ ± α)`, the
    /// tangency beyond the pole; [`SphereCap::dot_range`]'s ends are the other tangencies)
    /// and at the (up to two) points where the cone's boundary meets the horizon.
    pub fn kinks(&self, u: Vec3, out: &mut Breakpoints) {
        if self.alpha < math::PI {
            let theta = math::angle_between(u, self.axis);
            if theta + self.alpha > math::PI {
                out.push(math::cos(theta + self.alpha));
            }
            if theta < self.alpha {
                out.push(math::cos(theta - self.alpha));
            }
        }
        let r = math::sqrt(self.axis.x * self.axis.x + self.axis.y * self.axis.y);
        let c = math::cos(self.alpha) / r;
        if !(self.alpha < math::PI && r > 0.0 && math::abs(c) <= 1.0) {
            return;
        }
        let phi = math::atan2(self.axis.y, self.axis.x);
        let delta = math::acos(c);
        let mut k = 0;
        while k < 2 {
            let (sin_p, cos_p) = math::sin_cos(if k == 0 { phi + delta } else { phi - delta });
            out.push(u.x * cos_p + u.y * sin_p);
            k += 1;
        }
    }

    /// Adds where the band crosses the cone boundary (at most two points).
    pub fn crossings(&self, band: &BandCircle, out: &mut ArcPoints) {
        if self.alpha >= math::PI {
            return;
        }
        let (mt, mb, mz) = band.components(self.axis);
        let r = math::sqrt(mb * mb + mz * mz);
        // β = |θ_d − θ_c|, θ_d = atan2(r, m_t) the axis's angle from t₃ and θ_c = atan2(ρ, c)
        // the band's, as one atan2 of the difference's sine and cosine: the difference of
        // the two angles (each up to π) kept only their absolute accuracy ~1e-7 rad, which a
        // band crossing near the cone's edge magnifies (`reference/light_sweep.py`).
        let beta = math::abs(math::atan2(
            r * band.c - mt * band.rho,
            mt * band.c + r * band.rho,
        ));
        let slack =
            2.0 * math::sin(0.5 * (self.alpha + beta)) * math::sin(0.5 * (self.alpha - beta))
                / band.rho;
        band.plane_crossings(self.axis, math::cos(self.alpha), Some(slack), out);
    }
}
