//! The interface every evaluation backend implements (the CPU paths in `scratchwave-cpu`,
//! SPIR-V in `scratchwave-spirv`), so the conformance run and the CLI can hold any of them.

use crate::batch::{CaseBatch, FootprintBatch, FootprintRow, LightBatch, TableBatch};

/// Why a backend could not evaluate a batch.
#[derive(Debug, thiserror::Error)]
pub enum BackendError {
    /// The backend cannot be used on this machine (no Vulkan, no adapter, …).
    #[error("{backend} unavailable: {reason}")]
    Unavailable {
        /// Backend name.
        backend: String,
        /// What is missing, with the fix where there is one.
        reason: String,
    },
    /// A batch field holds a value the backend does not know (an enum code out of range).
    #[error("{backend}: {field}: {reason}")]
    InvalidInput {
        /// Backend name.
        backend: String,
        /// The field, e.g. `params.model`.
        field: String,
        /// What is wrong.
        reason: String,
    },
    /// The device failed while evaluating (lost device, out of memory, shader error).
    #[error("{backend}: {source}")]
    Device {
        /// Backend name.
        backend: String,
        /// The device-level error.
        #[source]
        source: Box<dyn std::error::Error + Send + Sync>,
    },
}

/// A backend that evaluates BRDF tables, light batches and footprint tables.
pub trait TableBackend {
    /// Short name (`cpu`, `simd`, `spirv`).
    fn name(&self) -> String;
    /// One BRDF value per query, in order.
    fn evaluate(&self, batch: &TableBatch) -> Result<Vec<f32>, BackendError>;
    /// One light integral per query, in order.
    fn evaluate_light(&self, batch: &LightBatch) -> Result<Vec<f32>, BackendError>;
    /// One footprint row per query, in order.
    fn evaluate_footprint(&self, batch: &FootprintBatch)
    -> Result<Vec<FootprintRow>, BackendError>;
    /// One value per query of a case, whichever kind it is.
    fn evaluate_case(&self, batch: &CaseBatch) -> Result<Vec<f32>, BackendError> {
        match batch {
            CaseBatch::Table(t) => self.evaluate(t),
            CaseBatch::Light(l) => self.evaluate_light(l),
        }
    }
}
