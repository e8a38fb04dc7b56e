//! Opening a [`Device`]: creation, the version check and, once per process, the probe of
//! the hit-record layout (which needs a scene, so it lives above both `device` and
//! `scene`).

use crate::device::{Device, Error};
use crate::ffi::{self, RTCRayHit};
use crate::scene::{SceneBuilder, to_rtc};
use scratchwave_kernel::ray::Ray;
use std::sync::OnceLock;

impl Device {
    /// A device with Embree's default configuration (all cores for builds, best ISA).
    pub fn new() -> Result<Device, Error> {
        Device::with_config("")
    }

    /// A device with an Embree configuration string, e.g. `"threads=1,isa=avx2"` (see the
    /// Embree manual, `rtcNewDevice`).
    pub fn with_config(config: &str) -> Result<Device, Error> {
        let device = Device::open_unchecked(config)?;
        static ABI: OnceLock<Result<(), Error>> = OnceLock::new();
        ABI.get_or_init(|| check_hit_layout(&device)).clone()?;
        Ok(device)
    }
}

/// Traces one ray against a one-triangle scene with guard words after the hit record and
/// checks that Embree wrote nothing past it. Run once per process by [`Device::new`].
fn check_hit_layout(device: &Device) -> Result<(), Error> {
    const GUARD: u32 = 0xDEAD_BEEF;
    #[repr(C, align(64))]
    struct Guarded {
        rayhit: RTCRayHit,
        guard: [u32; 32],
    }
    let mut builder = SceneBuilder::new(device)?;
    builder.add_triangle_mesh(
        &[[-1.0, -1.0, 1.0], [1.0, -1.0, 1.0], [0.0, 1.0, 1.0]],
        &[[0, 1, 2]],
    )?;
    let scene = builder.commit()?;
    let mut probe = Guarded {
        rayhit: RTCRayHit {
            ray: to_rtc(&Ray::new([0.0; 3], [0.0, 0.0, 1.0])),
            hit: ffi::RTCHit::default(),
        },
        guard: [GUARD; 32],
    };
    let mut args = ffi::RTCIntersectArguments::new(ffi::RTC_RAY_QUERY_FLAG_INCOHERENT);
    // SAFETY: the record is followed by 128 bytes we own, so even an ABI mismatch writes
    // only into our own memory.
    unsafe { (ffi::loaded().rtcIntersect1)(scene.as_raw(), &mut probe.rayhit, &mut args) };
    if probe.rayhit.hit.geomID != 0 || (probe.rayhit.ray.tfar - 1.0).abs() > 1e-5 {
        return Err(Error::IncompatibleAbi(format!(
            "probe ray reported geomID {} at t = {} (expected 0 at 1)",
            probe.rayhit.hit.geomID, probe.rayhit.ray.tfar
        )));
    }
    if let Some(i) = probe.guard.iter().position(|&g| g != GUARD) {
        return Err(Error::IncompatibleAbi(format!(
            "rtcIntersect1 wrote {} bytes past the 4.4-layout RTCRayHit",
            4 * (i + 1)
        )));
    }
    Ok(())
}
