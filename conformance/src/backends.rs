//! The backends the CLI and the conformance run can use.

use crate::light_case::LightBatch;
use crate::run::TableBackend;
use crate::spec::TableSpec;
use scratchwave_cpu::parallel::map;
use scratchwave_cpu::table::evaluate_ghs_table;
use scratchwave_cpu::{Backend, FootprintRow, ScratchLookup, evaluate_table, footprint_table};
use scratchwave_kernel::footprint::Ellipse;
use scratchwave_kernel::lights::light_integral;
use scratchwave_kernel::scratch::Scratch;

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

    fn evaluate_light(&self, batch: &LightBatch) -> Result<Vec<f32>, String> {
        let lookup = ScratchLookup::new(&batch.scratches, batch.params.sigma_um);
        let set = lookup.set();
        Ok(map(self.0, &batch.queries, |q| {
            light_integral(&batch.params, q, &set)
        }))
    }

    fn evaluate_footprint(
        &self,
        sigma: f32,
        queries: &[(Scratch, Ellipse)],
    ) -> Result<Vec<FootprintRow>, String> {
        Ok(footprint_table(self.0, sigma, queries))
    }
}

/// The SPIR-V backend: the kernel compiled by rust-gpu, dispatched through Vulkan on the
/// adapter `SCRATCHWAVE_ADAPTER` selects (default: a discrete GPU, else lavapipe).
pub struct Spirv(pub scratchwave_spirv::Gpu);

impl TableBackend for Spirv {
    fn name(&self) -> String {
        "spirv".into()
    }

    fn evaluate(&self, spec: &TableSpec) -> Result<Vec<f32>, String> {
        match &spec.ghs {
            Some(g) => self.0.evaluate_ghs_table(g, &spec.queries),
            None => self
                .0
                .evaluate_table(&spec.params, &spec.scratches, &spec.queries),
        }
        .map(|d| d.output)
        .map_err(|e| e.to_string())
    }

    fn evaluate_light(&self, batch: &LightBatch) -> Result<Vec<f32>, String> {
        let lookup = ScratchLookup::new(&batch.scratches, batch.params.sigma_um);
        self.0
            .light_table(&batch.params, &lookup, &batch.queries)
            .map(|d| d.output)
            .map_err(|e| e.to_string())
    }

    fn evaluate_footprint(
        &self,
        sigma: f32,
        queries: &[(Scratch, Ellipse)],
    ) -> Result<Vec<FootprintRow>, String> {
        self.0
            .footprint_table(sigma, queries)
            .map(|d| d.output)
            .map_err(|e| e.to_string())
    }
}

/// Opens the SPIR-V backend, or says why it is unavailable.
pub fn spirv() -> Result<Spirv, String> {
    scratchwave_spirv::Gpu::new()
        .map(Spirv)
        .map_err(|e| e.to_string())
}

/// Every backend available on this machine, with a note for each one that is not.
pub fn available() -> (Vec<Box<dyn TableBackend>>, Vec<String>) {
    let mut list: Vec<Box<dyn TableBackend>> =
        vec![Box::new(Cpu(Backend::Scalar)), Box::new(Cpu(Backend::Simd))];
    let mut notes = Vec::new();
    match spirv() {
        Ok(g) => {
            let a = g.0.adapter();
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

/// The backend called `name` (`cpu`, `simd`, `spirv`), or an error listing the choices.
pub fn by_name(name: &str) -> Result<Box<dyn TableBackend>, String> {
    match name {
        "cpu" => Ok(Box::new(Cpu(Backend::Scalar))),
        "simd" => Ok(Box::new(Cpu(Backend::Simd))),
        "spirv" => Ok(Box::new(spirv()?)),
        other => Err(format!("unknown backend {other:?} (cpu, simd, spirv)")),
    }
}
