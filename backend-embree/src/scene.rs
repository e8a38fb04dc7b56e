//! Triangle scenes: build with [`SceneBuilder`], query the committed [`Scene`] from any
//! number of threads.

use crate::device::{Device, Error};
use crate::ffi::{self, RTCRay, RTCRayHit, RTCScene, Valid};
use scratchwave_host::mesh::validate_mesh;
use scratchwave_host::{Coherence, RayQueries};
use scratchwave_kernel::ray::{Hit, Ray};

/// Embree's BVH build quality (`RTC_BUILD_QUALITY_*`): build time against trace speed.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum BuildQuality {
    /// Fastest build (Morton); for scenes rebuilt every frame.
    Low,
    /// Binned SAH: Embree's default.
    #[default]
    Medium,
    /// Spatial splits; slowest build, fastest traversal.
    High,
}

/// A scene handle plus the device reference that keeps the device alive at least as long.
struct RawScene {
    raw: RTCScene,
    device: Device,
}

// SAFETY: Embree scene handles may be used from any thread. Mutation (geometry, commit) is
// only reachable through `&mut SceneBuilder` or by value; a committed `Scene` offers only
// queries, which Embree allows concurrently.
unsafe impl Send for RawScene {}
// SAFETY: see above.
unsafe impl Sync for RawScene {}

impl Drop for RawScene {
    fn drop(&mut self) {
        // SAFETY: we own the one reference to the scene.
        unsafe { (ffi::loaded().rtcReleaseScene)(self.raw) }
    }
}

impl RawScene {
    fn new(device: &Device, quality: BuildQuality, robust: bool) -> Result<RawScene, Error> {
        let api = ffi::loaded();
        // SAFETY: valid device handle.
        let raw = unsafe { (api.rtcNewScene)(device.raw()) };
        device.check("rtcNewScene")?;
        if raw.is_null() {
            return Err(Error::Load("rtcNewScene returned null".into()));
        }
        let scene = RawScene {
            raw,
            device: device.clone(),
        };
        let quality = match quality {
            BuildQuality::Low => ffi::RTC_BUILD_QUALITY_LOW,
            BuildQuality::Medium => ffi::RTC_BUILD_QUALITY_MEDIUM,
            BuildQuality::High => ffi::RTC_BUILD_QUALITY_HIGH,
        };
        let flags = if robust {
            ffi::RTC_SCENE_FLAG_ROBUST
        } else {
            ffi::RTC_SCENE_FLAG_NONE
        };
        // SAFETY: valid, uncommitted scene.
        unsafe {
            (api.rtcSetSceneBuildQuality)(raw, quality);
            (api.rtcSetSceneFlags)(raw, flags);
        }
        device.check("scene settings")?;
        Ok(scene)
    }
}

/// Collects geometry for a [`Scene`].
pub struct SceneBuilder {
    scene: RawScene,
}

impl SceneBuilder {
    /// An empty scene with [`BuildQuality::Medium`].
    pub fn new(device: &Device) -> Result<SceneBuilder, Error> {
        SceneBuilder::with_options(device, BuildQuality::Medium, false)
    }

    /// An empty scene with the given build quality; `robust` selects Embree's watertight
    /// (slower) triangle test and traversal (`RTC_SCENE_FLAG_ROBUST`).
    pub fn with_options(
        device: &Device,
        quality: BuildQuality,
        robust: bool,
    ) -> Result<SceneBuilder, Error> {
        Ok(SceneBuilder {
            scene: RawScene::new(device, quality, robust)?,
        })
    }

    /// Adds an indexed triangle mesh (copied into Embree-owned buffers) and returns its
    /// geometry id. Primitive ids are positions in `indices`.
    pub fn add_triangle_mesh(
        &mut self,
        vertices: &[[f32; 3]],
        indices: &[[u32; 3]],
    ) -> Result<u32, Error> {
        validate_mesh(vertices.len(), indices)?;
        let api = ffi::loaded();
        let device = &self.scene.device;
        // SAFETY: valid device; the geometry is released on every path below.
        let geometry =
            unsafe { (api.rtcNewGeometry)(device.raw(), ffi::RTC_GEOMETRY_TYPE_TRIANGLE) };
        device.check("rtcNewGeometry")?;
        let result = (|| {
            // SAFETY: Embree allocates `count` items of `stride` bytes (vertex buffers padded
            // for 16-byte loads) and returns them, or null on error; we write exactly that
            // many items.
            unsafe {
                let vb = (api.rtcSetNewGeometryBuffer)(
                    geometry,
                    ffi::RTC_BUFFER_TYPE_VERTEX,
                    0,
                    ffi::RTC_FORMAT_FLOAT3,
                    12,
                    vertices.len(),
                );
                device.check("vertex buffer")?;
                if !vb.is_null() {
                    std::ptr::copy_nonoverlapping(vertices.as_ptr(), vb.cast(), vertices.len());
                }
                let ib = (api.rtcSetNewGeometryBuffer)(
                    geometry,
                    ffi::RTC_BUFFER_TYPE_INDEX,
                    0,
                    ffi::RTC_FORMAT_UINT3,
                    12,
                    indices.len(),
                );
                device.check("index buffer")?;
                if !ib.is_null() {
                    std::ptr::copy_nonoverlapping(indices.as_ptr(), ib.cast(), indices.len());
                }
                if (vb.is_null() && !vertices.is_empty()) || (ib.is_null() && !indices.is_empty()) {
                    return Err(Error::Load("rtcSetNewGeometryBuffer returned null".into()));
                }
                (api.rtcCommitGeometry)(geometry);
                device.check("rtcCommitGeometry")?;
                let id = (api.rtcAttachGeometry)(self.scene.raw, geometry);
                device.check("rtcAttachGeometry")?;
                Ok(id)
            }
        })();
        // SAFETY: drops our reference; the scene holds its own once attached.
        unsafe { (api.rtcReleaseGeometry)(geometry) };
        result
    }

    /// Builds the acceleration structure. The scene is immutable from here on.
    pub fn commit(self) -> Result<Scene, Error> {
        // SAFETY: valid scene; all geometry buffers were filled before.
        unsafe { (ffi::loaded().rtcCommitScene)(self.scene.raw) };
        self.scene.device.check("rtcCommitScene")?;
        Ok(Scene { scene: self.scene })
    }

    pub(crate) fn raw(&self) -> RTCScene {
        self.scene.raw
    }

    pub(crate) fn device(&self) -> &Device {
        &self.scene.device
    }
}

/// A committed, immutable Embree scene. `Send + Sync`: query it from rayon workers.
///
/// Queries return raw hits ([`Hit`]: `t`, geometry and primitive id, barycentrics, Embree's
/// unnormalized geometric normal `(v1 − v0) × (v2 − v0)`). Rays whose origin or direction is
/// not finite, or whose interval is not `0 ≤ t_near ≤ t_far` (NaN included), are reported as
/// misses without reaching Embree, whose behaviour on them is undefined.
pub struct Scene {
    scene: RawScene,
}

#[inline]
fn is_valid(ray: &Ray) -> bool {
    let ([o0, o1, o2], [d0, d1, d2]) = (ray.origin, ray.dir);
    // `&`, not `&&`: no branches, so all eight tests can run side by side.
    o0.is_finite()
        & o1.is_finite()
        & o2.is_finite()
        & d0.is_finite()
        & d1.is_finite()
        & d2.is_finite()
        & (ray.t_near >= 0.0)
        & (ray.t_near <= ray.t_far)
}

#[inline]
pub(crate) fn to_rtc(ray: &Ray) -> RTCRay {
    RTCRay {
        org_x: ray.origin[0],
        org_y: ray.origin[1],
        org_z: ray.origin[2],
        tnear: ray.t_near,
        dir_x: ray.dir[0],
        dir_y: ray.dir[1],
        dir_z: ray.dir[2],
        time: 0.0,
        tfar: ray.t_far,
        mask: u32::MAX,
        id: 0,
        flags: 0,
    }
}

fn query_flags(coherence: Coherence) -> u32 {
    match coherence {
        Coherence::Coherent => ffi::RTC_RAY_QUERY_FLAG_COHERENT,
        Coherence::Incoherent => ffi::RTC_RAY_QUERY_FLAG_INCOHERENT,
    }
}

/// Access to one packet layout (`RTCRayHit4/8/16`, `RTCRay4/8/16`).
trait Packet: Copy {
    const WIDTH: usize;
    type Rays: Copy;
    fn empty() -> Self;
    /// Loads `ray` into `lane` and marks the lane's hit as none (so a packet can be reused).
    fn set(&mut self, lane: usize, ray: &RTCRay);
    fn hit(&self, lane: usize) -> Option<Hit>;
    fn empty_rays() -> Self::Rays;
    fn set_ray(rays: &mut Self::Rays, lane: usize, ray: &RTCRay);
    fn is_occluded(rays: &Self::Rays, lane: usize) -> bool;
    /// # Safety
    /// `valid` must point to `WIDTH` lanes aligned like the packet; `scene` must be committed.
    unsafe fn intersect(
        valid: *const i32,
        scene: RTCScene,
        packet: &mut Self,
        args: &mut ffi::RTCIntersectArguments,
    );
    /// # Safety
    /// As for `intersect`.
    unsafe fn occluded(valid: *const i32, scene: RTCScene, rays: &mut Self::Rays, flags: u32);
}

macro_rules! impl_packet {
    ($rayhit:ty, $rays:ty, $hit:ty, $n:literal, $intersect:ident, $occluded:ident) => {
        impl Packet for $rayhit {
            const WIDTH: usize = $n;
            type Rays = $rays;

            fn empty() -> Self {
                let mut p = Self {
                    ray: Self::empty_rays(),
                    hit: <$hit>::zeroed(),
                };
                p.hit.geomID = [ffi::RTC_INVALID_GEOMETRY_ID; $n];
                p.hit.primID = [ffi::RTC_INVALID_GEOMETRY_ID; $n];
                p.hit.instID = [[ffi::RTC_INVALID_GEOMETRY_ID; $n]];
                p.hit.instPrimID = [[ffi::RTC_INVALID_GEOMETRY_ID; $n]];
                p
            }

            #[inline]
            fn set(&mut self, lane: usize, ray: &RTCRay) {
                Self::set_ray(&mut self.ray, lane, ray);
                self.hit.geomID[lane] = ffi::RTC_INVALID_GEOMETRY_ID;
                self.hit.primID[lane] = ffi::RTC_INVALID_GEOMETRY_ID;
                self.hit.instID[0][lane] = ffi::RTC_INVALID_GEOMETRY_ID;
                self.hit.instPrimID[0][lane] = ffi::RTC_INVALID_GEOMETRY_ID;
            }

            #[inline]
            fn hit(&self, i: usize) -> Option<Hit> {
                let h = &self.hit;
                (h.geomID[i] != ffi::RTC_INVALID_GEOMETRY_ID).then(|| Hit {
                    ng: [h.Ng_x[i], h.Ng_y[i], h.Ng_z[i]],
                    t: self.ray.tfar[i],
                    u: h.u[i],
                    v: h.v[i],
                    geom_id: h.geomID[i],
                    prim_id: h.primID[i],
                })
            }

            fn empty_rays() -> $rays {
                let mut r: $rays = <$rays>::zeroed();
                r.tfar = [f32::NEG_INFINITY; $n];
                r
            }

            #[inline]
            fn set_ray(rays: &mut $rays, i: usize, ray: &RTCRay) {
                rays.org_x[i] = ray.org_x;
                rays.org_y[i] = ray.org_y;
                rays.org_z[i] = ray.org_z;
                rays.tnear[i] = ray.tnear;
                rays.dir_x[i] = ray.dir_x;
                rays.dir_y[i] = ray.dir_y;
                rays.dir_z[i] = ray.dir_z;
                rays.time[i] = ray.time;
                rays.tfar[i] = ray.tfar;
                rays.mask[i] = ray.mask;
                rays.id[i] = ray.id;
                rays.flags[i] = ray.flags;
            }

            #[inline]
            fn is_occluded(rays: &$rays, i: usize) -> bool {
                rays.tfar[i] == f32::NEG_INFINITY
            }

            #[inline]
            unsafe fn intersect(
                valid: *const i32,
                scene: RTCScene,
                packet: &mut Self,
                args: &mut ffi::RTCIntersectArguments,
            ) {
                // SAFETY: per the trait contract; the packet has the 4.4 layout.
                unsafe { (ffi::loaded().$intersect)(valid, scene, packet, args) }
            }

            unsafe fn occluded(valid: *const i32, scene: RTCScene, rays: &mut $rays, flags: u32) {
                let mut args = ffi::RTCOccludedArguments::new(flags);
                // SAFETY: per the trait contract.
                unsafe { (ffi::loaded().$occluded)(valid, scene, rays, &mut args) }
            }
        }

        impl $hit {
            fn zeroed() -> Self {
                Self {
                    Ng_x: [0.0; $n],
                    Ng_y: [0.0; $n],
                    Ng_z: [0.0; $n],
                    u: [0.0; $n],
                    v: [0.0; $n],
                    primID: [0; $n],
                    geomID: [0; $n],
                    instID: [[0; $n]],
                    instPrimID: [[0; $n]],
                }
            }
        }

        impl $rays {
            fn zeroed() -> Self {
                Self {
                    org_x: [0.0; $n],
                    org_y: [0.0; $n],
                    org_z: [0.0; $n],
                    tnear: [0.0; $n],
                    dir_x: [0.0; $n],
                    dir_y: [0.0; $n],
                    dir_z: [0.0; $n],
                    time: [0.0; $n],
                    tfar: [0.0; $n],
                    mask: [u32::MAX; $n],
                    id: [0; $n],
                    flags: [0; $n],
                }
            }
        }
    };
}

impl_packet!(
    ffi::RTCRayHit4,
    ffi::RTCRay4,
    ffi::RTCHit4,
    4,
    rtcIntersect4,
    rtcOccluded4
);
impl_packet!(
    ffi::RTCRayHit8,
    ffi::RTCRay8,
    ffi::RTCHit8,
    8,
    rtcIntersect8,
    rtcOccluded8
);
impl_packet!(
    ffi::RTCRayHit16,
    ffi::RTCRay16,
    ffi::RTCHit16,
    16,
    rtcIntersect16,
    rtcOccluded16
);

impl Scene {
    /// The closest hit of one ray (`rtcIntersect1`, incoherent).
    #[inline]
    pub fn intersect(&self, ray: &Ray) -> Option<Hit> {
        let mut args = ffi::RTCIntersectArguments::new(ffi::RTC_RAY_QUERY_FLAG_INCOHERENT);
        self.intersect_with(ray, &mut args)
    }

    /// [`Scene::intersect`] with query arguments made once per batch, not per ray.
    #[inline]
    fn intersect_with(&self, ray: &Ray, args: &mut ffi::RTCIntersectArguments) -> Option<Hit> {
        if !is_valid(ray) {
            return None;
        }
        let mut rayhit = RTCRayHit {
            ray: to_rtc(ray),
            hit: ffi::RTCHit::default(),
        };
        // SAFETY: committed scene; a valid ray in a 4.4-layout RTCRayHit; Embree only reads
        // `args`.
        unsafe { (ffi::loaded().rtcIntersect1)(self.scene.raw, &mut rayhit, args) };
        let h = &rayhit.hit;
        (h.geomID != ffi::RTC_INVALID_GEOMETRY_ID).then_some(Hit {
            ng: [h.Ng_x, h.Ng_y, h.Ng_z],
            t: rayhit.ray.tfar,
            u: h.u,
            v: h.v,
            geom_id: h.geomID,
            prim_id: h.primID,
        })
    }

    /// `true` if `ray` hits anything in its interval (`rtcOccluded1`; shadow rays).
    pub fn occluded(&self, ray: &Ray) -> bool {
        if !is_valid(ray) {
            return false;
        }
        let mut rtc = to_rtc(ray);
        let mut args = ffi::RTCOccludedArguments::new(ffi::RTC_RAY_QUERY_FLAG_INCOHERENT);
        // SAFETY: committed scene; a valid ray.
        unsafe { (ffi::loaded().rtcOccluded1)(self.scene.raw, &mut rtc, &mut args) };
        rtc.tfar == f32::NEG_INFINITY
    }

    /// Traces consecutive groups of `P::WIDTH` rays as packets; lanes past the end and
    /// invalid rays are masked off. One packet, mask and argument record serve the whole
    /// batch (each lane is reloaded and its hit cleared before every call).
    fn intersect_packets<P: Packet>(
        &self,
        rays: &[Ray],
        hits: &mut [Option<Hit>],
        coherence: Coherence,
    ) {
        debug_assert!(hits.len() == rays.len());
        let mut args = ffi::RTCIntersectArguments::new(query_flags(coherence));
        let mut valid = Valid([0i32; 16]);
        let mut packet = P::empty();
        for (rays, hits) in rays.chunks(P::WIDTH).zip(hits.chunks_mut(P::WIDTH)) {
            for lane in 0..P::WIDTH {
                valid.0[lane] = match rays.get(lane) {
                    Some(ray) if is_valid(ray) => {
                        packet.set(lane, &to_rtc(ray));
                        -1
                    }
                    _ => 0,
                };
            }
            // SAFETY: `valid` is 64-byte aligned with ≥ WIDTH lanes; committed scene; Embree
            // only reads `args`.
            unsafe { P::intersect(valid.0.as_ptr(), self.scene.raw, &mut packet, &mut args) };
            for (lane, hit) in hits.iter_mut().enumerate() {
                *hit = if valid.0[lane] != 0 {
                    packet.hit(lane)
                } else {
                    None
                };
            }
        }
    }

    fn occluded_packet<P: Packet>(&self, rays: &[Ray], out: &mut [bool], coherence: Coherence) {
        debug_assert!(rays.len() <= P::WIDTH && out.len() == rays.len());
        let mut valid = Valid([0i32; 16]);
        let mut packet = P::empty_rays();
        for (lane, ray) in rays.iter().enumerate() {
            if is_valid(ray) {
                valid.0[lane] = -1;
                P::set_ray(&mut packet, lane, &to_rtc(ray));
            }
        }
        // SAFETY: as in `intersect_packets`.
        unsafe {
            P::occluded(
                valid.0.as_ptr(),
                self.scene.raw,
                &mut packet,
                query_flags(coherence),
            )
        };
        for (lane, o) in out.iter_mut().enumerate() {
            *o = valid.0[lane] != 0 && P::is_occluded(&packet, lane);
        }
    }

    /// Closest hits of a packet of 4 rays (`rtcIntersect4`).
    pub fn intersect4(&self, rays: &[Ray; 4], coherence: Coherence) -> [Option<Hit>; 4] {
        let mut hits = [None; 4];
        self.intersect_packets::<ffi::RTCRayHit4>(rays, &mut hits, coherence);
        hits
    }

    /// Closest hits of a packet of 8 rays (`rtcIntersect8`).
    pub fn intersect8(&self, rays: &[Ray; 8], coherence: Coherence) -> [Option<Hit>; 8] {
        let mut hits = [None; 8];
        self.intersect_packets::<ffi::RTCRayHit8>(rays, &mut hits, coherence);
        hits
    }

    /// Closest hits of a packet of 16 rays (`rtcIntersect16`).
    pub fn intersect16(&self, rays: &[Ray; 16], coherence: Coherence) -> [Option<Hit>; 16] {
        let mut hits = [None; 16];
        self.intersect_packets::<ffi::RTCRayHit16>(rays, &mut hits, coherence);
        hits
    }

    /// Occlusion of a packet of 8 rays (`rtcOccluded8`).
    pub fn occluded8(&self, rays: &[Ray; 8], coherence: Coherence) -> [bool; 8] {
        let mut out = [false; 8];
        self.occluded_packet::<ffi::RTCRayHit8>(rays, &mut out, coherence);
        out
    }

    /// Occlusion of a packet of 16 rays (`rtcOccluded16`).
    pub fn occluded16(&self, rays: &[Ray; 16], coherence: Coherence) -> [bool; 16] {
        let mut out = [false; 16];
        self.occluded_packet::<ffi::RTCRayHit16>(rays, &mut out, coherence);
        out
    }

    /// Closest hits of many rays in packets of `width` (1, 4, 8 or 16; other widths
    /// trace single rays). Consecutive rays form a packet, so order coherent rays in compact
    /// tiles (see `scratchwave_testkit::fixtures::camera_rays`).
    ///
    /// # Panics
    /// If `rays` and `hits` differ in length.
    pub fn intersect_many(
        &self,
        rays: &[Ray],
        hits: &mut [Option<Hit>],
        width: usize,
        coherence: Coherence,
    ) {
        assert_eq!(rays.len(), hits.len(), "one hit slot per ray");
        match width {
            4 => self.intersect_packets::<ffi::RTCRayHit4>(rays, hits, coherence),
            8 => self.intersect_packets::<ffi::RTCRayHit8>(rays, hits, coherence),
            16 => self.intersect_packets::<ffi::RTCRayHit16>(rays, hits, coherence),
            _ => {
                let mut args = ffi::RTCIntersectArguments::new(ffi::RTC_RAY_QUERY_FLAG_INCOHERENT);
                for (ray, hit) in rays.iter().zip(hits.iter_mut()) {
                    *hit = self.intersect_with(ray, &mut args);
                }
            }
        }
    }

    /// The device this scene belongs to.
    pub fn device(&self) -> &Device {
        &self.scene.device
    }

    /// The Embree handle, for direct calls through [`crate::ffi`]. Do not release or modify
    /// the scene through it.
    pub fn as_raw(&self) -> RTCScene {
        self.scene.raw
    }
}

impl RayQueries for Scene {
    fn closest_hit(&self, ray: &Ray) -> Option<Hit> {
        self.intersect(ray)
    }

    fn occluded(&self, ray: &Ray) -> bool {
        Scene::occluded(self, ray)
    }

    /// Traces 16-ray packets with Embree's coherence hint. On the reference machine
    /// (AVX-512, see the `rays` benchmark) packets were faster than single rays for coherent
    /// rays and no slower for random ones (within the run-to-run noise).
    fn closest_hits(&self, rays: &[Ray], hits: &mut [Option<Hit>], coherence: Coherence) {
        self.intersect_many(rays, hits, 16, coherence);
    }

    /// Coherent rays in packets of 16 (`rtcOccluded16`), incoherent ones one by one.
    fn occluded_many(&self, rays: &[Ray], out: &mut [bool], coherence: Coherence) {
        assert_eq!(rays.len(), out.len(), "one answer slot per ray");
        if coherence == Coherence::Coherent {
            for (rays, out) in rays.chunks(16).zip(out.chunks_mut(16)) {
                self.occluded_packet::<ffi::RTCRayHit16>(rays, out, coherence);
            }
        } else {
            for (ray, o) in rays.iter().zip(out.iter_mut()) {
                *o = Scene::occluded(self, ray);
            }
        }
    }
}
