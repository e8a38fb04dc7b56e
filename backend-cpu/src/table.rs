//! BRDF tables and footprint tables on the CPU.

use crate::lanes::{LANES, LaneFn, map_lanes, map_lanes_baseline};
use crate::parallel::{Backend, map};
use scratchwave_host::{FootprintRow, ScratchLookup};
use scratchwave_kernel::footprint::Ellipse;
use scratchwave_kernel::ghs::g1::G1Table;
use scratchwave_kernel::ghs::{self, GhsParams};
use scratchwave_kernel::lane::{Lanes, V3};
use scratchwave_kernel::scratch::response::CUTOFF_SIGMAS;
use scratchwave_kernel::scratch::{LaneUse, Scratch, ScratchBvh, Window};
use scratchwave_kernel::table::{TableParams, TableQuery, evaluate, evaluate_batch, evaluate_ghs};
use scratchwave_kernel::units::direction;
use std::sync::atomic::{AtomicU64, Ordering};

/// Evaluates every query against the scratch set (through the BVH lookup, built once).
///
/// The SIMD backends sort the queries by shading point ([`locality_order`]) and evaluate
/// them in batches of [`LANES`] that share one walk over their scratches
/// ([`evaluate_batch`]); the results come back in the input order.
pub fn evaluate_table(
    backend: Backend,
    params: &TableParams,
    scratches: &[Scratch],
    queries: &[TableQuery],
) -> Vec<f32> {
    evaluate_table_counted(backend, params, scratches, queries).0
}

/// [`evaluate_table`] and how the lanes were used (zero counts on [`Backend::Scalar`]).
pub fn evaluate_table_counted(
    backend: Backend,
    params: &TableParams,
    scratches: &[Scratch],
    queries: &[TableQuery],
) -> (Vec<f32>, LaneUse) {
    if backend == Backend::Scalar {
        let lookup = ScratchLookup::new(scratches, params.sigma_um);
        let f = ScratchTable::new(params, lookup.set());
        return (map_lanes(backend, queries, &f), LaneUse::default());
    }
    in_sorted_batches(params, scratches, queries, |q, f| map_lanes(backend, q, f))
}

/// [`evaluate_table`]'s lane path on one thread with the baseline instruction set (the
/// run-time dispatch's fallback; see [`crate::lanes::map_lanes_baseline`]).
pub fn evaluate_table_baseline(
    params: &TableParams,
    scratches: &[Scratch],
    queries: &[TableQuery],
) -> Vec<f32> {
    in_sorted_batches(params, scratches, queries, |q, f| map_lanes_baseline(q, f)).0
}

/// `run` over the queries in [`locality_order`], the results put back in input order.
fn in_sorted_batches(
    params: &TableParams,
    scratches: &[Scratch],
    queries: &[TableQuery],
    run: impl Fn(&[TableQuery], &ScratchTable) -> Vec<f32>,
) -> (Vec<f32>, LaneUse) {
    let lookup = ScratchLookup::new(scratches, params.sigma_um);
    let f = ScratchTable::new(params, lookup.set());
    let order = locality_order(queries, CUTOFF_SIGMAS * params.sigma_um);
    let sorted: Vec<TableQuery> = order.iter().map(|&i| queries[i]).collect();
    let values = run(&sorted, &f);
    let mut out = vec![0.0; queries.len()];
    for (&i, v) in order.iter().zip(values) {
        out[i] = v;
    }
    (out, f.lane_use())
}

/// The queries' indices sorted along a Z-order curve of their shading points on a grid of
/// `cell` µm, so that neighbours in the order share their scratch candidates. Points that
/// are not finite go last; ties keep the input order.
pub fn locality_order(queries: &[TableQuery], cell: f32) -> Vec<usize> {
    let inv = if cell > 0.0 && cell.is_finite() {
        1.0 / cell
    } else {
        1.0
    };
    // Grid coordinates offset into u32 (saturating casts; far points share the edge cells).
    let key = |q: &TableQuery| -> u64 {
        let [x, y] = q.x;
        if !(x.is_finite() && y.is_finite()) {
            return u64::MAX;
        }
        let cell = |v: f32| ((v * inv).floor() as i32 as i64 + (1 << 31)) as u32;
        spread_bits(cell(x)) | (spread_bits(cell(y)) << 1)
    };
    // Each key computed once; the index breaks ties, so the unstable sort keeps the input
    // order among equal keys.
    let mut keyed: Vec<(u64, usize)> = queries.iter().map(key).zip(0..).collect();
    keyed.sort_unstable();
    keyed.into_iter().map(|(_, i)| i).collect()
}

/// The 32 bits of `v` at the even bit positions of a u64 (one half of a Morton code).
fn spread_bits(v: u32) -> u64 {
    let mut x = u64::from(v);
    x = (x | (x << 16)) & 0x0000_ffff_0000_ffff;
    x = (x | (x << 8)) & 0x00ff_00ff_00ff_00ff;
    x = (x | (x << 4)) & 0x0f0f_0f0f_0f0f_0f0f;
    x = (x | (x << 2)) & 0x3333_3333_3333_3333;
    (x | (x << 1)) & 0x5555_5555_5555_5555
}

/// [`evaluate`] as a [`LaneFn`] ([`evaluate_batch`] on the lanes), counting lane use.
struct ScratchTable<'a> {
    params: &'a TableParams,
    set: ScratchBvh<'a>,
    use_counts: [AtomicU64; 3],
}

impl<'a> ScratchTable<'a> {
    fn new(params: &'a TableParams, set: ScratchBvh<'a>) -> Self {
        ScratchTable {
            params,
            set,
            use_counts: Default::default(),
        }
    }

    fn lane_use(&self) -> LaneUse {
        let [b, c, l] = &self.use_counts;
        LaneUse {
            batches: b.load(Ordering::Relaxed),
            candidates: c.load(Ordering::Relaxed),
            lanes: l.load(Ordering::Relaxed),
        }
    }
}

impl LaneFn for ScratchTable<'_> {
    type In = TableQuery;
    type Out = f32;
    #[inline(never)]
    fn lanes(&self, q: &[TableQuery; LANES]) -> [f32; LANES] {
        self.batch::<false>(q)
    }
    fn one(&self, q: &TableQuery) -> f32 {
        evaluate(self.params, q, &self.set)
    }
    #[cfg(target_arch = "x86_64")]
    #[inline(always)]
    unsafe fn lanes_avx2(&self, q: &[TableQuery; LANES]) -> [f32; LANES] {
        // SAFETY: the caller detected AVX2 and FMA (the trait's contract).
        unsafe {
            if Window::from_u32(self.params.window) == Window::Exact {
                batch_avx2_exact(self, q)
            } else {
                batch_avx2(self, q)
            }
        }
    }
}

impl ScratchTable<'_> {
    /// [`evaluate_batch`], counting lane use; `INLINE_EXACT` as there.
    #[inline(always)]
    fn batch<const INLINE_EXACT: bool>(&self, q: &[TableQuery; LANES]) -> [f32; LANES] {
        let mut u = LaneUse::default();
        let v = evaluate_batch::<_, LANES, INLINE_EXACT>(self.params, q, &self.set, &mut u);
        let [b, c, l] = &self.use_counts;
        b.fetch_add(u.batches, Ordering::Relaxed);
        c.fetch_add(u.candidates, Ordering::Relaxed);
        l.fetch_add(u.lanes, Ordering::Relaxed);
        v
    }
}

/// [`ScratchTable::batch`] compiled for AVX2 + FMA, out of line ([`LaneFn::lanes_avx2`]),
/// for the frozen window (the exact window's term out of line).
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2,fma")]
#[inline(never)]
fn batch_avx2(t: &ScratchTable, q: &[TableQuery; LANES]) -> [f32; LANES] {
    t.batch::<false>(q)
}

/// [`batch_avx2`] for tables with `window: exact`: an instance of its own with the exact
/// window's term inline, so that it runs with AVX2 + FMA too.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2,fma")]
#[inline(never)]
fn batch_avx2_exact(t: &ScratchTable, q: &[TableQuery; LANES]) -> [f32; LANES] {
    t.batch::<true>(q)
}

/// Evaluates footprint queries `(scratch, ellipse)`.
pub fn footprint_table(
    backend: Backend,
    sigma: f32,
    queries: &[(Scratch, Ellipse)],
) -> Vec<FootprintRow> {
    map(backend, queries, |(s, e)| FootprintRow::of(s, e, sigma))
}

/// Evaluates every query of a GHS table.
/// The SIMD backends run it in batches of [`LANES`] ([`map_lanes`]).
pub fn evaluate_ghs_table(
    backend: Backend,
    params: &GhsParams,
    queries: &[TableQuery],
) -> Vec<f32> {
    map_lanes(backend, queries, &GhsTable(params))
}

/// [`evaluate_ghs_table`]'s lane path on one thread with the baseline instruction set (the
/// run-time dispatch's fallback; see [`crate::lanes::map_lanes_baseline`]).
pub fn evaluate_ghs_table_baseline(params: &GhsParams, queries: &[TableQuery]) -> Vec<f32> {
    map_lanes_baseline(queries, &GhsTable(params))
}

/// [`evaluate_ghs`] as a [`LaneFn`].
struct GhsTable<'a>(&'a GhsParams);

impl LaneFn for GhsTable<'_> {
    type In = TableQuery;
    type Out = f32;
    #[inline(always)]
    fn lanes(&self, q: &[TableQuery; LANES]) -> [f32; LANES] {
        ghs::brdf_lanes(
            self.0,
            G1Table::BUILTIN,
            V3::from_vecs(q.map(|q| direction(q.wi))),
            V3::from_vecs(q.map(|q| direction(q.wo))),
            Lanes(q.map(|q| q.lambda_nm)),
        )
        .0
    }
    fn one(&self, q: &TableQuery) -> f32 {
        evaluate_ghs(self.0, q)
    }
}
