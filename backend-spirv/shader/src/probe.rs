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
    /// [`math::exp`] (libm / `GLSL.std.450 Exp`, or the own approximation under
    /// `portable-math`).
    Exp = 0,
    /// [`math::sin`].
    Sin = 1,
    /// [`math::cos`].
    Cos = 2,
    /// [`math::sqrt`].
    Sqrt = 3,
    /// [`math::sinc`].
    Sinc = 4,
    /// [`math::si`], the sine integral.
    Si = 5,
    /// [`math::erf`].
    Erf = 6,
    /// [`math::faddeeva`] `w(z)`, `z = arg[0] + i arg[1]`.
    Faddeeva = 7,
    /// [`math::portable::exp`], the kernel's own approximation, on every build.
    PortableExp = 8,
    /// [`math::portable::sin`].
    PortableSin = 9,
    /// [`math::portable::cos`].
    PortableCos = 10,
    /// [`math::acos`].
    Acos = 11,
    /// [`math::asin`].
    Asin = 12,
    /// [`math::atan`].
    Atan = 13,
    /// [`math::atan2`]`(arg[0], arg[1])`.
    Atan2 = 14,
    /// [`math::ln`].
    Ln = 15,
    /// [`math::sin_cos_pi`]: `[sin πx, cos πx]`.
    SinCosPi = 16,
    /// `arg[0] / arg[1]`: the one arithmetic operation Vulkan does not require to be
    /// correctly rounded (2.5 ULP), on which the phases' accuracy hangs.
    Div = 17,
}

impl MathFunction {
    /// Every function, in id order.
    pub const ALL: [Self; 18] = [
        Self::Exp,
        Self::Sin,
        Self::Cos,
        Self::Sqrt,
        Self::Sinc,
        Self::Si,
        Self::Erf,
        Self::Faddeeva,
        Self::PortableExp,
        Self::PortableSin,
        Self::PortableCos,
        Self::Acos,
        Self::Asin,
        Self::Atan,
        Self::Atan2,
        Self::Ln,
        Self::SinCosPi,
        Self::Div,
    ];

    /// The function with this id, if any.
    #[inline]
    pub fn from_id(id: u32) -> Option<Self> {
        match id {
            0 => Some(Self::Exp),
            1 => Some(Self::Sin),
            2 => Some(Self::Cos),
            3 => Some(Self::Sqrt),
            4 => Some(Self::Sinc),
            5 => Some(Self::Si),
            6 => Some(Self::Erf),
            7 => Some(Self::Faddeeva),
            8 => Some(Self::PortableExp),
            9 => Some(Self::PortableSin),
            10 => Some(Self::PortableCos),
            11 => Some(Self::Acos),
            12 => Some(Self::Asin),
            13 => Some(Self::Atan),
            14 => Some(Self::Atan2),
            15 => Some(Self::Ln),
            16 => Some(Self::SinCosPi),
            17 => Some(Self::Div),
            _ => None,
        }
    }

    /// Evaluates the function at `arg`.
    #[inline]
    pub fn evaluate(self, arg: [f32; 2]) -> [f32; 2] {
        let x = arg[0];
        let real = |y: f32| [y, 0.0];
        match self {
            Self::Exp => real(math::exp(x)),
            Self::Sin => real(math::sin(x)),
            Self::Cos => real(math::cos(x)),
            Self::Sqrt => real(math::sqrt(x)),
            Self::Sinc => real(math::sinc(x)),
            Self::Si => real(math::si(x)),
            Self::Erf => real(math::erf(x)),
            Self::Faddeeva => {
                let w = math::faddeeva(math::C32::new(arg[0], arg[1]));
                [w.re, w.im]
            }
            Self::PortableExp => real(math::portable::exp(x)),
            Self::PortableSin => real(math::portable::sin(x)),
            Self::PortableCos => real(math::portable::cos(x)),
            Self::Acos => real(math::acos(x)),
            Self::Asin => real(math::asin(x)),
            Self::Atan => real(math::atan(x)),
            Self::Atan2 => real(math::atan2(arg[0], arg[1])),
            Self::Ln => real(math::ln(x)),
            Self::SinCosPi => {
                let (s, c) = math::sin_cos_pi(x);
                [s, c]
            }
            Self::Div => real(arg[0] / arg[1]),
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
