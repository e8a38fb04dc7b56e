//! The SPIR-V backend as a [`TableBackend`]: the kernel compiled by rust-gpu, dispatched
//! through Vulkan on the adapter `SCRATCHWAVE_ADAPTER` selects (default: a discrete GPU,
//! else lavapipe).

use crate::error::SpirvError;
use crate::gpu::Gpu;
use scratchwave_host::{
    BackendError, FootprintBatch, FootprintRow, LightBatch, ScratchLookup, TableBackend, TableBatch,
};

fn device(e: SpirvError) -> BackendError {
    BackendError::Device {
        backend: "spirv".into(),
        source: Box::new(e),
    }
}

impl TableBackend for Gpu {
    fn name(&self) -> String {
        "spirv".into()
    }

    fn evaluate(&self, batch: &TableBatch) -> Result<Vec<f32>, BackendError> {
        match &batch.ghs {
            Some(g) => self.evaluate_ghs_table(g, &batch.queries),
            None => self.evaluate_table(&batch.params, &batch.scratches, &batch.queries),
        }
        .map(|d| d.output)
        .map_err(device)
    }

    fn evaluate_light(&self, batch: &LightBatch) -> Result<Vec<f32>, BackendError> {
        let lookup = ScratchLookup::new(&batch.scratches, batch.params.sigma_um);
        self.light_table(&batch.params, &lookup, &batch.queries)
            .map(|d| d.output)
            .map_err(device)
    }

    fn evaluate_footprint(
        &self,
        batch: &FootprintBatch,
    ) -> Result<Vec<FootprintRow>, BackendError> {
        self.footprint_table(batch.sigma_um, &batch.queries)
            .map(|d| d.output)
            .map_err(device)
    }
}
