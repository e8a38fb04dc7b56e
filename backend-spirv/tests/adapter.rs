//! Adapter selection on the real machine.

mod common;

use scratchwave_spirv::{AdapterChoice, Gpu, SpirvError};

#[test]
fn an_unknown_adapter_name_is_a_typed_error_listing_the_adapters() {
    if common::lavapipe().is_none() {
        return;
    }
    match Gpu::with_adapter(&AdapterChoice::NameContains("no-such-adapter".into())) {
        Err(SpirvError::NoMatchingAdapter { available, .. }) => {
            assert!(available.to_lowercase().contains("llvmpipe"), "{available}");
        }
        Err(other) => panic!("unexpected error: {other}"),
        Ok(gpu) => panic!("selected {}", gpu.adapter()),
    }
}

#[test]
fn lavapipe_is_found_by_kind_and_by_name() {
    let Some(gpu) = common::lavapipe() else {
        return;
    };
    assert!(gpu.adapter().is_lavapipe(), "{}", gpu.adapter());
    let by_name = Gpu::with_adapter(&AdapterChoice::NameContains("LLVMpipe".into())).unwrap();
    assert_eq!(by_name.adapter(), gpu.adapter());
}
