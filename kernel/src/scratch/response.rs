//! Base and scratch responses of the coherence window around `x0` (Werner 2017 Eqs. 15–17)
//! and the scratch area density ρc (Werner §5, Velinov Eq. 17 corrected).

use super::coherent_sum::CoherentSum;
use super::profile::{Profile, mask_minus_profile};
use super::record::{Scratch, SegmentFrame};
use super::set::{NearCursor, ScratchSet};
use super::spatial_phase::{EtaMode, eta, xi_local};
use crate::math::{self, C32};
use glam::Vec2;

/// Radius, in units of σ, beyond which a scratch's contribution is dropped: its amplitude
/// weight is at most `exp(−6²/2) = 1.5e-8`, below `f32` resolution of a nearby scratch.
pub const CUTOFF_SIGMAS: f32 = 6.0;

/// Base response `B(ξ) = 2πσ² exp(−2π²σ²|ξ|²)` (Werner Eq. 16): the Fourier transform of
/// the Gaussian coherence window.
#[inline]
pub fn base_response(xi: Vec2, sigma: f32) -> f32 {
    let s2 = sigma * sigma;
    math::TAU * s2 * math::exp(-2.0 * math::PI * math::PI * s2 * xi.length_squared())
}

/// Everything the models need from the scratches around one shading point, gathered in a
/// single pass.
#[derive(Clone, Copy, Debug)]
pub struct ScratchTerms {
    /// Coherent scratch response `S = Σ (M_k − P_k) η_k` (Werner Eq. 17), µm², summed
    /// exactly (use [`CoherentSum::subtracted_from`] for `B − S`).
    pub coherent: CoherentSum,
    /// Incoherent sum `Σ |S_k|²` (Velinov Eq. 7), µm⁴.
    pub incoherent: f32,
    /// Scratch area density ρc at `x0` (dimensionless; 1 for a fully scratched window);
    /// 0 unless [`ResponseInputs::area_density`] asked for it.
    pub area_density: f32,
}

/// Per-query inputs of the scratch response.
#[derive(Clone, Copy, Debug)]
pub struct ResponseInputs {
    /// Shading point (µm).
    pub x0: Vec2,
    /// `(wi + wo)_xy / λ` (1/µm).
    pub xi: Vec2,
    /// The depth phase in half-turns per µm of groove depth, `2γ/λ` (1/µm), with the
    /// effective `γ` of [`super::DepthTerm::gamma`] (see `units::depth_half_turns_per_um`).
    pub depth_half_turns_per_um: f32,
    /// Coherence σ (µm).
    pub sigma: f32,
    /// Finite or infinite spatial phase.
    pub eta: EtaMode,
    /// Also accumulate ρc (costs two more `erf` evaluations per scratch).
    pub area_density: bool,
}

/// Sums the scratch terms over every scratch within [`CUTOFF_SIGMAS`]·σ of `x0`.
pub fn scratch_response<S: ScratchSet>(set: &S, q: &ResponseInputs) -> ScratchTerms {
    let mut terms = ScratchTerms {
        coherent: CoherentSum::new(base_response(Vec2::ZERO, q.sigma)),
        incoherent: 0.0,
        area_density: 0.0,
    };
    let sigma = q.sigma;
    let mut cursor = NearCursor::default();
    while let Some(s) = set.next_near(&mut cursor, q.x0, CUTOFF_SIGMAS * sigma) {
        if let Some(frame) = s.frame() {
            let sk = scratch_term(
                &s,
                &frame,
                q.x0,
                q.xi,
                q.depth_half_turns_per_um,
                sigma,
                q.eta,
            );
            terms.coherent.add(sk);
            terms.incoherent += sk.norm_sqr();
            if q.area_density {
                terms.area_density += area_density_of(&frame, s.width, q.x0, sigma);
            }
        }
    }
    terms
}

/// One scratch's term `S_k = (M_k − P_k) η_k` (the summand of Werner Eq. 17), µm².
#[inline]
pub fn scratch_term(
    s: &Scratch,
    frame: &SegmentFrame,
    x0: Vec2,
    xi: Vec2,
    depth_half_turns_per_um: f32,
    sigma: f32,
    eta_mode: EtaMode,
) -> C32 {
    let (_, xi2) = xi_local(frame, xi);
    let profile = Profile::from_u32(s.profile);
    let m_p = mask_minus_profile(profile, s.width, s.depth, depth_half_turns_per_um, xi2);
    m_p * eta(eta_mode, frame, x0, xi, sigma)
}

/// Most wavelengths one [`scratch_response_spectral`] walk serves.
pub const MAX_SPECTRAL: usize = 4;

/// Per-query inputs of [`scratch_response_spectral`]: [`ResponseInputs`] for up to
/// [`MAX_SPECTRAL`] wavelengths at one shading point.
#[derive(Clone, Copy, Debug)]
pub struct SpectralInputs {
    /// Shading point (µm).
    pub x0: Vec2,
    /// `ξ` per wavelength (1/µm).
    pub xi: [Vec2; MAX_SPECTRAL],
    /// The depth phase per µm of depth per wavelength (see [`ResponseInputs`]).
    pub depth_half_turns_per_um: [f32; MAX_SPECTRAL],
    /// How many entries of `xi` and `depth_half_turns_per_um` are used (1 to 4).
    pub count: u32,
    /// Coherence σ (µm).
    pub sigma: f32,
    /// Finite or infinite spatial phase.
    pub eta: EtaMode,
    /// Also accumulate ρc (once: it does not depend on the wavelength).
    pub area_density: bool,
}

/// [`scratch_response`] for several wavelengths in one walk over the scratches near `x0`:
/// entry `j < count` equals `scratch_response` at wavelength `j` bit for bit (the same
/// terms added in the same order); entries past `count` stay empty. ρc, when asked for, is
/// accumulated once and copied into every entry.
pub fn scratch_response_spectral<S: ScratchSet>(
    set: &S,
    q: &SpectralInputs,
) -> [ScratchTerms; MAX_SPECTRAL] {
    let empty = ScratchTerms {
        coherent: CoherentSum::new(base_response(Vec2::ZERO, q.sigma)),
        incoherent: 0.0,
        area_density: 0.0,
    };
    let mut terms = [empty; MAX_SPECTRAL];
    let n = q.count as usize;
    let sigma = q.sigma;
    let mut rho = 0.0;
    let mut cursor = NearCursor::default();
    while let Some(s) = set.next_near(&mut cursor, q.x0, CUTOFF_SIGMAS * sigma) {
        if let Some(frame) = s.frame() {
            let mut j = 0;
            while j < MAX_SPECTRAL && j < n {
                let sk = scratch_term(
                    &s,
                    &frame,
                    q.x0,
                    q.xi[j],
                    q.depth_half_turns_per_um[j],
                    sigma,
                    q.eta,
                );
                // Load, update and store the whole element: rust-gpu lost updates made
                // in place through a run-time index into this array of structs (the
                // lavapipe test `backend-spirv/tests/bsdf.rs` caught it).
                let mut t = terms[j];
                t.coherent.add(sk);
                t.incoherent += sk.norm_sqr();
                terms[j] = t;
                j += 1;
            }
            if q.area_density {
                rho += area_density_of(&frame, s.width, q.x0, sigma);
            }
        }
    }
    let mut j = 0;
    while j < MAX_SPECTRAL {
        let mut t = terms[j];
        t.area_density = rho;
        terms[j] = t;
        j += 1;
    }
    terms
}

/// One segment's share of ρc: `W ∫ G ds / (2πσ²)`.
#[inline]
fn area_density_of(frame: &SegmentFrame, width: f32, x0: Vec2, sigma: f32) -> f32 {
    let (s_t, s_b) = frame.offset_from(x0);
    let along = math::gauss_interval_centered(s_t, frame.half_len, sigma);
    width * math::exp(-0.5 * s_b * s_b / (sigma * sigma)) * along / (math::TAU * sigma * sigma)
}

/// Scratch area density ρc(x0) = `(1/(2πσ²)) Σ W_k ∫_k G ds`.
///
/// Velinov Eq. 17 divides by `A_C = πσ²` instead of by `∫G dA = 2πσ²` and so reports 2 for
/// a fully scratched window; this is the corrected normalisation (1 when fully covered).
/// Werner Eq. 9's mask–scratch decomposition counts overlapping scratches twice, and so
/// does ρc: it can exceed 1 where scratches cross (a documented model limitation).
pub fn scratch_area_density<S: ScratchSet>(set: &S, x0: Vec2, sigma: f32) -> f32 {
    let mut rho = 0.0;
    let mut cursor = NearCursor::default();
    while let Some(s) = set.next_near(&mut cursor, x0, CUTOFF_SIGMAS * sigma) {
        if let Some(frame) = s.frame() {
            rho += area_density_of(&frame, s.width, x0, sigma);
        }
    }
    rho
}
