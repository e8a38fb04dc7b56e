//! Numerical reference for the area-light integrals: `∫_light f_r cos θi dωi` by nested
//! globally-adaptive Gauss–Kronrod (7/15) quadrature in direction-cosine space, with an
//! error estimate.
//!
//! Independent of the kernel's closed form ([`scratchwave_kernel::lights`]) except for the
//! BRDF itself, which is the kernel's own `table::evaluate` (model `velinov`, one scratch):
//! the reference tests the *integration* (band model, crossings, clipping, Jacobian), not
//! `f_r`. Geometry is redone here in `f64` from the light record with plain inside tests
//! (angle to the axis; point in a fan triangle), no crossing points.
//!
//! Coordinates: `u = (wi + wo)_xy` in the scratch frame (`u1` along `t`, `u2` along `b`);
//! `cos θi dωi = du1 du2` (Velinov Eqs. 23–24). The inner integral runs over `u1` across the
//! Gaussian band (±8 standard deviations, split at its centre and at ±2, ±6), cut into its lit
//! pieces by bisecting the inside test, so the adaptive rule integrates smooth functions; the
//! outer over `u2` across the light's bounding box (sampled, padded), split at the first sinc
//! zeros.

use scratchwave_kernel::lights::{Cone, LightKind, LightParams, LightQuery};
use scratchwave_kernel::scratch::{Scratch, ScratchSlice};
use scratchwave_kernel::table::{Model, TableParams, TableQuery, evaluate};
use std::collections::BinaryHeap;

/// A reference value with its estimated absolute error.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Reference {
    /// `∫ f_r cos θi dωi` (unit radiance).
    pub value: f64,
    /// Estimated absolute error (Kronrod − Gauss differences, inner errors propagated).
    pub err: f64,
    /// BRDF evaluations used.
    pub evals: u64,
}

use crate::dvec::{basis, unit};
use glam::DVec3;

/// The light's solid angle in `f64`, with an inside test only.
#[derive(Clone, Debug)]
pub enum RefRegion {
    /// Cone around `axis` of half-angle `alpha` (π: everything).
    Cone {
        /// Unit axis.
        axis: DVec3,
        /// Half-angle.
        alpha: f64,
    },
    /// Fan of spherical triangles `(c, u_m, u_{m+1})`.
    Fan {
        /// Unit vertex directions.
        u: Vec<DVec3>,
        /// Normalised mean direction.
        c: DVec3,
    },
    /// Nothing (degenerate).
    Empty,
}

impl RefRegion {
    /// From a kernel light record (same interpretation as the kernel, rebuilt in `f64`).
    pub fn new(q: &LightQuery) -> RefRegion {
        let l = &q.light;
        if LightKind::from_u32(l.kind) == LightKind::Polygon {
            let n = (l.count as usize).min(l.vertices.len());
            if n < 3 {
                return RefRegion::Empty;
            }
            let u: Vec<DVec3> = l.vertices[..n]
                .iter()
                .map(|v| unit(DVec3::new(v[0] as f64, v[1] as f64, v[2] as f64)))
                .collect();
            let s = u.iter().fold(DVec3::ZERO, |a, b| a + *b);
            RefRegion::Fan { c: unit(s), u }
        } else {
            let c = DVec3::new(l.sphere[0] as f64, l.sphere[1] as f64, l.sphere[2] as f64);
            let r = l.sphere[3] as f64;
            let d = c.dot(c).sqrt();
            if !(r > 0.0) || (d == 0.0 && Cone::from_u32(l.cone) == Cone::Atan) {
                return RefRegion::Empty;
            }
            let alpha = match Cone::from_u32(l.cone) {
                Cone::Asin if d <= r => std::f64::consts::PI,
                Cone::Asin => (r / d).asin(),
                Cone::Atan => r.atan2(d),
            };
            RefRegion::Cone {
                axis: unit(c),
                alpha,
            }
        }
    }

    /// Whether the unit direction `w` is inside.
    pub fn contains(&self, w: DVec3) -> bool {
        match self {
            RefRegion::Cone { axis, alpha } => {
                *alpha >= std::f64::consts::PI || w.dot(*axis).clamp(-1.0, 1.0).acos() <= *alpha
            }
            RefRegion::Fan { u, c } => (0..u.len()).any(|m| {
                let (a, b) = (u[m], u[(m + 1) % u.len()]);
                let det = a.cross(b).dot(*c);
                if det.abs() < 1e-15 {
                    return false;
                }
                let o = det.signum();
                o * c.cross(a).dot(w) >= 0.0
                    && o * a.cross(b).dot(w) >= 0.0
                    && o * b.cross(*c).dot(w) >= 0.0
            }),
            RefRegion::Empty => false,
        }
    }

    /// Sample directions covering the region (for bounding boxes).
    pub fn samples(&self) -> Vec<DVec3> {
        let mut out = Vec::new();
        match self {
            RefRegion::Cone { axis, alpha } => {
                let a = *axis;
                let (e1, e2) = basis(a);
                for i in 0..=64 {
                    let th = alpha * i as f64 / 64.0;
                    for j in 0..128 {
                        let ph = std::f64::consts::TAU * j as f64 / 128.0;
                        let (st, ct) = th.sin_cos();
                        let (sp, cp) = ph.sin_cos();
                        out.push(unit(ct * a + st * (cp * e1 + sp * e2)));
                    }
                }
            }
            RefRegion::Fan { u, c } => {
                let k = 48;
                for m in 0..u.len() {
                    let (a, b) = (u[m], u[(m + 1) % u.len()]);
                    for i in 0..=k {
                        for j in 0..=(k - i) {
                            let (x, y) = (i as f64 / k as f64, j as f64 / k as f64);
                            let z = 1.0 - x - y;
                            out.push(unit(x * a + y * b + z * *c));
                        }
                    }
                }
            }
            RefRegion::Empty => {}
        }
        out
    }
}

/// Gauss–Kronrod 7/15 nodes (positive half, Kronrod order) and weights.
const XK: [f64; 8] = [
    0.991455371120812639,
    0.949107912342758525,
    0.864864423359769073,
    0.741531185599394440,
    0.586087235467691130,
    0.405845151377397167,
    0.207784955007898468,
    0.000000000000000000,
];
const WK: [f64; 8] = [
    0.022935322010529225,
    0.063092092629978553,
    0.104790010322250184,
    0.140653259715525919,
    0.169004726639267903,
    0.190350578064785410,
    0.204432940075298892,
    0.209482141084727828,
];
const WG: [f64; 4] = [
    0.129484966168869693,
    0.279705391489276668,
    0.381830050505118945,
    0.417959183673469388,
];

/// One GK15 panel of `f` (returning `(value, inner error)`): `(K15, |K15 − G7|, Σ w·err)`.
fn gk15<F: FnMut(f64) -> (f64, f64)>(f: &mut F, a: f64, b: f64) -> (f64, f64, f64) {
    let (c, h) = (0.5 * (a + b), 0.5 * (b - a));
    let (mut k, mut g, mut e) = (0.0, 0.0, 0.0);
    for i in 0..8 {
        let pts: &[f64] = if i == 7 { &[0.0] } else { &[-1.0, 1.0] };
        for s in pts {
            let (v, ve) = f(c + s * h * XK[i]);
            k += WK[i] * v;
            e += WK[i] * ve;
            if i % 2 == 1 {
                g += WG[i / 2] * v;
            }
        }
    }
    (k * h, ((k - g) * h).abs(), e * h.abs())
}

#[derive(PartialEq)]
struct Panel {
    err: f64,
    a: f64,
    b: f64,
    val: f64,
    inner: f64,
}
impl Eq for Panel {}
impl PartialOrd for Panel {
    fn partial_cmp(&self, o: &Self) -> Option<std::cmp::Ordering> {
        Some(self.cmp(o))
    }
}
impl Ord for Panel {
    fn cmp(&self, o: &Self) -> std::cmp::Ordering {
        (self.err + self.inner).total_cmp(&(o.err + o.inner))
    }
}

/// Globally adaptive GK15 of `f` over the sorted `breaks`, to absolute `tol`.
/// Returns `(value, error estimate)`.
fn adaptive<F: FnMut(f64) -> (f64, f64)>(
    f: &mut F,
    breaks: &[f64],
    tol: f64,
    max_panels: usize,
) -> (f64, f64) {
    let mut heap = BinaryHeap::new();
    for w in breaks.windows(2) {
        if w[1] > w[0] {
            let (val, err, inner) = gk15(f, w[0], w[1]);
            heap.push(Panel {
                err,
                a: w[0],
                b: w[1],
                val,
                inner,
            });
        }
    }
    let total = |h: &BinaryHeap<Panel>| {
        h.iter()
            .fold((0.0, 0.0), |s, p| (s.0 + p.val, s.1 + p.err + p.inner))
    };
    let mut n = heap.len();
    loop {
        let (_, err) = total(&heap);
        if err <= tol || n >= max_panels {
            break;
        }
        let Some(p) = heap.pop() else { break };
        if p.err <= p.inner * 0.01 || p.b - p.a < 1e-13 {
            heap.push(p); // its error is the inner integrals': splitting cannot help
            break;
        }
        let m = 0.5 * (p.a + p.b);
        for (a, b) in [(p.a, m), (m, p.b)] {
            let (val, err, inner) = gk15(f, a, b);
            heap.push(Panel {
                err,
                a,
                b,
                val,
                inner,
            });
        }
        n += 1;
    }
    total(&heap)
}

/// `∫_light f_r cos θi dωi` for one scratch by nested adaptive quadrature, to about
/// `rel_tol` of the result (or of the band's peak scale when the result is ~0).
pub fn light_reference(
    params: &LightParams,
    q: &LightQuery,
    scratch: &Scratch,
    rel_tol: f64,
) -> Reference {
    light_reference_budget(params, q, scratch, rel_tol, 4000)
}

/// The kernel's incoherent (velinov) table BRDF of one scratch, in 1/sr without the cosine,
/// for the view, wavelength, shading point and material of `q`, as a function of the
/// incident direction: the integrand of the reference and of Monte Carlo light sampling.
pub fn scratch_brdf<'a>(
    params: &LightParams,
    q: &'a LightQuery,
    scratch: &'a Scratch,
) -> impl Fn(DVec3) -> f64 + 'a {
    let tp = TableParams {
        model: Model::Velinov as u32,
        eta: params.eta,
        depth_term: params.depth_term,
        sigma_um: params.sigma_um,
        ..TableParams::default()
    };
    move |wi: DVec3| {
        let tq = TableQuery {
            wi: [wi[0] as f32, wi[1] as f32, wi[2] as f32],
            lambda_nm: q.lambda_nm,
            wo: q.wo,
            x: q.x,
            material: q.material,
            ..TableQuery::default()
        };
        let set = ScratchSlice {
            scratches: std::slice::from_ref(scratch),
        };
        evaluate(&tp, &tq, &set) as f64
    }
}

/// [`light_reference`] with at most `max_panels` panels per adaptive integral (inner and
/// outer); when the budget ends first, `err` says how far the tolerance was missed.
pub fn light_reference_budget(
    params: &LightParams,
    q: &LightQuery,
    scratch: &Scratch,
    rel_tol: f64,
    max_panels: usize,
) -> Reference {
    let region = RefRegion::new(q);
    let wo = {
        let w = DVec3::new(q.wo[0] as f64, q.wo[1] as f64, q.wo[2] as f64);
        unit(w)
    };
    let (dx, dy) = (scratch.tangent[0] as f64, scratch.tangent[1] as f64);
    let tl = (dx * dx + dy * dy).sqrt();
    let len = 2.0 * scratch.half_len as f64;
    if !(len > 0.0 && tl > 0.0 && wo[2] > 0.0) || matches!(region, RefRegion::Empty) {
        return Reference::default();
    }
    let t = [dx / tl, dy / tl];
    let b = [-t[1], t[0]];
    let brdf = scratch_brdf(params, q, scratch);
    let evals = std::cell::Cell::new(0u64);
    let wi_of = |u1: f64, u2: f64| -> Option<DVec3> {
        let x = u1 * t[0] + u2 * b[0] - wo[0];
        let y = u1 * t[1] + u2 * b[1] - wo[1];
        let r2 = x * x + y * y;
        (r2 < 1.0).then(|| DVec3::new(x, y, (1.0 - r2).sqrt()))
    };
    let fr = |wi: DVec3| -> f64 {
        evals.set(evals.get() + 1);
        brdf(wi)
    };
    let f = |u1: f64, u2: f64| -> f64 {
        match wi_of(u1, u2) {
            Some(wi) if region.contains(wi) => fr(wi),
            _ => 0.0,
        }
    };
    // Bounding box of the lit u.
    let (mut lo1, mut hi1, mut lo2, mut hi2) = (f64::MAX, f64::MIN, f64::MAX, f64::MIN);
    for w in region.samples() {
        if w[2] < -0.05 {
            continue;
        }
        let (ux, uy) = (w[0] + wo[0], w[1] + wo[1]);
        let (u1, u2) = (ux * t[0] + uy * t[1], ux * b[0] + uy * b[1]);
        lo1 = lo1.min(u1);
        hi1 = hi1.max(u1);
        lo2 = lo2.min(u2);
        hi2 = hi2.max(u2);
    }
    if !(hi1 >= lo1 && hi2 >= lo2) {
        return Reference::default();
    }
    let pad = |lo: f64, hi: f64| {
        let p = 0.02 * (hi - lo) + 1e-4;
        ((lo - p).max(-2.0), (hi + p).min(2.0))
    };
    let ((lo1, hi1), (lo2, hi2)) = (pad(lo1, hi1), pad(lo2, hi2));
    let lambda = q.lambda_nm as f64 * 1e-3;
    let sigma = params.sigma_um as f64;
    // Standard deviation of |η|² along u1 (infinite scratch), widened for short segments.
    let sd =
        lambda / (2.0 * std::f64::consts::SQRT_2 * std::f64::consts::PI * sigma) + lambda / len;
    let breaks = |lo: f64, hi: f64, pts: &[f64]| -> Vec<f64> {
        let mut v = vec![lo, hi];
        v.extend(pts.iter().copied().filter(|p| *p > lo && *p < hi));
        v.sort_by(f64::total_cmp);
        v
    };
    let b1 = breaks(lo1, hi1, &[-6.0 * sd, -2.0 * sd, 0.0, 2.0 * sd, 6.0 * sd]);
    let w = (scratch.width as f64).max(1e-3);
    // Outer: 32 equal panels across the light plus the first sinc zeros, so no panel is
    // wider than a 32nd of the light (a coarser start let GK15 settle on a wrong value with
    // a small error estimate for lights a few band widths across).
    let mut outer_pts: Vec<f64> = (-4..=4).map(|k| k as f64 * lambda / w).collect();
    outer_pts.extend((1..32).map(|k| lo2 + (hi2 - lo2) * k as f64 / 32.0));
    let b2 = breaks(lo2, hi2, &outer_pts);
    // Scale: the peak BRDF times the band's area in u.
    let peak = {
        let m = DVec3::new(-wo[0], -wo[1], wo[2]);
        fr(m) * sd * 2.5 * (lambda / w).min(hi2 - lo2)
    };
    // Inner range: the band's ±8 standard deviations (|η|² < e^{−32} of its peak beyond,
    // for segments reaching ≥ 5σ past the shading point either way).
    let (a1, z1) = (lo1.max(-8.0 * sd), hi1.min(8.0 * sd));
    let lit = |u1: f64, u2: f64| wi_of(u1, u2).is_some_and(|wi| region.contains(wi));
    // The lit pieces of the inner line: the inside test on a 256-point grid, each change
    // located by 60 bisections, so the adaptive rule only ever sees smooth integrands.
    let pieces = |u2: f64| -> Vec<(f64, f64)> {
        let mut out = Vec::new();
        if !(z1 > a1) {
            return out;
        }
        let n = 256;
        let x = |i: usize| a1 + (z1 - a1) * i as f64 / n as f64;
        let mut start = lit(a1, u2).then_some(a1);
        let mut prev = (a1, start.is_some());
        for i in 1..=n {
            let xi = x(i);
            let now = lit(xi, u2);
            if now != prev.1 {
                let (mut lo, mut hi) = (prev.0, xi);
                for _ in 0..60 {
                    let m = 0.5 * (lo + hi);
                    if lit(m, u2) == prev.1 { lo = m } else { hi = m }
                }
                let edge = 0.5 * (lo + hi);
                match start.take() {
                    Some(s0) => out.push((s0, edge)),
                    None => start = Some(edge),
                }
            }
            prev = (xi, now);
        }
        if let Some(s0) = start {
            out.push((s0, z1));
        }
        out
    };
    let run = |tol: f64, max_panels: usize| {
        let mut outer = |u2: f64| {
            let mut inner = |u1: f64| (f(u1, u2), 0.0);
            let (mut v, mut e) = (0.0, 0.0);
            for (p, q) in pieces(u2) {
                let mut br: Vec<f64> = (0..=4).map(|k| p + (q - p) * k as f64 / 4.0).collect();
                br.extend(b1.iter().copied().filter(|x| *x > p && *x < q));
                br.sort_by(f64::total_cmp);
                let (pv, pe) = adaptive(&mut inner, &br, 0.1 * tol / (hi2 - lo2), max_panels);
                v += pv;
                e += pe;
            }
            (v, e)
        };
        adaptive(&mut outer, &b2, 0.9 * tol, max_panels)
    };
    let (rough, _) = run(1e-2 * peak.max(1e-300), 200);
    let tol = rel_tol * rough.abs().max(1e-4 * peak).max(1e-300);
    let (value, err) = run(tol, max_panels);
    Reference {
        value,
        err,
        evals: evals.get(),
    }
}
