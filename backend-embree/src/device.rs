//! The Embree device: library loading, version and ABI checks, error reporting.

use crate::ffi::{self, RTCDevice};
use scratchwave_host::MeshError;
use std::ffi::{CStr, CString, c_char};

/// Everything that can go wrong at the Embree boundary.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum Error {
    /// The Embree library could not be loaded or lacks a function.
    #[error("{0} (run scripts/fetch-embree.sh, or rebuild with EMBREE_DIR set)")]
    Load(String),
    /// The device configuration string contained a NUL byte.
    #[error("device configuration {0:?} contains a NUL byte")]
    InvalidConfig(String),
    /// The loaded Embree is not a 4.x release with the 4.3+ ABI this crate binds.
    #[error("Embree {found} found; scratchwave-embree needs Embree 4.3 or newer 4.x")]
    UnsupportedVersion {
        /// The version as Embree reports it (e.g. 40401 for 4.4.1).
        found: isize,
    },
    /// The loaded Embree writes hit records of a different size than this crate's.
    #[error("Embree ABI mismatch: {0}")]
    IncompatibleAbi(String),
    /// An Embree call reported an error.
    #[error("Embree {code} during {during}: {message}")]
    Embree {
        /// The `RTC_ERROR_*` name.
        code: String,
        /// Embree's message for it.
        message: String,
        /// The operation that failed.
        during: &'static str,
    },
    /// The mesh handed in was malformed.
    #[error(transparent)]
    Mesh(#[from] MeshError),
}

/// An Embree device: the owner of scenes and of Embree's build threads.
///
/// Cloning is cheap (Embree reference count). `Send + Sync`: Embree devices may be used from
/// any thread, and errors are tracked per thread.
pub struct Device {
    raw: RTCDevice,
}

// SAFETY: Embree device handles are thread-safe (the API may be called on one device from
// several threads; the error code is kept per thread and device).
unsafe impl Send for Device {}
// SAFETY: as above; `&Device` only exposes thread-safe calls.
unsafe impl Sync for Device {}

/// Oldest supported Embree (4.3.0): the first with the instance-array hit layout.
const MIN_VERSION: isize = 40300;

impl Device {
    /// Creates the device and checks the version, without the hit-layout probe (which
    /// needs a scene: [`Device::with_config`] in `open.rs` runs it).
    pub(crate) fn open_unchecked(config: &str) -> Result<Device, Error> {
        let api = ffi::api().map_err(|e| Error::Load(e.to_owned()))?;
        let c_config = CString::new(config).map_err(|_| Error::InvalidConfig(config.into()))?;
        // SAFETY: a valid C string; a null result is handled below.
        let raw = unsafe { (api.rtcNewDevice)(c_config.as_ptr()) };
        if raw.is_null() {
            // SAFETY: a null device is allowed here: it reports the creation error.
            let code = unsafe { (api.rtcGetDeviceError)(raw) };
            return Err(embree_error(raw, code, "rtcNewDevice"));
        }
        let device = Device { raw };
        let version = device.version();
        if !(MIN_VERSION..50000).contains(&version) {
            return Err(Error::UnsupportedVersion { found: version });
        }
        Ok(device)
    }

    /// Embree's version number (`major·10000 + minor·100 + patch`).
    pub fn version(&self) -> isize {
        // SAFETY: valid device handle.
        unsafe { (ffi::loaded().rtcGetDeviceProperty)(self.raw, ffi::RTC_DEVICE_PROPERTY_VERSION) }
    }

    /// Whether packets of `width` (4, 8 or 16) rays run natively rather than emulated.
    pub fn native_packet(&self, width: usize) -> bool {
        let property = match width {
            4 => ffi::RTC_DEVICE_PROPERTY_NATIVE_RAY4_SUPPORTED,
            8 => ffi::RTC_DEVICE_PROPERTY_NATIVE_RAY8_SUPPORTED,
            16 => ffi::RTC_DEVICE_PROPERTY_NATIVE_RAY16_SUPPORTED,
            _ => return false,
        };
        // SAFETY: valid device handle.
        unsafe { (ffi::loaded().rtcGetDeviceProperty)(self.raw, property) != 0 }
    }

    pub(crate) fn raw(&self) -> RTCDevice {
        self.raw
    }

    /// The Embree handle, for direct calls through [`crate::ffi`]. Do not release it.
    pub fn as_raw(&self) -> RTCDevice {
        self.raw
    }

    /// The error Embree recorded for this thread since the last check, if any.
    pub(crate) fn check(&self, during: &'static str) -> Result<(), Error> {
        // SAFETY: valid device handle.
        let code = unsafe { (ffi::loaded().rtcGetDeviceError)(self.raw) };
        if code == ffi::RTC_ERROR_NONE {
            Ok(())
        } else {
            Err(embree_error(self.raw, code, during))
        }
    }
}

impl Clone for Device {
    fn clone(&self) -> Device {
        // SAFETY: valid device handle; balanced by the clone's Drop.
        unsafe { (ffi::loaded().rtcRetainDevice)(self.raw) };
        Device { raw: self.raw }
    }
}

impl Drop for Device {
    fn drop(&mut self) {
        // SAFETY: we own one reference.
        unsafe { (ffi::loaded().rtcReleaseDevice)(self.raw) }
    }
}

impl std::fmt::Debug for Device {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Device")
            .field("version", &self.version())
            .finish()
    }
}

fn c_string(p: *const c_char) -> String {
    if p.is_null() {
        return String::new();
    }
    // SAFETY: Embree returns NUL-terminated static or device-owned strings.
    unsafe { CStr::from_ptr(p) }.to_string_lossy().into_owned()
}

fn embree_error(device: RTCDevice, code: u32, during: &'static str) -> Error {
    let api = ffi::loaded();
    // SAFETY: both calls accept any code and a null or valid device.
    let (name, message) = unsafe {
        (
            c_string((api.rtcGetErrorString)(code)),
            c_string((api.rtcGetDeviceLastErrorMessage)(device)),
        )
    };
    Error::Embree {
        code: name,
        message,
        during,
    }
}
