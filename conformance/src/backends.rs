//! The backends the CLI and the conformance run can use.

use crate::run::TableBackend;
use crate::spec::TableSpec;
use scratchwave_cpu::table::evaluate_ghs_table;
use scratchwave_cpu::{Backend, evaluate_table};

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

    fn evaluate(&self, spec: &TableSpec) -> Result<Vec<f32>, String> {
        Ok(match &spec.ghs {
            Some(g) => evaluate_ghs_table(self.0, g, &spec.queries),
            None => evaluate_table(self.0, &spec.params, &spec.scratches, &spec.queries),
        })
    }
}

/// Every backend available on this machine, with a note for each one that is not.
pub fn available() -> (Vec<Box<dyn TableBackend>>, Vec<String>) {
    let list: Vec<Box<dyn TableBackend>> =
        vec![Box::new(Cpu(Backend::Scalar)), Box::new(Cpu(Backend::Simd))];
    (list, Vec::new())
}

/// The backend called `name` (`cpu`, `simd`), or an error listing the choices.
pub fn by_name(name: &str) -> Result<Box<dyn TableBackend>, String> {
    match name {
        "cpu" => Ok(Box::new(Cpu(Backend::Scalar))),
        "simd" => Ok(Box::new(Cpu(Backend::Simd))),
        other => Err(format!("unknown backend {other:?} (cpu, simd, all)")),
    }
}
