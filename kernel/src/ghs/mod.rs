//! GHS two-scale BRDF (Holzschuch & Pacanowski 2016, RR-8964, §3–4): a Cook–Torrance lobe
//! with a generalized Beckmann NDF plus a Generalized Harvey–Shack diffraction lobe with a
//! K-correlation angle-spread function, optionally over a diffuse layer.
//!
//! | parameter | field | meaning |
//! |---|---|---|
//! | σs | `sigma_s_um` | RMS height of the diffraction-scale roughness (µm); splits energy between the lobes (Eq. 37) |
//! | β | `beta` | width of the NDF (slope scale; `p = 1` is Beckmann with α = β) |
//! | p | `p` | kurtosis of the NDF, supported range [0.1, 4] (clamped) |
//! | b | `b_um` | correlation length of the K-correlation PSD (µm); larger = narrower diffraction lobe |
//! | c | `c` | PSD falloff exponent, `c > 1` (clamped to ≥ 1 + 1e-4) |
//! | η | `n`, `k` | complex IOR of the surface at the evaluated wavelength |
//! | colour | `diff_color` | diffraction-lobe colour: 0 `Q/2` (default), 1 `Q`, 2 `F(θd)`, 3 none (1) |
//! | layer | `layer`, `layer_form`, `layer_albedo` | 0 none, 1 plastic (`ρd`), 2 subsurface (`α`); form 0 published, 1 energy-conserving |
//!
//! `ρ = ρ_refl + ρ_diff (+ ρ_layer)` (Eq. 34) with
//! `ρ_refl = exp(−(4π σs cosθd/λ)²) F(θd) D(θh) G / (4 cosθi cosθo)` (Eq. 35, corrected) and
//! `ρ_diff = (1 − A) S′(f) G · colour` (Eq. 36 with the colour factor the text describes).
//! Returned without the cosine, in 1/sr; λ in µm. Errata are documented in the sub-modules
//! ([`energy`], [`g1`], [`ndf`], [`spread`], [`layers`]).
//!
//! Not reciprocal as published: `σ_rel²` depends on θi only (Eq. 25).

pub mod color;
pub mod energy;
pub mod g1;
pub mod layers;
pub mod ndf;
pub mod presets;
pub mod spread;
pub mod tables;

use crate::conductor::{self, Conductor};
use crate::fresnel::fresnel;
use crate::lane::{Real, V3, branch};
use crate::math;
use crate::units::um_from_nm;
use bytemuck::{Pod, Zeroable};
use g1::G1Table;
use glam::Vec3;
use layers::LayerForm;
use ndf::GenBeckmann;
use spread::KCorrelation;

gpu_enum! {
    /// Diffraction-lobe colour (`diff_color`).
    pub enum DiffColor {
        /// `Q/2` (equals `F` in the specular direction). Default.
        HalfQ = 0,
        /// `Q` as printed in Eq. 27.
        Q = 1,
        /// `F(θd)`, as Löw et al. 2012 substitute.
        Fresnel = 2,
        /// No colour factor (Eq. 36 as printed).
        None = 3,
    }
    fallback = HalfQ;
}

gpu_enum! {
    /// Layer under the rough interface (`layer`).
    pub enum Layer {
        /// Single interface (conductors, or a dielectric without a diffuse body).
        None = 0,
        /// Diffuse base of reflectance `ρd` under a varnish (Eq. 49).
        Plastic = 1,
        /// Participating medium of single-scattering albedo `α` (Eqs. 45–48).
        Subsurface = 2,
    }
    fallback = None;
}

/// GPU-visible GHS material at one wavelength (`#[repr(C)]`, `Pod`, 48 bytes).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct GhsParams {
    /// σs (µm).
    pub sigma_s_um: f32,
    /// β.
    pub beta: f32,
    /// p.
    pub p: f32,
    /// b (µm).
    pub b_um: f32,
    /// c.
    pub c: f32,
    /// Real part of the IOR.
    pub n: f32,
    /// Imaginary part of the IOR (≥ 0).
    pub k: f32,
    /// A [`DiffColor`] as `u32`.
    pub diff_color: u32,
    /// A [`Layer`] as `u32`.
    pub layer: u32,
    /// A [`LayerForm`] as `u32`.
    pub layer_form: u32,
    /// `ρd` (plastic) or `α` (subsurface), in [0, 1].
    pub layer_albedo: f32,
    /// A [`Conductor`] as `u32`: when not `None`, its spectral IOR replaces `n`, `k`.
    pub conductor: u32,
}

const _: () = assert!(core::mem::size_of::<GhsParams>() == 48);

/// Clamp ranges applied by [`Ghs::new`] (documented so callers can validate up front).
pub mod limits {
    /// Smallest `β` (a near-mirror NDF).
    pub const BETA_MIN: f32 = 1.0e-4;
    /// Largest `β`.
    pub const BETA_MAX: f32 = 1.0e3;
    /// Smallest `c − 1`.
    pub const C_MINUS_1_MIN: f32 = 1.0e-4;
    /// Largest `c`.
    pub const C_MAX: f32 = 1.0e4;
    /// Smallest `b/λ`.
    pub const B_OVER_LAMBDA_MIN: f32 = 1.0e-6;
    /// Largest `b/λ`.
    pub const B_OVER_LAMBDA_MAX: f32 = 1.0e6;
    /// Largest `σs/λ` (beyond it `A` underflows to 0 everywhere anyway).
    pub const SIGMA_OVER_LAMBDA_MAX: f32 = 1.0e3;
    /// Smallest cosine used in `1/cosθ` terms.
    pub const COS_MIN: f32 = 1.0e-6;
}

impl GhsParams {
    /// A single-interface material with the default colour `Q/2`.
    pub const fn new(
        sigma_s_um: f32,
        beta: f32,
        p: f32,
        b_um: f32,
        c: f32,
        n: f32,
        k: f32,
    ) -> Self {
        GhsParams {
            sigma_s_um,
            beta,
            p,
            b_um,
            c,
            n,
            k,
            diff_color: 0,
            layer: 0,
            layer_form: 0,
            layer_albedo: 0.0,
            conductor: Conductor::None as u32,
        }
    }

    /// The same material with a diffuse layer.
    pub const fn with_layer(mut self, layer: Layer, form: LayerForm, albedo: f32) -> Self {
        self.layer = layer as u32;
        self.layer_form = form as u32;
        self.layer_albedo = albedo;
        self
    }

    /// The same material with another diffraction colour.
    pub const fn with_diff_color(mut self, c: DiffColor) -> Self {
        self.diff_color = c as u32;
        self
    }
}

/// A GHS material prepared for one wavelength: clamped parameters, derived constants and
/// the G1 table it reads (`'t`: the table's borrow; `'static` for the builtin one). The
/// wavelength-dependent fields are [`Real`]s: one wavelength per lane in the SIMD backend,
/// `f32` (the default) everywhere else.
#[derive(Clone, Copy, Debug)]
pub struct Ghs<'t, R = f32> {
    /// The Smith G1 table.
    pub g1_table: G1Table<'t>,
    /// σs/λ.
    pub sigma_over_lambda: R,
    /// The NDF.
    pub ndf: GenBeckmann,
    /// `ln p` (G1 table row).
    pub ln_p: f32,
    /// `β · m(p)`: `v = tanθ · beta_m` is the G1 table's abscissa.
    pub beta_m: f32,
    /// The diffraction lobe.
    pub spread: KCorrelation<R>,
    /// IOR real part (per lane: a spectral IOR differs between wavelengths).
    pub n: R,
    /// IOR imaginary part.
    pub k: R,
    /// Diffraction colour.
    pub diff_color: DiffColor,
    /// Layer type.
    pub layer: Layer,
    /// Layer form.
    pub layer_form: LayerForm,
    /// `ρd` or `α`.
    pub layer_albedo: f32,
}

/// `x` if finite and within `[lo, hi]`, else the nearest bound (NaN → `lo`).
#[inline(always)]
fn sane<R: Real>(x: R, lo: f32, hi: f32) -> R {
    math::clamp(x, R::splat(lo), R::splat(hi))
}

impl Ghs<'static> {
    /// [`Ghs::with_g1_table`] with the builtin table ([`G1Table::BUILTIN`]).
    pub fn new(params: &GhsParams, lambda_um: f32) -> Ghs<'static> {
        Ghs::with_g1_table(params, lambda_um, G1Table::BUILTIN)
    }
}

impl<'t, R: Real> Ghs<'t, R> {
    /// Clamps `params` into the supported ranges ([`limits`], [`g1::P_MIN`]…) and
    /// precomputes the wavelength-dependent constants. `lambda_um` is clamped to ≥ 1e-3 µm;
    /// a spectral IOR is read at `1000·lambda_um` nm ([`Ghs::at_nm`] reads it at the
    /// caller's nm).
    #[inline(always)]
    pub fn with_g1_table(params: &GhsParams, lambda_um: R, g1_table: G1Table<'t>) -> Self {
        let lambda = sane(lambda_um, 1.0e-3, 1.0e3);
        Ghs::prepare(params, lambda, lambda * R::splat(1.0e3), g1_table)
    }

    /// [`Ghs::with_g1_table`] at `lambda_nm` (nm, the unit of the material and table
    /// interfaces): the formulas get `λ = lambda_nm/1000` µm, a spectral IOR is read at
    /// `lambda_nm` itself (no round trip through µm). Clamped to 1 nm – 1 mm.
    #[inline(always)]
    pub fn at_nm(params: &GhsParams, lambda_nm: R, g1_table: G1Table<'t>) -> Self {
        let nm = sane(lambda_nm, 1.0, 1.0e6);
        Ghs::prepare(params, um_from_nm(nm), nm, g1_table)
    }

    /// The constructors' common part: `lambda` (µm) and `lambda_nm` already clamped.
    #[inline(always)]
    fn prepare(params: &GhsParams, lambda: R, lambda_nm: R, g1_table: G1Table<'t>) -> Self {
        let (n, k) = conductor::ior(
            Conductor::from_u32(params.conductor),
            lambda_nm,
            params.n,
            params.k,
        );
        let p = sane(params.p, g1::P_MIN, g1::P_MAX);
        let beta = sane(params.beta, limits::BETA_MIN, limits::BETA_MAX);
        let ndf = GenBeckmann::new(beta, p);
        let c = sane(params.c, 1.0 + limits::C_MINUS_1_MIN, limits::C_MAX);
        let b = sane(
            R::splat(params.b_um) / lambda,
            limits::B_OVER_LAMBDA_MIN,
            limits::B_OVER_LAMBDA_MAX,
        );
        Ghs {
            g1_table,
            sigma_over_lambda: sane(
                R::splat(params.sigma_s_um) / lambda,
                0.0,
                limits::SIGMA_OVER_LAMBDA_MAX,
            ),
            ndf,
            ln_p: math::ln(p),
            beta_m: beta * g1::mean_slope(p),
            spread: KCorrelation { b, c },
            n: sane(n, 1.0e-3, 1.0e3),
            k: sane(k, 0.0, 1.0e3),
            diff_color: DiffColor::from_u32(params.diff_color),
            layer: Layer::from_u32(params.layer),
            layer_form: LayerForm::from_u32(params.layer_form),
            layer_albedo: sane(params.layer_albedo, 0.0, 1.0),
        }
    }

    /// [`Ghs::g1`] in lanes.
    #[inline(always)]
    pub fn g1_lanes(&self, cos_t: R) -> R {
        let c = math::max(cos_t, R::splat(limits::COS_MIN));
        let tan = math::sqrt0(R::splat(1.0) - c * c) / c;
        g1::g1_from_v_lanes(&self.g1_table, tan * R::splat(self.beta_m), self.ln_p)
    }

    /// [`Ghs::sigma_rel_sq`] in lanes.
    #[inline(always)]
    pub fn sigma_rel_sq_lanes(&self, wi: V3<R>) -> R {
        self.spread
            .sigma_rel_sq(math::sqrt0(R::splat(1.0) - wi.z * wi.z))
    }

    /// [`Ghs::reflection`] in lanes.
    #[inline(always)]
    pub fn reflection_lanes(&self, wi: V3<R>, wo: V3<R>) -> R {
        let (h, cos_d, ok) = half_vector_lanes(wi, wo);
        branch!(
            ok,
            {
                let ci = math::max(wi.z, R::splat(limits::COS_MIN));
                let co = math::max(wo.z, R::splat(limits::COS_MIN));
                let g = self.g1_lanes(ci) * self.g1_lanes(co);
                energy::reflection_attenuation(self.sigma_over_lambda, cos_d)
                    * fresnel(cos_d, self.n, self.k)
                    * self.ndf.d_lanes(h)
                    * g
                    / (R::splat(4.0) * ci * co)
            },
            R::splat(0.0),
        )
    }

    /// [`Ghs::diffraction`] in lanes.
    #[inline(always)]
    pub fn diffraction_lanes(&self, wi: V3<R>, wo: V3<R>, sigma_rel_sq: R) -> R {
        let zero = R::splat(0.0);
        let one_minus_a = energy::diffracted_fraction(self.sigma_over_lambda, wi.z, wo.z);
        branch!(
            one_minus_a.gt(zero) & sigma_rel_sq.gt(zero),
            {
                // r = |i_p + o_p| (the lobe's offset from the mirror direction), with the
                // length correction of `direction_sum` where the two nearly cancel
                let d = direction_sum_lanes(wi, wo);
                let r = (d.x * d.x + d.y * d.y).sqrt();
                let s = self.spread.density(r) / sigma_rel_sq;
                let g = self.g1_lanes(wi.z) * self.g1_lanes(wo.z);
                let colour = match self.diff_color {
                    DiffColor::HalfQ => {
                        R::splat(0.5) * color::diffraction_color_lanes(wi, wo, self.n, self.k)
                    }
                    DiffColor::Q => color::diffraction_color_lanes(wi, wo, self.n, self.k),
                    DiffColor::Fresnel => {
                        let (_, cos_d, ok) = half_vector_lanes(wi, wo);
                        R::select(ok, fresnel(cos_d, self.n, self.k), zero)
                    }
                    DiffColor::None => R::splat(1.0),
                };
                one_minus_a * s * g * colour
            },
            zero,
        )
    }

    /// [`Ghs::layer_lobe`] in lanes.
    #[inline(always)]
    pub fn layer_lobe_lanes(&self, wi: V3<R>, wo: V3<R>) -> R {
        match self.layer {
            Layer::None => R::splat(0.0),
            Layer::Plastic => layers::plastic(
                wi.z,
                wo.z,
                self.n,
                self.k,
                self.layer_albedo,
                self.layer_form,
            ),
            Layer::Subsurface => layers::subsurface(
                wi.z,
                wo.z,
                self.n,
                self.k,
                self.layer_albedo,
                self.layer_form,
            ),
        }
    }

    /// [`Ghs::eval_with_sigma_rel`] in lanes.
    #[inline(always)]
    pub fn eval_with_sigma_rel_lanes(&self, wi: V3<R>, wo: V3<R>, sigma_rel_sq: R) -> R {
        let zero = R::splat(0.0);
        branch!(
            wi.z.gt(zero) & wo.z.gt(zero),
            {
                let v = self.reflection_lanes(wi, wo)
                    + self.diffraction_lanes(wi, wo, sigma_rel_sq)
                    + self.layer_lobe_lanes(wi, wo);
                R::select(v.is_finite(), v, zero)
            },
            zero,
        )
    }

    /// [`Ghs::eval`] in lanes.
    #[inline(always)]
    pub fn eval_lanes(&self, wi: V3<R>, wo: V3<R>) -> R {
        self.eval_with_sigma_rel_lanes(wi, wo, self.sigma_rel_sq_lanes(wi))
    }
}

impl<'t> Ghs<'t> {
    /// Smith `G1` for a direction with `cosθ = cos_t` (> 0).
    #[inline]
    pub fn g1(&self, cos_t: f32) -> f32 {
        self.g1_lanes(cos_t)
    }

    /// `σ_rel²` for the incident direction `wi`.
    #[inline]
    pub fn sigma_rel_sq(&self, wi: Vec3) -> f32 {
        self.sigma_rel_sq_lanes(wi.into())
    }

    /// The micro-facet (reflection) lobe, Eq. 35 (corrected).
    pub fn reflection(&self, wi: Vec3, wo: Vec3) -> f32 {
        self.reflection_lanes(wi.into(), wo.into())
    }

    /// The diffraction lobe, Eq. 36 with colour; `sigma_rel_sq` from [`Self::sigma_rel_sq`].
    pub fn diffraction(&self, wi: Vec3, wo: Vec3, sigma_rel_sq: f32) -> f32 {
        self.diffraction_lanes(wi.into(), wo.into(), sigma_rel_sq)
    }

    /// The diffuse layer's lobe (Eq. 49 or Eqs. 45–48), 0 without a layer.
    pub fn layer_lobe(&self, wi: Vec3, wo: Vec3) -> f32 {
        self.layer_lobe_lanes(wi.into(), wo.into())
    }

    /// Full BRDF with a precomputed `σ_rel²(θi)` (hoist it when `wi` is fixed).
    #[inline]
    pub fn eval_with_sigma_rel(&self, wi: Vec3, wo: Vec3, sigma_rel_sq: f32) -> f32 {
        self.eval_with_sigma_rel_lanes(wi.into(), wo.into(), sigma_rel_sq)
    }

    /// Full BRDF ρ(wi, wo) in 1/sr, without the cosine.
    #[inline]
    pub fn eval(&self, wi: Vec3, wo: Vec3) -> f32 {
        self.eval_lanes(wi.into(), wo.into())
    }
}

/// `wi/|wi| + wo/|wo|` up to a positive factor (1 within 1e-7), for directions that are unit
/// up to f32 rounding: the unnormalised half vector (H&P Eq. 38's `h`).
///
/// `wi + wo` alone counts the rounding of each vector's length (`|w| − 1` up to ~1e-7 for
/// an f32 unit vector) as part of the direction. Near the mirror configuration at grazing
/// angles `(wi + wo)_xy` is a small difference of large components, and length errors of
/// ±2e-8 in `wi`, `wo` put ρ off by 8.5e-3 (β = 0.0029, p = 2.44, θi = 88.8°) before this
/// correction (`docs/ghs.md`). With `ρ = |wi|/|wo|`, `wi/|wi| + wo/|wo| ∝ wi + ρ wo`, and
/// `ρ − 1 = (|wi|² − |wo|²)/2 + O(1e-14)` is formed as `(wi − wo)·(wi + wo)`, whose terms are
/// small exactly where the sum cancels.
#[inline]
pub fn direction_sum(wi: Vec3, wo: Vec3) -> Vec3 {
    direction_sum_lanes(wi.into(), wo.into()).into()
}

/// [`direction_sum`] for any [`Real`] (the one formula).
#[inline(always)]
pub fn direction_sum_lanes<R: Real>(wi: V3<R>, wo: V3<R>) -> V3<R> {
    let s = wi + wo;
    let rho_m1 = R::splat(0.5) * (wi - wo).dot(s);
    s + wo * rho_m1
}

/// Normalised half vector (of [`direction_sum`]) and `cosθd = wi·h`; `None` when `wi + wo`
/// vanishes.
#[inline]
pub fn half_vector(wi: Vec3, wo: Vec3) -> Option<(Vec3, f32)> {
    let (h, cos_d, ok) = half_vector_lanes(wi.into(), wo.into());
    if ok { Some((h.into(), cos_d)) } else { None }
}

/// [`half_vector`] for any [`Real`]: `(h, cosθd, defined)`, where `h` and `cosθd` are
/// meaningless in the lanes that are not `defined`.
#[inline(always)]
pub fn half_vector_lanes<R: Real>(wi: V3<R>, wo: V3<R>) -> (V3<R>, R, R::Mask) {
    let s = direction_sum_lanes(wi, wo);
    let l2 = s.dot(s);
    let h = s * (R::splat(1.0) / l2.sqrt());
    (
        h,
        math::clamp(wi.dot(h), R::splat(0.0), R::splat(1.0)),
        l2.gt(R::splat(1.0e-30)),
    )
}

/// The GHS BRDF ρ(wi, wo) in 1/sr without the cosine, at wavelength `lambda_um` (µm).
/// Directions in the local frame (z = normal), pointing away from the surface; 0 below the
/// horizon. Never NaN/Inf (non-finite intermediate results are masked to 0).
pub fn evaluate(params: &GhsParams, wi: Vec3, wo: Vec3, lambda_um: f32) -> f32 {
    evaluate_with_g1_table(params, G1Table::BUILTIN, wi, wo, lambda_um)
}

/// [`evaluate`] reading G1 from `g1_table` (a GPU entry point passes its storage buffer).
pub fn evaluate_with_g1_table(
    params: &GhsParams,
    g1_table: G1Table,
    wi: Vec3,
    wo: Vec3,
    lambda_um: f32,
) -> f32 {
    Ghs::with_g1_table(params, lambda_um, g1_table).eval(wi, wo)
}

/// The GHS BRDF (1/sr, no cosine) at `lambda_nm` (nm) for unit local directions: the
/// material interface's and the GHS table's one entry point ([`Ghs::at_nm`]). 0 below the
/// horizon, for `lambda_nm ≤ 0`, and wherever the value is not finite and positive.
#[inline(always)]
pub fn brdf_lanes<R: Real>(
    params: &GhsParams,
    g1_table: G1Table,
    wi: V3<R>,
    wo: V3<R>,
    lambda_nm: R,
) -> R {
    let zero = R::splat(0.0);
    branch!(
        wi.z.gt(zero) & wo.z.gt(zero) & lambda_nm.gt(zero),
        {
            let r = Ghs::at_nm(params, lambda_nm, g1_table).eval_lanes(wi, wo);
            R::select(r.is_finite() & r.gt(zero), r, zero)
        },
        zero,
    )
}

/// [`brdf_lanes`] for one query.
#[inline]
pub fn brdf(params: &GhsParams, g1_table: G1Table, wi: Vec3, wo: Vec3, lambda_nm: f32) -> f32 {
    brdf_lanes(params, g1_table, wi.into(), wo.into(), lambda_nm)
}

/// [`evaluate_with_g1_table`] for one query per lane (the SIMD backend's batch entry point):
/// the parameters and the table are shared, the directions and wavelengths are per lane.
#[inline(always)]
pub fn evaluate_lanes<R: Real>(
    params: &GhsParams,
    g1_table: G1Table,
    wi: V3<R>,
    wo: V3<R>,
    lambda_um: R,
) -> R {
    Ghs::with_g1_table(params, lambda_um, g1_table).eval_lanes(wi, wo)
}
