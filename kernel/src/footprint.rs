//! Pixel-footprint averages of a scratch's spatial term (Velinov 2018 §3.2–3.3).
//!
//! The footprint is an ellipse (centre, angle of the `a1` semi-axis, semi-axes `a1`, `a2`),
//! `A_P = π a1 a2`. The quantity averaged is `|η_s(x)|²`, the finite-segment spatial phase
//! of [`crate::scratch::eta_finite`] at `ξ = 0` (for an infinite scratch this is Velinov
//! Eq. 10's `2 A_C exp(−s_b²/σ²)`), and the area density ρc.
//!
//! * [`eta_p_eq15`]: Velinov Eq. 15, `2σ³√π l / (a1 a2)` (large footprints only);
//! * [`eta_p_eq16`]: Eq. 16 with the π its second term lacks restored, so that it tends to
//!   `|η_s(centre)|²` as `A_P → 0`;
//! * [`eta_p_accurate`]: this crate's method, accurate at every footprint size: the integral
//!   across the scratch is done in closed form (an `erf` difference) and the one along it by
//!   panelled Gauss–Legendre in `θ` with `u = u_c + U sin θ` (smooth at the ellipse's ends),
//!   panels split around the segment ends and where the ellipse boundary crosses the
//!   scratch's Gaussian band (lines `v = kσ` parallel to it); the 8 nodes of a panel are one
//!   formula over [`Real`], evaluated in one [`Lanes<8>`](crate::lane::Lanes) on the CPU
//!   and one node at a time on SPIR-V ([`Nodes`]);
//! * [`rho_p_eq18`]: Eq. 18 without its spurious factor 2 (`W l / A_P`), and
//!   [`rho_p_accurate`] by the same quadrature as `eta_p_accurate`.

#[cfg(not(target_arch = "spirv"))]
use crate::lane::Lanes;
use crate::lane::{Real, branch};
use crate::math;
use crate::math::gauss_fourier_centered_lanes;
use crate::math::portable::sin_cos_within_half_pi;
use crate::math::quadrature::{GL8_W as GL_W, GL8_X as GL_X};
use crate::scratch::Scratch;
use bytemuck::{Pod, Zeroable};
use glam::Vec2;

/// Elliptic pixel footprint on the tangent plane. GPU-visible: 32 bytes.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct Ellipse {
    /// Centre (µm).
    pub center: [f32; 2],
    /// Angle of the `a1` semi-axis against +x (radians).
    pub angle_rad: f32,
    /// First semi-axis (µm).
    pub a1: f32,
    /// Second semi-axis (µm).
    pub a2: f32,
    /// Explicit padding.
    pub pad: [f32; 3],
}

const _: () = assert!(core::mem::size_of::<Ellipse>() == 32);

impl Ellipse {
    /// `A_P = π a1 a2`.
    #[inline]
    pub fn area(&self) -> f32 {
        math::PI * self.a1 * self.a2
    }
}

/// Length of the segment inside the ellipse (`l_contained`, Velinov Eq. 14).
///
/// The line is parametrised by arc length from its point `m` closest to the ellipse centre
/// and mapped to the ellipse's unit-circle frame, where `|q_m + s e|² = 1` is solved with
/// the discriminant in the cancellation-free form `|e|² − (q_m × e)²` (the textbook form
/// `b² − ac` loses everything to `f32` rounding for long segments and needle-thin ellipses).
pub fn contained_length(s: &Scratch, e: &Ellipse) -> f32 {
    let Some(f) = s.frame() else { return 0.0 };
    if !(e.a1 > 0.0 && e.a2 > 0.0) {
        return 0.0;
    }
    let (sn, cs) = (math::sin(e.angle_rad), math::cos(e.angle_rad));
    let to_unit = |d: Vec2| Vec2::new((d.x * cs + d.y * sn) / e.a1, (-d.x * sn + d.y * cs) / e.a2);
    let c = Vec2::from_array(e.center);
    let s_c = (c - f.center).dot(f.tangent); // arc length of m from the segment centre
    let m = f.center + s_c * f.tangent;
    let qm = to_unit(m - c);
    let dir = to_unit(f.tangent);
    let a = dir.length_squared();
    let cross = qm.x * dir.y - qm.y * dir.x;
    let disc = a - cross * cross;
    if !(disc > 0.0 && a > 0.0) {
        return 0.0;
    }
    let r = math::sqrt(disc);
    let b = qm.dot(dir);
    // Roots in arc length from m, clipped to the segment [−L/2 − s_c, L/2 − s_c].
    let (r0, r1) = ((-b - r) / a, (-b + r) / a);
    let (e0, e1) = (-f.half_len - s_c, f.half_len - s_c);
    let s0 = math::max(r0, e0);
    let s1 = math::min(r1, e1);
    if !(s1 > s0) {
        0.0
    } else if r0 <= e0 && r1 >= e1 {
        // The whole segment is inside: its length, not the difference of its two ends
        // measured from m (each rounded at ulp(s_c), far more than a short segment's length).
        2.0 * f.half_len
    } else {
        s1 - s0
    }
}

/// Perpendicular distance of the ellipse centre from the scratch's line (`s_b`).
#[inline]
fn centre_offset(s: &Scratch, e: &Ellipse) -> f32 {
    match s.frame() {
        Some(f) => (Vec2::from_array(e.center) - f.center).dot(f.bitangent),
        None => 0.0,
    }
}

/// Velinov Eq. 15: `(1/A_P)∫|η_s|² ≈ 2σ³√π l / (a1 a2)`.
pub fn eta_p_eq15(s: &Scratch, e: &Ellipse, sigma: f32) -> f32 {
    let l = contained_length(s, e);
    2.0 * sigma * sigma * sigma * math::SQRT_PI * l / (e.a1 * e.a2)
}

/// Velinov Eq. 16 with the missing π restored:
/// `(2σ²/A_P) [α σ π^{3/2} l + (1 − α) π A_P exp(−s_b²/σ²)]`, `α = min(A_P/(2A_C), 1)`.
pub fn eta_p_eq16(s: &Scratch, e: &Ellipse, sigma: f32) -> f32 {
    let l = contained_length(s, e);
    let ap = e.area();
    let ac = math::PI * sigma * sigma;
    let alpha = math::min(0.5 * ap / ac, 1.0);
    let sb = centre_offset(s, e);
    let pi32 = math::PI * math::SQRT_PI;
    2.0 * sigma * sigma / ap
        * (alpha * sigma * pi32 * l
            + (1.0 - alpha) * math::PI * ap * math::exp(-sb * sb / (sigma * sigma)))
}

/// Velinov Eq. 18 without its factor 2: `ρ_P ≈ W l / A_P`.
pub fn rho_p_eq18(s: &Scratch, e: &Ellipse) -> f32 {
    s.width * contained_length(s, e) / e.area()
}

/// How the accurate averages evaluate the 8 Gauss–Legendre nodes of each panel: the same
/// formula ([`Real`]-generic) either way.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Nodes {
    /// One `f32` node after the other (what SPIR-V runs).
    OneAtATime,
    /// All eight at once in one [`Lanes<8>`](crate::lane::Lanes) (8 f32 per instruction
    /// with AVX2, two 4-wide halves with SSE2 or NEON). SPIR-V has no lanes and evaluates
    /// one node at a time instead.
    Lanes,
}

impl Nodes {
    /// The kernel's choice: [`Nodes::Lanes`] on the CPU, [`Nodes::OneAtATime`] on SPIR-V.
    pub const DEFAULT: Nodes = if cfg!(target_arch = "spirv") {
        Nodes::OneAtATime
    } else {
        Nodes::Lanes
    };
}

/// `(1/A_P) ∫_P |η_s(x)|² dx`, accurate for every footprint size (see the module docs).
pub fn eta_p_accurate(s: &Scratch, e: &Ellipse, sigma: f32) -> f32 {
    eta_p_accurate_by(s, e, sigma, Nodes::DEFAULT)
}

/// `(1/A_P) ∫_P ρc(x) dx` for one scratch, accurate for every footprint size.
pub fn rho_p_accurate(s: &Scratch, e: &Ellipse, sigma: f32) -> f32 {
    rho_p_accurate_by(s, e, sigma, Nodes::DEFAULT)
}

/// [`eta_p_accurate`] with the nodes evaluated as `nodes` says (tests and benchmarks compare
/// the two).
pub fn eta_p_accurate_by(s: &Scratch, e: &Ellipse, sigma: f32, nodes: Nodes) -> f32 {
    footprint_integral(s, e, sigma, true, nodes)
}

/// [`rho_p_accurate`] with the nodes evaluated as `nodes` says.
pub fn rho_p_accurate_by(s: &Scratch, e: &Ellipse, sigma: f32, nodes: Nodes) -> f32 {
    footprint_integral(s, e, sigma, false, nodes) * s.width / (math::TAU * sigma * sigma)
}

/// Number of breakpoint offsets per feature.
const N_OFFSETS: usize = 7;
/// Band lines `v = OFFSETS·s`, in units of the standard deviation `s` of the averaged
/// Gaussian (`σ/√2` for `|η_s|²`, `σ` for ρc): out to 6 s, so that no Gaussian tail above
/// ~1e-9 is left to a panel that runs on to the far end of a large footprint.
const OFFSETS: [f32; N_OFFSETS] = [-6.0, -4.0, -2.0, 0.0, 2.0, 4.0, 6.0];
/// Breakpoint offsets around each segment end, in `s`, positive outward: the tail of g out
/// to 6 s beyond the end, and inward to 24 s.
const END_OFFSETS: [f32; N_OFFSETS] = [-24.0, -12.0, -6.0, -3.0, 0.0, 3.0, 6.0];
/// Depths of the band lines into a footprint that lies wholly on one side of the scratch
/// (gap `d` between its near edge and the scratch line), in units of `ℓ = s²/(d + s)`, the
/// length over which the Gaussian falls by `e` there (`e^{−c}` at depth `c ℓ`, `d ≫ s`).
const GAP_DEPTHS: [f32; N_OFFSETS] = [0.125, 0.5, 1.25, 2.5, 5.0, 10.0, 20.0];
/// Maximum number of panel boundaries: the 2 ellipse ends, the offsets around each of the 2
/// segment ends (or one set beyond one end), one set past a crossing of the scratch line
/// beyond an end, and 2 boundary crossings for each band line.
const MAX_BREAKS: usize = 2 + 5 * N_OFFSETS;

/// `(1/A_P)∫_P |η_s|²` (`squared`) or `(1/A_P)∫_P exp(−v²/(2σ²)) g(u)` (not squared),
/// with `u, v` the scratch-frame coordinates of `x` and `g(u) = ∫_seg exp(−(s−u)²/(2σ²)) ds`.
fn footprint_integral(s: &Scratch, e: &Ellipse, sigma: f32, squared: bool, nodes: Nodes) -> f32 {
    let Some(frame) = s.frame() else { return 0.0 };
    if !(e.a1 > 0.0 && e.a2 > 0.0 && sigma > 0.0) {
        return 0.0;
    }
    // Ellipse in the scratch frame: centre (eu, ev), quadratic form [[qa, qb], [qb, qc]] =
    // R diag(1/a1², 1/a2²) Rᵀ.
    let d = Vec2::from_array(e.center) - frame.center;
    let (eu, ev) = (d.dot(frame.tangent), d.dot(frame.bitangent));
    let phi = e.angle_rad - math::atan2(frame.tangent.y, frame.tangent.x);
    let (sp, cp) = (math::sin(phi), math::cos(phi));
    let (i1, i2) = (1.0 / (e.a1 * e.a1), 1.0 / (e.a2 * e.a2));
    let qa = cp * cp * i1 + sp * sp * i2;
    let qb = cp * sp * (i1 - i2);
    let qc = sp * sp * i1 + cp * cp * i2;
    let ab = e.a1 * e.a2;
    let sqrt_qc = math::sqrt(qc);
    // Half extent of the ellipse along the scratch, and chord half-length cos θ / √qc.
    let half_u = ab * sqrt_qc;
    // Standard deviation of the averaged Gaussian (along and across the scratch).
    let sd = if squared {
        sigma * FRAC_1_SQRT_2
    } else {
        sigma
    };
    // Panel boundaries in θ (u = eu + half_u sin θ).
    let mut br = [0.0f32; MAX_BREAKS];
    let mut n = 0;
    br[n] = -0.5 * math::PI;
    n += 1;
    br[n] = 0.5 * math::PI;
    n += 1;
    // Segment ends: the along-scratch factor g(u) changes within a few σ of them, and
    // further in where the footprint's edge leaves the band near an end at a shallow angle
    // (the integrand then decays into the segment over many σ: END_OFFSETS reach 24 s in).
    let det = i1 * i2;
    let gap_u = math::abs(eu) - frame.half_len - half_u;
    if gap_u > 0.0 {
        // A footprint wholly beyond one end (gap `d` from it to the footprint's near end)
        // sees only the tail of g, which falls by `e` over `ℓ = s²/(d + s)`: the breaks sit
        // at depths `c ℓ` inside the near end, `u − eu = ±(δ − U)` (as for the band lines
        // below).
        let dir = math::sign(eu);
        let ell_u = sd * sd / (gap_u + sd);
        let mut o = 0;
        while o < N_OFFSETS {
            let depth = math::min(ell_u * GAP_DEPTHS[o], 2.0 * half_u);
            push_break(&mut br, &mut n, dir * (depth - half_u) / half_u);
            o += 1;
        }
    } else {
        let ends = [-frame.half_len, frame.half_len];
        let mut f = 0;
        while f < 2 {
            // outward from the segment: −1 at its start, +1 at its end
            let out = if f == 0 { -1.0 } else { 1.0 };
            let mut o = 0;
            while o < N_OFFSETS {
                push_break(
                    &mut br,
                    &mut n,
                    (ends[f] + out * END_OFFSETS[o] * sd - eu) / half_u,
                );
                o += 1;
            }
            f += 1;
        }
    }
    // A footprint that crosses the scratch line only beyond an end (`du = (qb ev ∓
    // √(qa − ev² det))/qa`, e.g. a needle steeply across the line past the end) peaks where
    // it crosses, not where it comes nearest in u: the same depths past the nearer crossing.
    let disc0 = qa - ev * ev * det;
    if disc0 > 0.0 {
        let r0 = math::sqrt(disc0);
        let (c0, c1) = ((qb * ev - r0) / qa, (qb * ev + r0) / qa);
        let (past_hi, past_lo) = (eu + c0 - frame.half_len, -frame.half_len - (eu + c1));
        let (cross, dir, gap_c) = if past_hi > 0.0 {
            (c0, 1.0, past_hi)
        } else {
            (c1, -1.0, past_lo)
        };
        if gap_c > 0.0 {
            let ell_c = sd * sd / (gap_c + sd);
            let mut o = 0;
            while o < N_OFFSETS {
                push_break(
                    &mut br,
                    &mut n,
                    (cross + dir * ell_c * GAP_DEPTHS[o]) / half_u,
                );
                o += 1;
            }
        }
    }
    // Where the ellipse boundary crosses the scratch's Gaussian band: the intersections of
    // the lines v = OFFSETS·s with the ellipse, qa du² + 2 qb dv du + qc dv² = 1, i.e.
    // du = (−qb dv ± √(qa − dv² det))/qa with det = qa qc − qb² = 1/(a1 a2)². For a large
    // footprint these are where the chords' ends leave the band; for a needle they bracket
    // where the whole chord crosses it.
    //
    // A footprint wholly on one side (its near edge a gap `d` > 0 from the scratch line,
    // half extent `V = a1 a2 √qa` across) meets none of these lines; its integrand peaks
    // where the edge comes closest, over a width that shrinks like `√(ℓ R)`. There the lines
    // sit at depths `δ = c ℓ` inside the near edge, `dv = ±(δ − V)`, with
    // `disc = det·δ(2V − δ)` written without the cancellation of `qa − dv² det`.
    let v_half = ab * math::sqrt(qa);
    let gap = math::abs(ev) - v_half;
    let ell = sd * sd / (gap + sd);
    let mut o = 0;
    while o < N_OFFSETS {
        let (dv, disc) = if gap > 0.0 {
            let depth = math::min(ell * GAP_DEPTHS[o], 2.0 * v_half);
            (
                math::sign(ev) * (depth - v_half),
                det * depth * (2.0 * v_half - depth),
            )
        } else {
            let dv = OFFSETS[o] * sd - ev;
            (dv, qa - dv * dv * det)
        };
        if disc > 0.0 && qa > 0.0 {
            let r = math::sqrt(disc);
            push_break(&mut br, &mut n, (-qb * dv - r) / qa / half_u);
            push_break(&mut br, &mut n, (-qb * dv + r) / qa / half_u);
        }
        o += 1;
    }
    sort(&mut br, n);
    let chords = Chords {
        eu,
        ev,
        half_u,
        sqrt_qc,
        qb_over_qc: qb / qc,
        half_len: frame.half_len,
        sigma,
        sd,
        squared,
    };
    let mut total = 0.0;
    let mut p = 0;
    while p + 1 < n {
        let (t0, t1) = (br[p], br[p + 1]);
        let half = 0.5 * (t1 - t0);
        total += half * panel(&chords, 0.5 * (t0 + t1), half, nodes);
        p += 1;
    }
    // du = U cos θ dθ.
    total * half_u / e.area()
}

/// What the chord integral at a node needs: the ellipse in the scratch frame (centre
/// `(eu, ev)`, half extent `U` along the scratch, chord half length `cos θ / √qc`, chord
/// centres sliding by `−qb/qc` per unit of `u`) and the two Gaussians.
#[derive(Clone, Copy)]
struct Chords {
    eu: f32,
    ev: f32,
    half_u: f32,
    sqrt_qc: f32,
    qb_over_qc: f32,
    half_len: f32,
    sigma: f32,
    sd: f32,
    squared: bool,
}

/// The 8-point Gauss–Legendre node `i` on `[−1, 1]` (ascending) and its weight.
#[inline(always)]
fn gl_node(i: usize) -> (f32, f32) {
    if i < 4 {
        (-GL_X[i], GL_W[i])
    } else {
        (GL_X[i - 4], GL_W[i - 4])
    }
}

/// One node of the θ quadrature (the one formula, per lane): at `θ`, `u = eu + U sin θ`,
/// the chord across the scratch at that `u` is integrated in closed form and multiplied by
/// the along-scratch factor and by `w cos θ` (the node weight and the Jacobian's angular
/// part).
#[inline(always)]
fn node_value<R: Real>(c: &Chords, theta: R, w: R) -> R {
    let k = R::splat;
    let (st, ct) = sin_cos_within_half_pi(theta);
    let du = k(c.half_u) * st;
    let u = k(c.eu) + du;
    // chord across the scratch at this u: v = ev − (qb/qc) du ± half_v
    let half_v = ct / k(c.sqrt_qc);
    let vc = k(c.ev) - k(c.qb_over_qc) * du;
    // Nodes whose chord misses the band |v| < 8σ, or that lie more than 8σ beyond a
    // segment end, carry a weight below e^{-32}: skip them before any erf.
    let reach = k(8.0 * c.sigma);
    let off_band = (vc - half_v).gt(reach) | (vc + half_v).lt(-reach);
    let off_ends = u.abs().gt(k(c.half_len) + reach);
    let inner = branch!(
        !(off_band | off_ends),
        {
            // Both intervals as centre and half length: a short segment or chord several
            // σ out loses its length to the rounding of its ends otherwise (2e-4 for a
            // 1e-3σ footprint 5σ from the scratch; issue #20).
            let g = gauss_fourier_centered_lanes(-u, k(c.half_len), k(c.sigma), k(0.0)).re;
            let across = gauss_fourier_centered_lanes(vc, half_v, k(c.sd), k(0.0)).re;
            if c.squared {
                g * g * across
            } else {
                g * across
            }
        },
        k(0.0)
    );
    w * inner * ct
}

/// `Σ_i w_i node_value(θ_i)` over the panel `[mid − half, mid + half]` (nodes in ascending
/// order), by `nodes`.
#[inline]
fn panel(c: &Chords, mid: f32, half: f32, nodes: Nodes) -> f32 {
    #[cfg(not(target_arch = "spirv"))]
    if nodes == Nodes::Lanes {
        let theta = Lanes(core::array::from_fn(|i| mid + half * gl_node(i).0));
        let w = Lanes(core::array::from_fn(|i| gl_node(i).1));
        let v: Lanes<8> = node_value(c, theta, w);
        let mut sum = 0.0;
        let mut i = 0;
        while i < 8 {
            sum += v.0[i];
            i += 1;
        }
        return sum;
    }
    #[cfg(target_arch = "spirv")]
    let _ = nodes;
    let mut sum = 0.0;
    let mut i = 0;
    while i < 8 {
        let (x, w) = gl_node(i);
        sum += node_value(c, mid + half * x, w);
        i += 1;
    }
    sum
}

/// 1/√2.
const FRAC_1_SQRT_2: f32 = core::f32::consts::FRAC_1_SQRT_2;

/// Adds the panel boundary `θ = asin(r)` when `r = (u − eu)/U` lies inside the ellipse.
#[inline]
fn push_break(br: &mut [f32; MAX_BREAKS], n: &mut usize, r: f32) {
    if r > -1.0 && r < 1.0 && *n < MAX_BREAKS {
        br[*n] = math::asin(r);
        *n += 1;
    }
}

/// Insertion sort of the first `n` entries (n ≤ MAX_BREAKS; no recursion for SPIR-V).
// Slice methods such as `swap` are avoided in the kernel (rust-gpu limits, ARCHITECTURE.md *What the kernel must avoid for SPIR-V*).
#[allow(clippy::manual_swap)]
fn sort(a: &mut [f32; MAX_BREAKS], n: usize) {
    let mut i = 1;
    while i < n && i < MAX_BREAKS {
        let mut j = i;
        while j > 0 && a[j - 1] > a[j] {
            let t = a[j - 1];
            a[j - 1] = a[j];
            a[j] = t;
            j -= 1;
        }
        i += 1;
    }
}
