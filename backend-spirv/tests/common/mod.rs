//! Shared by the integration tests: open lavapipe or skip with the reason.
// Each test binary uses a subset of these helpers.
#![allow(dead_code)]

use scratchwave_spirv::{AdapterChoice, Gpu, SpirvError};

/// lavapipe, the adapter every machine (and CI) has; `None` (test skipped, reason printed)
/// only when the machine has no Vulkan at all.
pub fn lavapipe() -> Option<Gpu> {
    match Gpu::with_adapter(&AdapterChoice::Lavapipe) {
        Ok(gpu) => Some(gpu),
        Err(SpirvError::NoVulkan) => {
            eprintln!("skipped: {}", SpirvError::NoVulkan);
            None
        }
        Err(error) => panic!("opening lavapipe: {error}"),
    }
}

/// Units in the last place between two finite `f32` (through the sign-magnitude order).
pub fn ulps(a: f32, b: f32) -> u64 {
    let key = |x: f32| {
        let bits = x.to_bits() as i64;
        if bits < 0x8000_0000 {
            bits
        } else {
            0x8000_0000 - bits
        }
    };
    (key(a) - key(b)).unsigned_abs()
}

/// `n` points evenly spaced over `[lo, hi]`, as probe arguments.
pub fn linspace(lo: f32, hi: f32, n: usize) -> Vec<[f32; 2]> {
    (0..n)
        .map(|i| [lo + (hi - lo) * (i as f64 / (n - 1) as f64) as f32, 0.0])
        .collect()
}
