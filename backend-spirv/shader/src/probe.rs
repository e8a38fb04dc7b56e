//! Element-wise probes of the kernel's `math` seam: the same [`evaluate`] runs on the CPU
//! and inside the [`crate::math_probe`] entry point, so a CPU-vs-GPU diff isolates what the
//! two targets do differently (libm vs. `GLSL.std.450`, rounding, `fma` contraction).

use bytemuck::{Pod, Zeroable};
use scratchwave_kernel::math;

/// Which function [`crate::math_probe`] evaluates; one per dispatch.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct ProbeParams {
    /// A [`MathFunction`] as `u32`.
    pub function: u32,
    /// Keeps the struct 16 bytes, a friendly size for any buffer layout.
    pub _pad: [u32; 3],
}

const _: () = assert!(core::mem::size_of::<ProbeParams>() == 16);

impl ProbeParams {
    /// Parameters selecting `function`.
    pub const fn new(function: MathFunction) -> Self {
        Self {
            function: function as u32,
            _pad: [0; 3],
        }
    }
}

/// The probed functions. Arguments and results are `[f32; 2]` so complex functions fit;
/// real functions read `arg[0]` and write `[f(arg[0]), 0]`.
#[repr(u32)]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MathFunction {
    /// [`math::exp`], whatever the `portable-math` feature routes it to.
    Exp = 0,
    /// [`math::portable::exp`], the kernel's own approximation, on every build.
    PortableExp = 1,
    /// [`math::portable::sin`].
    PortableSin = 2,
    /// [`math::portable::cos`].
    PortableCos = 3,
}

impl MathFunction {
    /// Every function, in id order.
    pub const ALL: [Self; 4] = [
        Self::Exp,
        Self::PortableExp,
        Self::PortableSin,
        Self::PortableCos,
    ];

    /// The function with this id, if any.
    #[inline]
    pub fn from_id(id: u32) -> Option<Self> {
        match id {
            0 => Some(Self::Exp),
            1 => Some(Self::PortableExp),
            2 => Some(Self::PortableSin),
            3 => Some(Self::PortableCos),
            _ => None,
        }
    }

    /// Evaluates the function at `arg`.
    #[inline]
    pub fn evaluate(self, arg: [f32; 2]) -> [f32; 2] {
        let x = arg[0];
        match self {
            Self::Exp => [math::exp(x), 0.0],
            Self::PortableExp => [math::portable::exp(x), 0.0],
            Self::PortableSin => [math::portable::sin(x), 0.0],
            Self::PortableCos => [math::portable::cos(x), 0.0],
        }
    }
}

/// [`MathFunction::evaluate`] by id; an unknown id gives NaN (the shader cannot fail).
#[inline]
pub fn evaluate(function: u32, arg: [f32; 2]) -> [f32; 2] {
    match MathFunction::from_id(function) {
        Some(f) => f.evaluate(arg),
        None => [f32::NAN, f32::NAN],
    }
}
