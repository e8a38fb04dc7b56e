//! Polygonal lights as spherical polygons (Velinov 2018 §3.4.2, Eqs. 36–41).
//!
//! Each vertex `V` (relative to the shading point) projects to `U = V/|V|` (Eq. 36); a
//! straight edge projects onto the great arc between its ends, whose plane has normal
//! `U_m × U_{m+1}`. The band crosses each edge plane where [`super::band_circle`] says
//! (Eqs. 38–40 solve the same problem in the arc's own parametrisation).
//!
//! The polygon is the union of the fan of spherical triangles `(ĉ, U_m, U_{m+1})` around the
//! normalised vertex mean `ĉ` — exact for every polygon that is star-shaped about `ĉ`
//! (all convex ones, and the star-shaped triangle sets of Velinov Fig. 10); either winding.
//! Degenerate triangles (collinear or repeated vertices, zero area, a vertex at the shading
//! point, the polygon's plane through the point) contain nothing. Emitters are two-sided.

use super::band_circle::{ArcPoints, BandCircle, Breakpoints};
use super::limits::MAX_VERTICES;
use crate::math;
use glam::Vec3;

/// Below this `|det(ĉ, U_m, U_{m+1})|` a fan triangle counts as degenerate.
const MIN_DET: f32 = 1.0e-12;

/// A spherical polygon with precomputed edge and spoke planes.
#[derive(Clone, Copy, Debug)]
pub struct SphericalPolygon {
    /// Number of vertices (3..=[`MAX_VERTICES`]).
    pub count: usize,
    /// Edge plane normals `U_m × U_{m+1}`.
    edge: [Vec3; MAX_VERTICES],
    /// Spoke plane normals `ĉ × U_m`.
    spoke: [Vec3; MAX_VERTICES],
    /// Orientation sign of fan triangle m (0: degenerate).
    orient: [f32; MAX_VERTICES],
    /// Unit vertex directions `U_m`.
    vertex: [Vec3; MAX_VERTICES],
    /// Normalised vertex mean ĉ.
    pub center: Vec3,
}

impl SphericalPolygon {
    /// The empty polygon (contains nothing).
    pub const EMPTY: SphericalPolygon = SphericalPolygon {
        count: 0,
        edge: [Vec3::ZERO; MAX_VERTICES],
        spoke: [Vec3::ZERO; MAX_VERTICES],
        orient: [0.0; MAX_VERTICES],
        vertex: [Vec3::ZERO; MAX_VERTICES],
        center: Vec3::Z,
    };

    /// The half-angle of the cone about [`center`](Self::center) that contains the polygon:
    /// the largest angle to a vertex (a polygon within a hemisphere has its farthest point
    /// from an inside direction at a vertex).
    pub fn half_angle(&self) -> f32 {
        let mut half = 0.0f32;
        let mut i = 0;
        while i < self.count && i < MAX_VERTICES {
            half = math::max(half, math::angle_between(self.center, self.vertex[i]));
            i += 1;
        }
        half
    }

    /// Projects `count` vertices (`xyz` of each `[f32; 4]`, relative to the shading point).
    /// `None` for fewer than 3 vertices, non-finite input, or a polygon entirely below the
    /// horizon.
    #[allow(clippy::manual_range_contains)] // see the comparison below
    pub fn new(vertices: &[[f32; 4]; MAX_VERTICES], count: u32) -> Option<SphericalPolygon> {
        let n = count as usize;
        // Plain comparisons: `RangeInclusive::contains` goes through `Bound<&usize>`, whose
        // pointer is not a logical pointer on SPIR-V (spirv-val rejects it).
        if n < 3 || n > MAX_VERTICES {
            return None;
        }
        let mut u = [Vec3::ZERO; MAX_VERTICES];
        let mut sum = Vec3::ZERO;
        let mut max_z = f32::NEG_INFINITY;
        let mut i = 0;
        while i < n && i < MAX_VERTICES {
            let v = vertices[i];
            let p = Vec3::new(v[0], v[1], v[2]);
            if !p.is_finite() {
                return None;
            }
            u[i] = p.normalize_or_zero();
            sum += u[i];
            max_z = math::max(max_z, u[i].z);
            i += 1;
        }
        if super::horizon::all_below(max_z) {
            return None;
        }
        let center = sum.normalize_or_zero();
        let mut poly = SphericalPolygon {
            count: n,
            edge: [Vec3::ZERO; MAX_VERTICES],
            spoke: [Vec3::ZERO; MAX_VERTICES],
            orient: [0.0; MAX_VERTICES],
            vertex: u,
            center,
        };
        let mut m = 0;
        while m < n && m < MAX_VERTICES {
            let next = if m + 1 < n { m + 1 } else { 0 };
            let a = u[m];
            let b = if next < MAX_VERTICES { u[next] } else { a };
            // `a × b` as `a × (b − a)`, `ĉ × a` as `ĉ × (a − ĉ)`: the same normals, but for
            // close directions (a small light) the plain products cancel to an absolute
            // error ~ε, which tilts the plane by ~ε/|a − b| — 2e-3 rad, a hundred times the
            // light, at 2.6e-5 rad (`reference/light_sweep.py`); the differences of nearby
            // f32 directions are exact, and the products then keep ~ε of relative accuracy.
            poly.edge[m] = a.cross(b - a);
            poly.spoke[m] = center.cross(a - center);
            let det = poly.edge[m].dot(center);
            poly.orient[m] = if math::abs(det) > MIN_DET {
                math::sign(det)
            } else {
                0.0
            };
            m += 1;
        }
        Some(poly)
    }

    /// Whether the unit direction `w` is inside one of the fan triangles.
    pub fn contains(&self, w: Vec3) -> bool {
        let mut m = 0;
        while m < self.count && m < MAX_VERTICES {
            let o = self.orient[m];
            let next = if m + 1 < self.count { m + 1 } else { 0 };
            if o != 0.0 && next < MAX_VERTICES {
                let inside = o * self.edge[m].dot(w) >= 0.0
                    && o * self.spoke[m].dot(w) >= 0.0
                    && o * self.spoke[next].dot(w) <= 0.0;
                if inside {
                    return true;
                }
            }
            m += 1;
        }
        false
    }

    /// `[min, max]` of `u · w` over the polygon's directions `w` (the union of its fan
    /// triangles; the horizon is not applied, so this may be wider than the lit part).
    pub fn dot_range(&self, u: Vec3) -> (f32, f32) {
        let mut range = (f32::INFINITY, f32::NEG_INFINITY);
        let mut m = 0;
        while m < self.count && m < MAX_VERTICES {
            let next = if m + 1 < self.count { m + 1 } else { 0 };
            if next < MAX_VERTICES {
                range = widen(range, arc_dot_range(self.vertex[m], self.vertex[next], u));
                range = widen(range, arc_dot_range(self.center, self.vertex[m], u));
            }
            m += 1;
        }
        // An extremum inside a fan triangle is at ±u itself.
        if self.contains(u) {
            range.1 = 1.0;
        }
        if self.contains(-u) {
            range.0 = -1.0;
        }
        range
    }

    /// Adds `u · w` at the vertices above the horizon, where edges cross the horizon, and
    /// where a band `u · w = c` is tangent to an edge above the horizon ([`arc_stationary`]):
    /// a band curves more than a great circle, so it can touch an edge from inside the light
    /// anywhere in its range, and its lit chord opens like a square root there.
    pub fn kinks(&self, u: Vec3, out: &mut Breakpoints) {
        let mut m = 0;
        while m < self.count && m < MAX_VERTICES {
            let next = if m + 1 < self.count { m + 1 } else { 0 };
            let a = self.vertex[m];
            if a.z >= 0.0 {
                out.push(u.dot(a));
            }
            if next < MAX_VERTICES {
                let b = self.vertex[next];
                arc_stationary(a, b, u, |value, w| {
                    if w.z >= 0.0 {
                        out.push(value);
                    }
                });
                if (a.z > 0.0 && b.z < 0.0) || (a.z < 0.0 && b.z > 0.0) {
                    // On the great circle through a and b, between them, at z = 0.
                    let p = a * math::abs(b.z) + b * math::abs(a.z);
                    out.push(u.dot(p.normalize_or_zero()));
                }
            }
            m += 1;
        }
    }

    /// Adds where the band crosses the great circles of the polygon's edges.
    pub fn crossings(&self, band: &BandCircle, out: &mut ArcPoints) {
        let mut m = 0;
        while m < self.count && m < MAX_VERTICES {
            band.plane_crossings(self.edge[m], 0.0, None, out);
            m += 1;
        }
    }
}

/// The union of two ranges.
#[inline]
fn widen(a: (f32, f32), b: (f32, f32)) -> (f32, f32) {
    (math::min(a.0, b.0), math::max(a.1, b.1))
}

/// `[min, max]` of `u · w` along the shorter great-circle arc from `a` to `b` (unit): the
/// ends and the stationary points on the arc ([`arc_stationary`]).
pub fn arc_dot_range(a: Vec3, b: Vec3, u: Vec3) -> (f32, f32) {
    let (ua, ub) = (u.dot(a), u.dot(b));
    let mut range = (math::min(ua, ub), math::max(ua, ub));
    arc_stationary(a, b, u, |value, _| range = widen(range, (value, value)));
    range
}

/// Visits `(u · w, w)` at the stationary points of `u · w` that lie on the shorter
/// great-circle arc from `a` to `b` (unit): `w(s) = a cos s + e sin s`, so
/// `u · w = A cos s + B sin s` peaks at `s = atan2(B, A)`, where `w = (A a + B e)/√(A² + B²)`
/// and the value is `√(A² + B²)`, and bottoms out half a turn away, at `−w`. There a band
/// `u · w = c` is tangent to the arc.
pub fn arc_stationary<V: FnMut(f32, Vec3)>(a: Vec3, b: Vec3, u: Vec3, mut visit: V) {
    let n = a.cross(b);
    let sin_t = n.length();
    if !(sin_t > 1.0e-7) {
        return;
    }
    let theta = math::atan2(sin_t, a.dot(b));
    let e = n.cross(a) * (1.0 / sin_t);
    let (p, q) = (u.dot(a), u.dot(e));
    let amp = math::sqrt(p * p + q * q);
    let s_max = math::atan2(q, p);
    let s_min = if s_max > 0.0 {
        s_max - math::PI
    } else {
        s_max + math::PI
    };
    let peak = if amp > 0.0 {
        (a * p + e * q) * (1.0 / amp)
    } else {
        a
    };
    if s_max >= 0.0 && s_max <= theta {
        visit(amp, peak);
    }
    if s_min >= 0.0 && s_min <= theta {
        visit(-amp, -peak);
    }
}
