//! `sample` and `pdf`: one-sample multiple importance sampling with the balance heuristic
//! (Veach & Guibas 1995) over the components of the BRDF, and over the wavelengths of the
//! call.
//!
//! Components, for the wavelength `λ_j` that drew the sample:
//! * the Gaussian base response (Werner Eq. 16) when the model has it (Werner; Velinov with
//!   its Gaussian base), weight 1 (Werner) or `1 − ρc` (Velinov Eq. 7);
//! * one lobe per scratch within the coherence window (within the footprint plus 6σ with a
//!   footprint), weight its share of the reflected energy: by Parseval,
//!   `∫|S_k|² dξ / ∫|B|² dξ = E_prof · ∫_k G² ds / (πσ²)` with
//!   `E_prof = ∫|m − p|² db` across the groove (`W|1 − e^{iκ}|²` for the rectangle,
//!   `2W(1 − sinc κ)` for the V-groove; floored at 1 % of its maximum so a groove whose
//!   estimated depth phase is a whole number of waves keeps a lobe) and `κ` at the
//!   estimate `γ ≈ 2 cosθo` (`wi` is unknown); with a footprint, `∫_k G² ds` becomes
//!   Velinov's footprint average `η_P/(2√π σ)` (Velinov Eqs. 13, 16);
//! * the GHS surface (the material, weight 1, or the blended base, weight `1 − ρc`), sampled
//!   by [`crate::sampling::ghs`] with `wo` in the role of its incident direction: that
//!   sampler draws the outgoing direction of a non-reciprocal model, so here it is a proposal
//!   whose pdf is evaluated with the same role swap.
//!
//! The component is chosen with probability weight/total, the wavelength uniformly among
//! those with a non-zero total, and the pdf is the balance-heuristic mixture
//! `(1/n) Σ_j Σ_c P_jc p_jc(wi)`, so `sample`'s pdf equals `pdf` and `value` equals
//! [`super::eval()`]. Lobes per [`Strategy`]: this crate's disk-product lobes (nothing drawn
//! below the horizon, pdf integrates to 1) or Werner §5's published ones (Gaussian base,
//! vMF ring with uniform azimuth).

use super::eval::eval;
use super::lobe1d::{Lobe1, Lobe1Kind};
use super::lobes::{
    DiskLobe, base_xi_std, gaussian_base_pdf, gaussian_base_sample, vmf_ring_pdf, vmf_ring_sample,
};
use super::{
    BsdfMaterial, BsdfSample, LOBE_BASE, LOBE_GHS, LOBE_SCRATCH, Lookup, ShadingFrame,
    ShadingPoint, Wavelengths,
};
use crate::footprint::{Ellipse, eta_p_eq16};
use crate::ghs::Ghs;
use crate::ghs::g1::G1Table;
use crate::math;
use crate::render::shading::SceneModel;
use crate::sampling::ghs::{pdf_prepared as ghs_pdf, sample_prepared as ghs_sample};
use crate::scratch::response::CUTOFF_SIGMAS;
use crate::scratch::{
    MAX_SPECTRAL, NearCursor, Profile, Scratch, ScratchSet, SegmentFrame, scratch_area_density,
};
use crate::units::{depth_half_turns_per_um, direction, um_from_nm};
use glam::{Vec2, Vec3};

gpu_enum! {
    /// Which lobes [`sample_with`] and [`pdf_with`] use.
    pub enum Strategy {
        /// Disk-product lobes: Gaussian base, logistic × Cauchy (mixture) per scratch,
        /// truncated to the hemisphere (this crate; the default).
        DiskProduct = 0,
        /// Werner 2017 §5 as published: Gaussian base (Eq. 21) and the vMF ring of d'Eon
        /// et al. per scratch, uniform azimuth.
        Werner2017 = 1,
    }
    fallback = DiskProduct;
}

/// √3/π: the logistic scale with the standard deviation of a unit Gaussian.
const LOGISTIC_PER_STD: f32 = 0.551_328_9;
/// Floor of a groove's energy factor, relative to its maximum (see the module docs).
const PROFILE_ENERGY_FLOOR: f32 = 0.01;

/// The wavelength-independent part of a call: weights of the base and GHS components.
#[derive(Clone, Copy, Debug)]
struct Fixed {
    base: f32,
    ghs: f32,
    footprint: Option<Ellipse>,
    radius: f32,
    gamma: f32,
}

#[inline]
fn fixed<S: ScratchSet>(m: &BsdfMaterial, sp: &ShadingPoint, wo: Vec3, set: &S) -> Fixed {
    let sigma = m.sigma_um;
    let model = m.scene_model();
    let ghs_model = model == SceneModel::Ghs;
    let needs_rho = m.has_ghs_base() || (model == SceneModel::Velinov && m.base_gaussian == 1);
    let rho = if needs_rho && sigma > 0.0 {
        scratch_area_density(set, sp.x(), sigma, m.window(), m.crossings())
    } else {
        0.0
    };
    let keep = math::max(1.0 - rho, 0.0);
    let base = match model {
        SceneModel::Werner => 1.0,
        SceneModel::Velinov if m.base_gaussian == 1 => keep,
        _ => 0.0,
    };
    let ghs = if ghs_model {
        1.0
    } else if m.has_ghs_base() {
        keep
    } else {
        0.0
    };
    let footprint = if model == SceneModel::Velinov {
        sp.footprint()
    } else {
        None
    };
    let radius = match footprint {
        Some(e) => math::max(e.a1, e.a2) + CUTOFF_SIGMAS * sigma,
        None => CUTOFF_SIGMAS * sigma,
    };
    Fixed {
        base,
        ghs,
        footprint,
        radius,
        gamma: m.depth_term().gamma(2.0 * wo.z),
    }
}

/// `E_prof/W`-normalised energy of a groove (see the module docs), floored.
#[inline]
fn profile_energy(s: &Scratch, half_turns_per_um: f32) -> f32 {
    let k = s.depth * half_turns_per_um;
    let (e, max) = match Profile::from_u32(s.profile) {
        Profile::Rect => (math::one_minus_cis_pi(k).norm_sqr(), 4.0),
        Profile::Triangle => (2.0 * (1.0 - math::sinc_pi(k)), 2.4),
    };
    s.width * math::max(e, PROFILE_ENERGY_FLOOR * max)
}

/// `∫_k G² ds` (point) or `η_P/(2√πσ)` (footprint, with Velinov Eq. 16's closed-form
/// `η_P`: weights only steer the sampling, and the accurate quadrature would cost more than
/// the rest of the pdf), µm; floored at `10⁻⁶σ` so that every scratch within reach keeps a
/// lobe.
#[inline]
fn window_energy(
    s: &Scratch,
    frame: &SegmentFrame,
    x0: Vec2,
    fp: &Option<Ellipse>,
    sigma: f32,
) -> f32 {
    let e = match fp {
        Some(e) => eta_p_eq16(s, e, sigma) / (2.0 * math::SQRT_PI * sigma),
        None => {
            let (s_t, s_b) = frame.offset_from(x0);
            let along = math::gauss_interval_centered(
                s_t,
                frame.half_len,
                sigma * core::f32::consts::FRAC_1_SQRT_2,
            );
            math::exp(-s_b * s_b / (sigma * sigma)) * along
        }
    };
    if e.is_finite() {
        math::max(e, WINDOW_ENERGY_FLOOR * sigma)
    } else {
        WINDOW_ENERGY_FLOOR * sigma
    }
}

/// Floor of [`window_energy`] in units of σ.
const WINDOW_ENERGY_FLOOR: f32 = 1.0e-6;

/// A scratch's weight for each wavelength (relative to the base response's 1).
#[inline]
fn scratch_weights(
    m: &BsdfMaterial,
    fx: &Fixed,
    sp: &ShadingPoint,
    s: &Scratch,
    frame: &SegmentFrame,
    wl: &Wavelengths,
) -> [f32; MAX_SPECTRAL] {
    let sigma = m.sigma_um;
    let win = window_energy(s, frame, sp.x(), &fx.footprint, sigma) / (math::PI * sigma * sigma);
    let mut w = [0.0; MAX_SPECTRAL];
    let n = wl.len();
    let mut j = 0;
    while j < MAX_SPECTRAL && j < n {
        let v = win * profile_energy(s, depth_half_turns_per_um(fx.gamma, wl.nm[j]));
        w[j] = if v.is_finite() && v > 0.0 { v } else { 0.0 };
        j += 1;
    }
    w
}

/// Along-scratch standard deviation of `ξ₁` (1/µm): the window's `1/(√8πσ)` or, for a
/// segment shorter than the window, that of `sinc²(πLξ₁)` matched in area.
#[inline]
fn along_xi_std(sigma: f32, half_len: f32) -> f32 {
    let short = 1.0 / (2.0 * half_len * math::sqrt(math::TAU));
    math::max(base_xi_std(sigma), short)
}

/// The disk-product lobe of the base response at `λ` (µm): the Gaussian of Werner Eq. 21
/// in each axis, truncated to the hemisphere.
#[inline]
fn base_disk_lobe(sigma: f32, lambda: f32) -> DiskLobe {
    let s = lambda * base_xi_std(sigma);
    let l = Lobe1::single(Lobe1Kind::Gaussian, 0.0, s);
    DiskLobe {
        e1: Vec2::X,
        l1: l,
        l2: l,
    }
}

/// The disk-product lobe of one scratch at `λ` (µm): logistic along the tangent, Cauchy
/// across it (for the V-groove, a mixture adding the two facets' mirror directions at
/// `d₂ = ±2γD/W`).
#[inline]
fn scratch_disk_lobe(
    sigma: f32,
    lambda: f32,
    gamma: f32,
    s: &Scratch,
    frame: &SegmentFrame,
) -> DiskLobe {
    let along = lambda * along_xi_std(sigma, frame.half_len) * LOGISTIC_PER_STD;
    let w = math::max(s.width, 1.0e-6);
    let scale = lambda / (math::PI * w);
    let across = if Profile::from_u32(s.profile) == Profile::Triangle {
        let c = 2.0 * gamma * s.depth / w;
        Lobe1 {
            kind: Lobe1Kind::Cauchy,
            count: 3,
            mu: [0.0, c, -c],
            scale: [scale, 2.0 * scale, 2.0 * scale],
            weight: [0.5, 0.25, 0.25],
        }
    } else {
        Lobe1::single(Lobe1Kind::Cauchy, 0.0, scale)
    };
    DiskLobe {
        e1: frame.tangent,
        l1: Lobe1::single(Lobe1Kind::Logistic, 0.0, along),
        l2: across,
    }
}

/// Werner §5's vMF concentration for one scratch: `1/s²` with `s` the along-scratch
/// standard deviation in direction cosines (the paper leaves κ unspecified).
#[inline]
fn ring_kappa(sigma: f32, lambda: f32, frame: &SegmentFrame) -> f32 {
    let s = lambda * along_xi_std(sigma, frame.half_len);
    1.0 / (s * s)
}

/// The GHS component's sampler input: the material prepared at `λ_nm`.
#[inline]
fn ghs_at<'t>(m: &BsdfMaterial, g1: G1Table<'t>, lambda_nm: f32) -> Ghs<'t> {
    Ghs::at_nm(&m.ghs, lambda_nm, g1)
}

/// Scratch lobe density at `wi` for one strategy.
#[inline]
fn scratch_pdf(
    strategy: Strategy,
    sigma: f32,
    lambda: f32,
    gamma: f32,
    s: &Scratch,
    frame: &SegmentFrame,
    wo: Vec3,
    wi: Vec3,
) -> f32 {
    match strategy {
        Strategy::DiskProduct => scratch_disk_lobe(sigma, lambda, gamma, s, frame).pdf(wo, wi),
        Strategy::Werner2017 => {
            vmf_ring_pdf(frame.tangent, ring_kappa(sigma, lambda, frame), wo, wi)
        }
    }
}

/// Base lobe density at `wi` for one strategy.
#[inline]
fn base_pdf(strategy: Strategy, sigma: f32, lambda: f32, wo: Vec3, wi: Vec3) -> f32 {
    match strategy {
        Strategy::DiskProduct => base_disk_lobe(sigma, lambda).pdf(wo, wi),
        Strategy::Werner2017 => gaussian_base_pdf(lambda * base_xi_std(sigma), wo, wi),
    }
}

/// [`pdf_with`] with [`Strategy::DiskProduct`].
pub fn pdf<S: ScratchSet>(
    m: &BsdfMaterial,
    sp: &ShadingPoint,
    wo: Vec3,
    wi: Vec3,
    wl: &Wavelengths,
    lk: &Lookup<'_, S>,
) -> f32 {
    pdf_with(Strategy::DiskProduct, m, sp, wo, wi, wl, lk)
}

/// Solid-angle pdf with which [`sample_with`] draws local `wi` given local `wo`.
pub fn pdf_with<S: ScratchSet>(
    strategy: Strategy,
    m: &BsdfMaterial,
    sp: &ShadingPoint,
    wo: Vec3,
    wi: Vec3,
    wl: &Wavelengths,
    lk: &Lookup<'_, S>,
) -> f32 {
    let set = &lk.scratches;
    let wo = direction(wo.to_array());
    let wi = direction(wi.to_array());
    if !(wo.z > 0.0 && wi.z > 0.0) {
        return 0.0;
    }
    let sigma = m.sigma_um;
    if m.scene_model() != SceneModel::Ghs && !(sigma > 0.0) {
        return 0.0;
    }
    let fx = fixed(m, sp, wo, set);
    let n = wl.len();
    let mut total = [0.0; MAX_SPECTRAL];
    let mut num = [0.0; MAX_SPECTRAL];
    let mut j = 0;
    while j < MAX_SPECTRAL && j < n {
        total[j] = fx.base + fx.ghs;
        if fx.base > 0.0 {
            num[j] += fx.base * base_pdf(strategy, sigma, um_from_nm(wl.nm[j]), wo, wi);
        }
        if fx.ghs > 0.0 {
            num[j] += fx.ghs * ghs_pdf(&ghs_at(m, lk.g1, wl.nm[j]), wo, wi);
        }
        j += 1;
    }
    if m.scene_model() != SceneModel::Ghs {
        let mut cursor = NearCursor::default();
        while let Some(s) = set.next_near(&mut cursor, sp.x(), fx.radius) {
            let Some(frame) = s.frame() else { continue };
            let w = scratch_weights(m, &fx, sp, &s, &frame, wl);
            let mut j = 0;
            while j < MAX_SPECTRAL && j < n {
                if w[j] > 0.0 {
                    total[j] += w[j];
                    let lambda = um_from_nm(wl.nm[j]);
                    num[j] +=
                        w[j] * scratch_pdf(strategy, sigma, lambda, fx.gamma, &s, &frame, wo, wi);
                }
                j += 1;
            }
        }
    }
    let mut p = 0.0;
    let mut used = 0.0;
    let mut j = 0;
    while j < MAX_SPECTRAL && j < n {
        if total[j] > 0.0 && total[j].is_finite() {
            p += num[j] / total[j];
            used += 1.0;
        }
        j += 1;
    }
    if used > 0.0 && p.is_finite() {
        p / used
    } else {
        0.0
    }
}

/// [`pdf`] for world directions in `frame`.
pub fn pdf_world<S: ScratchSet>(
    m: &BsdfMaterial,
    frame: &ShadingFrame,
    sp: &ShadingPoint,
    wo: Vec3,
    wi: Vec3,
    wl: &Wavelengths,
    lk: &Lookup<'_, S>,
) -> f32 {
    pdf(m, sp, frame.to_local(wo), frame.to_local(wi), wl, lk)
}

/// [`sample_with`] with [`Strategy::DiskProduct`].
pub fn sample<S: ScratchSet>(
    m: &BsdfMaterial,
    sp: &ShadingPoint,
    wo: Vec3,
    wl: &Wavelengths,
    u_select: f32,
    u: Vec2,
    lk: &Lookup<'_, S>,
) -> Option<BsdfSample> {
    sample_with(Strategy::DiskProduct, m, sp, wo, wl, u_select, u, lk)
}

/// Draws local `wi` given local `wo` (towards the viewer): `u_select` picks the wavelength
/// and the component (rescaled after each choice; Werner's ring also takes its azimuth from
/// what is left), `u` drives the component's warp. Returns the direction, `f` and
/// `f·cosθi/pdf` per wavelength, the mixture pdf and the lobe. `None` when nothing can be
/// drawn (no component, or a draw that lands below the horizon: Werner §5's evanescent
/// samples, or the GHS sampler's).
pub fn sample_with<S: ScratchSet>(
    strategy: Strategy,
    m: &BsdfMaterial,
    sp: &ShadingPoint,
    wo: Vec3,
    wl: &Wavelengths,
    u_select: f32,
    u: Vec2,
    lk: &Lookup<'_, S>,
) -> Option<BsdfSample> {
    let (wi, lobe, wavelength) = sample_direction_with(strategy, m, sp, wo, wl, u_select, u, lk)?;
    let wo = direction(wo.to_array());
    let pdf = pdf_with(strategy, m, sp, wo, wi, wl, lk);
    if !(pdf > 0.0) || !pdf.is_finite() {
        return None;
    }
    let value = eval(m, sp, wi, wo, wl, lk);
    Some(BsdfSample {
        wi,
        weight: value.scaled(wi.z / pdf),
        value,
        pdf,
        lobe,
        wavelength,
    })
}

/// The direction part of [`sample_with`]: `(wi, lobe, wavelength index)` without the pdf
/// and the BRDF value (for callers that evaluate them later, and for the χ² tests).
pub fn sample_direction_with<S: ScratchSet>(
    strategy: Strategy,
    m: &BsdfMaterial,
    sp: &ShadingPoint,
    wo: Vec3,
    wl: &Wavelengths,
    u_select: f32,
    u: Vec2,
    lk: &Lookup<'_, S>,
) -> Option<(Vec3, u32, u32)> {
    let set = &lk.scratches;
    let wo = direction(wo.to_array());
    if !(wo.z > 0.0) {
        return None;
    }
    let sigma = m.sigma_um;
    let scratch_model = m.scene_model() != SceneModel::Ghs;
    if scratch_model && !(sigma > 0.0) {
        return None;
    }
    let fx = fixed(m, sp, wo, set);
    let n = wl.len();
    let scratches = scratch_model;
    // Totals per wavelength (one walk).
    let mut total = [fx.base + fx.ghs; MAX_SPECTRAL];
    if scratches {
        let mut cursor = NearCursor::default();
        while let Some(s) = set.next_near(&mut cursor, sp.x(), fx.radius) {
            let Some(frame) = s.frame() else { continue };
            let w = scratch_weights(m, &fx, sp, &s, &frame, wl);
            let mut j = 0;
            while j < MAX_SPECTRAL && j < n {
                total[j] += w[j];
                j += 1;
            }
        }
    }
    // The wavelength: uniform among those with a positive total.
    let mut used = 0;
    let mut j = 0;
    while j < MAX_SPECTRAL && j < n {
        if total[j] > 0.0 && total[j].is_finite() {
            used += 1;
        }
        j += 1;
    }
    if used == 0 {
        return None;
    }
    let scaled = math::clamp(u_select, 0.0, 1.0) * used as f32;
    let pick = math::min(math::floor(scaled), (used - 1) as f32);
    let u_rest = math::clamp(scaled - pick, 0.0, 1.0);
    let mut lam_index = 0;
    let mut seen = 0;
    let mut j = 0;
    while j < MAX_SPECTRAL && j < n {
        if total[j] > 0.0 && total[j].is_finite() {
            if seen as f32 == pick {
                lam_index = j;
            }
            seen += 1;
        }
        j += 1;
    }
    let lam_index = if lam_index < MAX_SPECTRAL {
        lam_index
    } else {
        0
    };
    let lambda_nm = wl.nm[lam_index];
    let lambda = um_from_nm(lambda_nm);
    let t = total[lam_index];
    // The component.
    let target = u_rest * t;
    let (wi, lobe) = if target < fx.base {
        let wi = match strategy {
            Strategy::DiskProduct => base_disk_lobe(sigma, lambda).sample(wo, u)?,
            Strategy::Werner2017 => gaussian_base_sample(lambda * base_xi_std(sigma), wo, u)?,
        };
        (wi, LOBE_BASE)
    } else if target < fx.base + fx.ghs || !scratches {
        let u_lobe = math::clamp((target - fx.base) / fx.ghs, 0.0, 1.0);
        let g = ghs_at(m, lk.g1, lambda_nm);
        (ghs_sample(&g, wo, u_lobe, u)?.wo, LOBE_GHS)
    } else {
        let mut acc = fx.base + fx.ghs;
        let mut chosen: Option<(Scratch, SegmentFrame, f32, f32)> = None;
        let mut cursor = NearCursor::default();
        while let Some(s) = set.next_near(&mut cursor, sp.x(), fx.radius) {
            let Some(frame) = s.frame() else { continue };
            let w = scratch_weights(m, &fx, sp, &s, &frame, wl)[lam_index];
            if w > 0.0 {
                chosen = Some((s, frame, acc, w));
                if target < acc + w {
                    break;
                }
            }
            acc += w;
        }
        let (s, frame, below, w) = chosen?;
        let u_ring = math::clamp((target - below) / w, 0.0, 1.0);
        let wi = match strategy {
            Strategy::DiskProduct => {
                scratch_disk_lobe(sigma, lambda, fx.gamma, &s, &frame).sample(wo, u)?
            }
            Strategy::Werner2017 => vmf_ring_sample(
                frame.tangent,
                ring_kappa(sigma, lambda, &frame),
                wo,
                u_ring,
                u,
            )?,
        };
        (wi, LOBE_SCRATCH)
    };
    Some((wi, lobe, lam_index as u32))
}

/// [`sample`] for a world `wo` in `frame`; the returned `wi` is in world space.
pub fn sample_world<S: ScratchSet>(
    m: &BsdfMaterial,
    frame: &ShadingFrame,
    sp: &ShadingPoint,
    wo: Vec3,
    wl: &Wavelengths,
    u_select: f32,
    u: Vec2,
    lk: &Lookup<'_, S>,
) -> Option<BsdfSample> {
    let mut s = sample(m, sp, frame.to_local(wo), wl, u_select, u, lk)?;
    s.wi = frame.to_world(s.wi);
    Some(s)
}
