//! Light-integral conformance cases: a batch of area-light queries over a scratch set,
//! evaluated by every backend's `light` path and compared like a table.
//!
//! A case file holds the recipe `{"random_lights": {"seed", "queries", "eta", "bands",
//! "si"}}` and this module expands it: each query is one configuration of the accuracy
//! sweep (`scratchwave_cpu::light_configs`: spheres with either cone, 3–8-gons tilted up to
//! 50°, partly below the horizon, every scratch orientation), with its scratch and shading
//! point moved to a cell of its own on a grid (1 mm apart, beyond the 6σ lookup radius of
//! every other cell), so one BVH holds all scratches and each query sees exactly its own.
//! Odd queries use the V-groove (triangle) profile, which the kernel integrates numerically
//! across the band.

use crate::error::SpecError;
use crate::json::Obj;
use scratchwave_cpu::light_configs::{Rng, SweepRanges, random_case};
use scratchwave_kernel::lights::{LightParams, LightQuery, SiMode};
use scratchwave_kernel::scratch::{EtaMode, Profile, Scratch};
use serde_json::Value;

/// Distance between grid cells (µm): the sweep's scratches are 300 µm long within 10 µm of
/// the cell centre, σ = 10 µm.
const CELL_UM: f32 = 1000.0;
/// Cells per grid row.
const ROW: usize = 100;

/// A batch of light queries over one scratch set.
#[derive(Clone, Debug, PartialEq)]
pub struct LightBatch {
    /// Options shared by every query.
    pub params: LightParams,
    /// The scratches (one per query here).
    pub scratches: Vec<Scratch>,
    /// The queries.
    pub queries: Vec<LightQuery>,
}

/// Expands `{"seed", "queries", "eta": "finite"|"infinite", "bands": 1|3|5|20,
/// "si": "exact"|"velinov"|"fast"}` (`eta`, `bands`, `si` optional: finite, 1, exact).
pub fn random_light_batch(v: &Value, path: &str) -> Result<LightBatch, SpecError> {
    let o = Obj::new(v, path, &["seed", "queries", "eta", "bands", "si"])?;
    let seed = o.integer("seed", 1e15)?;
    let count = o.integer("queries", 1e6)? as usize;
    let eta = match o.opt_choice("eta", &["finite", "infinite"])? {
        Some("infinite") => EtaMode::Infinite,
        _ => EtaMode::Finite,
    };
    let bands = match o.get("bands") {
        None => 1,
        Some(_) => match o.integer("bands", 20.0)? {
            b @ (1 | 3 | 5 | 20) => b as u32,
            _ => {
                return Err(SpecError::field(
                    o.path_of("bands"),
                    "must be 1, 3, 5 or 20",
                ));
            }
        },
    };
    let si = match o.opt_choice("si", &["exact", "velinov", "fast"])? {
        Some("velinov") => SiMode::Velinov,
        Some("fast") => SiMode::Fast,
        _ => SiMode::Exact,
    };
    let mut rng = Rng::new(seed);
    let ranges = SweepRanges::default();
    let mut params = None;
    let mut scratches = Vec::with_capacity(count);
    let mut queries = Vec::with_capacity(count);
    for k in 0..count {
        let c = random_case(&mut rng, &ranges, eta as u32);
        let offset = [(k % ROW) as f32 * CELL_UM, (k / ROW) as f32 * CELL_UM];
        let mut s = c.scratch;
        s.center = [s.center[0] + offset[0], s.center[1] + offset[1]];
        if k % 2 == 1 {
            s.profile = Profile::Triangle as u32;
        }
        let mut q = c.query;
        q.x = [q.x[0] + offset[0], q.x[1] + offset[1]];
        scratches.push(s);
        queries.push(q);
        params.get_or_insert(c.params);
    }
    let params = LightParams {
        bands,
        si_mode: si as u32,
        ..params.unwrap_or_default()
    };
    Ok(LightBatch {
        params,
        scratches,
        queries,
    })
}
