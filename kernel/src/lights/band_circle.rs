//! The band ξ₁ = 0 seen on the unit sphere of incident directions, and where it crosses a
//! light's boundary (the role of Velinov 2018 Eqs. 32–35 and 38–40).
//!
//! The band is the line `(wi + wo)_xy · t = 0` in direction-cosine space. On the sphere it is
//! the small circle `wi · t₃ = c`, `c = −wo_xy · t`, `t₃ = (t, 0)`, of radius `ρ = √(1 − c²)`:
//!
//! `wi(φ) = c t₃ + ρ (sin φ b₃ + cos φ n)`, `b₃ = (b, 0)`, `n = z`,
//!
//! and the upper hemisphere is `cos φ ≥ 0` (see [`super::horizon`]). Along it
//! `ξ₂ = (ρ sin φ + wo_xy · b) / λ` is linear in `s = sin φ`. Every point of an interval
//! is kept as the pair `(s, z') = (sin φ, cos φ)` ([`ArcPoint`]), both as the crossing
//! formula gives them: near the horizon (`s → ±1`) an ulp of `s` is `1/cos φ` times longer
//! along the band, so a chord there is formed from the `z'` of its ends
//! ([`ArcPoint::s_minus`]) and midpoints from both coordinates, which resolves lit arcs far
//! below an ulp of `s` (a light straddling the horizon); beyond `|s| = 1/2` a crossing's `s`
//! is taken from its `z'`, so the two orders agree. A chord between the two crossings of one
//! plane (a small sphere light) is the difference of the formula's roots
//! ([`ArcPoints::chord`]), not of the two rounded `s`.
//!
//! Instead of the paper's half-angle quadratics in the light's own parametrisation, the
//! crossing of the circle with any plane `wi · m = h` (a light edge's great circle: `h = 0`;
//! a sphere's cone: `m = d̂`, `h = cos α`) is solved on the circle:
//! `s m_b + z' m_z = g`, `g = (h − c m_t)/ρ`, `R² = m_b² + m_z²`,
//! `s = (g m_b ± m_z √(R² − g²))/R²`, `z' = (g m_z ∓ m_b √(R² − g²))/R²`.
//! Which side of each crossing is lit is decided afterwards by testing interval midpoints,
//! so tangencies, vertices on the band ("a crossing on two arcs", Eq. 41) and spurious
//! crossings with the unused part of a great circle need no special cases.

use super::limits::{MAX_BREAKPOINTS, MAX_CUTS};
use crate::math;
use glam::{Vec2, Vec3};

/// The band of one scratch for one view direction.
#[derive(Clone, Copy, Debug)]
pub struct BandCircle {
    /// The family of parallel bands it belongs to (`t₃`, `b₃`, `wo·t`, `wo·b`, `ρ₀²`, `wo`,
    /// and the light's term where [`super::LightRegion::family`] formed it).
    pub family: BandFamily,
    /// `c = wi · t₃` on the band.
    pub c: f32,
    /// The offset `c − c₀` from the band's centre line, exact (`c` itself is rounded).
    pub offset: f32,
    /// `c₀ = −wo_xy · t`, the centre line's `c`.
    pub c0: f32,
    /// `ρ₀ = √(1 − c₀²)`, the centre line's radius. A light narrower than an ulp of `c`
    /// (~6e-8 near `|c| = 1/2`) keeps its shape across the bands only if each band is placed
    /// by its exact `offset` from this one ([`super::sphere::SphereCap::crossings`]).
    pub rho0: f32,
    /// Radius `√(1 − c²)`.
    pub rho: f32,
}

/// The parallel bands of one scratch for one view, by their offset `o = (wi + wo)_xy · t`
/// ([`BandCircle::new_offset`]): each the circle `c = o − wo·t`, `ρ² = ρ₀² + o(2 wo·t − o)`.
#[derive(Clone, Copy, Debug)]
pub struct BandFamily {
    /// `t₃ = (t, 0)`.
    pub t3: Vec3,
    /// `b₃ = (b, 0)`.
    pub b3: Vec3,
    /// `wo_xy · t` (`c₀ = −wo·t`).
    pub wo_t: f32,
    /// `wo_xy · b`.
    pub wo_b: f32,
    /// `ρ₀² = (wo_xy · b)² + wo_z²`, the centre line's `1 − c₀²` without cancellation.
    pub rho0_sq: f32,
    /// The view `wo` (unit), from which the above are formed.
    pub wo: Vec3,
    /// A sphere light's angle `A` from the centre line to its axis, the same for every band
    /// of the family, where the light formed it once (`LightRegion::family`); NaN
    /// otherwise, and each band forms it (`SphereCap::band_angles`).
    pub axis_angle: f32,
    /// A small polygon light's height over the centre line, likewise
    /// (`SphericalPolygon::local_band`).
    pub centre_height: f32,
}

/// A value the light forms once per band family and `BandFamily` carries (`axis_angle`,
/// `centre_height`), or, where it is not carried (NaN), `form()`.
#[inline]
pub fn carried_or(carried: f32, form: impl FnOnce() -> f32) -> f32 {
    if carried.is_nan() { form() } else { carried }
}

impl BandFamily {
    /// Whether the bands are small circles about `±t₃` (`|c₀| > ρ₀`): an ulp of `c` then
    /// moves a band across itself by more than `ε`, and a small light places them by their
    /// radius ([`super::polygon::SphericalPolygon::crossings`]).
    #[inline]
    pub fn narrow(&self) -> bool {
        self.wo_t * self.wo_t > self.rho0_sq
    }

    /// The bands of a scratch with unit tangent `t` and bitangent `b` for the view `wo`.
    #[inline]
    pub fn new(tangent: Vec2, bitangent: Vec2, wo: Vec3) -> BandFamily {
        let wo_xy = Vec2::new(wo.x, wo.y);
        let wo_b = wo_xy.dot(bitangent);
        BandFamily {
            t3: Vec3::new(tangent.x, tangent.y, 0.0),
            b3: Vec3::new(bitangent.x, bitangent.y, 0.0),
            wo_t: wo_xy.dot(tangent),
            wo_b,
            rho0_sq: wo_b * wo_b + wo.z * wo.z,
            wo,
            axis_angle: f32::NAN,
            centre_height: f32::NAN,
        }
    }
}

impl BandCircle {
    /// The band of a scratch with unit tangent `t` and bitangent `b` for the view `wo`
    /// (unit, `z > 0`); `None` when it degenerates to a point (`|wo_xy · t| = 1`).
    #[inline]
    pub fn new(tangent: Vec2, bitangent: Vec2, wo: Vec3) -> Option<BandCircle> {
        BandCircle::new_offset(tangent, bitangent, wo, 0.0)
    }

    /// The parallel line `(wi + wo)_xy · t = offset` (direction cosines, i.e. ξ₁ = offset/λ).
    #[inline]
    pub fn new_offset(tangent: Vec2, bitangent: Vec2, wo: Vec3, offset: f32) -> Option<BandCircle> {
        BandCircle::of_family(BandFamily::new(tangent, bitangent, wo), offset)
    }

    /// The band of `family` at `offset`; `None` where it degenerates to a point or is empty.
    #[inline]
    pub fn of_family(family: BandFamily, offset: f32) -> Option<BandCircle> {
        let (wo_t, rho0_sq) = (family.wo_t, family.rho0_sq);
        let c = offset - wo_t;
        if !(c > -1.0 && c < 1.0) {
            return None;
        }
        // `1 − c²` as `wo_b² + wo_z² + offset (2 wo_t − offset)` (|wo| = 1, t ⟂ b): for a
        // view along the scratch (c → ±1) the plain `1 − c²` keeps only the absolute
        // accuracy ~ε of c², which put 1e-5 rad into the crossings of a band circle of
        // radius 0.018 (`reference/light_sweep.py`).
        let rho = math::sqrt0(rho0_sq + offset * (2.0 * wo_t - offset));
        if !(rho > 0.0) {
            return None;
        }
        Some(BandCircle {
            family,
            c,
            offset,
            c0: -wo_t,
            rho0: math::sqrt0(rho0_sq),
            rho,
        })
    }

    /// The direction at the point `p` of the upper half.
    #[inline]
    pub fn point(&self, p: ArcPoint) -> Vec3 {
        self.c * self.family.t3 + self.rho * (p.s * self.family.b3 + p.z * Vec3::Z)
    }

    /// `ξ₂` (1/µm) at `s`, for the wavelength `lambda` (µm).
    #[inline]
    pub fn xi2(&self, s: f32, lambda: f32) -> f32 {
        (self.rho * s + self.family.wo_b) / lambda
    }

    /// `ξ₂(p1) − ξ₂(p0)` (1/µm) from `ds = s1 − s0` ([`ArcPoints::chord`]): the two `ξ₂`
    /// share the offset `wo_xy · b`, which can be far larger than the chord between them.
    #[inline]
    pub fn xi2_len(&self, ds: f32, lambda: f32) -> f32 {
        self.rho * ds / lambda
    }

    /// Components `(m_t, m_b, m_z)` of a plane normal in the circle's frame.
    #[inline]
    pub fn components(&self, m: Vec3) -> (f32, f32, f32) {
        (m.dot(self.family.t3), m.dot(self.family.b3), m.z)
    }

    /// Adds to `out` the (up to two) upper-half points where the circle meets the plane
    /// `wi · m = h`. `slack = R − g ≥ 0` may be passed when the caller can form it without
    /// cancellation (the sphere does); otherwise pass `None`.
    pub fn plane_crossings<const N: usize>(
        &self,
        m: Vec3,
        h: f32,
        slack: Option<f32>,
        out: &mut ArcPoints<N>,
    ) {
        let (mt, mb, mz) = self.components(m);
        let r2 = mb * mb + mz * mz;
        if !(r2 > 1.0e-24) {
            return;
        }
        let r = math::sqrt(r2);
        let (g, disc) = match slack {
            Some(d) => (r - d, d * (2.0 * r - d)),
            None => {
                let g = (h - self.c * mt) / self.rho;
                (g, r2 - g * g)
            }
        };
        if !(disc >= 0.0) {
            return;
        }
        let root = math::sqrt(disc);
        let mut pair = [ArcPoint::START; 2];
        let mut upper = 0;
        let mut k = 0;
        while k < 2 {
            let sgn = if k == 0 { 1.0 } else { -1.0 };
            let s = (g * mb + sgn * mz * root) / r2;
            let z = (g * mz - sgn * mb * root) / r2;
            if super::horizon::on_upper_half(z) {
                pair[k] = ArcPoint::crossing(s, z);
                out.push(pair[k]);
                upper += 1;
            }
            k += 1;
        }
        if upper == 2 {
            // s₊ − s₋ = 2 m_z √(R² − g²)/R²: the shared term g m_b/R² drops out.
            out.set_pair(pair, 2.0 * mz * root / r2);
        }
    }
}

/// A short list of values (band offsets, kinks), sorted on request; fixed capacity, no
/// allocation.
#[derive(Clone, Copy, Debug)]
pub struct Breakpoints {
    /// Values; only the first `len` are meaningful.
    pub s: [f32; MAX_CUTS],
    /// Number of values.
    pub len: usize,
}

impl Breakpoints {
    /// An empty list.
    #[inline]
    pub fn empty() -> Breakpoints {
        Breakpoints {
            s: [0.0; MAX_CUTS],
            len: 0,
        }
    }

    /// Appends `s` (ignored when full or not finite).
    #[inline]
    pub fn push(&mut self, s: f32) {
        if self.len < MAX_CUTS && s.is_finite() {
            self.s[self.len] = s;
            self.len += 1;
        }
    }

    /// Sorts ascending.
    pub fn sort(&mut self) {
        insertion_sort(&mut self.s, self.len, |a, b| a < b);
    }
}

/// A point of a band circle's upper half: `s = sin φ`, `z = cos φ ≥ 0`, and where a small
/// polygon's crossing formed it, `s` relative to the polygon's reference direction.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ArcPoint {
    /// `sin φ`, the coordinate `ξ₂` is linear in.
    pub s: f32,
    /// `cos φ`, the height above the horizon (relative to the circle's radius).
    pub z: f32,
    /// `s − r̂·b₃/ρ = (w − r̂)·b₃/ρ`, `r̂` a small polygon's reference direction, formed
    /// from the polygon's local offsets ([`super::polygon::SphericalPolygon`]); `+∞` where
    /// not formed. Two such points give their chord to the relative accuracy of the
    /// offsets, where `s₁ − s₀` keeps only an ulp of `|s|`.
    pub local: f32,
    /// `(w − r̂)_z/ρ` beside [`ArcPoint::local`] (`+∞` where not formed): with it and the
    /// band's height over `r̂`, a point between two crossings is placed relative to the
    /// polygon as finely as the crossings themselves.
    pub local_z: f32,
}

impl ArcPoint {
    /// The horizon end `φ = −π/2`.
    pub const START: ArcPoint = ArcPoint {
        s: -1.0,
        z: 0.0,
        local: f32::INFINITY,
        local_z: f32::INFINITY,
    };
    /// The horizon end `φ = π/2`.
    pub const END: ArcPoint = ArcPoint {
        s: 1.0,
        z: 0.0,
        local: f32::INFINITY,
        local_z: f32::INFINITY,
    };

    /// The point `(s, z)` (clamped to the circle's range), without a local coordinate.
    #[inline]
    pub fn on_circle(s: f32, z: f32) -> ArcPoint {
        ArcPoint {
            s: math::clamp(s, -1.0, 1.0),
            z: math::min(z, 1.0),
            local: f32::INFINITY,
            local_z: f32::INFINITY,
        }
    }

    /// A crossing found as `(s, z)`, [`ArcPoint::on_circle`] with `s` taken from `z` beyond
    /// `|s| = 1/2`: `z` places the point finer there (an ulp of `s` is `1/z` times longer
    /// along the circle), and `s` then falls as `z` rises, so the order by `s` agrees with
    /// the order by `z` ([`ArcPoint::before`], [`ArcPoint::s_minus`]).
    #[inline]
    pub fn crossing(s: f32, z: f32) -> ArcPoint {
        let s = if s > 0.5 {
            math::sqrt0(1.0 - z * z)
        } else if s < -0.5 {
            -math::sqrt0(1.0 - z * z)
        } else {
            s
        };
        ArcPoint::on_circle(s, z)
    }

    /// Whether `self` comes before `other` along the half circle (`φ` increasing): by `s`,
    /// and where two `s` round to the same value, by `z` (falling towards `s = 1`, rising
    /// from `s = −1`).
    #[inline]
    pub fn before(self, other: ArcPoint) -> bool {
        self.s < other.s
            || (self.s == other.s
                && if self.s > 0.0 {
                    self.z > other.z
                } else {
                    self.z < other.z
                })
    }

    /// `self.s − p0.s`. Where both lie on one side beyond `|s| = 1/2` it is
    /// `(z0 − z)(z0 + z)/(s0 + s)`: near the horizon `s` keeps only its absolute accuracy
    /// (an ulp of 6e-8 there is an arc of 3.5e-4 rad), `z` its relative one.
    #[inline]
    pub fn s_minus(self, p0: ArcPoint) -> f32 {
        self.s_minus_by(p0, p0.z - self.z, self.s - p0.s)
    }

    /// `self.s − p0.s` given `z_drop = p0.z − self.z` and `ds`, the plain difference, each
    /// formed as finely as the caller can ([`ArcPoint::s_minus`]; a small polygon's local
    /// coordinates, [`ArcPoints::chord`]): `z_drop (z0 + z)/(s0 + s)` where both lie on one
    /// side beyond `|s| = 1/2`, else `ds`.
    #[inline]
    fn s_minus_by(self, p0: ArcPoint, z_drop: f32, ds: f32) -> f32 {
        if (self.s >= 0.5 && p0.s >= 0.5) || (self.s <= -0.5 && p0.s <= -0.5) {
            z_drop * (p0.z + self.z) / (p0.s + self.s)
        } else {
            ds
        }
    }

    /// A point strictly between `self` and `other` (the bisector of the two directions;
    /// `φ = 0` between the two horizon ends).
    #[inline]
    pub fn between(self, other: ArcPoint) -> ArcPoint {
        let (s, z) = (self.s + other.s, self.z + other.z);
        let len = math::sqrt(s * s + z * z);
        if len > 0.0 {
            ArcPoint::on_circle(s / len, z / len)
        } else {
            ArcPoint::on_circle(0.0, 1.0)
        }
    }
}

/// A short list of [`ArcPoint`]s on one band circle, fixed capacity, no allocation: its
/// horizon ends and where it crosses a light's boundary.
///
/// Beside them, the two crossings of the last plane met twice on the upper half and the
/// exact difference of their `s`: each `s` is rounded to an ulp of `|s|`, so `s₁ − s₀`
/// carries that error into a chord far shorter than `|s|` (a small sphere light), while
/// the difference of the crossing formula's two roots is formed without it.
#[derive(Clone, Copy, Debug)]
pub struct ArcPoints<const N: usize = MAX_BREAKPOINTS> {
    /// Points; only the first `len` are meaningful.
    pub p: [ArcPoint; N],
    /// Number of points.
    pub len: usize,
    /// Two crossings of one plane (the horizon ends until a plane has two).
    pair: [ArcPoint; 2],
    /// `pair[0].s − pair[1].s`, exactly as the crossing formula gives it.
    pair_chord: f32,
}

impl<const N: usize> ArcPoints<N> {
    /// The two ends of the upper half circle (the horizon).
    #[inline]
    pub fn half_circle() -> ArcPoints<N> {
        let mut b = ArcPoints {
            p: [ArcPoint::START; N],
            len: 0,
            pair: [ArcPoint::END, ArcPoint::START],
            pair_chord: 2.0,
        };
        b.push(ArcPoint::START);
        b.push(ArcPoint::END);
        b
    }

    /// Appends `p` (ignored when full or not finite).
    #[inline]
    pub fn push(&mut self, p: ArcPoint) {
        if self.len < N && p.s.is_finite() && p.z.is_finite() {
            self.p[self.len] = p;
            self.len += 1;
        }
    }

    /// Records two crossings of one plane and `pair[0].s − pair[1].s`.
    #[inline]
    pub fn set_pair(&mut self, pair: [ArcPoint; 2], chord: f32) {
        if chord.is_finite() {
            self.pair = pair;
            self.pair_chord = chord;
        }
    }

    /// `p1.s − p0.s`: the difference of their local coordinates where both have one, the
    /// recorded pair's own difference where `(p0, p1)` are its two crossings, else
    /// [`ArcPoint::s_minus`].
    #[inline]
    pub fn chord(&self, p0: ArcPoint, p1: ArcPoint) -> f32 {
        if p0.local.is_finite() && p1.local.is_finite() {
            // Beyond |s| = 1/2 on one side from the heights, whose difference the local form
            // keeps (near the band's horizon end `s` moves only at second order along the
            // band, and so does its local coordinate).
            p1.s_minus_by(p0, p0.local_z - p1.local_z, p1.local - p0.local)
        } else if p0 == self.pair[1] && p1 == self.pair[0] {
            self.pair_chord
        } else if p0 == self.pair[0] && p1 == self.pair[1] {
            -self.pair_chord
        } else {
            p1.s_minus(p0)
        }
    }

    /// Sorts along the circle ([`ArcPoint::before`]).
    pub fn sort(&mut self) {
        insertion_sort(&mut self.p, self.len, ArcPoint::before);
    }

    /// Sorts, then calls `visit(p0, p1, ds)` for every maximal run of consecutive arcs
    /// `(a, b)` that are `lit(a, b)` (a test of a point between them; adjacent lit pieces are
    /// merged, so the band integral is evaluated once per lit interval);
    /// `ds = p1.s − p0.s` ([`ArcPoints::chord`]).
    pub fn lit_intervals<
        I: FnMut(ArcPoint, ArcPoint) -> bool,
        V: FnMut(ArcPoint, ArcPoint, f32),
    >(
        &mut self,
        mut lit_between: I,
        mut visit: V,
    ) {
        self.sort();
        let mut open = false;
        let mut start = ArcPoint::START;
        let mut i = 0;
        while i + 1 < self.len && i + 1 < N {
            let (a, b) = (self.p[i], self.p[i + 1]);
            let lit = a.before(b) && lit_between(a, b);
            if lit && !open {
                start = a;
                open = true;
            } else if !lit && open && a.before(b) {
                visit(start, a, self.chord(start, a));
                open = false;
            }
            i += 1;
        }
        if open && self.len > 0 && self.len <= N {
            let end = self.p[self.len - 1];
            visit(start, end, self.chord(start, end));
        }
    }
}

/// Sorts `v[..len]` so that no element comes `before` an earlier one (insertion sort, stable:
/// a few dozen values).
#[inline]
fn insertion_sort<T: Copy, F: Fn(T, T) -> bool, const N: usize>(
    v: &mut [T; N],
    len: usize,
    before: F,
) {
    let mut i = 1;
    while i < len && i < N {
        let x = v[i];
        let mut j = i;
        while j > 0 && before(x, v[j - 1]) {
            v[j] = v[j - 1];
            j -= 1;
        }
        v[j] = x;
        i += 1;
    }
}
