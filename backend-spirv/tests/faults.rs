//! Injected faults on lavapipe (no real GPU needed): a binding over the device's size limit
//! (capped with `Gpu::with_max_binding_bytes` so the test need not allocate the real limit)
//! is a typed error naming the limit, and per-item inputs under the same cap are split into
//! dispatches that each fit and give the uncapped result; a lost device (`Gpu::lose_device`)
//! turns every later dispatch into a typed error; a memory budget below what a dispatch
//! needs is a typed out-of-memory error before anything is allocated; damaged shader
//! modules are refused before the driver sees them; a dispatch sliced to a tight time
//! budget gives the same bits as one in a few long slices. The missing-driver fault is
//! `tests/no_vulkan.rs` (its own process: it hides every Vulkan driver).

mod common;

use common::{lavapipe, linspace};
use scratchwave_spirv::{
    AdapterChoice, Gpu, Input, MathFunction, Pace, ProbeParams, SHADER_SPV, SpirvError,
};
use std::time::Duration;

#[test]
fn whole_input_over_the_binding_limit_is_a_typed_error_naming_it() {
    let Some(gpu) = lavapipe() else { return };
    let gpu = gpu.with_max_binding_bytes(1024);
    // The parameter binding padded to 2048 bytes (> 1024); the dispatch is refused before
    // anything is uploaded.
    let params = [ProbeParams::new(MathFunction::Exp); 128];
    assert_eq!(std::mem::size_of_val(&params), 2048);
    let args = [[1.0_f32, 0.0]; 64];
    let r = gpu.dispatch::<[f32; 2]>(
        "math_probe",
        &[Input::whole(&params), Input::per_item(&args)],
        64,
    );
    match r {
        Err(e @ SpirvError::TooLarge { .. }) => {
            let m = e.to_string();
            assert!(
                m.contains("max_storage_buffer_binding_size") && m.contains("2048"),
                "{m}"
            );
        }
        other => panic!("expected TooLarge, got {other:?}"),
    }
}

#[test]
fn per_item_inputs_are_split_to_fit_the_binding_budget() {
    let Some(gpu) = lavapipe() else { return };
    let args = linspace(-20.0, 20.0, 10_007);
    let whole = gpu.math_probe(MathFunction::Exp, &args).unwrap().output;
    // 8-byte elements under a 4 KiB budget: many dispatches of at most 512 elements.
    let capped = gpu.with_max_binding_bytes(4096);
    let split = capped.math_probe(MathFunction::Exp, &args).unwrap().output;
    assert_eq!(split.len(), args.len());
    assert!(
        whole
            .iter()
            .zip(&split)
            .all(|(a, b)| a[0].to_bits() == b[0].to_bits())
    );
    // A budget below one aligned chunk of elements cannot be met: a typed error naming it.
    let tiny = capped.with_max_binding_bytes(8);
    match tiny.math_probe(MathFunction::Exp, &args) {
        Err(e @ SpirvError::TooLarge { .. }) => {
            assert!(
                e.to_string().contains("max_storage_buffer_binding_size"),
                "{e}"
            );
        }
        other => panic!("expected TooLarge, got {other:?}"),
    }
}

#[test]
fn a_lost_device_is_a_typed_error_not_a_panic() {
    let Some(gpu) = lavapipe() else { return };
    let args = linspace(-1.0, 1.0, 256);
    let before = gpu
        .math_probe(MathFunction::Exp, &args)
        .expect("dispatch before the loss");
    assert_eq!(before.output.len(), args.len());
    gpu.lose_device();
    for _ in 0..2 {
        match gpu.math_probe(MathFunction::Exp, &args) {
            Err(e @ SpirvError::Gpu { .. }) => {
                let m = e.to_string();
                assert!(m.contains("vulkaninfo --summary"), "{m}");
            }
            other => panic!("expected SpirvError::Gpu after the device was lost, got {other:?}"),
        }
    }
}

#[test]
fn a_dispatch_over_the_memory_budget_is_refused_before_allocating() {
    let Some(gpu) = lavapipe() else { return };
    let args = linspace(-20.0, 20.0, 10_007);
    let free = gpu.math_probe(MathFunction::Exp, &args).unwrap().output;
    // Inputs 16 + 80 056 bytes, output and readback 2 × 80 056: 240 184 bytes.
    let gpu = gpu.with_memory_budget(240_184);
    let fits = gpu.math_probe(MathFunction::Exp, &args).unwrap().output;
    assert!(free.iter().zip(&fits).all(|(a, b)| a == b));
    let gpu = gpu.with_memory_budget(240_183);
    match gpu.math_probe(MathFunction::Exp, &args) {
        Err(e @ SpirvError::OutOfMemory { .. }) => {
            let m = e.to_string();
            assert!(
                m.contains("240184 bytes")
                    && m.contains("memory budget of 240183")
                    && m.contains("vulkaninfo"),
                "{m}"
            );
        }
        other => panic!("expected OutOfMemory, got {other:?}"),
    }
    // Nothing was left half-done: the device still works.
    let again = gpu.with_memory_budget(u64::MAX);
    let after = again.math_probe(MathFunction::Exp, &args).unwrap().output;
    assert!(free.iter().zip(&after).all(|(a, b)| a == b));
}

/// Word offsets of the module's instructions after the header.
fn instruction_starts(words: &[u32]) -> Vec<usize> {
    let mut starts = Vec::new();
    let mut at = 5;
    while at < words.len() {
        starts.push(at);
        at += (words[at] >> 16) as usize;
    }
    starts
}

#[test]
fn damaged_shader_modules_never_reach_the_driver() {
    let words: Vec<u32> = SHADER_SPV
        .chunks_exact(4)
        .map(|w| u32::from_le_bytes([w[0], w[1], w[2], w[3]]))
        .collect();
    let to_bytes = |w: &[u32]| -> Vec<u8> { w.iter().flat_map(|x| x.to_le_bytes()).collect() };
    let starts = instruction_starts(&words);
    let middle = starts[starts.len() / 2];
    let mut zero_count = words.clone();
    zero_count[middle] &= 0xffff;
    let mut overrun = words.clone();
    overrun[*starts.last().unwrap()] |= 0xffff << 16;
    let cases: [(&str, Vec<u8>, &str); 5] = [
        (
            "cut mid-word",
            SHADER_SPV[..SHADER_SPV.len() - 3].to_vec(),
            "whole number",
        ),
        ("truncated", to_bytes(&words[..middle + 1]), "truncated"),
        ("empty", Vec::new(), "header"),
        ("zero word count", to_bytes(&zero_count), "word count of 0"),
        (
            "overrunning length",
            to_bytes(&overrun),
            "claims 65535 words",
        ),
    ];
    for (what, bytes, expect) in cases {
        // SAFETY: the structural check refuses each of these before the driver sees it,
        // which is what the test asserts; nothing reaches the passthrough.
        match unsafe { Gpu::with_module(&AdapterChoice::Lavapipe, &bytes) } {
            Err(e @ SpirvError::BadShader { .. }) => {
                let m = e.to_string();
                assert!(m.contains(expect) && m.contains("spirv-val"), "{what}: {m}");
            }
            Err(other) => panic!("{what}: expected BadShader, got {other}"),
            Ok(_) => panic!("{what}: a damaged module was accepted"),
        }
    }
}

#[test]
fn the_module_given_explicitly_is_the_one_dispatched() {
    // SAFETY: the embedded module, rust-gpu's validated output for `shader/`.
    let gpu = match unsafe { Gpu::with_module(&AdapterChoice::Lavapipe, SHADER_SPV) } {
        Ok(gpu) => gpu,
        Err(SpirvError::NoVulkan) => return,
        Err(e) => panic!("{e}"),
    };
    assert!(gpu.module_entry_points().any(|e| e == "math_probe"));
    let args = linspace(-3.0, 3.0, 300);
    let out = gpu.math_probe(MathFunction::Exp, &args).unwrap().output;
    assert_eq!(out.len(), args.len());
    match gpu.dispatch::<f32>("no_such_entry", &[], 4) {
        Err(e @ SpirvError::UnknownEntryPoint { .. }) => {
            assert!(e.to_string().contains("math_probe"), "{e}");
        }
        other => panic!("expected UnknownEntryPoint, got {other:?}"),
    }
}

#[test]
fn a_tight_time_budget_slices_the_dispatch_without_changing_a_bit() {
    let Some(gpu) = lavapipe() else { return };
    let args = linspace(-20.0, 20.0, 100_003);
    let default = gpu.math_probe(MathFunction::Exp, &args).unwrap();
    assert!(default.timings.slices >= 1);
    // A budget no slice can meet: every slice shrinks to the smallest aligned size.
    let tight = gpu.with_pace(Pace {
        first: 4096,
        target: Duration::from_nanos(1),
    });
    let sliced = tight.math_probe(MathFunction::Exp, &args).unwrap();
    let t = sliced.timings;
    assert!(t.slices > default.timings.slices && t.slices >= 20, "{t:?}");
    assert!(t.longest_slice > Duration::ZERO && t.longest_slice <= t.dispatch);
    assert!(
        default
            .output
            .iter()
            .zip(&sliced.output)
            .all(|(a, b)| a[0].to_bits() == b[0].to_bits() && a[1].to_bits() == b[1].to_bits())
    );
}
