//! The sampling sweeps of issue #20 on SPIR-V (lavapipe): the scratch models' sampling
//! lobes — `Lobe1` mass, density and inverse CDF, the disk lobes' density and `u → wi`
//! map, Werner §5's vMF ring density and sample — through the `lobe_probe` entry point, at
//! the very f32 inputs the mpmath references evaluated (`reference/lobe1_sweep.py`,
//! `disk_lobe_sweep.py`, `vmf_ring_sweep.py`), held to the kernel tests' rule
//! `err ≤ max(1e-4, 8κ)` by the same checks (`kernel/tests/sweep_common/sampling.rs`).
//! Also counts the results that differ from the same probe compiled for the CPU. Vulkan
//! lets a device flush subnormal f32 to zero (lavapipe does): a `Lobe1` density whose
//! exact numerator is below the smallest normal f32 may come out as 0, which is accepted
//! here (1 of the committed 3 000 queries; `sweep_common::sampling::check_lobe1`).
//!
//! The committed subsets run by default; `LOBE1_SWEEP_DIR`, `DISK_LOBE_SWEEP_DIR`,
//! `VMF_RING_SWEEP_DIR` name larger samples. Run with `--nocapture` for the tables.

mod common;

#[path = "../../kernel/tests/sweep_common/mod.rs"]
mod sweep_common;

use scratchwave_spirv::Gpu;
use scratchwave_spirv_shader::lobe_probe::{
    LobeFunction, LobeQuery, LobeRecord, decode_direction, evaluate,
};
use sweep_common::Table;
use sweep_common::sampling::{
    DISK_LOBE_MIN, LOBE1_MIN, VMF_RING_MIN, check_disk_lobe, check_lobe1, check_vmf_ring,
    disk_lobe_of, lobe1_args, lobe1_of, vmf_ring_of,
};

/// Runs `queries` on the GPU; prints how many results differ from the CPU's and returns
/// the GPU's.
fn run(gpu: &Gpu, family: &str, queries: &[LobeQuery]) -> Vec<[f32; 4]> {
    let out = gpu.lobe_probe(queries).expect("lobe_probe dispatch").output;
    let differ = queries
        .iter()
        .zip(&out)
        .filter(|(q, g)| evaluate(q).map(f32::to_bits) != g.map(f32::to_bits))
        .count();
    println!(
        "{family}: {} probe results, {differ} not bitwise equal to the CPU's",
        queries.len()
    );
    out
}

#[test]
fn lobe1_on_spirv_is_within_the_sweep_bound() {
    let Some(gpu) = common::lavapipe() else {
        return;
    };
    let table = Table::load("LOBE1_SWEEP_DIR", "reference/golden/sweep", "lobe1");
    sweep_common::check_size("LOBE1_SWEEP_DIR", &table, LOBE1_MIN);
    let mut queries = Vec::new();
    for r in table.rows() {
        let l1 = LobeRecord::new(&lobe1_of(&r, ""));
        let (a, b, x, u) = lobe1_args(&r);
        for (function, args) in [
            (LobeFunction::Lobe1Mass, [a, b, 0.0, 0.0]),
            (LobeFunction::Lobe1Pdf, [a, b, x, 0.0]),
            (LobeFunction::Lobe1Sample, [a, b, 0.0, u]),
        ] {
            queries.push(LobeQuery {
                l1,
                args,
                ..LobeQuery::new(function)
            });
        }
    }
    let out = run(&gpu, "lobe1", &queries);
    let bad = check_lobe1(&table, true, |i, _| {
        let s = out[3 * i + 2];
        [
            out[3 * i][0],
            out[3 * i + 1][0],
            if s[3] != 0.0 { s[0] } else { f32::NAN },
        ]
    });
    assert!(bad.is_empty(), "over the bound:\n{}", bad.join("\n"));
}

#[test]
fn disk_lobes_on_spirv_are_within_the_sweep_bound() {
    let Some(gpu) = common::lavapipe() else {
        return;
    };
    let table = Table::load("DISK_LOBE_SWEEP_DIR", "reference/golden/sweep", "disk_lobe");
    sweep_common::check_size("DISK_LOBE_SWEEP_DIR", &table, DISK_LOBE_MIN);
    let mut queries = Vec::new();
    for r in table.rows() {
        let (l, wo, wi, u) = disk_lobe_of(&r);
        let base = LobeQuery {
            l1: LobeRecord::new(&l.l1),
            l2: LobeRecord::new(&l.l2),
            wo: [wo.x, wo.y, wo.z, 0.0],
            wi: [wi.x, wi.y, wi.z, 0.0],
            ..LobeQuery::new(LobeFunction::DiskPdf)
        };
        queries.push(LobeQuery {
            args: [l.e1.x, l.e1.y, 0.0, 0.0],
            ..base
        });
        queries.push(LobeQuery {
            function: LobeFunction::DiskSample as u32,
            args: [l.e1.x, l.e1.y, u.x, u.y],
            ..base
        });
    }
    let out = run(&gpu, "disk_lobe", &queries);
    let bad = check_disk_lobe(&table, |i, _| {
        (out[2 * i][0], decode_direction(out[2 * i + 1]))
    });
    assert!(bad.is_empty(), "over the bound:\n{}", bad.join("\n"));
}

#[test]
fn vmf_ring_on_spirv_is_within_the_sweep_bound() {
    let Some(gpu) = common::lavapipe() else {
        return;
    };
    let table = Table::load("VMF_RING_SWEEP_DIR", "reference/golden/sweep", "vmf_ring");
    sweep_common::check_size("VMF_RING_SWEEP_DIR", &table, VMF_RING_MIN);
    let mut queries = Vec::new();
    for r in table.rows() {
        let q = vmf_ring_of(&r);
        let wo = [q.wo.x, q.wo.y, q.wo.z, 0.0];
        queries.push(LobeQuery {
            args: [q.t.x, q.t.y, q.kappa, 0.0],
            wo,
            wi: [q.wi.x, q.wi.y, q.wi.z, 0.0],
            ..LobeQuery::new(LobeFunction::VmfPdf)
        });
        queries.push(LobeQuery {
            args: [q.t.x, q.t.y, q.kappa, q.u_ring],
            wo,
            wi: [q.u.x, q.u.y, 0.0, 0.0],
            ..LobeQuery::new(LobeFunction::VmfSample)
        });
    }
    let out = run(&gpu, "vmf_ring", &queries);
    let bad = check_vmf_ring(&table, |i, _| {
        (out[2 * i][0], decode_direction(out[2 * i + 1]))
    });
    assert!(bad.is_empty(), "over the bound:\n{}", bad.join("\n"));
}
