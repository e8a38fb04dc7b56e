//! Primary rays of an orthographic or perspective camera, with ray differentials (Igehy
//! 1999) for the pixel footprint (Velinov 2018 §4: screen-space derivatives of the hit
//! position).
//!
//! Frame: `f = normalize(target − eye)`, `r = normalize(f × up)`, `u = r × f`. A point
//! `(px, py)` of the image (pixels, from the left and from the top; the centre of pixel
//! `(i, j)` is `(i + 0.5, j + 0.5)`) maps to
//! `s = (px/W − 0.5)·h·W/H`, `t = (0.5 − py/H)·h`, with `h` the view height (orthographic,
//! scene units) or `2 tan(fov_y/2)` (perspective). Orthographic rays start at
//! `eye + s r + t u` along `f`; perspective rays start at `eye` along
//! `normalize(f + s r + t u)`.

use crate::ray::Ray;
use bytemuck::{Pod, Zeroable};
use glam::Vec3;

gpu_enum! {
    /// The camera's projection ([`Camera::projection`]).
    pub enum Projection {
        /// Parallel rays along `f`.
        Orthographic = 0,
        /// Rays from the eye.
        Perspective = 1,
    }
    fallback = Orthographic;
}

/// A camera, its frame already orthonormalised ([`Camera::look_at`]). GPU-visible: 64 bytes.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct Camera {
    /// Eye position.
    pub eye: [f32; 3],
    /// A [`Projection`] as `u32`.
    pub projection: u32,
    /// `f`, the unit view direction.
    pub forward: [f32; 3],
    /// `h`: view height (orthographic) or `2 tan(fov_y/2)` (perspective).
    pub h: f32,
    /// `r = normalize(f × up)`.
    pub right: [f32; 3],
    /// Image width W (pixels).
    pub width_px: u32,
    /// `u = r × f`.
    pub up: [f32; 3],
    /// Image height H (pixels).
    pub height_px: u32,
}

const _: () = assert!(core::mem::size_of::<Camera>() == 64);

/// A primary ray and its differentials per pixel step in x (`dx`) and y (`dy`, downwards).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RayDifferential {
    /// The ray (`dir` unit length for both projections).
    pub ray: Ray,
    /// ∂origin/∂px.
    pub d_origin_dx: Vec3,
    /// ∂origin/∂py.
    pub d_origin_dy: Vec3,
    /// ∂dir/∂px (of the normalised direction).
    pub d_dir_dx: Vec3,
    /// ∂dir/∂py.
    pub d_dir_dy: Vec3,
}

impl Camera {
    /// The camera frame from eye, target and up: `f = normalize(target − eye)`,
    /// `r = normalize(f × up)`, `u = r × f`. `h` as in the module documentation.
    pub fn look_at(
        projection: Projection,
        eye: [f32; 3],
        target: [f32; 3],
        up: [f32; 3],
        h: f32,
        width_px: u32,
        height_px: u32,
    ) -> Camera {
        let e = Vec3::from_array(eye);
        let f = (Vec3::from_array(target) - e).normalize_or_zero();
        let r = f.cross(Vec3::from_array(up)).normalize_or_zero();
        let u = r.cross(f);
        Camera {
            eye,
            projection: projection as u32,
            forward: f.to_array(),
            h,
            right: r.to_array(),
            width_px,
            up: u.to_array(),
            height_px,
        }
    }

    /// `(s, t)` of the image point `(px, py)` (pixels from the left and top edges).
    #[inline]
    pub fn screen(&self, px: f32, py: f32) -> (f32, f32) {
        let w = self.width_px as f32;
        let hp = self.height_px as f32;
        let s = (px / w - 0.5) * self.h * w / hp;
        let t = (0.5 - py / hp) * self.h;
        (s, t)
    }

    /// The ray through image point `(px, py)` with its differentials.
    pub fn ray(&self, px: f32, py: f32) -> RayDifferential {
        let (s, t) = self.screen(px, py);
        let e = Vec3::from_array(self.eye);
        let f = Vec3::from_array(self.forward);
        let r = Vec3::from_array(self.right);
        let u = Vec3::from_array(self.up);
        // One pixel step: ds/dpx = h/H, dt/dpy = −h/H.
        let step = self.h / self.height_px as f32;
        if Projection::from_u32(self.projection) == Projection::Perspective {
            let d = f + r * s + u * t;
            let len = d.length();
            let dir = d / len;
            // ∂(d/|d|)/∂s = (r − dir (dir·r)) / |d|, likewise for t with u.
            let dds = (r - dir * dir.dot(r)) / len;
            let ddt = (u - dir * dir.dot(u)) / len;
            RayDifferential {
                ray: Ray::new(self.eye, dir.to_array()),
                d_origin_dx: Vec3::ZERO,
                d_origin_dy: Vec3::ZERO,
                d_dir_dx: dds * step,
                d_dir_dy: ddt * -step,
            }
        } else {
            let o = e + r * s + u * t;
            RayDifferential {
                ray: Ray::new(o.to_array(), self.forward),
                d_origin_dx: r * step,
                d_origin_dy: u * -step,
                d_dir_dx: Vec3::ZERO,
                d_dir_dy: Vec3::ZERO,
            }
        }
    }
}
