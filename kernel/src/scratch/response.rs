//! Base and scratch responses of the coherence window around `x0` (Werner 2017 Eqs. 15–17)
//! and the scratch area density ρc (Werner §5, Velinov Eq. 17 corrected).

use super::coherent_sum::CoherentSum;
use super::crossing::{
    Crossings, Share, crossing_correction_lanes, crossing_overlap_weight_lanes, may_overlap,
};
use super::profile::{Profile, mask_minus_profile_lanes};
use super::record::{Scratch, SegmentFrame};
use super::set::{NearCursor, ScratchSet};
use super::spatial_phase::{EtaMode, eta_lanes, infinite_along_lanes, xi_local_lanes};
use super::window::{Window, exact_across_intervals};
use crate::lane::{Blend, Cx, Real};
#[cfg(not(target_arch = "spirv"))]
use crate::lane::{LaneMask, Lanes};
use crate::math::{self, C32};
use glam::Vec2;

/// Radius, in units of σ, beyond which a scratch's contribution is dropped: its amplitude
/// weight is at most `exp(−6²/2) = 1.5e-8`, below `f32` resolution of a nearby scratch.
pub const CUTOFF_SIGMAS: f32 = 6.0;

/// Base response `B(ξ) = 2πσ² exp(−2π²σ²|ξ|²)` (Werner Eq. 16): the Fourier transform of
/// the Gaussian coherence window.
#[inline]
pub fn base_response(xi: Vec2, sigma: f32) -> f32 {
    base_response_lanes([xi.x, xi.y], sigma)
}

/// [`base_response`] for one `ξ` per lane.
#[inline(always)]
pub fn base_response_lanes<R: Real>(xi: [R; 2], sigma: f32) -> R {
    let s2 = R::splat(sigma * sigma);
    R::splat(math::TAU)
        * s2
        * (R::splat(-2.0 * math::PI * math::PI) * s2 * (xi[0] * xi[0] + xi[1] * xi[1])).exp()
}

/// Everything the models need from the scratches around one shading point (per lane),
/// gathered in a single pass.
#[derive(Clone, Copy, Debug)]
pub struct ScratchTerms<R = f32> {
    /// Coherent scratch response `S = Σ (M_k − P_k) η_k` (Werner Eq. 17), µm², summed
    /// exactly (use [`CoherentSum::subtracted_from`] for `B − S`).
    pub coherent: CoherentSum<R>,
    /// Incoherent sum `Σ |S_k|²` (Velinov Eq. 7), µm⁴; with [`Crossings::Deepest`] each
    /// term less what its groove loses to deeper partners ([`cut_of`]) before squaring.
    pub incoherent: R,
    /// Scratch area density ρc at `x0` (dimensionless; 1 for a fully scratched window);
    /// 0 unless [`ResponseInputs::area_density`] asked for it.
    pub area_density: R,
}

impl<R: Real> ScratchTerms<R> {
    /// No scratch yet, for a window of the given σ.
    #[inline]
    pub fn empty(sigma: f32) -> Self {
        ScratchTerms {
            coherent: CoherentSum::new(base_response(Vec2::ZERO, sigma)),
            incoherent: R::splat(0.0),
            area_density: R::splat(0.0),
        }
    }

    /// Adds scratch `s` (with its `frame`) in the lanes of `take`: its term `S_k` to the
    /// sums and, when `q` asks for it, its share of ρc. The one accumulation step of the
    /// scalar walk and of the lane batches.
    #[inline(always)]
    pub fn accumulate(
        &mut self,
        s: &Scratch,
        frame: &SegmentFrame,
        q: &ResponseInputs<R>,
        take: R::Mask,
    ) {
        let sk = term_of(s, frame, q);
        self.add(sk, s, frame, q, take);
    }

    /// [`Self::accumulate`] with the term less `cut`, what the scratch loses where other
    /// grooves cut deeper ([`Crossings::Deepest`]: [`cut_of`] summed over its partners).
    #[inline(always)]
    pub fn accumulate_less(
        &mut self,
        s: &Scratch,
        frame: &SegmentFrame,
        q: &ResponseInputs<R>,
        cut: Cx<R>,
        take: R::Mask,
    ) {
        let sk = term_of(s, frame, q) - cut;
        self.add(sk, s, frame, q, take);
    }

    /// Adds the term `sk` of scratch `s` (coherent and incoherent sums) and its ρc share.
    #[inline(always)]
    fn add(
        &mut self,
        sk: Cx<R>,
        s: &Scratch,
        frame: &SegmentFrame,
        q: &ResponseInputs<R>,
        take: R::Mask,
    ) {
        let sk = Cx::blend(take, sk, Cx::zero());
        self.coherent.add(sk);
        self.incoherent = self.incoherent + sk.norm_sqr();
        if q.area_density {
            let rho = area_density_lanes(frame, s.width, q.x0, q.sigma, q.window);
            self.area_density = self.area_density + R::select(take, rho, R::splat(0.0));
        }
    }
}

/// Scratch `s`'s term `S_k` for the queries of `q` (the one call of [`scratch_term_lanes`]
/// in the walks).
#[inline(always)]
fn term_of<R: Real>(s: &Scratch, frame: &SegmentFrame, q: &ResponseInputs<R>) -> Cx<R> {
    scratch_term_lanes(
        s,
        frame,
        q.x0,
        q.xi,
        q.depth_half_turns_per_um,
        q.sigma,
        q.eta,
        q.window,
    )
}

/// What scratch `a` loses to partner `b` where `b` cuts deeper ([`Crossings::Deepest`]):
/// the pieces of their overlap where `a` is the shallower groove, with the pair ordered as
/// the walk yields it (`a_first`: `a` before `b`; on a tie in depth the later groove is cut
/// away). Summed over a scratch's partners it is what its term loses; summed over both
/// grooves of a pair, the pair's whole correction `C_ab`.
#[inline(always)]
pub fn cut_of<R: Real>(
    a: (&Scratch, &SegmentFrame),
    b: (&Scratch, &SegmentFrame),
    a_first: bool,
    q: &ResponseInputs<R>,
    near: (Vec2, f32),
) -> Cx<R> {
    // The records by value (a choice between references is a phi of pointers, which
    // SPIR-V's logical addressing does not allow).
    let (a, b) = ((*a.0, *a.1), (*b.0, *b.1));
    let ((first, f_first), (second, f_second), share) = if a_first {
        (a, b, Share::First)
    } else {
        (b, a, Share::Second)
    };
    crossing_correction_lanes(
        first,
        f_first,
        second,
        f_second,
        q.x0,
        q.xi,
        q.depth_half_turns_per_um,
        q.sigma,
        q.window,
        near,
        share,
    )
}

/// The overlap of `a` and `b` in ρc: `∫_O G dA / (2πσ²)`.
#[inline(always)]
fn overlap_density_lanes<R: Real>(
    a: (&Scratch, &SegmentFrame),
    b: (&Scratch, &SegmentFrame),
    x0: [R; 2],
    sigma: f32,
    window: Window,
    near: (Vec2, f32),
) -> R {
    crossing_overlap_weight_lanes(*a.0, *a.1, *b.0, *b.1, x0, sigma, window, near)
        / R::splat(math::TAU * sigma * sigma)
}

/// Per-query inputs of the scratch response (one query per lane).
#[derive(Clone, Copy, Debug)]
pub struct ResponseInputs<R = f32> {
    /// Shading point (µm).
    pub x0: [R; 2],
    /// `(wi + wo)_xy / λ` (1/µm).
    pub xi: [R; 2],
    /// The depth phase in half-turns per µm of groove depth, `2γ/λ` (1/µm), with the
    /// effective `γ` of [`super::DepthTerm::gamma`] (see `units::depth_half_turns_per_um`).
    pub depth_half_turns_per_um: R,
    /// Coherence σ (µm), shared by the lanes.
    pub sigma: f32,
    /// Finite or infinite spatial phase.
    pub eta: EtaMode,
    /// The coherence window across a groove.
    pub window: Window,
    /// How overlapping grooves cut (the coherent sum and ρc).
    pub crossings: Crossings,
    /// Also accumulate ρc (costs two more `erf` evaluations per scratch).
    pub area_density: bool,
}

/// The scratch walk for `N` queries at once, one wavelength each (the SIMD backend's batch;
/// CPU only).
///
/// The gather strategy: one walk over the scratches near the circle that holds all `N`
/// shading points (each lane's disk of radius [`CUTOFF_SIGMAS`]·σ inside it), and each
/// candidate added in the lanes whose own disk reaches it, by the same distance test as the
/// scalar walk. The lookup yields the candidates in its fixed order, a lane's own
/// scratches among them in the order its scalar walk finds them, and a lane skips the
/// others by adding exact zeros: every lane's sums are those of
/// [`scratch_response_spectral`] at the lane's wavelength up to the lane arithmetic. The
/// batch is fastest when its points are close together (the caller sorts them); [`LaneUse`]
/// counts how many lanes each candidate served.
///
/// `INLINE_EXACT` puts the exact window's term inline in the walk, so that it runs in the
/// caller's instruction set (measured: the 10-scratch table with the exact window went from
/// 0.60 to 0.93 M evaluations/s in the AVX2 instance, `profile_brdf werner 10 10 simd
/// exact`). Set it only in an instance of its own that serves tables with the exact window:
/// in the instance that serves the frozen one the inlined term would only grow the code
/// around the frozen walk (which then lost 15–30 % of its speed). Either value gives the
/// same results for either window.
#[cfg(not(target_arch = "spirv"))]
#[inline(always)]
pub fn scratch_response_batch<S: ScratchSet, const N: usize, const INLINE_EXACT: bool>(
    set: &S,
    q: &ResponseInputs<Lanes<N>>,
    lane_use: &mut LaneUse,
) -> ScratchTerms<Lanes<N>> {
    // One walk per window, each with its window a constant, so that the frozen walk holds
    // no call (the exact window's terms are out of line unless `INLINE_EXACT`).
    if q.window == Window::Exact {
        let exact = ResponseInputs {
            window: Window::Exact,
            ..*q
        };
        batch_walk::<S, N, INLINE_EXACT>(set, &exact, lane_use)
    } else {
        let frozen = ResponseInputs {
            window: Window::Frozen,
            ..*q
        };
        batch_walk::<S, N, false>(set, &frozen, lane_use)
    }
}

/// [`scratch_response_batch`]'s walk.
#[cfg(not(target_arch = "spirv"))]
#[inline(always)]
fn batch_walk<S: ScratchSet, const N: usize, const INLINE_EXACT: bool>(
    set: &S,
    q: &ResponseInputs<Lanes<N>>,
    lane_use: &mut LaneUse,
) -> ScratchTerms<Lanes<N>> {
    let mut terms = ScratchTerms::empty(q.sigma);
    let radius = CUTOFF_SIGMAS * q.sigma;
    let points: [Vec2; N] = core::array::from_fn(|i| Vec2::new(q.x0[0].0[i], q.x0[1].0[i]));
    let (lo, hi) = points.iter().fold((points[0], points[0]), |(lo, hi), p| {
        (lo.min(*p), hi.max(*p))
    });
    let centre = 0.5 * (lo + hi);
    // Every lane's disk inside the union's (with a margin for the rounding of the centre).
    // `math::sqrt`, not glam's `distance` (libm's legacy-SSE `sqrtf` inside AVX2 code).
    let spread = points.iter().fold(0.0_f32, |m, p| {
        m.max(math::sqrt((*p - centre).length_squared()))
    });
    let union = radius + spread * (1.0 + 1.0e-5) + 1.0e-6 * radius;
    let near = (centre, union);
    let mut cursor = NearCursor::default();
    // `me`: the candidate's place in the walk ([`Partners`] counts the same way).
    let mut me = 0u32;
    while let Some(s) = set.next_near(&mut cursor, centre, union) {
        if let Some(frame) = s.frame() {
            let take = LaneMask(points.map(|p| {
                if s.distance_to(p) <= radius {
                    u32::MAX
                } else {
                    0
                }
            }));
            let n = take.0.iter().filter(|&&m| m != 0).count();
            lane_use.candidates += 1;
            lane_use.lanes += n as u64;
            if n > 0 {
                // `INLINE_EXACT` is instanced only for the exact window (above).
                let sk = if INLINE_EXACT {
                    exact_window_term_inline(
                        &s,
                        &frame,
                        q.x0,
                        q.xi,
                        q.depth_half_turns_per_um,
                        q.sigma,
                        q.eta,
                    )
                } else {
                    term_of(&s, &frame, q)
                };
                let (cut, overlap) = if q.crossings == Crossings::Deepest {
                    deepest_cut(set, me, (&s, &frame), take, &points, q, near)
                } else {
                    (Cx::zero(), Lanes::splat(0.0))
                };
                terms.area_density = terms.area_density - overlap;
                terms.add(sk - cut, &s, &frame, q, take);
            }
        }
        me += 1;
    }
    lane_use.batches += 1;
    terms
}

/// What one candidate of the batch loses with [`Crossings::Deepest`]: the sum of its
/// [`cut_of`] over every other candidate, in the lanes that reach both, and the overlaps'
/// second count in ρc (once per pair, at the earlier one), to subtract from its term and
/// from ρc. The partners walked again over the batch's disk `near` ([`Partners`]; `me`: the
/// candidate's number). Out of line, in the baseline instruction set as the corrections it
/// calls, so that the SIMD batches hold one call for it and their own code stays small.
#[cfg(not(target_arch = "spirv"))]
#[inline(never)]
#[allow(clippy::too_many_arguments)]
fn deepest_cut<S: ScratchSet, const N: usize>(
    set: &S,
    me: u32,
    a: (&Scratch, &SegmentFrame),
    take: LaneMask<N>,
    points: &[Vec2; N],
    q: &ResponseInputs<Lanes<N>>,
    near: (Vec2, f32),
) -> (Cx<Lanes<N>>, Lanes<N>) {
    let radius = CUTOFF_SIGMAS * q.sigma;
    let zero = Lanes::splat(0.0);
    let mut cut = Cx::zero();
    let mut overlap = zero;
    let mut partners = Partners::default();
    while let Some((s2, frame2, i)) = partners.next(set, me, a, near) {
        let both = LaneMask(core::array::from_fn(|l| {
            if take.0[l] != 0 && s2.distance_to(points[l]) <= radius {
                u32::MAX
            } else {
                0
            }
        }));
        if both.0.iter().any(|&m| m != 0) {
            let b = (&s2, &frame2);
            cut = cut + Cx::blend(both, cut_of(a, b, me < i, q, near), Cx::zero());
            if me < i && q.area_density {
                let w = overlap_density_lanes(a, b, q.x0, q.sigma, q.window, near);
                overlap = overlap + Lanes::select(both, w, zero);
            }
        }
    }
    (cut, overlap)
}

/// How well the lanes of [`scratch_response_batch`] were used: over all candidates, the
/// share of lanes that needed each one.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct LaneUse {
    /// Batches walked.
    pub batches: u64,
    /// Candidate scratches evaluated (one lane-wide evaluation each, or none when no lane
    /// reached it).
    pub candidates: u64,
    /// Σ over candidates of the lanes that took it.
    pub lanes: u64,
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
    window: Window,
) -> C32 {
    scratch_term_lanes(
        s,
        frame,
        [x0.x, x0.y],
        [xi.x, xi.y],
        depth_half_turns_per_um,
        sigma,
        eta_mode,
        window,
    )
    .into()
}

/// [`scratch_term`] for one `x0`, `ξ` and depth phase per lane (the one formula).
///
/// The frozen window inline; the exact window out of line on the CPU
/// (`exact_window_term_lanes`), so that the frozen path's code inside the SIMD batches
/// stays as it was.
#[inline(always)]
pub fn scratch_term_lanes<R: Real>(
    s: &Scratch,
    frame: &SegmentFrame,
    x0: [R; 2],
    xi: [R; 2],
    depth_half_turns_per_um: R,
    sigma: f32,
    eta_mode: EtaMode,
    window: Window,
) -> Cx<R> {
    if window == Window::Exact {
        return exact_window_term_lanes(s, frame, x0, xi, depth_half_turns_per_um, sigma, eta_mode);
    }
    let (_, xi2) = xi_local_lanes(frame, xi);
    let profile = Profile::from_u32(s.profile);
    let m_p = mask_minus_profile_lanes(
        profile,
        R::splat(s.width),
        R::splat(s.depth),
        depth_half_turns_per_um,
        xi2,
    );
    m_p * eta_lanes(eta_mode, frame, x0, xi, sigma)
}

/// [`scratch_term_lanes`] with the exact across-groove window, out of line on the CPU
/// ([`exact_window_term_inline`]): inside a `#[target_feature]` caller it runs in the
/// baseline instruction set, and the frozen path's code around the call stays small.
#[cfg_attr(not(target_arch = "spirv"), inline(never))]
fn exact_window_term_lanes<R: Real>(
    s: &Scratch,
    frame: &SegmentFrame,
    x0: [R; 2],
    xi: [R; 2],
    depth_half_turns_per_um: R,
    sigma: f32,
    eta_mode: EtaMode,
) -> Cx<R> {
    exact_window_term_inline(s, frame, x0, xi, depth_half_turns_per_um, sigma, eta_mode)
}

/// The exact across-groove window's term: `S_k = A · η_along` ([`super::window`]). Inline
/// only in a batch instance of its own (`scratch_response_batch` with `INLINE_EXACT`), so
/// that it runs in that caller's instruction set.
///
/// The interval integrals, each without its centre's phase, share one loop (`j = 0` along
/// the segment when finite, `j ≥ 1` across it), so the function holds one copy of the
/// Faddeeva path.
#[inline(always)]
fn exact_window_term_inline<R: Real>(
    s: &Scratch,
    frame: &SegmentFrame,
    x0: [R; 2],
    xi: [R; 2],
    depth_half_turns_per_um: R,
    sigma: f32,
    eta_mode: EtaMode,
) -> Cx<R> {
    let c = R::splat;
    let (s_t, s_b) = frame.offset_from_lanes(x0);
    let (xi1, xi2) = xi_local_lanes(frame, xi);
    let profile = Profile::from_u32(s.profile);
    let (width, depth) = (c(s.width), c(s.depth));
    let sig = c(sigma);
    let iv = exact_across_intervals(profile, width, depth, depth_half_turns_per_um, s_b, xi2);
    let finite = eta_mode == EtaMode::Finite;
    let mut along = Cx::splat(0.0, 0.0);
    let mut sum = Cx::splat(0.0, 0.0);
    let mut j = if finite { 0 } else { 1 };
    while j <= iv.count {
        let (mid, half, nu) = if j == 0 {
            (s_t, c(frame.half_len), xi1)
        } else {
            (iv.mid[j - 1], iv.half[j - 1], iv.nu[j - 1])
        };
        let v = math::gauss_fourier_reduced_lanes(mid, half, sig, nu);
        if j == 0 {
            along = v;
        } else {
            sum = sum + iv.weight[j - 1] * v;
        }
        j += 1;
    }
    let across = math::cis_pi_lanes(c(-2.0) * s_b * xi2) * sum;
    if finite {
        across * (math::cis_pi_lanes(c(-2.0) * xi1 * s_t) * along)
    } else {
        across.scale(infinite_along_lanes(sig, xi1))
    }
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
    /// The coherence window across a groove.
    pub window: Window,
    /// How overlapping grooves cut (the coherent sum and ρc).
    pub crossings: Crossings,
    /// Also accumulate ρc (once: it does not depend on the wavelength).
    pub area_density: bool,
}

impl SpectralInputs {
    /// Wavelength `j`'s [`ResponseInputs`] (without ρc, which the walk gathers once).
    #[inline]
    fn one(&self, j: usize) -> ResponseInputs {
        ResponseInputs {
            x0: [self.x0.x, self.x0.y],
            xi: [self.xi[j].x, self.xi[j].y],
            depth_half_turns_per_um: self.depth_half_turns_per_um[j],
            sigma: self.sigma,
            eta: self.eta,
            window: self.window,
            crossings: self.crossings,
            area_density: false,
        }
    }
}

/// Sums the scratch terms over every scratch within [`CUTOFF_SIGMAS`]·σ of `x0`, for up to
/// [`MAX_SPECTRAL`] wavelengths in one walk: entry `j < count` holds wavelength `j`'s terms
/// added in the walk's order, so it does not depend on the other wavelengths of the call
/// (a one-wavelength call gives the same bits); entries past `count` stay empty. ρc, when asked for, is
/// accumulated once and copied into every entry.
///
/// On the CPU the walk is unswitched on [`SpectralInputs::crossings`]: the summed walk holds
/// no pair code (with it, the scalar table's default path ran 7 % slower).
pub fn scratch_response_spectral<S: ScratchSet>(
    set: &S,
    q: &SpectralInputs,
) -> [ScratchTerms; MAX_SPECTRAL] {
    #[cfg(not(target_arch = "spirv"))]
    if q.crossings == Crossings::Summed {
        return spectral_walk::<S, false>(set, q);
    }
    spectral_walk::<S, true>(set, q)
}

/// [`scratch_response_spectral`]'s walk; the crossings' pairs only with `PAIRS`.
#[inline(always)]
fn spectral_walk<S: ScratchSet, const PAIRS: bool>(
    set: &S,
    q: &SpectralInputs,
) -> [ScratchTerms; MAX_SPECTRAL] {
    let mut terms = [ScratchTerms::empty(q.sigma); MAX_SPECTRAL];
    let n = q.count as usize;
    let sigma = q.sigma;
    let mut rho = 0.0;
    let mut cursor = NearCursor::default();
    // `me`: the scratch's place in the walk (as [`Partners`] counts).
    let mut me = 0u32;
    while let Some(s) = set.next_near(&mut cursor, q.x0, CUTOFF_SIGMAS * sigma) {
        if let Some(frame) = s.frame() {
            // What the scratch loses to deeper partners, per wavelength (one call site of
            // the term in either instance: on SPIR-V the cuts are zero when summed).
            let deepest = PAIRS && q.crossings == Crossings::Deepest;
            let (cuts, overlap) = if deepest {
                deepest_losses(set, me, (&s, &frame), q)
            } else {
                ([Cx::zero(); MAX_SPECTRAL], 0.0)
            };
            let mut j = 0;
            while j < MAX_SPECTRAL && j < n {
                let one = q.one(j);
                // Load, update and store the whole element: rust-gpu lost updates made
                // in place through a run-time index into this array of structs (the
                // lavapipe test `backend-spirv/tests/bsdf.rs` caught it).
                let mut t = terms[j];
                if PAIRS {
                    t.accumulate_less(&s, &frame, &one, cuts[j], true);
                } else {
                    t.accumulate(&s, &frame, &one, true);
                }
                terms[j] = t;
                j += 1;
            }
            if q.area_density {
                rho += area_density_of(&frame, s.width, q.x0, sigma, q.window);
                if deepest {
                    rho -= overlap;
                }
            }
        }
        me += 1;
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

/// [`Crossings::Deepest`] in [`scratch_response_spectral`]: what scratch `a`, the walk's
/// scratch number `me`, loses to every other scratch of the walk ([`Partners`]), per
/// wavelength ([`cut_of`]), and, with [`SpectralInputs::area_density`], its overlaps with
/// the later ones in ρc (each pair's once, at the earlier of the two). One partner walk
/// serves both; with `q.count = 0` it gives the overlaps alone ([`scratch_area_density`]).
fn deepest_losses<S: ScratchSet>(
    set: &S,
    me: u32,
    a: (&Scratch, &SegmentFrame),
    q: &SpectralInputs,
) -> ([Cx<f32>; MAX_SPECTRAL], f32) {
    let mut cuts = [Cx::zero(); MAX_SPECTRAL];
    let mut overlap = 0.0;
    let near = (q.x0, CUTOFF_SIGMAS * q.sigma);
    let mut partners = Partners::default();
    while let Some((s2, frame2, i)) = partners.next(set, me, a, near) {
        let b = (&s2, &frame2);
        let mut j = 0;
        while j < MAX_SPECTRAL && j < q.count as usize {
            cuts[j] = cuts[j] + cut_of(a, b, me < i, &q.one(j), near);
            j += 1;
        }
        if q.area_density && me < i {
            overlap += overlap_density_lanes(a, b, [q.x0.x, q.x0.y], q.sigma, q.window, near);
        }
    }
    (cuts, overlap)
}

/// The walk over a scratch's partners with [`Crossings::Deepest`]: the walk again from the
/// start, counted as the walks count their scratches, so that `me < i` says which of the two
/// comes first (the tie rule of [`cut_of`]).
#[derive(Clone, Copy, Default)]
struct Partners {
    cursor: NearCursor,
    count: u32,
}

impl Partners {
    /// The next scratch in the disk `near` (centre, radius) that may overlap `a`, other than
    /// `a` itself (the walk's scratch number `me`), with its frame and its number.
    #[inline(always)]
    fn next<S: ScratchSet>(
        &mut self,
        set: &S,
        me: u32,
        a: (&Scratch, &SegmentFrame),
        near: (Vec2, f32),
    ) -> Option<(Scratch, SegmentFrame, u32)> {
        while let Some(s2) = set.next_near(&mut self.cursor, near.0, near.1) {
            let i = self.count;
            self.count += 1;
            if i != me
                && let Some(frame2) = s2.frame()
                && may_overlap(a.1, a.0, &frame2, &s2)
            {
                return Some((s2, frame2, i));
            }
        }
        None
    }
}

/// One segment's share of ρc: `∫∫ G dA / (2πσ²)` over the groove, with the window across
/// it frozen (`W ∫ G ds`) or exact ([`super::window`]).
#[inline]
fn area_density_of(frame: &SegmentFrame, width: f32, x0: Vec2, sigma: f32, window: Window) -> f32 {
    area_density_lanes(frame, width, [x0.x, x0.y], sigma, window)
}

/// [`area_density_of`] for one `x0` per lane; the exact window out of line (as in
/// [`scratch_term_lanes`]).
#[inline(always)]
fn area_density_lanes<R: Real>(
    frame: &SegmentFrame,
    width: f32,
    x0: [R; 2],
    sigma: f32,
    window: Window,
) -> R {
    if window == Window::Exact {
        return exact_window_area_density_lanes(frame, width, x0, sigma);
    }
    let (s_t, s_b) = frame.offset_from_lanes(x0);
    let c = R::splat;
    let along = math::gauss_fourier_centered_lanes(s_t, c(frame.half_len), c(sigma), c(0.0)).re;
    c(width) * (c(-0.5) * s_b * s_b / (c(sigma) * c(sigma))).exp() * along
        / c(math::TAU * sigma * sigma)
}

/// [`area_density_lanes`] with the exact window: `∫ G ds` along times `∫ G dv` across the
/// width, in one loop (one Faddeeva path; at ν = 0 the reduced integral is the integral).
#[cfg_attr(not(target_arch = "spirv"), inline(never))]
fn exact_window_area_density_lanes<R: Real>(
    frame: &SegmentFrame,
    width: f32,
    x0: [R; 2],
    sigma: f32,
) -> R {
    let (s_t, s_b) = frame.offset_from_lanes(x0);
    let c = R::splat;
    let mut weight = c(1.0);
    let mut j = 0;
    while j < 2 {
        let (mid, half) = if j == 0 {
            (s_t, c(frame.half_len))
        } else {
            (s_b, c(0.5 * width))
        };
        weight = weight * math::gauss_fourier_reduced_lanes(mid, half, c(sigma), c(0.0)).re;
        j += 1;
    }
    weight / c(math::TAU * sigma * sigma)
}

/// Scratch area density ρc(x0) = `(1/(2πσ²)) Σ W_k ∫_k G ds`.
///
/// Velinov Eq. 17 divides by `A_C = πσ²` instead of by `∫G dA = 2πσ²` and so reports 2 for
/// a fully scratched window; this is the corrected normalisation (1 when fully covered).
/// Werner Eq. 9's mask–scratch decomposition counts overlapping scratches twice, and so
/// does ρc with [`Crossings::Summed`]: it can exceed 1 where scratches cross. With
/// [`Crossings::Deepest`] each pair's overlap counts once.
pub fn scratch_area_density<S: ScratchSet>(
    set: &S,
    x0: Vec2,
    sigma: f32,
    window: Window,
    crossings: Crossings,
) -> f32 {
    // The overlaps alone: no wavelength.
    let overlaps = SpectralInputs {
        x0,
        xi: [Vec2::ZERO; MAX_SPECTRAL],
        depth_half_turns_per_um: [0.0; MAX_SPECTRAL],
        count: 0,
        sigma,
        eta: EtaMode::Finite,
        window,
        crossings,
        area_density: true,
    };
    let mut rho = 0.0;
    let mut cursor = NearCursor::default();
    let mut me = 0u32;
    while let Some(s) = set.next_near(&mut cursor, x0, CUTOFF_SIGMAS * sigma) {
        if let Some(frame) = s.frame() {
            rho += area_density_of(&frame, s.width, x0, sigma, window);
            if crossings == Crossings::Deepest {
                rho -= deepest_losses(set, me, (&s, &frame), &overlaps).1;
            }
        }
        me += 1;
    }
    rho
}
