//! Hand-written bindings for the part of the Embree 4 C API this crate uses, with every struct
//! in the **Embree 4.4 layout** (`RTC_MAX_INSTANCE_LEVEL_COUNT = 1`,
//! `RTC_GEOMETRY_INSTANCE_ARRAY` defined: the defaults of Embree ≥ 4.3 and what the pinned
//! library was built with).
//!
//! Why not `embree4-sys`: it vendors the 4.2 headers, whose `RTCHit`/`RTCHitN` lack
//! `instPrimID`; Embree ≥ 4.3 writes that field on every hit, past the end of a 4.2-layout
//! `RTCRayHit` (see `tests/abi.rs`). Writing the few dozen declarations here avoids patching
//! over those types and the bindgen/libclang build step.
//!
//! The library is opened with `dlopen` from the absolute path the build script found, and
//! all functions are resolved once (see [`api`]).
//!
//! Layout notes, checked at compile time below and at run time by [`crate::Device::new`]:
//! - `RTCHit` is 36 bytes of fields, padded to 48 by its 16-byte alignment; `RTCRayHit` = 96.
//! - `RTCPointQueryContext` has `instPrimID` before `instStackSize` (144 bytes). We zero it, so
//!   a library built without instance arrays reads `instStackSize = 0` from the same place.
//! - `RTCIntersectArguments`/`RTCOccludedArguments` carry the trailing
//!   `minWidthDistanceFactor` that exists only when Embree is built with `EMBREE_MIN_WIDTH`;
//!   passing it always is harmless and keeps such builds from reading past the struct.

#![allow(non_camel_case_types, non_snake_case, missing_docs)]

use std::ffi::{c_char, c_void};
use std::sync::OnceLock;

/// Opaque handle types.
pub enum RTCDeviceTy {}
pub enum RTCSceneTy {}
pub enum RTCGeometryTy {}
pub type RTCDevice = *mut RTCDeviceTy;
pub type RTCScene = *mut RTCSceneTy;
pub type RTCGeometry = *mut RTCGeometryTy;

pub const RTC_INVALID_GEOMETRY_ID: u32 = u32::MAX;

// enum RTCError
pub const RTC_ERROR_NONE: u32 = 0;

// enum RTCDeviceProperty
pub const RTC_DEVICE_PROPERTY_VERSION: u32 = 0;
pub const RTC_DEVICE_PROPERTY_NATIVE_RAY4_SUPPORTED: u32 = 32;
pub const RTC_DEVICE_PROPERTY_NATIVE_RAY8_SUPPORTED: u32 = 33;
pub const RTC_DEVICE_PROPERTY_NATIVE_RAY16_SUPPORTED: u32 = 34;

// enum RTCBuildQuality
pub const RTC_BUILD_QUALITY_LOW: u32 = 0;
pub const RTC_BUILD_QUALITY_MEDIUM: u32 = 1;
pub const RTC_BUILD_QUALITY_HIGH: u32 = 2;

// enum RTCSceneFlags
pub const RTC_SCENE_FLAG_NONE: u32 = 0;
pub const RTC_SCENE_FLAG_ROBUST: u32 = 1 << 2;

// enum RTCGeometryType
pub const RTC_GEOMETRY_TYPE_TRIANGLE: u32 = 0;
pub const RTC_GEOMETRY_TYPE_USER: u32 = 120;

// enum RTCBufferType
pub const RTC_BUFFER_TYPE_INDEX: u32 = 0;
pub const RTC_BUFFER_TYPE_VERTEX: u32 = 1;

// enum RTCFormat
pub const RTC_FORMAT_UINT3: u32 = 0x5003;
pub const RTC_FORMAT_FLOAT3: u32 = 0x9003;

// enum RTCRayQueryFlags
pub const RTC_RAY_QUERY_FLAG_INCOHERENT: u32 = 0;
pub const RTC_RAY_QUERY_FLAG_COHERENT: u32 = 1 << 16;

// enum RTCFeatureFlags
pub const RTC_FEATURE_FLAG_ALL: u32 = 0xffff_ffff;

#[repr(C, align(16))]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct RTCRay {
    pub org_x: f32,
    pub org_y: f32,
    pub org_z: f32,
    pub tnear: f32,
    pub dir_x: f32,
    pub dir_y: f32,
    pub dir_z: f32,
    pub time: f32,
    pub tfar: f32,
    pub mask: u32,
    pub id: u32,
    pub flags: u32,
}

#[repr(C, align(16))]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RTCHit {
    pub Ng_x: f32,
    pub Ng_y: f32,
    pub Ng_z: f32,
    pub u: f32,
    pub v: f32,
    pub primID: u32,
    pub geomID: u32,
    pub instID: [u32; 1],
    pub instPrimID: [u32; 1],
}

impl Default for RTCHit {
    fn default() -> Self {
        RTCHit {
            Ng_x: 0.0,
            Ng_y: 0.0,
            Ng_z: 0.0,
            u: 0.0,
            v: 0.0,
            primID: RTC_INVALID_GEOMETRY_ID,
            geomID: RTC_INVALID_GEOMETRY_ID,
            instID: [RTC_INVALID_GEOMETRY_ID],
            instPrimID: [RTC_INVALID_GEOMETRY_ID],
        }
    }
}

#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct RTCRayHit {
    pub ray: RTCRay,
    pub hit: RTCHit,
}

macro_rules! packet_types {
    ($ray:ident, $hit:ident, $rayhit:ident, $n:literal, $align:literal) => {
        #[repr(C, align($align))]
        #[derive(Clone, Copy, Debug)]
        pub struct $ray {
            pub org_x: [f32; $n],
            pub org_y: [f32; $n],
            pub org_z: [f32; $n],
            pub tnear: [f32; $n],
            pub dir_x: [f32; $n],
            pub dir_y: [f32; $n],
            pub dir_z: [f32; $n],
            pub time: [f32; $n],
            pub tfar: [f32; $n],
            pub mask: [u32; $n],
            pub id: [u32; $n],
            pub flags: [u32; $n],
        }

        #[repr(C, align($align))]
        #[derive(Clone, Copy, Debug)]
        pub struct $hit {
            pub Ng_x: [f32; $n],
            pub Ng_y: [f32; $n],
            pub Ng_z: [f32; $n],
            pub u: [f32; $n],
            pub v: [f32; $n],
            pub primID: [u32; $n],
            pub geomID: [u32; $n],
            pub instID: [[u32; $n]; 1],
            pub instPrimID: [[u32; $n]; 1],
        }

        #[repr(C)]
        #[derive(Clone, Copy, Debug)]
        pub struct $rayhit {
            pub ray: $ray,
            pub hit: $hit,
        }
    };
}

packet_types!(RTCRay4, RTCHit4, RTCRayHit4, 4, 16);
packet_types!(RTCRay8, RTCHit8, RTCRayHit8, 8, 32);
packet_types!(RTCRay16, RTCHit16, RTCRayHit16, 16, 64);

/// `valid` masks for packet calls (-1 = active lane), aligned like the packets.
#[repr(C, align(64))]
#[derive(Clone, Copy, Debug)]
pub struct Valid<const N: usize>(pub [i32; N]);

pub type RTCFilterFunctionN = Option<unsafe extern "C" fn(args: *const c_void)>;
pub type RTCIntersectFunctionN = Option<unsafe extern "C" fn(args: *const c_void)>;
pub type RTCOccludedFunctionN = Option<unsafe extern "C" fn(args: *const c_void)>;

#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct RTCIntersectArguments {
    pub flags: u32,
    pub feature_mask: u32,
    pub context: *mut c_void,
    pub filter: RTCFilterFunctionN,
    pub intersect: RTCIntersectFunctionN,
    pub minWidthDistanceFactor: f32,
}

#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct RTCOccludedArguments {
    pub flags: u32,
    pub feature_mask: u32,
    pub context: *mut c_void,
    pub filter: RTCFilterFunctionN,
    pub occluded: RTCOccludedFunctionN,
    pub minWidthDistanceFactor: f32,
}

impl RTCIntersectArguments {
    /// The header-inline `rtcInitIntersectArguments`, with a coherence hint.
    pub fn new(flags: u32) -> Self {
        RTCIntersectArguments {
            flags,
            feature_mask: RTC_FEATURE_FLAG_ALL,
            context: std::ptr::null_mut(),
            filter: None,
            intersect: None,
            minWidthDistanceFactor: 0.0,
        }
    }
}

impl RTCOccludedArguments {
    /// The header-inline `rtcInitOccludedArguments`, with a coherence hint.
    pub fn new(flags: u32) -> Self {
        RTCOccludedArguments {
            flags,
            feature_mask: RTC_FEATURE_FLAG_ALL,
            context: std::ptr::null_mut(),
            filter: None,
            occluded: None,
            minWidthDistanceFactor: 0.0,
        }
    }
}

#[repr(C, align(16))]
#[derive(Clone, Copy, Debug, Default)]
pub struct RTCBounds {
    pub lower_x: f32,
    pub lower_y: f32,
    pub lower_z: f32,
    pub align0: f32,
    pub upper_x: f32,
    pub upper_y: f32,
    pub upper_z: f32,
    pub align1: f32,
}

#[repr(C)]
#[derive(Debug)]
pub struct RTCBoundsFunctionArguments {
    pub geometryUserPtr: *mut c_void,
    pub primID: u32,
    pub timeStep: u32,
    pub bounds_o: *mut RTCBounds,
}

pub type RTCBoundsFunction = Option<unsafe extern "C" fn(args: *const RTCBoundsFunctionArguments)>;

#[repr(C, align(16))]
#[derive(Clone, Copy, Debug, Default)]
pub struct RTCPointQuery {
    pub x: f32,
    pub y: f32,
    pub z: f32,
    pub time: f32,
    pub radius: f32,
}

#[repr(C, align(16))]
#[derive(Clone, Copy, Debug)]
pub struct RTCPointQueryContext {
    pub world2inst: [[f32; 16]; 1],
    pub inst2world: [[f32; 16]; 1],
    pub instID: [u32; 1],
    pub instPrimID: [u32; 1],
    pub instStackSize: u32,
}

impl Default for RTCPointQueryContext {
    fn default() -> Self {
        Self::new()
    }
}

impl RTCPointQueryContext {
    /// The header-inline `rtcInitPointQueryContext`, except that `instPrimID` is 0 rather
    /// than invalid: it is unused at stack size 0, and a library without instance arrays
    /// reads that word as `instStackSize`.
    pub fn new() -> Self {
        RTCPointQueryContext {
            world2inst: [[0.0; 16]; 1],
            inst2world: [[0.0; 16]; 1],
            instID: [RTC_INVALID_GEOMETRY_ID],
            instPrimID: [0],
            instStackSize: 0,
        }
    }
}

#[repr(C, align(16))]
#[derive(Debug)]
pub struct RTCPointQueryFunctionArguments {
    pub query: *mut RTCPointQuery,
    pub userPtr: *mut c_void,
    pub primID: u32,
    pub geomID: u32,
    pub context: *mut RTCPointQueryContext,
    pub similarityScale: f32,
}

pub type RTCPointQueryFunction =
    Option<unsafe extern "C" fn(args: *mut RTCPointQueryFunctionArguments) -> bool>;

// Sizes from the 4.4 headers with RTC_GEOMETRY_INSTANCE_ARRAY (x86-64).
const _: () = {
    use std::mem::{align_of, size_of};
    assert!(size_of::<RTCRay>() == 48);
    assert!(size_of::<RTCHit>() == 48);
    assert!(size_of::<RTCRayHit>() == 96 && align_of::<RTCRayHit>() == 16);
    assert!(size_of::<RTCRayHit4>() == 336 && align_of::<RTCRayHit4>() == 16);
    assert!(size_of::<RTCRayHit8>() == 672 && align_of::<RTCRayHit8>() == 32);
    assert!(size_of::<RTCRayHit16>() == 1344 && align_of::<RTCRayHit16>() == 64);
    assert!(size_of::<RTCRay16>() == 768);
    assert!(size_of::<RTCBounds>() == 32);
    assert!(size_of::<RTCBoundsFunctionArguments>() == 24);
    assert!(size_of::<RTCPointQuery>() == 32);
    assert!(size_of::<RTCPointQueryContext>() == 144);
    assert!(size_of::<RTCPointQueryFunctionArguments>() == 48);
    assert!(size_of::<RTCIntersectArguments>() == 40);
};

/// Declares the function table and its loader.
macro_rules! functions {
    ($( fn $name:ident($($arg:ty),* $(,)?) $(-> $ret:ty)?; )*) => {
        /// Every Embree entry point this crate calls, resolved from the loaded library.
        pub struct Functions {
            $( pub $name: unsafe extern "C" fn($($arg),*) $(-> $ret)?, )*
        }

        impl Functions {
            /// # Safety
            /// `library` must be an Embree 4 library, whose symbols have these signatures.
            unsafe fn resolve(library: &libloading::Library) -> Result<Functions, String> {
                Ok(Functions {
                    $( $name: unsafe {
                        *library
                            .get::<unsafe extern "C" fn($($arg),*) $(-> $ret)?>(
                                concat!(stringify!($name), "\0").as_bytes(),
                            )
                            .map_err(|e| format!("symbol {}: {e}", stringify!($name)))?
                    }, )*
                })
            }
        }
    };
}

functions! {
    fn rtcNewDevice(*const c_char) -> RTCDevice;
    fn rtcRetainDevice(RTCDevice);
    fn rtcReleaseDevice(RTCDevice);
    fn rtcGetDeviceProperty(RTCDevice, u32) -> isize;
    fn rtcGetDeviceError(RTCDevice) -> u32;
    fn rtcGetDeviceLastErrorMessage(RTCDevice) -> *const c_char;
    fn rtcGetErrorString(u32) -> *const c_char;
    fn rtcNewScene(RTCDevice) -> RTCScene;
    fn rtcReleaseScene(RTCScene);
    fn rtcSetSceneBuildQuality(RTCScene, u32);
    fn rtcSetSceneFlags(RTCScene, u32);
    fn rtcCommitScene(RTCScene);
    fn rtcAttachGeometry(RTCScene, RTCGeometry) -> u32;
    fn rtcNewGeometry(RTCDevice, u32) -> RTCGeometry;
    fn rtcReleaseGeometry(RTCGeometry);
    fn rtcCommitGeometry(RTCGeometry);
    fn rtcSetNewGeometryBuffer(RTCGeometry, u32, u32, u32, usize, usize) -> *mut c_void;
    fn rtcSetGeometryUserPrimitiveCount(RTCGeometry, u32);
    fn rtcSetGeometryUserData(RTCGeometry, *mut c_void);
    fn rtcSetGeometryBoundsFunction(RTCGeometry, RTCBoundsFunction, *mut c_void);
    fn rtcSetGeometryIntersectFunction(RTCGeometry, RTCIntersectFunctionN);
    fn rtcSetGeometryOccludedFunction(RTCGeometry, RTCOccludedFunctionN);
    fn rtcIntersect1(RTCScene, *mut RTCRayHit, *mut RTCIntersectArguments);
    fn rtcIntersect4(*const i32, RTCScene, *mut RTCRayHit4, *mut RTCIntersectArguments);
    fn rtcIntersect8(*const i32, RTCScene, *mut RTCRayHit8, *mut RTCIntersectArguments);
    fn rtcIntersect16(*const i32, RTCScene, *mut RTCRayHit16, *mut RTCIntersectArguments);
    fn rtcOccluded1(RTCScene, *mut RTCRay, *mut RTCOccludedArguments);
    fn rtcOccluded4(*const i32, RTCScene, *mut RTCRay4, *mut RTCOccludedArguments);
    fn rtcOccluded8(*const i32, RTCScene, *mut RTCRay8, *mut RTCOccludedArguments);
    fn rtcOccluded16(*const i32, RTCScene, *mut RTCRay16, *mut RTCOccludedArguments);
    fn rtcPointQuery(
        RTCScene,
        *mut RTCPointQuery,
        *mut RTCPointQueryContext,
        RTCPointQueryFunction,
        *mut c_void,
    ) -> bool;
}

/// Path of the Embree library found by the build script.
pub const LIBRARY_PATH: &str = env!("SCRATCHWAVE_EMBREE_LIBRARY");

/// The Embree library this process loads: `SCRATCHWAVE_EMBREE_LIBRARY` from the
/// environment when set and not empty (binaries copied to another machine, where the
/// build machine's path does not exist), else [`LIBRARY_PATH`].
pub fn library_path() -> std::path::PathBuf {
    match std::env::var_os("SCRATCHWAVE_EMBREE_LIBRARY") {
        Some(path) if !path.is_empty() => path.into(),
        _ => LIBRARY_PATH.into(),
    }
}

struct Loaded {
    functions: Functions,
    // Never unloaded: the function pointers above stay valid for the life of the process
    // (and TBB's worker threads do not survive dlclose well).
    _library: libloading::Library,
}

static EMBREE: OnceLock<Result<Loaded, String>> = OnceLock::new();

/// The resolved Embree functions, loading the library on first use. The error says what
/// failed (missing file, missing symbol).
pub fn api() -> Result<&'static Functions, &'static str> {
    let loaded = EMBREE.get_or_init(|| {
        // SAFETY: loading runs Embree's and TBB's static initializers, which have no
        // preconditions; the path is the library the build script verified exists, or the
        // one the user named instead.
        let path = library_path();
        let library = unsafe { libloading::Library::new(&path) }
            .map_err(|e| format!("cannot load {}: {e}", path.display()))?;
        // SAFETY: it is an Embree 4 library (checked by version after device creation).
        let functions = unsafe { Functions::resolve(&library) }?;
        Ok(Loaded {
            functions,
            _library: library,
        })
    });
    match loaded {
        Ok(l) => Ok(&l.functions),
        Err(e) => Err(e.as_str()),
    }
}

/// The loaded functions; only called after [`api`] succeeded (every [`crate::Device`] is
/// proof of that).
#[inline]
pub fn loaded() -> &'static Functions {
    match EMBREE.get() {
        Some(Ok(l)) => &l.functions,
        _ => unreachable!("Embree functions used before the library loaded"),
    }
}
