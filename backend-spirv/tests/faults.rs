//! Injected faults on lavapipe (no real GPU needed): a binding over the device's size limit
//! (capped with `Gpu::with_max_binding_bytes` so the test need not allocate the real limit)
//! is a typed error naming the limit, and per-item inputs under the same cap are split into
//! dispatches that each fit and give the uncapped result; a lost device (`Gpu::lose_device`)
//! turns every later dispatch into a typed error. The missing-driver fault is
//! `tests/no_vulkan.rs` (its own process: it hides every Vulkan driver).

mod common;

use common::{lavapipe, linspace};
use scratchwave_spirv::{Input, MathFunction, ProbeParams, SpirvError};

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
