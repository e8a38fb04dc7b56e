//! The probes: one kernel `math` function evaluated element-wise, and the sampling lobes.

use crate::dispatch::{Dispatched, Input};
use crate::error::Result;
use crate::gpu::Gpu;
use scratchwave_spirv_shader::lobe_probe::LobeQuery;
use scratchwave_spirv_shader::probe::{MathFunction, ProbeParams};

impl Gpu {
    /// Evaluates `function` at each of `args` in the `math_probe` entry point.
    pub fn math_probe(
        &self,
        function: MathFunction,
        args: &[[f32; 2]],
    ) -> Result<Dispatched<[f32; 2]>> {
        let params = [ProbeParams::new(function)];
        self.dispatch(
            "math_probe",
            &[Input::whole(&params), Input::per_item(args)],
            args.len(),
        )
    }

    /// Evaluates each of `queries` in the `lobe_probe` entry point
    /// (`scratchwave_spirv_shader::lobe_probe::evaluate`).
    pub fn lobe_probe(&self, queries: &[LobeQuery]) -> Result<Dispatched<[f32; 4]>> {
        self.dispatch("lobe_probe", &[Input::per_item(queries)], queries.len())
    }
}

/// The CPU side of [`Gpu::math_probe`]: the same function, compiled for the host.
pub fn math_probe_cpu(function: MathFunction, args: &[[f32; 2]]) -> Vec<[f32; 2]> {
    args.iter().map(|&arg| function.evaluate(arg)).collect()
}
