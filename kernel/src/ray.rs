//! Rays, triangles and the portable ray queries over a [`crate::bvh`] hierarchy.
//!
//! The triangle test follows Embree's Möller–Trumbore variant (`e1 = v0 − v1`,
//! `e2 = v2 − v0`, `Ng = e2 × e1`, edge tests inclusive, scaled by `|Ng·d|` before dividing),
//! so the portable BVH and Embree report the same primitive, barycentrics and unnormalized
//! geometric normal up to rounding. Hits are ordered by `t`, then by primitive id, so a
//! closest-hit query has one answer regardless of traversal order ([`is_closer`]).

use crate::bvh::{Aabb, BvhCursor, BvhNode, next_slot};
use bytemuck::{Pod, Zeroable};
use glam::Vec3;

/// A ray `origin + t·dir` for `t ∈ (t_near, t_far]`. `dir` need not be normalized; `t` is in
/// units of `|dir|`.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct Ray {
    /// Origin.
    pub origin: [f32; 3],
    /// Start of the ray interval (exclusive).
    pub t_near: f32,
    /// Direction.
    pub dir: [f32; 3],
    /// End of the ray interval (inclusive).
    pub t_far: f32,
}

const _: () = assert!(core::mem::size_of::<Ray>() == 32);

impl Ray {
    /// The ray over `(0, ∞]`.
    #[inline]
    pub const fn new(origin: [f32; 3], dir: [f32; 3]) -> Ray {
        Ray {
            origin,
            t_near: 0.0,
            dir,
            t_far: f32::INFINITY,
        }
    }

    /// The same ray restricted to `(t_near, t_far]`.
    #[inline]
    pub const fn with_interval(self, t_near: f32, t_far: f32) -> Ray {
        Ray {
            t_near,
            t_far,
            ..self
        }
    }
}

/// Primitive id of "no hit".
pub const INVALID_ID: u32 = u32::MAX;

/// A ray hit: raw geometry only, shading happens elsewhere.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct Hit {
    /// Unnormalized geometric normal `(v1 − v0) × (v2 − v0)` (Embree's convention).
    pub ng: [f32; 3],
    /// Ray parameter of the hit.
    pub t: f32,
    /// Barycentric weight of `v1`.
    pub u: f32,
    /// Barycentric weight of `v2` (the hit point is `(1−u−v)·v0 + u·v1 + v·v2`).
    pub v: f32,
    /// Geometry id (0 for the portable single-mesh structures).
    pub geom_id: u32,
    /// Primitive id in the caller's original order.
    pub prim_id: u32,
}

const _: () = assert!(core::mem::size_of::<Hit>() == 32);

/// The total order on hits used by every closest-hit query: smaller `t` wins, equal `t` goes
/// to the smaller `(geom_id, prim_id)`.
#[inline]
pub fn is_closer(a: &Hit, b: &Hit) -> bool {
    a.t < b.t
        || (a.t == b.t
            && (a.geom_id < b.geom_id || (a.geom_id == b.geom_id && a.prim_id < b.prim_id)))
}

/// A triangle, stored by value in GPU buffers.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct Triangle {
    /// First vertex.
    pub v0: [f32; 3],
    /// Second vertex.
    pub v1: [f32; 3],
    /// Third vertex.
    pub v2: [f32; 3],
}

const _: () = assert!(core::mem::size_of::<Triangle>() == 36);

impl Triangle {
    /// Bounding box of the three vertices.
    #[inline]
    pub fn bounds(&self) -> Aabb {
        Aabb::from_point(self.v0).grow(self.v1).grow(self.v2)
    }
}

/// The result of [`intersect_triangle`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TriangleHit {
    /// Ray parameter.
    pub t: f32,
    /// Barycentric weight of `v1`.
    pub u: f32,
    /// Barycentric weight of `v2`.
    pub v: f32,
    /// Unnormalized geometric normal.
    pub ng: [f32; 3],
}

impl TriangleHit {
    /// The full hit record for primitive `prim_id` of geometry `geom_id`.
    #[inline]
    pub fn to_hit(&self, geom_id: u32, prim_id: u32) -> Hit {
        Hit {
            ng: self.ng,
            t: self.t,
            u: self.u,
            v: self.v,
            geom_id,
            prim_id,
        }
    }
}

/// Ray–triangle intersection for `t ∈ (ray.t_near, t_max]`. Both faces hit; a degenerate
/// triangle or a ray in its plane never hits; NaN anywhere means no hit.
#[inline]
pub fn intersect_triangle(ray: &Ray, tri: &Triangle, t_max: f32) -> Option<TriangleHit> {
    let o = Vec3::from_array(ray.origin);
    let d = Vec3::from_array(ray.dir);
    let v0 = Vec3::from_array(tri.v0);
    let e1 = v0 - Vec3::from_array(tri.v1);
    let e2 = Vec3::from_array(tri.v2) - v0;
    let ng = e2.cross(e1);
    let c = v0 - o;
    let r = c.cross(d);
    let den = ng.dot(d);
    let abs_den = den.abs();
    let sign = if den < 0.0 { -1.0 } else { 1.0 };
    let u = r.dot(e2) * sign;
    let v = r.dot(e1) * sign;
    if !(den != 0.0 && u >= 0.0 && v >= 0.0 && u + v <= abs_den) {
        return None;
    }
    let t = ng.dot(c) * sign / abs_den;
    if !(t > ray.t_near && t <= t_max) {
        return None;
    }
    Some(TriangleHit {
        t,
        u: u / abs_den,
        v: v / abs_den,
        ng: ng.to_array(),
    })
}

/// Per-ray precomputation for conservative ray–box tests (Ize 2013, "Robust BVH ray
/// traversal": the far slab distance is scaled up by `1 + 2γ₃` so rounding can only keep a
/// box, never drop one).
#[derive(Clone, Copy, Debug)]
pub struct RayBoxTest {
    origin: Vec3,
    inv_dir: Vec3,
    t_near: f32,
}

/// `1 + 2γ₃` rounded up, with `γₙ = n·u/(1 − n·u)` and `u = 2⁻²⁴`.
const SLAB_SLACK: f32 = 1.0 + 4.0 * f32::EPSILON;

/// `1/d`, with a huge finite stand-in for `d ≈ 0` so that `0·(1/d)` never makes a NaN.
#[inline]
fn safe_recip(d: f32) -> f32 {
    if d.abs() > 1e-30 {
        1.0 / d
    } else if d.is_sign_negative() {
        -1e30
    } else {
        1e30
    }
}

impl RayBoxTest {
    /// Precomputes the inverse direction of `ray`.
    #[inline]
    pub fn new(ray: &Ray) -> RayBoxTest {
        RayBoxTest {
            origin: Vec3::from_array(ray.origin),
            inv_dir: Vec3::new(
                safe_recip(ray.dir[0]),
                safe_recip(ray.dir[1]),
                safe_recip(ray.dir[2]),
            ),
            t_near: ray.t_near,
        }
    }

    /// `true` if the ray may meet `b` within `[t_near, t_max]` (never `false` when it does).
    #[inline]
    pub fn hits(&self, b: &Aabb, t_max: f32) -> bool {
        let t0 = (Vec3::from_array(b.min) - self.origin) * self.inv_dir;
        let t1 = (Vec3::from_array(b.max) - self.origin) * self.inv_dir;
        let lo = t0.min(t1);
        let hi = t0.max(t1);
        let enter = lo.x.max(lo.y).max(lo.z).max(self.t_near);
        let exit = hi.x.min(hi.y).min(hi.z) * SLAB_SLACK;
        enter <= exit && enter <= t_max
    }
}

/// The closest hit of `ray` with the triangles of a hierarchy.
///
/// `triangles[slot]` and `prim_ids[slot]` are in the builder's primitive order; the hit
/// reports `prim_ids[slot]` and `geom_id` 0. Ties in `t` go to the smaller primitive id.
///
/// A cursor loop over [`next_slot`] with a `move` closure that copies the current closest
/// `t` (no captured references, so it compiles for SPIR-V as well).
pub fn closest_hit(
    nodes: &[BvhNode],
    triangles: &[Triangle],
    prim_ids: &[u32],
    ray: &Ray,
) -> Option<Hit> {
    let boxes = RayBoxTest::new(ray);
    let mut best = Hit {
        ng: [0.0; 3],
        t: ray.t_far,
        u: 0.0,
        v: 0.0,
        geom_id: INVALID_ID,
        prim_id: INVALID_ID,
    };
    let mut cursor = BvhCursor::default();
    loop {
        let t_max = best.t;
        let Some(slot) = next_slot(nodes, &mut cursor, move |b: &Aabb| boxes.hits(b, t_max)) else {
            break;
        };
        let s = slot as usize;
        if s < triangles.len()
            && s < prim_ids.len()
            && let Some(h) = intersect_triangle(ray, &triangles[s], best.t)
        {
            let hit = h.to_hit(0, prim_ids[s]);
            if is_closer(&hit, &best) {
                best = hit;
            }
        }
    }
    if best.prim_id == INVALID_ID {
        None
    } else {
        Some(best)
    }
}

/// `true` if `ray` hits any triangle within `(t_near, t_far]` (a shadow-ray query).
pub fn occluded(nodes: &[BvhNode], triangles: &[Triangle], ray: &Ray) -> bool {
    let boxes = RayBoxTest::new(ray);
    let t_far = ray.t_far;
    let mut cursor = BvhCursor::default();
    // One exit (see `bvh::next_slot_before`).
    let mut hit = false;
    while !hit {
        match next_slot(nodes, &mut cursor, move |b: &Aabb| boxes.hits(b, t_far)) {
            Some(slot) => {
                let s = slot as usize;
                hit =
                    s < triangles.len() && intersect_triangle(ray, &triangles[s], t_far).is_some();
            }
            None => break,
        }
    }
    hit
}

#[cfg(test)]
mod tests {
    use super::*;

    const TRI: Triangle = Triangle {
        v0: [0.0, 0.0, 1.0],
        v1: [1.0, 0.0, 1.0],
        v2: [0.0, 1.0, 1.0],
    };

    #[test]
    fn hit_reports_t_barycentrics_and_normal() {
        let fields = |h: TriangleHit| (h.t, h.u, h.v, h.ng);
        let front = intersect_triangle(&Ray::new([0.25, 0.5, 0.0], [0.0, 0.0, 1.0]), &TRI, 10.0);
        assert_eq!(front.map(fields), Some((1.0, 0.25, 0.5, [0.0, 0.0, 1.0])));
        // Back face hits too, same normal.
        let back = intersect_triangle(&Ray::new([0.25, 0.5, 2.0], [0.0, 0.0, -1.0]), &TRI, 10.0);
        assert_eq!(back.map(fields), Some((1.0, 0.25, 0.5, [0.0, 0.0, 1.0])));
    }

    #[test]
    fn interval_is_open_below_closed_above() {
        let ray = Ray::new([0.25, 0.25, 0.0], [0.0, 0.0, 1.0]);
        assert!(intersect_triangle(&ray, &TRI, 1.0).is_some());
        assert!(intersect_triangle(&ray, &TRI, 0.999).is_none());
        assert!(intersect_triangle(&ray.with_interval(1.0, 2.0), &TRI, 2.0).is_none());
    }

    #[test]
    fn edges_are_inclusive_and_misses_miss() {
        let down = |x: f32, y: f32| Ray::new([x, y, 0.0], [0.0, 0.0, 1.0]);
        assert!(intersect_triangle(&down(0.5, 0.0), &TRI, 9.0).is_some());
        assert!(intersect_triangle(&down(0.5, 0.5), &TRI, 9.0).is_some());
        assert!(intersect_triangle(&down(0.6, 0.6), &TRI, 9.0).is_none());
        assert!(intersect_triangle(&down(-0.1, 0.5), &TRI, 9.0).is_none());
        // In the triangle's plane, NaN, degenerate.
        let grazing = Ray::new([-1.0, 0.2, 1.0], [1.0, 0.0, 0.0]);
        assert!(intersect_triangle(&grazing, &TRI, 9.0).is_none());
        assert!(intersect_triangle(&down(f32::NAN, 0.5), &TRI, 9.0).is_none());
        let flat = Triangle {
            v2: [2.0, 0.0, 1.0],
            ..TRI
        };
        assert!(intersect_triangle(&down(0.5, 0.0), &flat, 9.0).is_none());
    }

    #[test]
    fn ray_box_test_is_conservative_for_axis_parallel_rays() {
        // Node bounds are rounded out by the builder, which keeps rays lying in a face plane.
        let b = Aabb::new([0.0; 3], [1.0; 3]).round_out();
        let ray = Ray::new([0.0, 0.5, -1.0], [0.0, 0.0, 1.0]);
        assert!(RayBoxTest::new(&ray).hits(&b, f32::INFINITY));
        let ray = Ray::new([1.0, 1.0, -1.0], [-0.0, 0.0, 1.0]);
        assert!(RayBoxTest::new(&ray).hits(&b, f32::INFINITY));
        // Without rounding out, a ray in the face plane y = max is (wrongly) dropped.
        let exact = Aabb::new([0.0; 3], [1.0; 3]);
        assert!(!RayBoxTest::new(&ray).hits(&exact, f32::INFINITY));
        let ray = Ray::new([1.5, 0.5, -1.0], [0.0, 0.0, 1.0]);
        assert!(!RayBoxTest::new(&ray).hits(&b, 1e20));
        // Behind the origin or beyond t_max.
        let ray = Ray::new([0.5, 0.5, 2.0], [0.0, 0.0, 1.0]);
        assert!(!RayBoxTest::new(&ray).hits(&b, f32::INFINITY));
        let ray = Ray::new([0.5, 0.5, -2.0], [0.0, 0.0, 1.0]);
        assert!(!RayBoxTest::new(&ray).hits(&b, 1.5));
        assert!(RayBoxTest::new(&ray).hits(&b, 2.0));
    }

    #[test]
    fn hit_order_is_total() {
        let h = |t: f32, prim_id: u32| TRI_HIT.to_hit(0, prim_id).with_t(t);
        assert!(is_closer(&h(1.0, 5), &h(2.0, 0)));
        assert!(is_closer(&h(1.0, 0), &h(1.0, 5)));
        assert!(!is_closer(&h(1.0, 5), &h(1.0, 5)));
    }

    const TRI_HIT: TriangleHit = TriangleHit {
        t: 0.0,
        u: 0.0,
        v: 0.0,
        ng: [0.0; 3],
    };

    impl Hit {
        fn with_t(self, t: f32) -> Hit {
            Hit { t, ..self }
        }
    }
}
