//! The CPU paths as a [`TableBackend`].

use crate::parallel::{Backend, map};
use crate::table::{evaluate_ghs_table, evaluate_table, footprint_table};
use scratchwave_host::{
    BackendError, FootprintBatch, FootprintRow, LightBatch, ScratchLookup, TableBackend, TableBatch,
};
use scratchwave_kernel::lights::light_integral;

/// A CPU path (`cpu` = scalar, `simd` = rayon + SIMD code generation).
pub struct Cpu(pub Backend);

impl TableBackend for Cpu {
    fn name(&self) -> String {
        match self.0 {
            Backend::Scalar => "cpu".into(),
            Backend::Simd => "simd".into(),
            Backend::SimdSingleThread => "simd1".into(),
        }
    }

    fn evaluate(&self, batch: &TableBatch) -> Result<Vec<f32>, BackendError> {
        Ok(match &batch.ghs {
            Some(g) => evaluate_ghs_table(self.0, g, &batch.queries),
            None => evaluate_table(self.0, &batch.params, &batch.scratches, &batch.queries),
        })
    }

    fn evaluate_light(&self, batch: &LightBatch) -> Result<Vec<f32>, BackendError> {
        let lookup = ScratchLookup::new(&batch.scratches, batch.params.sigma_um);
        let set = lookup.set();
        Ok(map(self.0, &batch.queries, |q| {
            light_integral(&batch.params, q, &set)
        }))
    }

    fn evaluate_footprint(
        &self,
        batch: &FootprintBatch,
    ) -> Result<Vec<FootprintRow>, BackendError> {
        Ok(footprint_table(self.0, batch.sigma_um, &batch.queries))
    }
}
