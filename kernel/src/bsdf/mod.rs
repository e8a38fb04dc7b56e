//! The material interface a path tracer calls at a hit, on the CPU and in SPIR-V alike
//! (`docs/bsdf.md`): `eval`, `pdf` and `sample` of a [`BsdfMaterial`] at a
//! [`ShadingPoint`] for a set of [`Wavelengths`], in the spirit of pbrt-v4's
//! `BxDF::f/Sample_f/PDF` and Mitsuba 3's `BSDF::eval/sample/pdf`, without trait objects:
//! the material is a `Pod` record whose model is a `u32` enum.
//!
//! Conventions: `wo` points towards the viewer (known at a hit), `wi` towards the light (the
//! sampled direction), both away from the surface; [`sample`] draws `wi` given `wo`. Every
//! `eval` value is the BRDF **without** the cosine (1/sr); [`BsdfSample::weight`] is
//! `f·cosθi/pdf` (**with** the cosine). Positions in µm in scratch space, wavelengths in
//! nm. Functions ending in `_world` take world directions and a [`ShadingFrame`]; the others
//! take local directions (`z` = normal, `x` = tangent = scratch-space `x`).
//!
//! | file | what |
//! |---|---|
//! | `frame` | [`ShadingFrame`]: world ↔ local |
//! | `wavelengths` | [`Wavelengths`]: RGB set, stratified spectral sampling with pdf |
//! | `material` | [`BsdfMaterial`], its per-paper depth-phase default, conversion from the renderer's record |
//! | `eval` | [`eval()`]: every wavelength from one scratch walk; its point values are the table interface's |
//! | `scratch_models` | [`scratch_models::Model`] and the one formula from scratch terms to BRDF (Werner Eq. 15, §5; Velinov Eqs. 6–7) |
//! | `lobe1d` | truncated logistic / Cauchy mixtures (closed-form CDF and inverse) |
//! | `lobes` | the directional lobes: disk-product lobes (this crate), Werner §5's Gaussian base and vMF ring |
//! | `mixture` | component weights, [`sample`] and [`pdf`]: balance heuristic over base, scratches and GHS, and over the wavelengths |

/// `docs/bsdf.md`, compiled and run as a doc test.
#[cfg(doctest)]
#[doc = include_str!("../../../docs/bsdf.md")]
pub struct BsdfGuide;

pub mod eval;
pub mod frame;
pub mod lobe1d;
pub mod lobes;
pub mod material;
pub mod mixture;
pub mod scratch_models;
pub mod wavelengths;

pub use eval::{eval, eval_world};
pub use frame::ShadingFrame;
pub use material::{BsdfMaterial, DepthChoice};
pub use mixture::{
    Strategy, pdf, pdf_with, pdf_world, sample, sample_direction_with, sample_with, sample_world,
};
pub use wavelengths::Wavelengths;

use crate::footprint::Ellipse;
use crate::ghs::g1::G1Table;
use crate::scratch::{MAX_SPECTRAL, ScratchSet};
use glam::{Vec2, Vec3};

/// What the BSDF reads besides the material: the scratch lookup and the GHS Smith G1 table
/// (the builtin `const` on the CPU; on the GPU a storage buffer holding
/// [`G1Table::FLAT`], since a large `const` table indexed at run time does not compile
/// there, see `ARCHITECTURE.md`).
///
/// The scratch set is held by value (`ScratchSlice` and `ScratchBvh` are two slices; a
/// reference `&S` is a set too): a pointer to a local stored in a struct is not a logical
/// pointer on SPIR-V.
#[derive(Clone, Copy, Debug)]
pub struct Lookup<'a, S: ScratchSet> {
    /// The scratches near a shading point.
    pub scratches: S,
    /// The G1 table of the GHS lobes.
    pub g1: G1Table<'a>,
}

impl<S: ScratchSet> Lookup<'static, S> {
    /// `scratches` with the builtin G1 table.
    pub fn new(scratches: S) -> Lookup<'static, S> {
        Lookup {
            scratches,
            g1: G1Table::BUILTIN,
        }
    }
}

impl<'a, S: ScratchSet> Lookup<'a, S> {
    /// `scratches` with the given G1 table.
    pub fn with_g1_table(scratches: S, g1: G1Table<'a>) -> Lookup<'a, S> {
        Lookup { scratches, g1 }
    }
}

/// Per-wavelength values (entries past the [`Wavelengths`] count are 0).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Spectrum {
    /// One value per wavelength.
    pub v: [f32; MAX_SPECTRAL],
}

impl Spectrum {
    /// All zero.
    pub const ZERO: Spectrum = Spectrum {
        v: [0.0; MAX_SPECTRAL],
    };

    /// Each entry times `s`.
    #[inline]
    pub fn scaled(self, s: f32) -> Spectrum {
        let mut v = self.v;
        let mut j = 0;
        while j < MAX_SPECTRAL {
            v[j] *= s;
            j += 1;
        }
        Spectrum { v }
    }
}

/// Where a material is evaluated: the scratch-space position and the optional pixel
/// footprint. GPU-visible: 48 bytes.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct ShadingPoint {
    /// Scratch-space position (µm): the footprint centre.
    pub x_um: [f32; 2],
    /// Explicit padding.
    pub pad: [f32; 2],
    /// Pixel footprint in scratch space (µm); `a1 = 0` (the default) for none. Its `center`
    /// is ignored (`x_um` is used).
    pub footprint: Ellipse,
}

const _: () = assert!(core::mem::size_of::<ShadingPoint>() == 48);

impl ShadingPoint {
    /// A point without footprint.
    pub fn at(x_um: [f32; 2]) -> ShadingPoint {
        ShadingPoint {
            x_um,
            ..ShadingPoint::default()
        }
    }

    /// A point with footprint `e` (its centre is replaced by `x_um`).
    pub fn with_footprint(x_um: [f32; 2], e: Ellipse) -> ShadingPoint {
        ShadingPoint {
            x_um,
            pad: [0.0; 2],
            footprint: Ellipse { center: x_um, ..e },
        }
    }

    /// The position as a vector.
    #[inline]
    pub fn x(&self) -> Vec2 {
        Vec2::from_array(self.x_um)
    }

    /// The footprint when there is one (`a1 > 0` and `a2 > 0`), centred at `x_um`.
    #[inline]
    pub fn footprint(&self) -> Option<Ellipse> {
        if self.footprint.a1 > 0.0 && self.footprint.a2 > 0.0 {
            Some(Ellipse {
                center: self.x_um,
                ..self.footprint
            })
        } else {
            None
        }
    }
}

/// Lobe index of [`BsdfSample::lobe`]: the Gaussian base response (Werner Eq. 16).
pub const LOBE_BASE: u32 = 0;
/// Lobe index: one scratch's response.
pub const LOBE_SCRATCH: u32 = 1;
/// Lobe index: the GHS surface (the material, or the base of a blended model).
pub const LOBE_GHS: u32 = 2;

/// One sampled direction.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct BsdfSample {
    /// The sampled direction towards the light (local frame, or world for `sample_world`).
    pub wi: Vec3,
    /// `f·cosθi/pdf` per wavelength (with the cosine).
    pub weight: Spectrum,
    /// `f` per wavelength (without the cosine), equal to [`eval()`] at `wi`.
    pub value: Spectrum,
    /// Solid-angle pdf of `wi`, equal to [`pdf`] at `wi`.
    pub pdf: f32,
    /// The lobe that produced it ([`LOBE_BASE`], [`LOBE_SCRATCH`], [`LOBE_GHS`]).
    pub lobe: u32,
    /// The wavelength whose mixture produced it (index into [`Wavelengths::nm`]).
    pub wavelength: u32,
}
