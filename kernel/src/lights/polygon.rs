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
//!
//! A small polygon (every vertex direction within 0.1 of the first, `r̂`) is also kept in
//! local form: each vertex as `U_m − r̂`, formed from differences of the positions, so that
//! its shape keeps ~ε of its own size rather than of 1 (a light 1e-5 rad across would
//! otherwise be reshaped by 0.6 %). Its crossings, the test of which arcs are lit, the
//! range of bands it meets and their kinks are all formed from these offsets and from the
//! reference's height over the band's centre line, `r̂·t̂ + ŵo·t̂` for unit `r̂`, `t̂`, `ŵo`,
//! formed in two-fold precision ([`crate::math::twofold`]): a light and a view near a
//! coordinate axis are resolved far more finely than `ε` of 1, and the `f32` directions'
//! norms alone moved such a light against the band by ~ε (11× the bound near the horizon).
//! The chord between two crossings is the difference of their local coordinates
//! ([`ArcPoint::local`]).

use super::band_circle::{ArcPoint, ArcPoints, BandCircle, BandFamily, Breakpoints, carried_or};
use super::limits::MAX_VERTICES;
use crate::math;
use crate::math::twofold;
use glam::Vec3;

/// Below this `|det(ĉ, U_m, U_{m+1})|` a fan triangle counts as degenerate.
const MIN_DET: f32 = 1.0e-12;

/// Edge parameters `τ` whose crossings the wide-band local form keeps: the edge
/// (`0 ≤ τ ≤ 1`) and a margin, so that a crossing at a vertex is found on both of its edges.
const LOCAL_TAU: (f32, f32) = (-0.5, 1.5);

/// Edges longer than `√` this (chord, rad) correct the wide-band crossing equation for the
/// arc's `N` once ([`SphericalPolygon::edge_crossings`]).
const LOCAL_EXACT_N: f32 = 1.0e-4;

/// Edges longer than `√` this (chord, rad) correct it twice.
const LOCAL_TWICE_N: f32 = 1.0e-2;

/// A polygon whose vertex directions all lie within this chord of the first one's crosses
/// the bands in its local form ([`SphericalPolygon::crossings`]); a larger light's chords
/// are long enough that O(1) roundings do not matter. 0.05 before: a 0.034-rad triangle
/// about the zenith, a band through it near a vertex, was 1.4× the bound
/// (`reference/light_sweep.py`, 10^5 further queries).
const LOCAL_MAX: f32 = 0.1;

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
    /// `U_m − r̂`, `r̂ = p₀/|p₀|` the first vertex's direction, formed from the differences
    /// of the vertex positions (each to ~ε of its own length, where `U_m` itself keeps ~ε
    /// of 1: an edge of a light 1e-5 rad across would move by 0.6 % of the light).
    offset: [Vec3; MAX_VERTICES],
    /// `r̂` rounded: only the O(1) components that every vertex shares are taken from it.
    reference: Vec3,
    /// The first vertex's position `p₀` (relative to the shading point), from which a
    /// local polygon's height over a band is formed ([`SphericalPolygon::centre_height`]).
    first: Vec3,
    /// 1 where every `|U_m − r̂|` is below [`LOCAL_MAX`] (and finite), else 0: the bands
    /// cross in local form ([`SphericalPolygon::is_local`]; a `u32`, not a `bool`, whose
    /// niche would carry `Option<SphericalPolygon>`'s tag, which rust-gpu cannot copy),
    /// and [`edge`](Self::edge), [`spoke`](Self::spoke) are formed from the offsets, with
    /// `edge_k`, `spoke_k` the planes' values at `r̂`.
    local: u32,
    /// `(U_m × U_{m+1})·r̂` of a local polygon (else 0): `edge_m·(r̂ + e) = edge_m·e + edge_k`.
    edge_k: [f32; MAX_VERTICES],
    /// `(C × U_m)·r̂` of a local polygon (else 0), `C` the fan's centre.
    spoke_k: [f32; MAX_VERTICES],
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
        offset: [Vec3::ZERO; MAX_VERTICES],
        reference: Vec3::Z,
        first: Vec3::Z,
        local: 0,
        edge_k: [0.0; MAX_VERTICES],
        spoke_k: [0.0; MAX_VERTICES],
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
        let mut offset = [Vec3::ZERO; MAX_VERTICES];
        let mut local = true;
        let p0 = Vec3::new(vertices[0][0], vertices[0][1], vertices[0][2]);
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
            offset[i] = direction_offset(p, p0);
            // `!(a < b)` rather than `a >= b`: NaN (a vertex at the point) counts as far.
            if !(offset[i].length_squared() < LOCAL_MAX * LOCAL_MAX) {
                local = false;
            }
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
            offset,
            reference: u[0],
            first: p0,
            local: u32::from(local),
            edge_k: [0.0; MAX_VERTICES],
            spoke_k: [0.0; MAX_VERTICES],
        };
        if local {
            poly.local_planes();
            return Some(poly);
        }
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

    /// Whether the polygon is kept in local form (every vertex direction within 0.1 of
    /// the first).
    #[inline]
    pub fn is_local(&self) -> bool {
        self.local != 0
    }

    /// A local polygon's planes from its offsets: `U_a × U_b = r̂ × Δ + a × Δ` (`a = U_a − r̂`,
    /// `Δ = U_b − U_a`), `C × U_a = r̂ × (a − e_c) + e_c × a` about the fan's centre
    /// `C = r̂ + e_c` (`e_c` the offsets' mean, `C` along ĉ), and their values at `r̂`,
    /// `(a × Δ)·r̂` and `(e_c × a)·r̂`: every term small and formed to its relative accuracy,
    /// where `U_a × (U_b − U_a)` keeps ~ε of 1 in each rounded `U`. The orientation is the
    /// edge plane's sign at `C` (no threshold: a triangle of a light 1e-6 rad across has a
    /// determinant of 1e-12).
    fn local_planes(&mut self) {
        let r = self.reference;
        let n = self.count;
        let mut centre = Vec3::ZERO;
        let mut m = 0;
        while m < n && m < MAX_VERTICES {
            centre += self.offset[m];
            m += 1;
        }
        let centre = centre * (1.0 / n as f32);
        let mut m = 0;
        while m < n && m < MAX_VERTICES {
            let a = self.offset[m];
            let ca = centre.cross(a);
            self.spoke[m] = r.cross(a - centre) + ca;
            self.spoke_k[m] = ca.dot(r);
            m += 1;
        }
        let mut m = 0;
        while m < n && m < MAX_VERTICES {
            let next = if m + 1 < n { m + 1 } else { 0 };
            if next < MAX_VERTICES {
                let a = self.offset[m];
                let along = self.offset[next] - a;
                let aa = a.cross(along);
                self.edge[m] = r.cross(along) + aa;
                self.edge_k[m] = aa.dot(r);
                let det = self.edge[m].dot(centre) + self.edge_k[m];
                self.orient[m] = if det != 0.0 { math::sign(det) } else { 0.0 };
            }
            m += 1;
        }
    }

    /// Whether the unit direction `w` is inside one of the fan triangles.
    pub fn contains(&self, w: Vec3) -> bool {
        self.inside::<false>(w)
    }

    /// Whether `p` is inside one of the fan triangles, each plane's value taken as `n·p`
    /// for a direction `p = w` ([`SphericalPolygon::contains`]), or as `n·p + k` for a
    /// local offset `p = e`, the direction `r̂ + e` (`LOCAL`, `contains_local`).
    fn inside<const LOCAL: bool>(&self, p: Vec3) -> bool {
        let at_r = |k: f32| if LOCAL { k } else { 0.0 };
        let mut m = 0;
        while m < self.count && m < MAX_VERTICES {
            let o = self.orient[m];
            let next = if m + 1 < self.count { m + 1 } else { 0 };
            if o != 0.0 && next < MAX_VERTICES {
                let inside = o * (self.edge[m].dot(p) + at_r(self.edge_k[m])) >= 0.0
                    && o * (self.spoke[m].dot(p) + at_r(self.spoke_k[m])) >= 0.0
                    && o * (self.spoke[next].dot(p) + at_r(self.spoke_k[next])) <= 0.0;
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
    /// Each value is added shifted by `shift` (`wo·t` for [`SphericalPolygon::offset_kinks`]).
    pub fn kinks(&self, u: Vec3, shift: f32, out: &mut Breakpoints) {
        let mut m = 0;
        while m < self.count && m < MAX_VERTICES {
            let next = if m + 1 < self.count { m + 1 } else { 0 };
            let a = self.vertex[m];
            if a.z >= 0.0 {
                out.push(u.dot(a) + shift);
            }
            if next < MAX_VERTICES {
                let b = self.vertex[next];
                arc_stationary(a, b, u, |value, w| {
                    if w.z >= 0.0 {
                        out.push(value + shift);
                    }
                });
                if (a.z > 0.0 && b.z < 0.0) || (a.z < 0.0 && b.z > 0.0) {
                    // On the great circle through a and b, between them, at z = 0.
                    let p = a * math::abs(b.z) + b * math::abs(a.z);
                    out.push(u.dot(p.normalize_or_zero()) + shift);
                }
            }
            m += 1;
        }
    }

    /// `[min, max]` of the offsets `o` of the bands of `family` that meet the polygon:
    /// [`dot_range`] along `t₃` shifted by `wo·t`, or for a small polygon the same from its
    /// local offsets (`band_offset_of`), which agree with its crossings
    /// to the offsets' relative accuracy where `t₃ · w` keeps only ~ε of 1.
    ///
    /// [`dot_range`]: SphericalPolygon::dot_range
    pub fn offset_range(&self, family: &BandFamily) -> (f32, f32) {
        if !self.is_local() {
            let (lo, hi) = self.dot_range(family.t3);
            return (lo + family.wo_t, hi + family.wo_t);
        }
        let height = carried_or(family.centre_height, || self.centre_height(family));
        let mut range = (f32::INFINITY, f32::NEG_INFINITY);
        let mut m = 0;
        while m < self.count && m < MAX_VERTICES {
            let next = if m + 1 < self.count { m + 1 } else { 0 };
            if next < MAX_VERTICES {
                let v = self.band_offset_of(family, height, self.offset[m]);
                range = widen(range, (v, v));
                let tau = self.local_stationary(family.t3, self.offset[m], self.offset[next]);
                if tau > 0.0 && tau < 1.0 {
                    let v = self.band_offset_of(
                        family,
                        height,
                        self.local_point(self.offset[m], self.offset[next], tau).0,
                    );
                    range = widen(range, (v, v));
                }
            }
            m += 1;
        }
        if self.contains(family.t3) {
            range.1 = 1.0 + family.wo_t;
        }
        if self.contains(-family.t3) {
            range.0 = -1.0 + family.wo_t;
        }
        range
    }

    /// Adds the offsets of the bands of `family` where the chord has a kink ([`kinks`]
    /// along `t₃`, shifted by `wo·t`), for a small polygon from its local offsets, as
    /// [`SphericalPolygon::offset_range`].
    ///
    /// [`kinks`]: SphericalPolygon::kinks
    pub fn offset_kinks(&self, family: &BandFamily, out: &mut Breakpoints) {
        if !self.is_local() {
            self.kinks(family.t3, family.wo_t, out);
            return;
        }
        let height = carried_or(family.centre_height, || self.centre_height(family));
        let mut m = 0;
        while m < self.count && m < MAX_VERTICES {
            let next = if m + 1 < self.count { m + 1 } else { 0 };
            if next < MAX_VERTICES {
                if self.reference.z + self.offset[m].z >= 0.0 {
                    out.push(self.band_offset_of(family, height, self.offset[m]));
                }
                let tau = self.local_stationary(family.t3, self.offset[m], self.offset[next]);
                if tau > 0.0 && tau < 1.0 {
                    let (e, z) = self.local_point(self.offset[m], self.offset[next], tau);
                    if z >= 0.0 {
                        out.push(self.band_offset_of(family, height, e));
                    }
                }
                let za = self.reference.z + self.offset[m].z;
                let zb = self.reference.z + self.offset[next].z;
                if (za > 0.0 && zb < 0.0) || (za < 0.0 && zb > 0.0) {
                    // `z` is linear in τ before the division by N.
                    let tau = za / (za - zb);
                    out.push(self.band_offset_of(
                        family,
                        height,
                        self.local_point(self.offset[m], self.offset[next], tau).0,
                    ));
                }
            }
            m += 1;
        }
    }

    /// The offset `o` of the band of `family` through the direction `r̂ + e` (`e` a local
    /// offset, `r̂ + e` unit), `height` the reference's over the centre line
    /// ([`SphericalPolygon::centre_height`]). Where the bands are wide (`|c₀| ≤ ρ₀`) it is
    /// `height + e·t₃`; where they are small circles about `±t₃` (`|c₀| > ρ₀`) an
    /// ulp of `c` would move them by `ε/ρ`, and the band is placed by its radius instead:
    /// `ρ(o)² = ρ₀² + o(2 wo·t − o)` equals the direction's `ρ_w² = (r̂_b + e_b)² + (r̂_z +
    /// e_z)²` at `o = D/(wo·t + sgn(wo·t)√(wo·t² − D))`, `D = ρ_w² − ρ₀²` formed as
    /// `(r̂_b² + r̂_z² − ρ₀²) + 2(r̂_b e_b + r̂_z e_z) + e_b² + e_z²`, the first term, for unit
    /// `r̂`, `c₀² − (r̂·t₃)² = −height (r̂·t₃ + c₀)` as the crossings form it
    /// ([`LocalBand::excess`]).
    fn band_offset_of(&self, family: &BandFamily, height: f32, e: Vec3) -> f32 {
        let r = self.reference;
        if !family.narrow() {
            return height + e.dot(family.t3);
        }
        let (rb, eb) = (r.dot(family.b3), e.dot(family.b3));
        let d = -height * (r.dot(family.t3) - family.wo_t)
            + (2.0 * (rb * eb + r.z * e.z) + (eb * eb + e.z * e.z));
        let wo_t = family.wo_t;
        d / (wo_t + math::sign(wo_t) * math::sqrt0(wo_t * wo_t - d))
    }

    /// `(w − r̂, w_z)` at `w(τ) = ((1 − τ) U_a + τ U_b)/N` on the arc from `U_a` to `U_b`,
    /// `N² = 1 − τ(1 − τ) L²`: `w − r̂ = (G + r̂ (1 − N))/N`, `G = (1 − τ)(U_a − r̂) + τ(U_b −
    /// r̂)`, `1 − N = τ(1 − τ) L²/(1 + N)`, each small and formed to its relative accuracy.
    fn local_point(&self, da: Vec3, db: Vec3, tau: f32) -> (Vec3, f32) {
        let along = db - da;
        let bend = tau * (1.0 - tau) * along.length_squared();
        let n = math::sqrt0(1.0 - bend);
        let g = da + along * tau;
        let e = (g + self.reference * (bend / (1.0 + n))) * (1.0 / n);
        (e, (self.reference.z + g.z) / n)
    }

    /// Where `u · w(τ)` is stationary on the arc from `U_a` to `U_b` (small polygons):
    /// `τ* = 1/2 + (U_b − U_a)·u/(r̂·u L²)` to first order in `L²`; the value there is
    /// second-order in `τ`'s error. NaN or outside `(0, 1)` where it is not on the edge.
    fn local_stationary(&self, u: Vec3, da: Vec3, db: Vec3) -> f32 {
        let along = db - da;
        0.5 + along.dot(u) / (self.reference.dot(u) * along.length_squared())
    }

    /// `r̂·t₃ − c₀`, the reference's height over the centre line `w·t₃ = c₀` of `family`'s
    /// bands, for unit `r̂ = p₀/|p₀|`, `t₃` and `wo`: `((p₀·t)/|p₀| + (wo·t)/|wo|)/|t|`,
    /// the two quotients in two-fold precision ([`twofold`]), so that the difference keeps
    /// what the inputs resolve. In `f32` the two O(1) terms, and the rounded directions'
    /// norms, put ~ε between the light and the band; a light and a view near a coordinate
    /// axis are resolved to ~1e-10 (`reference/light_sweep.py`, 11× the bound near the
    /// horizon).
    pub fn centre_height(&self, family: &BandFamily) -> f32 {
        let (p, t, wo) = (self.first, family.t3, family.wo);
        let along = |v: Vec3| twofold::dot2(v.x, t.x, v.y, t.y) / twofold::length(v.x, v.y, v.z);
        (along(p) + along(wo)).value() / math::sqrt(t.x * t.x + t.y * t.y)
    }

    /// The reference direction `r̂` seen from `band` ([`LocalBand`]), formed once for the
    /// band's crossings and the test of its arcs; zeros for a polygon not in local form.
    pub fn local_band(&self, band: &BandCircle) -> LocalBand {
        if !self.is_local() {
            return LocalBand::default();
        }
        let r = self.reference;
        let rb = r.dot(band.family.b3);
        let height = carried_or(band.family.centre_height, || {
            self.centre_height(&band.family)
        }) - band.offset;
        LocalBand {
            height,
            excess: -height * (r.dot(band.family.t3) + band.c),
            rb,
            s_ref: rb / band.rho,
            z_ref: r.z / band.rho,
        }
    }

    /// Whether the arc of `band` between its consecutive points `a` and `b` is lit: for a
    /// small polygon, the arc's midpoint from their local offsets (`w − r̂`; a horizon end's
    /// from `s = ±1`, `z = 0`) against the fan in local form
    /// (`contains_local`), which sees the polygon its crossings see;
    /// otherwise [`SphericalPolygon::contains`] at [`ArcPoint::between`].
    pub fn lit_between(&self, band: &BandCircle, at: &LocalBand, a: ArcPoint, b: ArcPoint) -> bool {
        if !self.is_local() || !(a.local.is_finite() || b.local.is_finite()) {
            return self.contains(band.point(a.between(b)));
        }
        let end = |p: ArcPoint| {
            if p.local.is_finite() {
                (p.local, p.local_z)
            } else {
                // A horizon end (the only points without a local form here).
                (p.s - at.s_ref, -at.z_ref)
            }
        };
        let ((ba, za), (bb, zb)) = (end(a), end(b));
        // The arc's midpoint, on the circle: the chord's midpoint `m` (in units of ρ, about
        // the circle's centre) pushed out to the circle, `m/|m| = m (1 + k)`, with
        // `|m|² = 1 − x`, `x = (d/2)²` from the chord `d` in local coordinates; the chord's
        // own midpoint lies `d²/8` inside, 6 % of a 0.05-rad light on a band of radius 0.1.
        let (db, dz) = (ba - bb, za - zb);
        let x = math::min(0.25 * (db * db + dz * dz), 0.75);
        let root = math::sqrt(1.0 - x);
        let k = x / (root * (1.0 + root));
        let (mb, mz) = (0.5 * (ba + bb), 0.5 * (za + zb));
        let (mb, mz) = (mb + (at.s_ref + mb) * k, mz + (at.z_ref + mz) * k);
        let f = &band.family;
        let e = f.t3 * (-at.height) + (f.b3 * mb + Vec3::Z * mz) * band.rho;
        self.contains_local(e)
    }

    /// [`SphericalPolygon::contains`] for the direction `r̂ + e` (`e` small) of a local
    /// polygon: each plane's value `n·(r̂ + e)` as `n·e + n·r̂`, the latter formed from the
    /// offsets (`local_planes`), so that the test sees the polygon its crossings see.
    #[inline]
    fn contains_local(&self, e: Vec3) -> bool {
        self.inside::<true>(e)
    }

    /// Adds where the band crosses the great circles of the polygon's edges: for a small
    /// polygon (every vertex within `LOCAL_MAX` = 0.1 of the first) in local form, with
    /// [`ArcPoint::local`] set (`edge_crossings` on wide bands, `edge_crossings_narrow` on
    /// narrow ones); otherwise on the whole
    /// circles ([`BandCircle::plane_crossings`]).
    pub fn crossings(&self, band: &BandCircle, out: &mut ArcPoints) {
        self.crossings_with(band, &self.local_band(band), out);
    }

    /// [`SphericalPolygon::crossings`] with the band's [`LocalBand`] already formed.
    pub fn crossings_with(&self, band: &BandCircle, at: &LocalBand, out: &mut ArcPoints) {
        let narrow = band.family.narrow();
        let mut m = 0;
        while m < self.count && m < MAX_VERTICES {
            if self.is_local() {
                let next = if m + 1 < self.count { m + 1 } else { 0 };
                if next < MAX_VERTICES {
                    if narrow {
                        self.edge_crossings_narrow(band, at, self.edge[m], self.edge_k[m], out);
                    } else {
                        self.edge_crossings(band, at, self.offset[m], self.offset[next], out);
                    }
                }
            } else {
                band.plane_crossings(self.edge[m], 0.0, None, out);
            }
            m += 1;
        }
    }

    /// The band's crossings with the great arc from `U_a` to `U_b` (extended by
    /// [`LOCAL_TAU`]), in local form, for a wide band (`|c₀| ≤ ρ₀`, where an ulp of `c` moves
    /// the band by at most `√2 ε`). Along the arc `w(τ) = ((1 − τ) U_a + τ U_b)/N`
    /// ([`SphericalPolygon::local_point`]), and with `h = U·t₃ − c` the vertices' heights over
    /// the band (`h_r + (U − r̂)·t₃`, `h_r` [`LocalBand::height`]), `w·t₃ = c`
    /// is
    ///
    /// `h_a + τ (h_b − h_a) + c τ(1 − τ) L²/(1 + N) = 0`,
    ///
    /// a quadratic in `τ` once `N` is fixed: taken as 1, which puts an error of `L⁴/128` into
    /// heights of size `L`, below `εL` up to `L² = LOCAL_EXACT_N`; beyond, once more at the
    /// root's own `N` (leaving `L⁶/2048`, below `εL` up to `L = 0.1`), and beyond
    /// `L² = LOCAL_TWICE_N` twice (`~L⁸/32768`, below `εL` up to `L = 0.2`, twice
    /// `LOCAL_MAX`). The kinks ([`SphericalPolygon::band_offset_of`]) take the same `h_r`.
    fn edge_crossings(
        &self,
        band: &BandCircle,
        at: &LocalBand,
        da: Vec3,
        db: Vec3,
        out: &mut ArcPoints,
    ) {
        let along = db - da;
        let l2 = along.length_squared();
        let t3 = band.family.t3;
        let ha = at.height + da.dot(t3);
        let dh = along.dot(t3);
        let roots = edge_roots(ha, dh, band.c * l2 * 0.5);
        let mut k = 0;
        while k < 2 {
            let mut tau = roots[k];
            // A root far outside the edge (the far one of a nearly straight edge) is left
            // alone: its `N` would move it, and `nearest` could then pick the other root.
            let near_edge = tau >= 2.0 * LOCAL_TAU.0 && tau <= 2.0 * LOCAL_TAU.1;
            let passes = if l2 > LOCAL_TWICE_N {
                2
            } else {
                u32::from(l2 > LOCAL_EXACT_N)
            };
            let mut pass = 0;
            while near_edge && pass < passes {
                let n = math::sqrt0(1.0 - tau * (1.0 - tau) * l2);
                tau = nearest(edge_roots(ha, dh, band.c * l2 / (1.0 + n)), tau);
                pass += 1;
            }
            if near_edge && tau >= LOCAL_TAU.0 && tau <= LOCAL_TAU.1 {
                let e = self.local_point(da, db, tau).0;
                self.push_local(band, at, e.dot(band.family.b3), e.z, out);
            }
            k += 1;
        }
    }

    /// Adds the point `w = r̂ + e` of the band's upper half (`e_b = (w − r̂)·b₃`,
    /// `e_z = (w − r̂)_z`), with its local coordinates ([`ArcPoint::crossing`]).
    #[inline]
    fn push_local(&self, band: &BandCircle, at: &LocalBand, eb: f32, ez: f32, out: &mut ArcPoints) {
        let z = (self.reference.z + ez) / band.rho;
        if super::horizon::on_upper_half(z) {
            let mut p = ArcPoint::crossing((at.rb + eb) / band.rho, z);
            p.local = eb / band.rho;
            p.local_z = ez / band.rho;
            out.push(p);
        }
    }

    /// The band's crossings with the great circle through `U_a` and `U_b`, in local form,
    /// for a narrow band (`|c₀| > ρ₀`, a small circle about `±t₃`): the problem of
    /// [`BandCircle::plane_crossings`] with every point written `w = r̂ + e`. The plane
    /// `(U_a × U_b)·w = 0` is `P·e + k = 0`, `P` its local-form `normal` and `k` its value at
    /// `r̂` (`local_planes`: small, each to its relative accuracy). On the band
    /// `e_t = c − r̂·t₃` (the band's height, [`LocalBand::height`]), so the
    /// crossings are where the line `P_b e_b + P_z e_z = −(k + P_t e_t)` meets the circle
    /// `(r̂_b + e_b)² + (r̂_z + e_z)² = ρ²`, whose `r̂_b² + r̂_z² − ρ²` is
    /// [`LocalBand::excess`], from the reference's height as the kinks form it. As in
    /// the band circle's own form, an ulp of `c` moves the band along `t₃` (by ~ερ across
    /// it), not across it by `ε/ρ` as the height form would (2e-6 rad on a band of radius
    /// 0.03).
    fn edge_crossings_narrow(
        &self,
        band: &BandCircle,
        at: &LocalBand,
        normal: Vec3,
        k: f32,
        out: &mut ArcPoints,
    ) {
        let r = self.reference;
        let (pt, pb, pz) = band.components(normal);
        let r2 = pb * pb + pz * pz;
        if !(r2 > 0.0) {
            return;
        }
        let et = -at.height;
        let g = -(k + pt * et);
        // The line's point nearest `r̂` (`e = 0`), and its unit direction.
        let (e0b, e0z) = (g * pb / r2, g * pz / r2);
        let len = math::sqrt(r2);
        let (db_, dz_) = (-pz / len, pb / len);
        let rb = at.rb;
        let (xb, xz) = (rb + e0b, r.z + e0z);
        // λ² + 2 B λ + C = 0 along the line.
        let bq = db_ * xb + dz_ * xz;
        let cq = at.excess + (2.0 * (rb * e0b + r.z * e0z) + (e0b * e0b + e0z * e0z));
        let disc = bq * bq - cq;
        if !(disc >= 0.0) {
            return;
        }
        let q = -(bq + math::sign(bq) * math::sqrt(disc));
        let roots = [if q != 0.0 { cq / q } else { 0.0 }, q];
        let mut i = 0;
        while i < 2 {
            let lambda = roots[i];
            self.push_local(band, at, e0b + lambda * db_, e0z + lambda * dz_, out);
            i += 1;
        }
    }
}

/// `U − r̂` for the unit directions of `p` and `p0` (`r̂ = p₀/|p₀|`), from `Δ = p − p₀`:
/// `Δ/|p| − p₀ (Δ·(p + p₀))/(|p| |p₀| (|p| + |p₀|))`. For close vertices `Δ` is formed
/// exactly and both terms to ~ε of themselves; NaN for a vertex at the shading point.
#[inline]
fn direction_offset(p: Vec3, p0: Vec3) -> Vec3 {
    let delta = p - p0;
    let (n, n0) = (p.length(), p0.length());
    delta * (1.0 / n) - p0 * (delta.dot(p + p0) / (n * n0 * (n + n0)))
}

/// A small polygon's reference direction `r̂` seen from one band
/// ([`SphericalPolygon::local_band`]): the numbers its crossings and the test of its arcs
/// share, formed once per band.
#[derive(Clone, Copy, Debug, Default)]
pub struct LocalBand {
    /// `r̂·t₃ − c`, the reference's height over the band: over the centre line in two-fold
    /// precision (`SphericalPolygon::centre_height`), the exact offset `o` apart.
    pub height: f32,
    /// `r̂_b² + r̂_z² − ρ²`, the reference's squared distance from the `t₃` axis less the
    /// band's: for unit `r̂`, `c² − (r̂·t₃)² = −height (r̂·t₃ + c)`, to the height's relative
    /// accuracy (narrow bands' crossings).
    pub excess: f32,
    /// `r̂·b₃`.
    pub rb: f32,
    /// `r̂·b₃/ρ`, the reference's `s`.
    pub s_ref: f32,
    /// `r̂_z/ρ`, the reference's `z`.
    pub z_ref: f32,
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

/// The roots `τ` of `h_a + τ dh + k τ(1 − τ) = 0` (NaN where there is none), each by the
/// form that does not cancel.
#[inline]
fn edge_roots(ha: f32, dh: f32, k: f32) -> [f32; 2] {
    // −k τ² + (dh + k) τ + h_a = 0
    let (qa, qb) = (-k, dh + k);
    let disc = qb * qb + 4.0 * k * ha;
    if !(disc >= 0.0) {
        return [f32::NAN; 2];
    }
    let q = -0.5 * (qb + math::sign(qb) * math::sqrt(disc));
    let near = if q != 0.0 { ha / q } else { f32::NAN };
    let far = if qa != 0.0 { q / qa } else { f32::NAN };
    [near, far]
}

/// The one of `roots` nearest `tau` (NaN if neither is finite).
#[inline]
fn nearest(roots: [f32; 2], tau: f32) -> f32 {
    let (r0, r1) = (roots[0], roots[1]);
    if !r1.is_finite() || (r0.is_finite() && math::abs(r0 - tau) <= math::abs(r1 - tau)) {
        r0
    } else {
        r1
    }
}
