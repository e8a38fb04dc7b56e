//! The reflectance of a query's surface: a constant, or the Fresnel term of a complex IOR
//! (constant, or a metal's spectral curve from [`crate::conductor`]) at a chosen angle
//! (H&P Eqs. 11–13). GPU-visible; used by the tables, the area lights
//! and the renderer alike.

use crate::conductor::{self, Conductor};
use crate::fresnel::fresnel;
use bytemuck::{Pod, Zeroable};
use glam::Vec3;

gpu_enum! {
    /// What [`Material`] holds.
    pub enum MaterialKind {
        /// A constant reflectance `f`.
        Constant = 0,
        /// Fresnel of the complex IOR `n + ik`, or of the spectral IOR of `conductor`.
        Ior = 1,
    }
    fallback = Ior;
}

gpu_enum! {
    /// Which angle the Fresnel term is evaluated at.
    pub enum FresnelAngle {
        /// θd: between `wi` and the half vector (default).
        ThetaD = 0,
        /// θi: between `wi` and the normal.
        ThetaI = 1,
        /// Normal incidence.
        Normal = 2,
    }
    fallback = ThetaD;
}

/// Material of one query: a constant reflectance or a complex IOR.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct Material {
    /// A [`MaterialKind`] as `u32`.
    pub kind: u32,
    /// A [`FresnelAngle`] as `u32` (kind 1 only).
    pub fresnel_angle: u32,
    /// Constant reflectance (kind 0).
    pub f: f32,
    /// Real part of the IOR (kind 1).
    pub n: f32,
    /// Imaginary part of the IOR (kind 1).
    pub k: f32,
    /// A [`Conductor`] as `u32` (kind 1): when not `None`, its spectral IOR replaces `n`, `k`.
    pub conductor: u32,
    /// Explicit padding.
    pub pad: [u32; 2],
}

const _: () = assert!(core::mem::size_of::<Material>() == 32);

impl Material {
    /// A constant reflectance `F`.
    pub const fn constant(f: f32) -> Material {
        Material {
            kind: MaterialKind::Constant as u32,
            fresnel_angle: 0,
            f,
            n: 0.0,
            k: 0.0,
            conductor: Conductor::None as u32,
            pad: [0; 2],
        }
    }

    /// Fresnel reflectance of `n + ik` at the given angle.
    pub const fn ior(n: f32, k: f32, angle: FresnelAngle) -> Material {
        Material {
            kind: MaterialKind::Ior as u32,
            fresnel_angle: angle as u32,
            f: 0.0,
            n,
            k,
            conductor: Conductor::None as u32,
            pad: [0; 2],
        }
    }

    /// Fresnel reflectance of the spectral IOR of `metal` at the given angle.
    pub const fn conductor(metal: Conductor, angle: FresnelAngle) -> Material {
        let mut m = Material::ior(0.0, 0.0, angle);
        m.conductor = metal as u32;
        m
    }

    /// The reflectance for unit directions `wi`, `wo` at `lambda_nm` (which only a
    /// spectral IOR reads).
    #[inline]
    pub fn reflectance(&self, wi: Vec3, wo: Vec3, lambda_nm: f32) -> f32 {
        if MaterialKind::from_u32(self.kind) == MaterialKind::Constant {
            return self.f;
        }
        let cos = match FresnelAngle::from_u32(self.fresnel_angle) {
            FresnelAngle::ThetaI => wi.z,
            FresnelAngle::Normal => 1.0,
            FresnelAngle::ThetaD => cos_theta_d(wi, wo),
        };
        let (n, k) = conductor::ior(
            Conductor::from_u32(self.conductor),
            lambda_nm,
            self.n,
            self.k,
        );
        fresnel(cos, n, k)
    }

    /// Whether [`Material::reflectance`] depends on the wavelength.
    #[inline]
    pub fn is_spectral(&self) -> bool {
        MaterialKind::from_u32(self.kind) == MaterialKind::Ior
            && Conductor::from_u32(self.conductor) != Conductor::None
    }
}

/// `cosθd = wi·h` with `h = (wi + wo)/|wi + wo|`, formed as `|wi + wo|/2` (equal for unit
/// directions: `wi·(wi + wo) = 1 + wi·wo = |wi + wo|²/2`). Symmetric in `wi`, `wo` bit for
/// bit (`wi + wo` is a commutative sum), so Fresnel at θd keeps the BRDF reciprocal bit for
/// bit; `wi·normalize(wi + wo)` differs from `wo·normalize(wi + wo)` in the last bits, which
/// Fresnel below the critical angle of `n < 1` amplifies (its slope is infinite there).
/// 0 when `wo = −wi`.
#[inline]
pub fn cos_theta_d(wi: Vec3, wo: Vec3) -> f32 {
    0.5 * crate::math::sqrt((wi + wo).length_squared())
}

/// [`Material::reflectance`] at fixed directions for several wavelengths: formed once, at
/// the first wavelength asked for, when the material is not spectral
/// ([`Material::is_spectral`]), and per wavelength otherwise. Every value is bitwise the
/// one `reflectance` returns (a non-spectral material does not read the wavelength).
#[derive(Clone, Copy, Debug)]
pub struct Reflectance {
    material: Material,
    wi: Vec3,
    wo: Vec3,
    /// The value for every wavelength, once `formed` (non-spectral materials).
    shared: f32,
    formed: bool,
}

impl Reflectance {
    /// The reflectance of `material` for unit directions `wi`, `wo`.
    #[inline]
    pub fn new(material: &Material, wi: Vec3, wo: Vec3) -> Reflectance {
        Reflectance {
            material: *material,
            wi,
            wo,
            shared: 0.0,
            formed: false,
        }
    }

    /// The reflectance at `lambda_nm`.
    #[inline]
    pub fn at(&mut self, lambda_nm: f32) -> f32 {
        if self.material.is_spectral() {
            return self.material.reflectance(self.wi, self.wo, lambda_nm);
        }
        if !self.formed {
            self.shared = self.material.reflectance(self.wi, self.wo, lambda_nm);
            self.formed = true;
        }
        self.shared
    }
}
