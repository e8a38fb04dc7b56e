//! The one seam for transcendental functions.
//!
//! Every `exp`, `sin`, `sqrt`, … in the kernel goes through this module, so the CPU and
//! the GPU see exactly the same code. On the CPU the calls go to `libm`; rust-gpu maps the
//! same `libm` calls onto GLSL.std.450 instructions.

pub mod portable;

/// e^x.
#[inline]
pub fn exp(x: f32) -> f32 {
    #[cfg(feature = "portable-math")]
    return portable::exp(x);
    #[cfg(not(feature = "portable-math"))]
    libm::expf(x)
}
