//! The scratch-segment radius query on Embree: segments as a USER geometry (one primitive
//! per segment, a bounds callback giving its z = 0 box) and `rtcPointQuery` with a callback
//! that keeps the segments within the radius.
//!
//! Embree's built-in linear curves cannot serve here: their BVH does not implement point
//! queries (the callback is never invoked; measured in the prototype).

use crate::device::{Device, Error};
use crate::ffi;
use crate::scene::{BuildQuality, SceneBuilder};
use scratchwave_host::SegmentRadiusQuery;
use scratchwave_host::mesh::check_count;
use scratchwave_kernel::bvh::RADIUS_SLACK;
use scratchwave_kernel::segment2d::Segment2;
use std::ffi::c_void;

/// Segments indexed by an Embree BVH for radius queries. `Send + Sync`.
pub struct SegmentIndex {
    // Field order matters: the scene (whose geometry points into `segments`) is released
    // before the segments are freed.
    scene: crate::Scene,
    segments: Box<SegmentData>,
}

/// What the bounds callback reads through the geometry's user pointer.
struct SegmentData {
    segments: Box<[Segment2]>,
}

/// Per-query state behind `rtcPointQuery`'s user pointer.
struct QueryState<'a> {
    segments: &'a [Segment2],
    p: [f32; 2],
    radius: f32,
    out: &'a mut Vec<u32>,
}

unsafe extern "C" fn segment_bounds(args: *const ffi::RTCBoundsFunctionArguments) {
    // SAFETY: Embree passes valid arguments whose user pointer is the `SegmentData` set in
    // `SegmentIndex::new`, alive until the scene is released; `bounds_o` is writable.
    unsafe {
        let args = &*args;
        let data = &*(args.geometryUserPtr as *const SegmentData);
        let b = match data.segments.get(args.primID as usize) {
            Some(s) => s.bounds(),
            None => scratchwave_kernel::bvh::Aabb::EMPTY,
        };
        *args.bounds_o = ffi::RTCBounds {
            lower_x: b.min[0],
            lower_y: b.min[1],
            lower_z: b.min[2],
            align0: 0.0,
            upper_x: b.max[0],
            upper_y: b.max[1],
            upper_z: b.max[2],
            align1: 0.0,
        };
    }
}

/// Ray queries are never made on a segment scene; these keep the geometry well-formed.
unsafe extern "C" fn no_ray_intersection(_: *const c_void) {}

unsafe extern "C" fn keep_if_within(args: *mut ffi::RTCPointQueryFunctionArguments) -> bool {
    // SAFETY: the user pointer is the `QueryState` of the `rtcPointQuery` call in progress on
    // this thread, exclusively borrowed for its duration.
    unsafe {
        let args = &*args;
        let state = &mut *(args.userPtr as *mut QueryState<'_>);
        if let Some(s) = state.segments.get(args.primID as usize)
            && s.is_within(state.p, state.radius)
        {
            state.out.push(args.primID);
        }
    }
    false // the query radius is unchanged
}

impl SegmentIndex {
    /// Indexes `segments` (copied). Segment ids are positions in `segments`.
    pub fn new(device: &Device, segments: &[Segment2]) -> Result<SegmentIndex, Error> {
        check_count(segments.len())?;
        let data = Box::new(SegmentData {
            segments: segments.into(),
        });
        let builder = SceneBuilder::with_options(device, BuildQuality::Medium, false)?;
        let api = ffi::loaded();
        let user = (&*data as *const SegmentData).cast_mut().cast::<c_void>();
        // SAFETY: valid device; the geometry's user pointer targets `data`, which the returned
        // index keeps alive (and unmoved, being boxed) for as long as the scene.
        unsafe {
            let g = (api.rtcNewGeometry)(device.raw(), ffi::RTC_GEOMETRY_TYPE_USER);
            builder.device().check("rtcNewGeometry")?;
            (api.rtcSetGeometryUserPrimitiveCount)(g, segments.len() as u32);
            (api.rtcSetGeometryUserData)(g, user);
            (api.rtcSetGeometryBoundsFunction)(g, Some(segment_bounds), user);
            (api.rtcSetGeometryIntersectFunction)(g, Some(no_ray_intersection));
            (api.rtcSetGeometryOccludedFunction)(g, Some(no_ray_intersection));
            (api.rtcCommitGeometry)(g);
            (api.rtcAttachGeometry)(builder.raw(), g);
            (api.rtcReleaseGeometry)(g);
        }
        builder.device().check("segment geometry")?;
        let scene = builder.commit()?;
        Ok(SegmentIndex {
            scene,
            segments: data,
        })
    }

    /// The indexed segments, in id order.
    pub fn segments(&self) -> &[Segment2] {
        &self.segments.segments
    }
}

impl SegmentRadiusQuery for SegmentIndex {
    fn segments_within(&self, p: [f32; 2], radius: f32, out: &mut Vec<u32>) {
        out.clear();
        if !(p[0].is_finite() && p[1].is_finite() && radius >= 0.0 && radius.is_finite()) {
            return;
        }
        // Embree culls with its own rounding; a slightly larger search radius makes it a
        // superset, and the callback applies the exact test.
        let mut query = ffi::RTCPointQuery {
            x: p[0],
            y: p[1],
            z: 0.0,
            time: 0.0,
            radius: radius * (1.0 + RADIUS_SLACK),
        };
        let mut context = ffi::RTCPointQueryContext::new();
        let mut state = QueryState {
            segments: &self.segments.segments,
            p,
            radius,
            out,
        };
        // SAFETY: committed scene; `query`/`context` are 4.4-layout and 16-byte aligned;
        // `state` outlives the call and the callback only touches it on this thread.
        unsafe {
            (ffi::loaded().rtcPointQuery)(
                self.scene.as_raw(),
                &mut query,
                &mut context,
                Some(keep_if_within),
                (&mut state as *mut QueryState<'_>).cast(),
            );
        }
    }
}
