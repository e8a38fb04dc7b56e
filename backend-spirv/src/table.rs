//! BRDF tables and footprint tables on the GPU, mirroring the CPU backend's `table` module.

use crate::dispatch::{Dispatched, Input, Timings};
use crate::error::Result;
use crate::error::SpirvError;
use crate::gpu::Gpu;
use scratchwave_host::{FootprintRow, ScratchLookup};
use scratchwave_kernel::footprint::Ellipse;
use scratchwave_kernel::ghs::GhsParams;
use scratchwave_kernel::ghs::g1::G1Table;
use scratchwave_kernel::lights::{LightParams, LightQuery};
use scratchwave_kernel::scratch::Scratch;
use scratchwave_kernel::table::{Model, TableParams, TableQuery};
use scratchwave_spirv_shader::FootprintParams;

/// Selects one field of a [`FootprintRow`].
type Column = fn(&mut FootprintRow) -> &mut f32;

impl Gpu {
    /// Evaluates every query against the scratch set: builds the BVH lookup on the CPU
    /// (as the CPU backend does) and runs [`Gpu::evaluate_table_with`].
    pub fn evaluate_table(
        &self,
        params: &TableParams,
        scratches: &[Scratch],
        queries: &[TableQuery],
    ) -> Result<Dispatched<f32>> {
        self.evaluate_table_with(
            params,
            &ScratchLookup::new(scratches, params.sigma_um),
            queries,
        )
    }

    /// Evaluates every query with a lookup built beforehand (reuse it across tables of the
    /// same scratches): `kernel::table::evaluate` in the entry point of `params.model`,
    /// traversing the uploaded BVH nodes and slot-ordered scratches.
    pub fn evaluate_table_with(
        &self,
        params: &TableParams,
        lookup: &ScratchLookup,
        queries: &[TableQuery],
    ) -> Result<Dispatched<f32>> {
        let model = Model::try_from(params.model).map_err(|e| SpirvError::BadInput {
            entry: "table".into(),
            index: 0,
            problem: format!("params.model: {e}"),
        })?;
        let entry = match model {
            Model::Werner => "table_werner",
            Model::WernerBlended => "table_werner_blended",
            Model::Velinov => "table_velinov",
        };
        let inputs = [
            Input::whole(std::slice::from_ref(params)),
            Input::whole(lookup.nodes()),
            Input::whole(lookup.scratches()),
            Input::per_item(queries),
        ];
        self.dispatch(entry, &inputs, queries.len())
    }

    /// Evaluates a GHS table: `kernel::table::evaluate_ghs_with_g1_table` per query, with
    /// the G1 table uploaded as a buffer.
    pub fn evaluate_ghs_table(
        &self,
        params: &GhsParams,
        queries: &[TableQuery],
    ) -> Result<Dispatched<f32>> {
        let inputs = [
            Input::whole(std::slice::from_ref(params)),
            Input::whole(G1Table::FLAT),
            Input::per_item(queries),
        ];
        self.dispatch("table_ghs", &inputs, queries.len())
    }

    /// Evaluates area-light queries: `kernel::lights::light_integral` per query over the
    /// BVH lookup of `lookup` (build it with the light's σ).
    pub fn light_table(
        &self,
        params: &LightParams,
        lookup: &ScratchLookup,
        queries: &[LightQuery],
    ) -> Result<Dispatched<f32>> {
        let inputs = [
            Input::whole(std::slice::from_ref(params)),
            Input::whole(lookup.nodes()),
            Input::whole(lookup.scratches()),
            Input::per_item(queries),
        ];
        self.dispatch("light", &inputs, queries.len())
    }

    /// Evaluates footprint queries `(scratch, ellipse)`: one dispatch per average.
    /// The timings are summed over the four dispatches.
    pub fn footprint_table(
        &self,
        sigma: f32,
        queries: &[(Scratch, Ellipse)],
    ) -> Result<Dispatched<FootprintRow>> {
        let params = [FootprintParams {
            sigma_um: sigma,
            pad: [0.0; 3],
        }];
        let scratches: Vec<Scratch> = queries.iter().map(|q| q.0).collect();
        let ellipses: Vec<Ellipse> = queries.iter().map(|q| q.1).collect();
        let inputs = [
            Input::whole(&params),
            Input::per_item(&scratches),
            Input::per_item(&ellipses),
        ];
        let mut rows = vec![FootprintRow::default(); queries.len()];
        let mut timings = Timings::default();
        let columns: [(&str, Column); 4] = [
            ("footprint_eq15", |r| &mut r.eq15),
            ("footprint_eq16", |r| &mut r.eq16),
            ("footprint_accurate", |r| &mut r.accurate),
            ("footprint_rho_p", |r| &mut r.rho_p),
        ];
        for (entry, field) in columns {
            let column = self.dispatch::<f32>(entry, &inputs, queries.len())?;
            for (row, value) in rows.iter_mut().zip(column.output) {
                *field(row) = value;
            }
            timings.absorb(&column.timings);
        }
        Ok(Dispatched {
            output: rows,
            timings,
        })
    }
}
