//! Seeded random area-light configurations (scratch, view, light) for the accuracy sweep,
//! the stability sweep and the speed-vs-accuracy chart.
//!
//! Every configuration is built so that the band ξ₁ = 0 crosses the light: a direction
//! `wi_p` inside the light (above the horizon) is drawn first and the view is chosen with
//! `(wi_p + wo)_xy · t = 0`. Light sizes, distances, elevations (down to partly below the
//! horizon) and scratch orientations are drawn from the ranges in [`SweepRanges`].

use crate::dvec::{basis_from, unit};
use glam::DVec3;
use scratchwave_kernel::lights::{
    Cone, Light, LightParams, LightQuery, MAX_VERTICES, SiMode, light_integral,
};
use scratchwave_kernel::material::Material;
use scratchwave_kernel::scratch::{Profile, Scratch, ScratchSlice};

/// The sweeps' generator (seeded, so every sweep replays exactly).
pub use scratchwave_host::rng::SplitMix64 as Rng;

/// What was drawn, for reports.
#[derive(Clone, Copy, Debug, Default)]
pub struct CaseMeta {
    /// Angular radius of the light (rad; polygons: of the circumscribed cone).
    pub alpha: f64,
    /// Elevation of the light centre above the horizon (rad).
    pub elevation: f64,
    /// Scratch direction (rad from +x).
    pub scratch_angle: f64,
    /// Number of polygon vertices (0: sphere).
    pub vertices: usize,
}

/// One configuration.
#[derive(Clone, Copy, Debug)]
pub struct LightCase {
    /// Options.
    pub params: LightParams,
    /// The query (view, wavelength, shading point, light).
    pub query: LightQuery,
    /// The one scratch.
    pub scratch: Scratch,
    /// What was drawn.
    pub meta: CaseMeta,
}

impl LightCase {
    /// The kernel's closed form for this configuration with Si method `si` and band rule
    /// `bands` (see `LightParams::bands`).
    pub fn closed_form(&self, si: SiMode, bands: u32) -> f32 {
        let params = LightParams {
            si_mode: si as u32,
            bands,
            ..self.params
        };
        let set = ScratchSlice {
            scratches: std::slice::from_ref(&self.scratch),
        };
        light_integral(&params, &self.query, &set)
    }
}

/// Ranges of a sweep.
#[derive(Clone, Copy, Debug)]
pub struct SweepRanges {
    /// Angular radius α of the light (rad), log-uniform.
    pub alpha: (f64, f64),
    /// Lowest centre elevation as a multiple of −α (1: touching the horizon from below).
    pub below: f64,
    /// Probability of a polygon (else a sphere).
    pub polygon: f64,
}

impl Default for SweepRanges {
    fn default() -> Self {
        SweepRanges {
            alpha: (0.05, 0.6),
            below: 0.7,
            polygon: 0.5,
        }
    }
}

/// The sweep's basis about a light direction (`e1` from `dir × ẑ`, or `dir × x̂` near the
/// pole). It differs from [`crate::dvec::basis`] only in the helper axis; it is kept so the
/// seeded sweeps replay the configurations their published numbers came from.
fn sweep_basis(dir: DVec3) -> (DVec3, DVec3) {
    let helper = if dir.z.abs() < 0.9 {
        DVec3::Z
    } else {
        DVec3::X
    };
    basis_from(dir, helper)
}

/// Draws one configuration whose band crosses the light.
pub fn random_case(rng: &mut Rng, ranges: &SweepRanges, eta: u32) -> LightCase {
    loop {
        if let Some(c) = try_case(rng, ranges, eta) {
            return c;
        }
    }
}

fn try_case(rng: &mut Rng, ranges: &SweepRanges, eta: u32) -> Option<LightCase> {
    let alpha = rng.log_range_f64(ranges.alpha.0, ranges.alpha.1);
    let elevation = rng.range_f64(-ranges.below * alpha, 1.5);
    let azimuth = rng.range_f64(0.0, std::f64::consts::TAU);
    let dir = DVec3::new(
        elevation.cos() * azimuth.cos(),
        elevation.cos() * azimuth.sin(),
        elevation.sin(),
    );
    let dist = rng.log_range_f64(1.0, 100.0);
    let center = dir * dist;
    let is_poly = rng.next_f64() < ranges.polygon;
    let (light, vertices, wi_p) = if is_poly {
        // A radially jittered n-gon, tilted up to 50° away from facing the point.
        let n = 3 + (rng.next_f64() * 6.0) as usize;
        let r = dist * alpha.tan();
        let (e1, e2) = sweep_basis(dir);
        let tilt = rng.range_f64(0.0, 0.87);
        let (st, ct) = tilt.sin_cos();
        let n_axis = ct * dir + st * e1;
        let a1 = unit(n_axis.cross(e2));
        let rot = rng.range_f64(0.0, std::f64::consts::TAU);
        let mut vs = Vec::new();
        for k in 0..n {
            let ph = rot + std::f64::consts::TAU * k as f64 / n as f64;
            let rr = r * rng.range_f64(0.8, 1.2);
            let (s, c) = ph.sin_cos();
            vs.push((center + rr * (c * a1 + s * e2)).as_vec3().to_array());
        }
        // A point inside: random fan triangle, random barycentric.
        let k = (rng.next_f64() * n as f64) as usize % n;
        let (mut x, mut y) = (rng.next_f64(), rng.next_f64());
        if x + y > 1.0 {
            (x, y) = (1.0 - x, 1.0 - y);
        }
        let a = DVec3::from_array(vs[k].map(f64::from));
        let b = DVec3::from_array(vs[(k + 1) % n].map(f64::from));
        let p = center + x * (a - center) + y * (b - center);
        debug_assert!(n <= MAX_VERTICES);
        (Light::polygon(&vs), n, unit(p))
    } else {
        let cone = if rng.next_f64() < 0.5 {
            Cone::Asin
        } else {
            Cone::Atan
        };
        let r = match cone {
            Cone::Asin => dist * alpha.sin(),
            Cone::Atan => dist * alpha.tan(),
        };
        // A direction inside the cone.
        let (e1, e2) = sweep_basis(dir);
        let th = alpha * rng.next_f64().sqrt();
        let ph = rng.range_f64(0.0, std::f64::consts::TAU);
        let (st, ct) = th.sin_cos();
        let p = ct * dir + st * (ph.cos() * e1 + ph.sin() * e2);
        let light = Light::sphere(center.as_vec3().to_array(), r as f32, cone);
        (light, 0, p)
    };
    if wi_p.z < 0.02 {
        return None;
    }
    let scratch_angle = rng.range_f64(0.0, std::f64::consts::PI);
    let t = [scratch_angle.cos(), scratch_angle.sin()];
    let b = [-t[1], t[0]];
    let c = -(wi_p.x * t[0] + wi_p.y * t[1]);
    let room = 0.95 - c * c;
    if room <= 0.0 {
        return None;
    }
    let wb = rng.range_f64(-room.sqrt(), room.sqrt());
    let wx = c * t[0] + wb * b[0];
    let wy = c * t[1] + wb * b[1];
    let wo = [wx, wy, (1.0 - wx * wx - wy * wy).sqrt()];
    let sb = rng.range_f64(-10.0, 10.0);
    let scratch = Scratch::from_endpoints(
        [-150.0 * t[0] + sb * b[0], -150.0 * t[1] + sb * b[1]],
        [150.0 * t[0] + sb * b[0], 150.0 * t[1] + sb * b[1]],
        rng.log_range_f64(0.2, 5.0) as f32,
        rng.range_f64(0.02, 0.5) as f32,
        Profile::Rect,
    );

    let query = LightQuery {
        wo: wo.map(|v| v as f32),
        lambda_nm: rng.range_f64(380.0, 780.0) as f32,
        x: [0.0, 0.0],
        material: Material::constant(1.0),
        light,
        ..LightQuery::default()
    };
    let params = LightParams {
        sigma_um: 10.0,
        eta,
        ..LightParams::default()
    };
    Some(LightCase {
        params,
        query,
        scratch,
        meta: CaseMeta {
            alpha,
            elevation,
            scratch_angle,
            vertices,
        },
    })
}

/// Distance between the cells of a [`grid_batch`] (µm): the sweep's scratches are 300 µm
/// long within 10 µm of their cell's centre, σ = 10 µm.
pub const GRID_CELL_UM: f32 = 1000.0;
/// Cells per row of a [`grid_batch`].
const GRID_ROW: usize = 100;

/// `count` sweep configurations as one batch over one scratch set: configuration `k`'s
/// scratch and shading point move to a cell of their own on a grid ([`GRID_CELL_UM`]
/// apart, beyond the 6σ lookup radius of every other cell), so a single scratch lookup
/// serves every query and each query sees exactly its own scratch. Odd configurations use
/// the V-groove (triangle) profile. Returns the options of the first configuration (the
/// sweep's are all alike), the scratches and the queries.
pub fn grid_batch(
    rng: &mut Rng,
    ranges: &SweepRanges,
    eta: u32,
    count: usize,
) -> (LightParams, Vec<Scratch>, Vec<LightQuery>) {
    let mut params = LightParams::default();
    let mut scratches = Vec::with_capacity(count);
    let mut queries = Vec::with_capacity(count);
    for k in 0..count {
        let c = random_case(rng, ranges, eta);
        let offset = [
            (k % GRID_ROW) as f32 * GRID_CELL_UM,
            (k / GRID_ROW) as f32 * GRID_CELL_UM,
        ];
        let mut s = c.scratch;
        s.center = [s.center[0] + offset[0], s.center[1] + offset[1]];
        if k % 2 == 1 {
            s.profile = Profile::Triangle as u32;
        }
        let mut q = c.query;
        q.x = [q.x[0] + offset[0], q.x[1] + offset[1]];
        scratches.push(s);
        queries.push(q);
        if k == 0 {
            params = c.params;
        }
    }
    (params, scratches, queries)
}
