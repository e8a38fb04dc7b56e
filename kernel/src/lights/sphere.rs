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

use super::band_circle::{ArcPoint, ArcPoints, BandCircle, BandFamily, Breakpoints, carried_or};
use crate::math;
use crate::math::twofold;
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

/// The bands tangent to a cone's boundary, seen along `u` ([`SphereCap::tangents`]).
struct Tangents {
    /// `u · d̂`.
    m_t: f32,
    /// `cos(θ − α) − m_t`.
    near: f32,
    /// `cos(θ + α) − m_t`.
    far: f32,
    /// `θ < α`: the cone holds `u` (by [`SphereCap::contains`], which resolves a tiny cone).
    holds_u: bool,
    /// `θ + α > π`: the cone holds `−u`.
    holds_minus_u: bool,
}

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

    /// The two bands `u · w = cos(θ ∓ α)` tangent to the cone's boundary (`θ` the angle from
    /// `u` to `d̂`), from `m_t = u · d̂` and `|u × d̂|` (the components
    /// [`SphereCap::crossings`] meets a band with) as `cos θ cos α ± sin θ sin α`. Forming `θ`
    /// first rounded it to ~6e-8 rad near `π/2`, a noticeable part of a light below 1e-3 rad.
    fn tangents(&self, u: Vec3) -> Tangents {
        let m_t = u.dot(self.axis);
        let r = u.cross(self.axis).length();
        let sin_a = math::sin(self.alpha);
        let h = math::sin(0.5 * self.alpha);
        // cos(θ ∓ α) − m_t, with cos α = 1 − 2 sin²(α/2); `m_t` and `r` are taken as they
        // are, not renormalised, as the crossings take them.
        let common = -2.0 * m_t * h * h;
        Tangents {
            m_t,
            near: common + r * sin_a,
            far: common - r * sin_a,
            holds_u: self.contains(u),
            holds_minus_u: self.contains(-u),
        }
    }

    /// `[min, max]` of `u · w` (unit `u`) over the cone's directions `w`: the angle to `u`
    /// ranges over `θ ∓ α` clamped to `[0, π]`.
    pub fn dot_range(&self, u: Vec3) -> (f32, f32) {
        if self.alpha >= math::PI {
            return (-1.0, 1.0);
        }
        let t = self.tangents(u);
        let lo = if t.holds_minus_u { -1.0 } else { t.m_t + t.far };
        let hi = if t.holds_u { 1.0 } else { t.m_t + t.near };
        (math::max(lo, -1.0), math::min(hi, 1.0))
    }

    /// The offsets `(wi + wo)_xy · t` of the bands of the scratch (`tangent`, `bitangent`)
    /// and view `wo` that meet the cone, `[min, max]`: where `θ_c`, the band's angle from
    /// `t₃`, is `θ_d ± α`. With `θ_d = θ₀ + A` (`SphereCap::band_angles`) and `B = θ₀ − θ_c`,
    /// each end is `cos(θ₀ − B) − cos θ₀ = 2 sin(θ₀ − B/2) sin(B/2)`, which agrees with the
    /// crossings to the rounding of `A` and `B` rather than an ulp of `cos θ_c` (~6e-8, as
    /// much as 0.4 % of the range of a light below 1e-3 rad: a lit chord then began inside
    /// the range's first panel or was cut off before its end, 5e-4 of a 2.7e-4-rad sphere's
    /// power).
    pub fn offset_range(&self, family: &BandFamily) -> (f32, f32) {
        let wo_t = family.wo_t;
        let Some(band) = BandCircle::of_family(*family, 0.0) else {
            // A view along the scratch: the band is a point; the plain range.
            let (lo, hi) = self.dot_range(family.t3);
            return (lo + wo_t, hi + wo_t);
        };
        if self.alpha >= math::PI {
            return (wo_t - 1.0, wo_t + 1.0);
        }
        let (a, ..) = self.band_angles(&band);
        let theta0 = math::atan2(band.rho0, band.c0);
        let end = |b: f32| 2.0 * math::sin(theta0 - 0.5 * b) * math::sin(0.5 * b);
        let lo = if theta0 + a + self.alpha >= math::PI {
            wo_t - 1.0
        } else {
            end(-(a + self.alpha))
        };
        let hi = if theta0 + a - self.alpha <= 0.0 {
            wo_t + 1.0
        } else {
            end(self.alpha - a)
        };
        (lo, hi)
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
    /// Each value is added shifted by `shift` (`wo·t` for the offsets of a band family).
    pub fn kinks(&self, u: Vec3, shift: f32, out: &mut Breakpoints) {
        if self.alpha < math::PI {
            let t = self.tangents(u);
            if t.holds_minus_u {
                out.push((t.m_t + t.far) + shift);
            }
            if t.holds_u {
                out.push((t.m_t + t.near) + shift);
            }
        }
        // The boundary meets the horizon at azimuths `φ ± δ` from the axis's own, `cos δ =
        // cos α / cos e` (`e` the axis's elevation), with `1 − cos δ = (cos e − cos α)/cos e =
        // 2 sin((α+e)/2) sin((α−e)/2)/cos e`: `acos(cos α / cos e)` kept only the rounding of
        // two numbers within ~1e-7 of 1 for a cone below ~1e-3 rad at the horizon (δ 30 %
        // off, the lit range's kinks 4e-5 off in `u · w` for a 5e-4-rad sphere).
        let r = math::sqrt(self.axis.x * self.axis.x + self.axis.y * self.axis.y);
        if !(self.alpha < math::PI && r > 0.0) {
            return;
        }
        let e = math::atan2(math::abs(self.axis.z), r);
        let one_minus = 2.0 * math::sin(0.5 * (self.alpha + e)) * math::sin(0.5 * (self.alpha - e))
            / math::cos(e);
        if !(one_minus >= 0.0) || one_minus > 2.0 {
            return;
        }
        let phi = math::atan2(self.axis.y, self.axis.x);
        let delta = 2.0 * math::asin(math::sqrt(0.5 * one_minus));
        let mut k = 0;
        while k < 2 {
            let (sin_p, cos_p) = math::sin_cos(if k == 0 { phi + delta } else { phi - delta });
            out.push((u.x * cos_p + u.y * sin_p) + shift);
            k += 1;
        }
    }

    /// `A = θ_d − θ₀` and `B = θ₀ − θ_c`: the angles from `t₃` of the cone's axis (`θ_d`:
    /// `cos θ_d = m_t`, `sin θ_d = R = √(m_b² + m_z²)`), of the band's centre line (`θ₀`: `c₀`,
    /// `ρ₀`) and of the band (`θ_c`: `c`, `ρ`), each difference from its sine and cosine,
    /// with `(m_b, m_z, R)`. `sin B ∝ ρ₀ c − c₀ ρ` is formed as
    /// `offset (ρ₀ + c₀ (c + c₀)/(ρ₀ + ρ))` (`ρ₀ − ρ = offset (c + c₀)/(ρ₀ + ρ)`, both circles
    /// on the same sphere `|wo|`) from the exact `offset`: the plain difference of products,
    /// like `c` itself, kept ~6e-8 of absolute accuracy, noise in every chord across a light
    /// below ~1e-3 rad (5e-4 of a 2.7e-4-rad sphere's power). `A` is the same for all the
    /// bands of one scratch and view, so its rounding moves the whole light and leaves its
    /// shape alone; at `offset = 0`, `B = 0`.
    fn band_angles(&self, band: &BandCircle) -> (f32, f32, f32, f32, f32) {
        let (mb, mz) = (self.axis.dot(band.family.b3), self.axis.z);
        let r = math::sqrt(mb * mb + mz * mz);
        let (c0, rho0) = (band.c0, band.rho0);
        let a = carried_or(band.family.axis_angle, || self.axis_angle(&band.family));
        let b = if band.offset == 0.0 {
            0.0
        } else {
            let sin_b = band.offset * (rho0 + c0 * (band.c + c0) / (rho0 + band.rho));
            math::atan2(sin_b, c0 * band.c + rho0 * band.rho)
        };
        (a, b, mb, mz, r)
    }

    /// `A = θ_d − θ₀`, the angle from the band family's centre line to the cone's axis
    /// (`SphereCap::band_angles`): `atan2(R c₀ − m_t ρ₀, m_t c₀ + R ρ₀)` with the sine's
    /// four factors (`m_t = d̂·t₃`, `R = |d̂ × t₃|`, `c₀ = −wo·t₃`, `ρ₀ = |wo × t₃|`) and its
    /// two products in [`twofold::Twofold`] precision from the `f32` axis, view and tangent. In `f32`
    /// the sine, a difference of two products near 1/2, kept ~6e-8 rad of absolute
    /// accuracy, while one ulp of an input can move the light by less than 1e-8 rad: a band
    /// crossing a light below ~1e-3 rad near its edge magnifies that, 4.7e-4 of a
    /// 9.3e-5-rad sphere's power (`reference/light_sweep.py`, rows 462 and 464 of the
    /// committed subset).
    pub fn axis_angle(&self, family: &BandFamily) -> f32 {
        let (d, t, b, wo) = (self.axis, family.t3, family.b3, family.wo);
        let mt = twofold::dot2(d.x, t.x, d.y, t.y);
        let mb = twofold::dot2(d.x, b.x, d.y, b.y);
        let r = (mb * mb + twofold::two_prod(d.z, d.z)).sqrt();
        let wo_t = twofold::dot2(wo.x, t.x, wo.y, t.y);
        let wo_b = twofold::dot2(wo.x, b.x, wo.y, b.y);
        let rho0 = (wo_b * wo_b + twofold::two_prod(wo.z, wo.z)).sqrt();
        // c₀ = −wo·t₃: sin A = −(R wo_t + m_t ρ₀), cos A = R ρ₀ − m_t wo_t.
        let sin_a = -(r * wo_t + mt * rho0).value();
        let cos_a = r.hi * rho0.hi - mt.hi * wo_t.hi;
        math::atan2(sin_a, cos_a)
    }

    /// How far the band reaches into the cone, in the circle's own terms: the band meets the
    /// boundary where `s m_b + z' m_z = g` ([`BandCircle::plane_crossings`]), and the slack
    /// is `R − g = (cos β − cos α)/ρ = 2 sin((α+β)/2) sin((α−β)/2)/ρ`, `β = |A + B|` the
    /// angle from the axis to the band (`SphereCap::band_angles`).
    pub fn band_reach(&self, band: &BandCircle) -> BandReach {
        if self.alpha >= math::PI {
            return BandReach::ALL;
        }
        let (a, b, mb, mz, r) = self.band_angles(band);
        let beta = math::abs(a + b);
        let slack =
            2.0 * math::sin(0.5 * (self.alpha + beta)) * math::sin(0.5 * (self.alpha - beta))
                / band.rho;
        BandReach { slack, mb, mz, r }
    }

    /// Adds where the band crosses the cone boundary (at most two points).
    pub fn crossings<const N: usize>(&self, band: &BandCircle, out: &mut ArcPoints<N>) {
        self.crossings_with(band, &self.band_reach(band), out);
    }

    /// [`SphereCap::crossings`] with the band's [`BandReach`] already formed.
    pub fn crossings_with<const N: usize>(
        &self,
        band: &BandCircle,
        reach: &BandReach,
        out: &mut ArcPoints<N>,
    ) {
        if self.alpha >= math::PI {
            return;
        }
        band.plane_crossings(self.axis, math::cos(self.alpha), Some(reach.slack), out);
    }

    /// Whether the point `p` of the band is inside the cone, by the slack of its crossings:
    /// `R − (s m_b + z' m_z) = R |p − p*|²/2 ≤ R − g`, `p*` the point nearest the axis.
    /// [`SphereCap::contains`] of the band's point decided it apart from them, and for a
    /// light below ~1e-3 rad the two disagreed by the rounding of `m_t`, which cut the lit
    /// chord off short of its crossings near one end.
    pub fn holds_on(&self, band: &BandCircle, reach: &BandReach, p: ArcPoint) -> bool {
        if self.alpha >= math::PI {
            return true;
        }
        if !(reach.r > 1.0e-12) {
            // The band circle is centred on the axis: all or none of it is inside.
            return self.contains(band.point(p));
        }
        let (ds, dz) = (p.s - reach.mb / reach.r, p.z - reach.mz / reach.r);
        0.5 * reach.r * (ds * ds + dz * dz) <= reach.slack
    }
}

/// How far one band reaches into a cone ([`SphereCap::band_reach`]), for its crossings and
/// for deciding which of its arcs are lit by the same numbers.
#[derive(Clone, Copy, Debug)]
pub struct BandReach {
    /// `R − g`.
    pub slack: f32,
    /// The axis's component along `b₃`.
    pub mb: f32,
    /// The axis's component along `z`.
    pub mz: f32,
    /// `R = √(m_b² + m_z²)`.
    pub r: f32,
}

impl BandReach {
    /// A cone that holds every direction.
    const ALL: BandReach = BandReach {
        slack: f32::INFINITY,
        mb: 0.0,
        mz: 0.0,
        r: 1.0,
    };
}
