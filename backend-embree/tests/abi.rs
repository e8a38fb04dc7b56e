//! ABI canaries: every struct Embree writes (or hands to our callbacks) is surrounded by guard
//! words, and Embree must write exactly the fields the 4.4 layout declares, nothing before or
//! after. If these fail, the loaded Embree was built with a different layout
//! (`RTC_MAX_INSTANCE_LEVEL_COUNT`, instance arrays) and the bindings must not be used with it.

use scratchwave_embree::ffi::{self, RTC_INVALID_GEOMETRY_ID as INVALID};
use scratchwave_embree::{Device, SceneBuilder};
use scratchwave_kernel::ray::Ray;
use std::ffi::c_void;

const GUARD: u32 = 0xDEAD_BEEF;
const SENTINEL: u32 = 0xA5A5_A5A5;

/// `T` with 64 guard bytes on each side, 64-byte aligned like the largest packet.
#[repr(C, align(64))]
struct Guarded<T> {
    before: [u32; 16],
    value: T,
    after: [u32; 16],
}

impl<T> Guarded<T> {
    fn new(value: T) -> Self {
        Guarded {
            before: [GUARD; 16],
            value,
            after: [GUARD; 16],
        }
    }

    fn assert_intact(&self, what: &str) {
        assert_eq!(
            self.before, [GUARD; 16],
            "{what}: Embree wrote before the struct"
        );
        assert_eq!(
            self.after, [GUARD; 16],
            "{what}: Embree wrote past the struct"
        );
    }
}

fn api() -> &'static ffi::Functions {
    ffi::api().expect("Embree loads")
}

/// A unit quad at z = 1 (two triangles) and the device.
fn quad_scene() -> (Device, scratchwave_embree::Scene) {
    let device = Device::new().expect("device");
    let mut b = SceneBuilder::new(&device).expect("scene");
    b.add_triangle_mesh(
        &[
            [-1.0, -1.0, 1.0],
            [1.0, -1.0, 1.0],
            [1.0, 1.0, 1.0],
            [-1.0, 1.0, 1.0],
        ],
        &[[0, 1, 2], [0, 2, 3]],
    )
    .expect("mesh");
    let scene = b.commit().expect("commit");
    (device, scene)
}

fn raw_scene(scene: &scratchwave_embree::Scene) -> ffi::RTCScene {
    scene.as_raw()
}

fn rtc_ray(x: f32, y: f32) -> ffi::RTCRay {
    ffi::RTCRay {
        org_x: x,
        org_y: y,
        org_z: 0.0,
        tnear: 0.0,
        dir_x: 0.0,
        dir_y: 0.0,
        dir_z: 1.0,
        time: 0.0,
        tfar: f32::INFINITY,
        mask: u32::MAX,
        id: 0,
        flags: 0,
    }
}

#[test]
fn single_ray_hit_record_is_the_4_4_layout() {
    let (_device, scene) = quad_scene();
    let mut g = Guarded::new(ffi::RTCRayHit {
        ray: rtc_ray(0.5, -0.5),
        hit: ffi::RTCHit {
            instPrimID: [SENTINEL],
            ..Default::default()
        },
    });
    let mut args = ffi::RTCIntersectArguments::new(ffi::RTC_RAY_QUERY_FLAG_INCOHERENT);
    // SAFETY: committed scene, 4.4-layout record with guards.
    unsafe { (api().rtcIntersect1)(raw_scene(&scene), &mut g.value, &mut args) };
    g.assert_intact("rtcIntersect1");
    let h = g.value.hit;
    assert_eq!((h.geomID, h.primID), (0, 0));
    assert!((g.value.ray.tfar - 1.0).abs() < 1e-6);
    // Embree ≥ 4.3 writes instPrimID, at bytes 80..84 of the record: just past the end of
    // the 80-byte RTCRayHit of the 4.2 headers that embree4-sys/embree4-rs declare.
    assert_eq!(
        h.instPrimID,
        [INVALID],
        "instPrimID written (instance-array layout)"
    );
    assert_eq!(h.instID, [INVALID]);
    let offset =
        std::mem::offset_of!(ffi::RTCRayHit, hit) + std::mem::offset_of!(ffi::RTCHit, instPrimID);
    assert_eq!(offset, 80);
}

macro_rules! packet_canary {
    ($name:ident, $rayhit:ty, $ray:ty, $hit:ty, $n:literal, $intersect:ident, $occluded:ident) => {
        #[test]
        fn $name() {
            let (_device, scene) = quad_scene();
            // Even lanes hit triangle 0 or 1, odd lanes miss; the last lane is masked off.
            let mut valid = ffi::Valid([-1i32; $n]);
            valid.0[$n - 1] = 0;
            let mut rays: $ray = unsafe { std::mem::zeroed() };
            for i in 0..$n {
                let r = if i % 2 == 0 {
                    rtc_ray(if i % 4 == 0 { 0.5 } else { -0.5 }, -0.25)
                } else {
                    rtc_ray(5.0, 5.0)
                };
                rays.org_x[i] = r.org_x;
                rays.org_y[i] = r.org_y;
                rays.dir_z[i] = 1.0;
                rays.tfar[i] = f32::INFINITY;
                rays.mask[i] = u32::MAX;
            }
            let mut hit: $hit = unsafe { std::mem::zeroed() };
            hit.geomID = [INVALID; $n];
            hit.instPrimID = [[SENTINEL; $n]];
            let mut g = Guarded::new(<$rayhit>::from_parts(rays, hit));
            let mut args = ffi::RTCIntersectArguments::new(ffi::RTC_RAY_QUERY_FLAG_COHERENT);
            // SAFETY: committed scene, aligned 4.4-layout packet with guards, aligned mask.
            unsafe {
                (api().$intersect)(valid.0.as_ptr(), raw_scene(&scene), &mut g.value, &mut args)
            };
            g.assert_intact(stringify!($intersect));
            let h = &g.value.hit;
            for i in 0..$n - 1 {
                if i % 2 == 0 {
                    assert_eq!(
                        (h.geomID[i], h.primID[i]),
                        (0, if i % 4 == 0 { 0 } else { 1 }),
                        "lane {i}"
                    );
                    assert!((g.value.ray.tfar[i] - 1.0).abs() < 1e-6, "lane {i}");
                    assert_eq!(h.instPrimID[0][i], INVALID, "lane {i}: instPrimID written");
                } else {
                    assert_eq!(h.geomID[i], INVALID, "lane {i}");
                }
            }
            assert_eq!(h.instPrimID[0][$n - 1], SENTINEL, "masked lane untouched");
            assert_eq!(h.geomID[$n - 1], INVALID, "masked lane untouched");

            // Occlusion writes tfar = -inf into the ray packet only.
            let mut g = Guarded::new(rays);
            let mut args = ffi::RTCOccludedArguments::new(ffi::RTC_RAY_QUERY_FLAG_COHERENT);
            // SAFETY: as above.
            unsafe {
                (api().$occluded)(valid.0.as_ptr(), raw_scene(&scene), &mut g.value, &mut args)
            };
            g.assert_intact(stringify!($occluded));
            for i in 0..$n - 1 {
                let occluded = g.value.tfar[i] == f32::NEG_INFINITY;
                assert_eq!(occluded, i % 2 == 0, "lane {i}");
            }
            assert_eq!(g.value.tfar[$n - 1], f32::INFINITY, "masked lane untouched");
        }
    };
}

trait FromParts<R, H> {
    fn from_parts(ray: R, hit: H) -> Self;
}

macro_rules! from_parts {
    ($rayhit:ty, $ray:ty, $hit:ty) => {
        impl FromParts<$ray, $hit> for $rayhit {
            fn from_parts(ray: $ray, hit: $hit) -> Self {
                Self { ray, hit }
            }
        }
    };
}
from_parts!(ffi::RTCRayHit4, ffi::RTCRay4, ffi::RTCHit4);
from_parts!(ffi::RTCRayHit8, ffi::RTCRay8, ffi::RTCHit8);
from_parts!(ffi::RTCRayHit16, ffi::RTCRay16, ffi::RTCHit16);

packet_canary!(
    packet4_layout,
    ffi::RTCRayHit4,
    ffi::RTCRay4,
    ffi::RTCHit4,
    4,
    rtcIntersect4,
    rtcOccluded4
);
packet_canary!(
    packet8_layout,
    ffi::RTCRayHit8,
    ffi::RTCRay8,
    ffi::RTCHit8,
    8,
    rtcIntersect8,
    rtcOccluded8
);
packet_canary!(
    packet16_layout,
    ffi::RTCRayHit16,
    ffi::RTCRay16,
    ffi::RTCHit16,
    16,
    rtcIntersect16,
    rtcOccluded16
);

#[test]
fn single_ray_occlusion_writes_only_tfar() {
    let (_device, scene) = quad_scene();
    let mut g = Guarded::new(rtc_ray(0.5, -0.5));
    let mut args = ffi::RTCOccludedArguments::new(ffi::RTC_RAY_QUERY_FLAG_INCOHERENT);
    // SAFETY: committed scene, guarded ray.
    unsafe { (api().rtcOccluded1)(raw_scene(&scene), &mut g.value, &mut args) };
    g.assert_intact("rtcOccluded1");
    let expected = ffi::RTCRay {
        tfar: f32::NEG_INFINITY,
        ..rtc_ray(0.5, -0.5)
    };
    assert_eq!(g.value, expected);
}

/// What the callbacks below saw.
#[derive(Default)]
struct Seen {
    bounds_calls: usize,
    bounds_ok: bool,
    query_calls: usize,
    query_ok: bool,
}

struct Probe {
    user: *mut c_void,
    query: *mut ffi::RTCPointQuery,
    context: *mut ffi::RTCPointQueryContext,
    seen: std::sync::Mutex<Seen>,
}

unsafe extern "C" fn probe_bounds(args: *const ffi::RTCBoundsFunctionArguments) {
    // SAFETY: Embree passes valid arguments; the user pointer is our `Probe`.
    unsafe {
        let a = &*args;
        let probe = &*(a.geometryUserPtr as *const Probe);
        let mut seen = probe.seen.lock().unwrap();
        seen.bounds_calls += 1;
        seen.bounds_ok &= a.geometryUserPtr == probe.user && a.primID < 3 && a.timeStep == 0;
        let x = a.primID as f32;
        *a.bounds_o = ffi::RTCBounds {
            lower_x: x,
            upper_x: x + 0.5,
            upper_y: 0.5,
            ..Default::default()
        };
    }
}

unsafe extern "C" fn probe_query(args: *mut ffi::RTCPointQueryFunctionArguments) -> bool {
    // SAFETY: Embree passes valid arguments; the user pointer is our `Probe`.
    unsafe {
        let a = &*args;
        let probe = &*(a.userPtr as *const Probe);
        let mut seen = probe.seen.lock().unwrap();
        seen.query_calls += 1;
        seen.query_ok &= a.query == probe.query
            && a.context == probe.context
            && a.geomID == 0
            && a.primID < 3
            && a.similarityScale == 1.0
            && (*a.context).instStackSize == 0;
    }
    false
}

unsafe extern "C" fn no_ray(_: *const c_void) {}

#[test]
fn point_query_structs_and_callback_arguments_are_the_4_4_layout() {
    let device = Device::new().expect("device");
    let api = api();
    let mut probe = Box::new(Probe {
        user: std::ptr::null_mut(),
        query: std::ptr::null_mut(),
        context: std::ptr::null_mut(),
        seen: std::sync::Mutex::new(Seen {
            bounds_ok: true,
            query_ok: true,
            ..Default::default()
        }),
    });
    let user = (&mut *probe as *mut Probe).cast::<c_void>();
    probe.user = user;
    let mut query = Guarded::new(ffi::RTCPointQuery {
        x: 1.2,
        y: 0.2,
        z: 0.0,
        time: 0.0,
        radius: 0.3,
    });
    let mut context = Guarded::new(ffi::RTCPointQueryContext::new());
    probe.query = &mut query.value;
    probe.context = &mut context.value;
    let query_before = query.value;
    // SAFETY: a user geometry of 3 boxes whose callbacks read `probe`, alive throughout.
    unsafe {
        let scene = (api.rtcNewScene)(device.as_raw());
        let g = (api.rtcNewGeometry)(device.as_raw(), ffi::RTC_GEOMETRY_TYPE_USER);
        (api.rtcSetGeometryUserPrimitiveCount)(g, 3);
        (api.rtcSetGeometryUserData)(g, user);
        (api.rtcSetGeometryBoundsFunction)(g, Some(probe_bounds), user);
        (api.rtcSetGeometryIntersectFunction)(g, Some(no_ray));
        (api.rtcSetGeometryOccludedFunction)(g, Some(no_ray));
        (api.rtcCommitGeometry)(g);
        (api.rtcAttachGeometry)(scene, g);
        (api.rtcReleaseGeometry)(g);
        (api.rtcCommitScene)(scene);
        (api.rtcPointQuery)(
            scene,
            &mut query.value,
            &mut context.value,
            Some(probe_query),
            user,
        );
        (api.rtcReleaseScene)(scene);
    }
    query.assert_intact("RTCPointQuery");
    context.assert_intact("RTCPointQueryContext");
    assert_eq!(query.value.radius, query_before.radius);
    assert_eq!(context.value.instStackSize, 0);
    let seen = probe.seen.lock().unwrap();
    assert_eq!(seen.bounds_calls, 3);
    assert!(seen.bounds_ok, "bounds callback arguments");
    // Boxes [0,0.5], [1,1.5], [2,2.5] in x: the disc around x = 1.2 (r = 0.3) meets box 1,
    // and a leaf may hand over its neighbours too.
    assert!(seen.query_calls >= 1, "point query callback invoked");
    assert!(seen.query_ok, "point query callback arguments");
}

#[test]
fn ray_through_the_safe_api_matches() {
    let (_device, scene) = quad_scene();
    let hit = scene
        .intersect(&Ray::new([0.5, -0.5, 0.0], [0.0, 0.0, 1.0]))
        .expect("hit");
    assert_eq!((hit.geom_id, hit.prim_id), (0, 0));
    assert!((hit.t - 1.0).abs() < 1e-6);
}

/// Negative control for `scripts/valgrind-embree.sh`: hands Embree a hit record of the
/// 4.2 size (80 bytes, as `embree4-sys` declares it) in a heap block of exactly that size.
/// Embree 4.4 writes `instPrimID` 4 bytes past the block, which memcheck must report.
/// Outside memcheck this is a real heap overflow, hence ignored.
#[test]
#[ignore = "deliberate 4-byte heap overflow; run only under memcheck by scripts/valgrind-embree.sh"]
fn memcheck_catches_a_4_2_layout_hit_record() {
    let (_device, scene) = quad_scene();
    let layout = std::alloc::Layout::from_size_align(80, 16).expect("layout");
    // SAFETY: none — this test exists to perform the overflow that the 4.2 layout causes.
    unsafe {
        let block = std::alloc::alloc_zeroed(layout);
        assert!(!block.is_null());
        block.cast::<ffi::RTCRay>().write(rtc_ray(0.5, -0.5));
        block.add(48 + 24).cast::<u32>().write(INVALID); // geomID
        let mut args = ffi::RTCIntersectArguments::new(ffi::RTC_RAY_QUERY_FLAG_INCOHERENT);
        (api().rtcIntersect1)(raw_scene(&scene), block.cast(), &mut args);
        assert_eq!(block.add(48 + 24).cast::<u32>().read(), 0, "hit geomID");
        std::alloc::dealloc(block, layout);
    }
}
