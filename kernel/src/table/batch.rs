//! The SIMD backend's batch of table queries (CPU only): `N` queries per instruction
//! stream, sharing the material interface's set-up ([`BsdfMaterial::from_table`],
//! [`crate::bsdf::eval::upper_directions`], its phases and reflectance) and the one formula
//! ([`model_value_lanes`]) with [`evaluate`].

use super::{TableParams, TableQuery, evaluate};
use crate::bsdf::eval::{spectral_phases, upper_directions};
use crate::bsdf::scratch_models::model_value_lanes;
use crate::bsdf::{BsdfMaterial, Wavelengths};
use crate::lane::Lanes;
use crate::material::Reflectance;
use crate::scratch::{LaneUse, ResponseInputs, ScratchSet, scratch_response_batch};
use crate::units::um_from_nm;
use glam::{Vec2, Vec3};

/// [`evaluate`] for `N` queries at once: one walk over the scratches near all `N` shading
/// points ([`scratch_response_batch`]), the scratch terms and the model in lanes, the
/// per-query set-up (directions, ξ, reflectance) one query at a time as in [`evaluate`]. A
/// query whose shading point is not finite is evaluated on its own by [`evaluate`] (it has
/// no place in the batch's lookup circle).
///
/// `#[inline(always)]`, as every lane function, so that the walk and the model compile to
/// the instruction set of the caller (the SIMD backend's AVX2 + FMA dispatch); the scalar
/// set-up and the lone queries are kept out of line (`prepare`, `finish`), so that the
/// inlined code stays the lanes' arithmetic.
///
/// `INLINE_EXACT`: the exact window's term inline ([`scratch_response_batch`]), for an
/// instance of its own that serves tables with `window: exact`.
#[inline(always)]
pub fn evaluate_batch<S: ScratchSet, const N: usize, const INLINE_EXACT: bool>(
    params: &TableParams,
    qs: &[TableQuery; N],
    set: &S,
    lane_use: &mut LaneUse,
) -> [f32; N] {
    // The table's model and options (each query brings its own F).
    let m = &BsdfMaterial::from_table(params, qs[0].material);
    let prepared = prepare(m, qs);
    let Some(first) = prepared.iter().flatten().copied().find(Prepared::in_lanes) else {
        return finish(params, qs, set, &prepared, [0.0; N]);
    };
    // Lanes without a query for the walk compute the first one's value (and report their
    // own).
    let p = prepared.map(|p| p.filter(Prepared::in_lanes).unwrap_or(first));
    let lanes = |f: fn(&Prepared) -> f32| Lanes(p.each_ref().map(f));
    let xi = [lanes(|p| p.xi.x), lanes(|p| p.xi.y)];
    let inputs = ResponseInputs {
        x0: [lanes(|p| p.x0.x), lanes(|p| p.x0.y)],
        xi,
        depth_half_turns_per_um: lanes(|p| p.depth),
        sigma: m.sigma_um,
        eta: m.eta_mode(),
        window: m.window(),
        crossings: m.crossings(),
        area_density: m.needs_area_density(),
    };
    let terms = scratch_response_batch::<S, N, INLINE_EXACT>(set, &inputs, lane_use);
    let v = model_value_lanes(
        m.table_model(),
        m.base_gaussian == 1,
        &terms,
        xi,
        m.sigma_um,
        lanes(|p| p.f),
        lanes(|p| p.lambda),
    );
    finish(params, qs, set, &prepared, v.0)
}

/// Every query's set-up ([`Prepared::of`]), out of line.
#[inline(never)]
fn prepare<const N: usize>(m: &BsdfMaterial, qs: &[TableQuery; N]) -> [Option<Prepared>; N] {
    qs.each_ref().map(|q| Prepared::of(m, q))
}

/// The batch's results: the lanes' values `v` for the queries in the lanes, 0 for a query
/// without a value, and [`evaluate`] for a query outside the lanes (out of line).
#[inline(never)]
fn finish<S: ScratchSet, const N: usize>(
    params: &TableParams,
    qs: &[TableQuery; N],
    set: &S,
    prepared: &[Option<Prepared>; N],
    v: [f32; N],
) -> [f32; N] {
    core::array::from_fn(|i| match prepared[i] {
        None => 0.0,
        Some(p) if p.in_lanes() => v[i],
        Some(_) => evaluate(params, &qs[i], set),
    })
}

/// One query's set-up: what [`crate::bsdf::eval::scratch_point_values`] forms for its one
/// wavelength before the scratch walk.
#[derive(Clone, Copy, Debug)]
struct Prepared {
    /// Shading point (µm).
    x0: Vec2,
    /// ξ (1/µm).
    xi: Vec2,
    /// The depth phase per µm of depth.
    depth: f32,
    /// Reflectance F.
    f: f32,
    /// λ (µm).
    lambda: f32,
}

impl Prepared {
    /// Whether the query can share the batch's walk (its shading point is finite).
    #[inline]
    fn in_lanes(&self) -> bool {
        self.x0.is_finite()
    }

    /// The set-up, or `None` for a query whose value is 0 (below the horizon, degenerate
    /// direction, σ or λ not positive).
    #[inline]
    fn of(m: &BsdfMaterial, q: &TableQuery) -> Option<Prepared> {
        let (wi, wo) = upper_directions(Vec3::from_array(q.wi), Vec3::from_array(q.wo))?;
        let lambda = um_from_nm(q.lambda_nm);
        if !(m.sigma_um > 0.0 && lambda > 0.0) {
            return None;
        }
        let (xi, depth) = spectral_phases(m, wi, wo, &Wavelengths::single(q.lambda_nm));
        Some(Prepared {
            x0: Vec2::from_array(q.x),
            xi: xi[0],
            depth: depth[0],
            f: Reflectance::new(&q.material, wi, wo).at(q.lambda_nm),
            lambda,
        })
    }
}
