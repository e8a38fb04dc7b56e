//! Crossings cut once (issue #21): where two grooves overlap, the surface has the deeper
//! cut, not both.
//!
//! Werner Eq. 9 sums the groove terms, `S = Σ S_k`, so where grooves `a` and `b` overlap the
//! summed reflectance is `T_a + T_b − 1` where the surface has the deeper groove's `T`. The
//! pair's correction adds the shallower groove's `1 − T` back over the overlap `O`:
//!
//! `S = Σ_k S_k − Σ_pairs C_ab`,  `C_ab = ∫_O G(p) (1 − T_sh(p)) e^{−2πi ξ·(p − x0)} dp`,
//!
//! `sh` the shallower groove at `p`, `G` the coherence window: [`Window::Exact`] the window
//! itself, [`Window::Frozen`] the shallower groove's centre-line window (the point is taken
//! away as the frozen model evaluated it). Where the depths tie, the later groove of the
//! pair is the one taken away. Only pairs are corrected: where three grooves overlap, the
//! triple overlap is corrected once per pair (not modelled).
//!
//! **Shares.** `C_ab` splits by the groove cut away ([`Share`]): `C_ab = C_a←b + C_b←a`,
//! `C_a←b` the pieces where `a` is the shallower one. The walks give each groove its own
//! part of the surface, `S'_a = S_a − Σ_b C_a←b`, and sum `S = Σ S'_a`; Velinov's
//! incoherent sum takes the same parts, `Σ |S'_a|²` (its intensity form: each groove's
//! intensity from the part of the surface it cuts).
//!
//! **Pieces.** `O` is a convex polygon: the two strips' parallelogram cut by the segments'
//! ends. A V groove's depth is linear on each side of its centre line, so `O` is cut along
//! the V centre lines and then along the line where both depths are equal: up to 8 convex
//! pieces, on each of which the shallower groove, and so the phase of `1 − T`, is one linear
//! function of `p`.
//!
//! **One piece**, in the shallower groove's frame (`u` along, `v` across): the piece is cut
//! into slabs between its vertices' `u`. A slab is `u ∈ [u_a, u_b]`, `v = lo(u) + t Δ(u)`,
//! `t ∈ [0, 1]`, with `lo` and `Δ` linear. At fixed `t` the integrand along `u` is a
//! Gaussian (the isotropic window on a line of slope `a` is a Gaussian of width
//! `σ/√(1 + a²)`), times a linear phase, times the Jacobian `Δ(u)`: closed forms through
//! [`math::gauss_fourier_reduced_lanes`] and its first moment. Across (`t`): Gauss–Legendre
//! panels of 4 nodes, each over at most [`PANEL_RADIANS`] of the phase and window change
//! across the slab. A slab's ends in `u` do not move with `t`, so the long oblique edges of
//! a shallow-angle overlap cost nothing: quadrature resolves only the groove's width. A
//! slab no longer along `u` than its widest chord or than σ/2 (a sliver, a steep edge near
//! 90°, a small overlap) is integrated the other way round: closed form across each chord,
//! Gauss–Legendre along `u`. There the first moment's closed form along `u` would lose a
//! factor ~(σ/h)² of precision to cancellation (catastrophically for slivers).
//!
//! Measured against the heightfield reference (`testkit/tests/heightfield_reference.rs`,
//! 24 crossing cases at 90°, 45° and 10°): worst median 7.5e-7, worst 4.6e-5 relative, for
//! either window.

use super::record::{Scratch, SegmentFrame};
use super::window::Window;
use crate::lane::{Cx, Mask, Real};
use crate::math;
use crate::math::quadrature::{GL4_W, GL4_X};
use glam::Vec2;

gpu_enum! {
    /// How grooves that overlap are cut.
    pub enum Crossings {
        /// Each groove cuts the surface on its own: the overlap is cut twice (Werner Eq. 9).
        Summed = 0,
        /// The deeper groove cuts the overlap once ([`crossing_correction_lanes`]; issue #21):
        /// each groove's term loses the pieces of its overlaps where it is the shallower one,
        /// `S'_k = S_k − Σ_j C_kj`, in the coherent sum `S = Σ S'_k`, in Velinov's incoherent
        /// sum `Σ |S'_k|²` (its intensity form) and in ρc.
        Deepest = 1,
    }
    fallback = Summed;
}

/// Which pieces of a pair's overlap [`crossing_correction_lanes`] integrates: those where
/// the pair's first groove is cut away, those where the second is, or both (the pair's
/// whole correction `C_ab`). The shares are what each groove's own term loses (Velinov's
/// intensity form needs them before squaring).
#[repr(u32)]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Share {
    /// Every piece: `C_ab`.
    Both = 0,
    /// The pieces where the first groove (`a`) is the shallower one.
    First = 1,
    /// The pieces where the second groove (`b`) is the shallower one (ties included).
    Second = 2,
}

/// Largest phase-and-window change (radians) across one Gauss–Legendre panel of a slab:
/// 4 nodes per panel integrate `e^{iθ}` over 3 rad to about 1e-6.
pub const PANEL_RADIANS: f32 = 3.0;

/// Most panels across one slab (a cap on the cost of one piece: 4 nodes each; a slab takes
/// as many as its span needs), for a span of up to 3 072 rad. Over the domain the sweeps
/// certify (W ≤ 50 µm, D ≤ 10 µm, λ ≥ 360 nm) the phase across a groove is at most
/// `2π |ξ·b| W ≤ 2π (2/λ) W` = 1 745 rad plus a V groove's depth phase across its half,
/// `2πγD/λ ≤` 349 rad: 2 094 rad, the rest a margin for the exact window's slope. The cap
/// was 256 panels (768 rad, `W < 22 µm` at 360 nm) until the reference's wide crossings
/// (`reference/heightfield_golden.py`, W = 50 µm at 360 nm) were measured. Beyond it the
/// quadrature under-resolves the phase across the groove.
pub const MAX_PANELS: f32 = 1024.0;

/// Most vertices of a piece: the parallelogram (4) cut by 4 segment ends, the 4 sides of
/// the walk's square and 3 more lines.
const MAX_VERTS: usize = 16;

/// `a[i]`, 0 past the end. No index here may panic: on SPIR-V rust-gpu inlines a function
/// that may panic at every call site (its abort must reach the entry point), so one
/// bounds check would copy the whole pair integral into every walk of every entry point.
/// The shader's form selects among constant indices, branch-free (rust-gpu cannot make a
/// slice of a local array, and MIR keeps a guarded index's check).
#[inline(always)]
fn load(a: &[f32; MAX_VERTS], i: usize) -> f32 {
    #[cfg(target_arch = "spirv")]
    {
        let mut x = 0.0;
        macro_rules! pick {
            ($($k:literal)*) => { $( x = if i == $k { a[$k] } else { x }; )* };
        }
        pick!(0 1 2 3 4 5 6 7 8 9 10 11 12 13 14 15);
        x
    }
    #[cfg(not(target_arch = "spirv"))]
    {
        match a.get(i) {
            Some(x) => *x,
            None => 0.0,
        }
    }
}

/// `a[i] = x`, nothing past the end (panic-free, as [`load`]).
#[inline(always)]
fn store(a: &mut [f32; MAX_VERTS], i: usize, x: f32) {
    #[cfg(target_arch = "spirv")]
    {
        macro_rules! put {
            ($($k:literal)*) => { $( a[$k] = if i == $k { x } else { a[$k] }; )* };
        }
        put!(0 1 2 3 4 5 6 7 8 9 10 11 12 13 14 15);
    }
    #[cfg(not(target_arch = "spirv"))]
    {
        if let Some(slot) = a.get_mut(i) {
            *slot = x;
        }
    }
}

/// A convex polygon in coordinates relative to the pair's origin (µm).
#[derive(Clone, Copy)]
struct Poly {
    x: [f32; MAX_VERTS],
    y: [f32; MAX_VERTS],
    n: usize,
}

impl Poly {
    const EMPTY: Poly = Poly {
        x: [0.0; MAX_VERTS],
        y: [0.0; MAX_VERTS],
        n: 0,
    };

    fn push(&mut self, p: Vec2) {
        if self.n < MAX_VERTS {
            store(&mut self.x, self.n, p.x);
            store(&mut self.y, self.n, p.y);
            self.n += 1;
        }
    }

    fn at(&self, i: usize) -> Vec2 {
        Vec2::new(load(&self.x, i), load(&self.y, i))
    }

    /// The part where `a·p + a0 ≥ 0` (Sutherland–Hodgman, one line). Out of line on
    /// SPIR-V: one copy for the dozen clips of a pair.
    #[cfg_attr(target_arch = "spirv", inline(never))]
    fn clip(&self, a: Vec2, a0: f32) -> Poly {
        let mut out = Poly::EMPTY;
        let mut i = 0;
        while i < self.n {
            let p = self.at(i);
            let q = self.at(if i + 1 == self.n { 0 } else { i + 1 });
            let (fp, fq) = (a.dot(p) + a0, a.dot(q) + a0);
            if fp >= 0.0 {
                out.push(p);
            }
            if (fp >= 0.0) != (fq >= 0.0) {
                out.push(p + (q - p) * (fp / (fp - fq)));
            }
            i += 1;
        }
        out
    }
}

/// One groove of the pair, relative to the pair's origin `o`.
#[derive(Clone, Copy)]
struct Groove {
    t: Vec2,
    b: Vec2,
    /// `(o − c)·t`, `(o − c)·b` (µm).
    off_t: f32,
    off_b: f32,
    half_len: f32,
    half_w: f32,
    width: f32,
    depth: f32,
    vee: bool,
}

impl Groove {
    fn new(s: &Scratch, f: &SegmentFrame, o: Vec2) -> Groove {
        let d = o - f.center;
        Groove {
            t: f.tangent,
            b: f.bitangent,
            off_t: d.dot(f.tangent),
            off_b: d.dot(f.bitangent),
            half_len: f.half_len,
            half_w: 0.5 * s.width,
            width: s.width,
            depth: s.depth,
            vee: super::profile::Profile::from_u32(s.profile) == super::profile::Profile::Triangle,
        }
    }

    /// The part of `p` within the segment's ends.
    fn clip_ends(&self, p: Poly) -> Poly {
        p.clip(self.t, self.off_t + self.half_len)
            .clip(-self.t, self.half_len - self.off_t)
    }

    /// The part of `p` within the groove's width.
    fn clip_sides(&self, p: Poly) -> Poly {
        p.clip(self.b, self.off_b + self.half_w)
            .clip(-self.b, self.half_w - self.off_b)
    }

    /// Sides of the centre line to take one by one: a V's two, a rectangle's one.
    fn sides(&self) -> usize {
        if self.vee { 2 } else { 1 }
    }

    /// Side `i` of [`Self::sides`]: its sign (+1 for `i = 0`, else −1) and the part of `p`
    /// there (all of `p` for a rectangle).
    fn side(&self, p: Poly, i: usize) -> (f32, Poly) {
        let sign = if i == 0 { 1.0 } else { -1.0 };
        let part = if self.vee {
            p.clip(sign * self.b, sign * self.off_b)
        } else {
            p
        };
        (sign, part)
    }

    /// Depth on the side `side` (±1) of the centre line as `k·q + k0` (a V is linear there).
    fn depth_plane(&self, side: f32) -> (Vec2, f32) {
        if !self.vee {
            return (Vec2::ZERO, self.depth);
        }
        let k = -2.0 * side * self.depth / self.width;
        (k * self.b, self.depth + k * self.off_b)
    }
}

/// The signs of corner `i` (0–3), in order around a rectangle or parallelogram:
/// (−,−), (+,−), (+,+), (−,+).
#[inline(always)]
fn corner(i: usize) -> (f32, f32) {
    let sa = if i == 1 || i == 2 { 1.0 } else { -1.0 };
    let sb = if i >= 2 { 1.0 } else { -1.0 };
    (sa, sb)
}

/// The overlap of the two grooves' rectangles, relative to the returned origin: the
/// crossing of the centre lines where the strips' parallelogram is shorter than segment
/// `a` (its corners then lie within a few widths of it), else the middle of the part of `a`
/// alongside `b` (nearly parallel grooves), so that the corners' coordinates stay near the
/// overlap's own size.
fn overlap(a: &Scratch, fa: &SegmentFrame, b: &Scratch, fb: &SegmentFrame) -> (Vec2, Poly) {
    let det = fa.tangent.perp_dot(fb.tangent);
    let reach = 0.5 * (a.width + b.width);
    let mut p = Poly::EMPTY;
    if math::abs(det) * fa.half_len > reach {
        // Along a, where the centre lines cross.
        let along = (fb.center - fa.center).perp_dot(fb.tangent) / det;
        let o = fa.center + along * fa.tangent;
        let ga = Groove::new(a, fa, o);
        let gb = Groove::new(b, fb, o);
        // The strips' parallelogram: q·b_a + off_b_a = ±W_a/2, q·b_b + off_b_b = ±W_b/2.
        let (ba, bb) = (ga.b, gb.b);
        let den = ba.perp_dot(bb);
        let mut i = 0;
        while i < 4 {
            let (sa, sb) = corner(i);
            let (r1, r2) = (sa * ga.half_w - ga.off_b, sb * gb.half_w - gb.off_b);
            p.push(Vec2::new(r1 * bb.y - r2 * ba.y, ba.x * r2 - bb.x * r1) / den);
            i += 1;
        }
        return (o, gb.clip_ends(ga.clip_ends(p)));
    }
    // Nearly parallel: a's rectangle over the part of a alongside b, cut by b.
    let mid = (fb.center - fa.center).dot(fa.tangent);
    let spread = fb.half_len * math::abs(fb.tangent.dot(fa.tangent))
        + 0.5 * b.width * math::abs(fb.bitangent.dot(fa.tangent));
    let lo = math::max(mid - spread, -fa.half_len);
    let hi = math::min(mid + spread, fa.half_len);
    if !(hi > lo) {
        return (fa.center, p);
    }
    let o = fa.center + (0.5 * (lo + hi)) * fa.tangent;
    let ga = Groove::new(a, fa, o);
    let gb = Groove::new(b, fb, o);
    let half = 0.5 * (hi - lo);
    let mut i = 0;
    while i < 4 {
        let (sa, sb) = corner(i);
        p.push((sa * half) * ga.t + (sb * ga.half_w - ga.off_b) * ga.b);
        i += 1;
    }
    (o, gb.clip_ends(gb.clip_sides(p)))
}

/// Per-lane inputs of one pair's correction.
#[derive(Clone, Copy)]
struct Query<R> {
    /// `o − x0` (µm).
    o_x0: [R; 2],
    xi: [R; 2],
    half_turns_per_um: R,
    sigma: f32,
    window: Window,
}

/// The crossing correction `C_ab` of grooves `a` and `b` (module docs), `a` before `b` in
/// the set's order (on a tie in depth `b` is taken away), for one query per lane, over the
/// part of the overlap inside the square around the disk `near` (centre, radius: the disk
/// the walk gathered its scratches from, which holds every lane's window where it matters).
/// Zero when they do not overlap. Subtract it from `S`. `share` picks the pieces: with
/// [`Share::First`] or [`Share::Second`] only what that groove's own term loses.
///
/// Out of line: on the CPU (as the exact window's terms) it holds two more Faddeeva paths,
/// which inlined into every SIMD batch would multiply the CPU crates' build time; on SPIR-V
/// it would be copied into every walk of every entry point. The records come by value, as
/// rust-gpu must inline a function given a pointer into a storage buffer; nothing in its
/// body may panic (its arrays are read through the module's panic-free `load` and `store`).
#[inline(never)]
#[allow(clippy::too_many_arguments)]
pub fn crossing_correction_lanes<R: Real>(
    a: Scratch,
    fa: SegmentFrame,
    b: Scratch,
    fb: SegmentFrame,
    x0: [R; 2],
    xi: [R; 2],
    half_turns_per_um: R,
    sigma: f32,
    window: Window,
    near: (Vec2, f32),
    share: Share,
) -> Cx<R> {
    let q = (x0, xi, half_turns_per_um);
    pair_integral(&a, &fa, &b, &fb, q, sigma, window, near, share, false)
}

/// `∫_O G dA` over the pair's overlap (the window and `near` as in
/// [`crossing_correction_lanes`]): what the overlap adds twice to the scratch area density
/// ρc. Out of line (as [`crossing_correction_lanes`]).
#[inline(never)]
#[allow(clippy::too_many_arguments)]
pub fn crossing_overlap_weight_lanes<R: Real>(
    a: Scratch,
    fa: SegmentFrame,
    b: Scratch,
    fb: SegmentFrame,
    x0: [R; 2],
    sigma: f32,
    window: Window,
    near: (Vec2, f32),
) -> R {
    let zero = R::splat(0.0);
    pair_integral(
        &a,
        &fa,
        &b,
        &fb,
        (x0, [zero; 2], zero),
        sigma,
        window,
        near,
        Share::Both,
        true,
    )
    .re
}

/// Whether the two grooves' rectangles can overlap: their centres closer than their half
/// lengths and widths allow (a cheap test before [`crossing_correction_lanes`]).
#[inline]
pub fn may_overlap(fa: &SegmentFrame, a: &Scratch, fb: &SegmentFrame, b: &Scratch) -> bool {
    let reach = fa.half_len + fb.half_len + 0.5 * (a.width + b.width);
    (fa.center - fb.center).length_squared() <= reach * reach
}

/// [`crossing_correction_lanes`], or with `area` the window's integral over the overlap.
#[inline(always)]
#[allow(clippy::too_many_arguments)]
fn pair_integral<R: Real>(
    a: &Scratch,
    fa: &SegmentFrame,
    b: &Scratch,
    fb: &SegmentFrame,
    (x0, xi, half_turns_per_um): ([R; 2], [R; 2], R),
    sigma: f32,
    window: Window,
    near: (Vec2, f32),
    share: Share,
    area: bool,
) -> Cx<R> {
    let mut sum = Cx::splat(0.0, 0.0);
    let (o, whole) = overlap(a, fa, b, fb);
    // Within the square around `near` (relative to o).
    let (cx, r) = (near.0 - o, near.1);
    let whole = whole
        .clip(Vec2::X, r - cx.x)
        .clip(-Vec2::X, r + cx.x)
        .clip(Vec2::Y, r - cx.y)
        .clip(-Vec2::Y, r + cx.y);
    if whole.n < 3 || !(sigma > 0.0) {
        return sum;
    }
    let ga = Groove::new(a, fa, o);
    let gb = Groove::new(b, fb, o);
    let q = Query {
        o_x0: [R::splat(o.x) - x0[0], R::splat(o.y) - x0[1]],
        xi,
        half_turns_per_um,
        sigma,
        window,
    };
    // Sides of each V's centre line (one pass for a rectangle).
    let mut i = 0;
    while i < ga.sides() {
        let (sa, pa) = ga.side(whole, i);
        let mut j = 0;
        while j < gb.sides() {
            let (sb, p) = gb.side(pa, j);
            // depth_a − depth_b = k·q + k0, linear on p: b is taken away where it is ≥ 0
            // (on a tie too), a where it is < 0. One call site (one copy of the piece's
            // integral in the code).
            let (ka, ka0) = ga.depth_plane(sa);
            let (kb, kb0) = gb.depth_plane(sb);
            let (k, k0) = (ka - kb, ka0 - kb0);
            // Half 0: b cut away; half 1: a.
            let (first, last) = match share {
                Share::Both => (0, 2),
                Share::First => (1, 2),
                Share::Second => (0, 1),
            };
            let mut half = first;
            while half < last && p.n >= 3 {
                let (g, side, sign) = if half == 0 {
                    (gb, sb, 1.0)
                } else {
                    (ga, sa, -1.0)
                };
                let piece = if k != Vec2::ZERO {
                    p.clip(sign * k, sign * k0)
                } else if (k0 >= 0.0) == (half == 0) {
                    p
                } else {
                    Poly::EMPTY
                };
                sum = sum + piece_integral(&piece, &g, side, &q, area);
                half += 1;
            }
            j += 1;
        }
        i += 1;
    }
    if area {
        sum
    } else {
        // ξ·(o − x0), factored out of every piece.
        let (ox, oy) = (q.o_x0[0], q.o_x0[1]);
        math::cis_pi_lanes(R::splat(-2.0) * (xi[0] * ox + xi[1] * oy)) * sum
    }
}

/// `∫_piece G (1 − T_g) e^{−2πi ξ·(p − o)} dp` for the groove `g` cut away on the piece,
/// on the side `side` of its centre line (a V), or with `area` `∫_piece G dp`. Out of line:
/// one copy of its two Faddeeva paths per lane type (one in the shader), shared by the
/// correction and the overlap's weight.
#[inline(never)]
fn piece_integral<R: Real>(p: &Poly, g: &Groove, side: f32, q: &Query<R>, area: bool) -> Cx<R> {
    let mut sum = Cx::splat(0.0, 0.0);
    if p.n < 3 {
        return sum;
    }
    // The piece in g's frame, relative to o: u along, v across.
    let mut u = [0.0f32; MAX_VERTS];
    let mut v = [0.0f32; MAX_VERTS];
    let mut us = [0.0f32; MAX_VERTS];
    let mut i = 0;
    while i < p.n {
        let pt = p.at(i);
        let ui = pt.dot(g.t);
        store(&mut u, i, ui);
        store(&mut v, i, pt.dot(g.b));
        // Insertion into the sorted u's.
        let mut j = i;
        while j > 0 && load(&us, j - 1) > ui {
            let before = load(&us, j - 1);
            store(&mut us, j, before);
            j -= 1;
        }
        store(&mut us, j, ui);
        i += 1;
    }
    let c = R::splat;
    let xi1 = q.xi[0] * c(g.t.x) + q.xi[1] * c(g.t.y);
    let xi2 = q.xi[0] * c(g.b.x) + q.xi[1] * c(g.b.y);
    let p_t = q.o_x0[0] * c(g.t.x) + q.o_x0[1] * c(g.t.y);
    let p_b = q.o_x0[0] * c(g.b.x) + q.o_x0[1] * c(g.b.y);
    // The terms of 1 − T: a rectangle's (1 − e^{iπκ}) at ν = 0; a V's 1 at ν = 0 and
    // −e^{iπκ} at ν = side·κ/W (its depth phase is linear across, Werner Eq. 29); the area
    // alone: 1.
    let kappa = c(g.depth) * q.half_turns_per_um;
    let (terms, w0, w1, nu1) = if area {
        (1, Cx::splat(1.0, 0.0), Cx::splat(0.0, 0.0), c(0.0))
    } else if g.vee {
        (
            2,
            Cx::splat(1.0, 0.0),
            -math::cis_pi_lanes(kappa),
            c(side / g.width) * kappa,
        )
    } else {
        (
            1,
            math::one_minus_cis_pi_lanes(kappa),
            Cx::splat(0.0, 0.0),
            c(0.0),
        )
    };
    let mut k = 0;
    while k + 1 < p.n {
        let (ua, ub) = (load(&us, k), load(&us, k + 1));
        let slab = slab_of(&u, &v, p.n, ua, ub);
        if ub > ua && slab.h > 0.0 {
            let mut term = 0;
            while term < terms {
                let (w, nu) = if term == 0 { (w0, c(0.0)) } else { (w1, nu1) };
                // Along u only for slabs longer than their widest chord and than σ/2:
                // there the first moment's closed form loses at most a factor ~(σ/h)² of
                // f32 precision (16 here); shorter slabs go across.
                let long = math::max(slab.d + math::abs(slab.d1) * slab.h, 0.5 * q.sigma);
                let f = InFrame {
                    xi1,
                    xi2,
                    nu,
                    p_t,
                    p_b,
                };
                let s = if 2.0 * slab.h <= long {
                    slab_integral_across(&slab, g, &f, q)
                } else {
                    slab_integral(&slab, g, &f, q)
                };
                sum = sum + w * s;
                term += 1;
            }
        }
        k += 1;
    }
    sum
}

/// A slab of a piece: `u ∈ [um − h, um + h]`, `v = lo + l1 (u − um) + t (d + d1 (u − um))`.
#[derive(Clone, Copy)]
struct Slab {
    um: f32,
    h: f32,
    lo: f32,
    l1: f32,
    d: f32,
    d1: f32,
}

/// The slab between `ua < ub` of the convex polygon `(u, v)`: its lower and upper edges
/// at the slab's middle.
fn slab_of(u: &[f32; MAX_VERTS], v: &[f32; MAX_VERTS], n: usize, ua: f32, ub: f32) -> Slab {
    let um = 0.5 * (ua + ub);
    let (mut lo, mut l1, mut hi, mut h1) = (f32::INFINITY, 0.0f32, f32::NEG_INFINITY, 0.0f32);
    let mut i = 0;
    while i < n {
        let j = if i + 1 == n { 0 } else { i + 1 };
        let (u0, u1) = (load(u, i), load(u, j));
        if u0 != u1 && (u0 - um) * (u1 - um) <= 0.0 {
            let (v0, v1) = (load(v, i), load(v, j));
            let slope = (v1 - v0) / (u1 - u0);
            let at = v0 + slope * (um - u0);
            if at < lo {
                lo = at;
                l1 = slope;
            }
            if at > hi {
                hi = at;
                h1 = slope;
            }
        }
        i += 1;
    }
    if !(hi >= lo) {
        // No edge spans the slab (a degenerate piece): nothing to integrate.
        return Slab {
            um,
            h: 0.0,
            lo: 0.0,
            l1: 0.0,
            d: 0.0,
            d1: 0.0,
        };
    }
    Slab {
        um,
        h: 0.5 * (ub - ua),
        lo,
        l1,
        d: hi - lo,
        d1: h1 - l1,
    }
}

/// One query in the frame of the groove taken away, `g`: `ξ·t` (`xi1`), `ξ·b` (`xi2`),
/// the frequency across of the `1 − T` term (`nu`), and `(o − x0)·t`, `(o − x0)·b`
/// (`p_t`, `p_b`; µm).
#[derive(Clone, Copy)]
struct InFrame<R> {
    xi1: R,
    xi2: R,
    nu: R,
    p_t: R,
    p_b: R,
}

/// `∫∫_slab G(p) e^{−2πi [ξ·(p − o) + ν v']} dp`, `v'` across from g's centre line (a slab
/// of positive length).
#[inline(always)]
fn slab_integral<R: Real>(s: &Slab, g: &Groove, f: &InFrame<R>, q: &Query<R>) -> Cx<R> {
    let c = R::splat;
    let mut sum = Cx::splat(0.0, 0.0);
    let sigma = c(q.sigma);
    let inv_2s2 = c(0.5 / (q.sigma * q.sigma));
    let exact = q.window == Window::Exact;
    let d_max = s.d + math::abs(s.d1) * s.h;
    // Panels across: the phase 2π|ξ₂ + ν| and, for the exact window, its log-slope |v|/σ²
    // over the slab's widest chord.
    let rate = c(math::TAU) * (f.xi2 + f.nu).abs()
        + if exact {
            ((f.p_b + c(s.lo + 0.5 * s.d)).abs() + c(d_max)) * c(2.0) * inv_2s2
        } else {
            c(0.0)
        };
    let panels = panels_for(rate * c(d_max));
    let p = f.p_t + c(s.um);
    // Frozen: the centre line's window across, (c − x0)·b = p_b − off_b.
    let frozen_across = f.p_b - c(g.off_b);
    let mut j = 0.0f32;
    while c(j).lt(panels).any() {
        let mut node = 0;
        while node < 4 {
            let (t, wt) = panel_node(j, node, panels);
            let c0 = c(s.lo) + t * c(s.d);
            let a1 = c(s.l1) + t * c(s.d1);
            let qv = f.p_b + c0;
            let (mu, r2, sig_e) = if exact {
                let s2 = c(1.0) + a1 * a1;
                let cross = p * a1 - qv;
                ((p + a1 * qv) / s2, cross * cross / s2, sigma / s2.sqrt())
            } else {
                (p, frozen_across * frozen_across, sigma)
            };
            let along = f.xi1 + (f.xi2 + f.nu) * a1;
            let jac = line_integral(mu, c(s.h), sig_e, along, c(s.d), c(s.d1));
            let phase = math::cis_pi_lanes(
                c(-2.0) * (f.xi1 * c(s.um) + f.xi2 * c0 + f.nu * (c0 + c(g.off_b))),
            );
            sum = sum + (phase * jac).scale(wt * (-r2 * inv_2s2).exp());
            node += 1;
        }
        j += 1.0;
    }
    sum
}

/// [`slab_integral`] for a slab no longer along `u` than its widest chord across or than
/// σ/2 (a sliver, a steep edge, a small overlap): closed form across each chord (a
/// Gaussian-windowed interval for the exact window, a sinc for the frozen one),
/// Gauss–Legendre along `u`. No Jacobian, so no moment: the along-`u` moment's closed form
/// loses a factor ~(σ/h)² of precision to cancellation.
#[inline(always)]
fn slab_integral_across<R: Real>(s: &Slab, g: &Groove, f: &InFrame<R>, q: &Query<R>) -> Cx<R> {
    let c = R::splat;
    let mut sum = Cx::splat(0.0, 0.0);
    let inv_2s2 = c(0.5 / (q.sigma * q.sigma));
    let exact = q.window == Window::Exact;
    let h1 = s.l1 + s.d1;
    let steep = math::max(math::abs(s.l1), math::abs(h1));
    let p = f.p_t + c(s.um);
    let freq = f.xi2 + f.nu;
    // Panels along: the phase of ξ₁u and of the chord's ends, and the window's log-slope.
    let rate = c(math::TAU) * (f.xi1.abs() + freq.abs() * c(steep))
        + (p.abs() + c(s.h)) * c(2.0) * inv_2s2;
    let panels = panels_for(rate * c(2.0 * s.h));
    let frozen_across = f.p_b - c(g.off_b);
    let mut j = 0.0f32;
    while c(j).lt(panels).any() {
        let mut node = 0;
        while node < 4 {
            let (t, wt) = panel_node(j, node, panels);
            let (xs, wt) = (c(s.h) * (c(2.0) * t - c(1.0)), c(2.0 * s.h) * wt);
            let lo = c(s.lo) + c(s.l1) * xs;
            let half = c(0.5) * (c(s.d) + c(s.d1) * xs);
            let mid = lo + half;
            let chord = if exact {
                math::gauss_fourier_reduced_lanes(f.p_b + mid, half, c(q.sigma), freq)
            } else {
                Cx::real(
                    c(2.0)
                        * half
                        * math::sinc_pi_lanes(c(2.0) * freq * half)
                        * (-(frozen_across * frozen_across) * inv_2s2).exp(),
                )
            };
            let u = p + xs;
            let phase = math::cis_pi_lanes(
                c(-2.0) * (f.xi1 * (c(s.um) + xs) + f.xi2 * mid + f.nu * (mid + c(g.off_b))),
            );
            sum = sum + (phase * chord).scale(wt * (-(u * u) * inv_2s2).exp());
            node += 1;
        }
        j += 1.0;
    }
    sum
}

/// Node `node` (0–3) of panel `j` of `panels` equal panels over `[0, 1]`: its position and
/// 4-point Gauss–Legendre weight, the weight 0 in lanes with fewer panels.
#[inline(always)]
fn panel_node<R: Real>(j: f32, node: usize, panels: R) -> (R, R) {
    let c = R::splat;
    // Nodes −x₀, −x₁, x₀, x₁ (constant indices: no bounds check, as [`load`]).
    let (x, w) = if node == 0 || node == 2 {
        (GL4_X[0], GL4_W[0])
    } else {
        (GL4_X[1], GL4_W[1])
    };
    let x = if node < 2 { -x } else { x };
    let live = c(j).lt(panels);
    (
        c(j + 0.5 + 0.5 * x) / panels,
        R::select(live, c(0.5 * w) / panels, c(0.0)),
    )
}

/// Panels for a phase-and-window change of `span` radians across an interval: at most
/// [`PANEL_RADIANS`] each, at most [`MAX_PANELS`], 1 where the inputs are not finite.
#[inline(always)]
fn panels_for<R: Real>(span: R) -> R {
    let c = R::splat;
    let want = (span * c(1.0 / PANEL_RADIANS)).floor() + c(1.0);
    let panels = math::min(want, c(MAX_PANELS));
    R::select(panels.is_finite(), panels, c(1.0))
}

/// `∫_{−h}^{h} (d + d1 x) e^{−(μ + x)²/(2σ²)} e^{−2πi f x} dx`: the reduced interval
/// integral `I` ([`math::gauss_fourier_reduced_lanes`]) and its first moment, by parts
/// (`(μ + x) e^{−(μ+x)²/2σ²} = −σ² ∂ₓ e^{−(μ+x)²/2σ²}`).
#[inline(always)]
fn line_integral<R: Real>(mu: R, h: R, sigma: R, f: R, d: R, d1: R) -> Cx<R> {
    let c = R::splat;
    let i0 = math::gauss_fourier_reduced_lanes(mu, h, sigma, f);
    let s2 = sigma * sigma;
    let inv = c(-0.5) / s2;
    let (e_hi, e_lo) = (
        ((mu + h) * (mu + h) * inv).exp(),
        ((mu - h) * (mu - h) * inv).exp(),
    );
    let turn = math::cis_pi_lanes(c(-2.0) * f * h);
    // ∫ (μ + x) g = −σ² [e e^{−2πifx}]_{−h}^{h} − 2πi f σ² I
    let ends = turn.scale(e_hi) - turn.conj().scale(e_lo);
    let by_parts = ends.scale(-s2) - i0.mul_i().scale(c(math::TAU) * f * s2);
    let first = by_parts - i0.scale(mu);
    i0.scale(d) + first.scale(d1)
}
