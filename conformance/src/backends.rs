//! The backends the CLI and the conformance run can use, by name.

use scratchwave_cpu::{Backend, Cpu};
use scratchwave_host::{BackendError, TableBackend};
use scratchwave_spirv::Gpu;

/// Every backend available on this machine, with a note for each one that is not.
pub fn available() -> (Vec<Box<dyn TableBackend>>, Vec<String>) {
    let mut list: Vec<Box<dyn TableBackend>> =
        vec![Box::new(Cpu(Backend::Scalar)), Box::new(Cpu(Backend::Simd))];
    let mut notes = Vec::new();
    match Gpu::new() {
        Ok(g) => {
            let a = g.adapter();
            notes.push(format!(
                "spirv: {} ({:?}, driver {})",
                a.name, a.kind, a.driver
            ));
            list.push(Box::new(g));
        }
        Err(e) => notes.push(format!("spirv unavailable: {e}")),
    }
    (list, notes)
}

/// The backend called `name` (`cpu`, `simd`, `spirv`); an unknown name or a backend this
/// machine cannot open is [`BackendError::Unavailable`].
pub fn by_name(name: &str) -> Result<Box<dyn TableBackend>, BackendError> {
    match name {
        "cpu" => Ok(Box::new(Cpu(Backend::Scalar))),
        "simd" => Ok(Box::new(Cpu(Backend::Simd))),
        "spirv" => Ok(Box::new(Gpu::new().map_err(|e| {
            BackendError::Unavailable {
                backend: "spirv".into(),
                reason: e.to_string(),
            }
        })?)),
        other => Err(BackendError::Unavailable {
            backend: format!("{other:?}"),
            reason: "unknown backend (cpu, simd, spirv)".into(),
        }),
    }
}
