//! Clipping at the horizon.
//!
//! Light below the tangent plane does not reach the surface. Velinov 2018 §3.4.1 snaps
//! crossing points below the surface onto the horizon arc and clips polygons into new
//! triangles (§3.4.2). Here the band is parametrised on its upper half circle only
//! (`cos φ ≥ 0`, see [`super::band_circle`]), so clipping reduces to dropping crossings with
//! `cos φ < 0` and always keeping the two horizon ends `s = ±1` as breakpoints: a light
//! partly below the horizon is cut exactly where the band meets the horizon, a light fully
//! below it has no lit midpoint. The quick rejects below only save work.

/// Whether a crossing with circle coordinate `z' = cos φ` lies on the upper half circle.
#[inline]
pub fn on_upper_half(z: f32) -> bool {
    z >= 0.0
}

/// A sphere of `radius` whose centre is at height `center_z` (same units) lies entirely
/// below the horizon (Velinov's "fully below" test; touching counts as below: zero
/// measure).
#[inline]
pub fn sphere_below(center_z: f32, radius: f32) -> bool {
    center_z <= -radius
}

/// Every vertex of a polygon is on or below the horizon (`z ≤ 0`), so its spherical
/// polygon is too (great arcs between points of the closed lower hemisphere stay in it).
#[inline]
pub fn all_below(max_z: f32) -> bool {
    max_z <= 0.0
}
