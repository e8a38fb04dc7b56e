//! Without a Vulkan driver the backend reports what to install, and the command that
//! diagnoses it, instead of panicking.
//! Its own test binary: it points the Vulkan loader at no driver for the whole process.

use scratchwave_spirv::{Gpu, SpirvError};

#[test]
fn no_vulkan_driver_is_a_typed_error_naming_the_packages() {
    // SAFETY: this binary has one test and nothing else runs concurrently; the variables
    // are set before any thread reads the environment.
    unsafe {
        std::env::set_var("VK_DRIVER_FILES", "/nonexistent/scratchwave-no-icd.json");
        std::env::set_var("VK_ICD_FILENAMES", "/nonexistent/scratchwave-no-icd.json");
    }
    match Gpu::new() {
        Err(error @ SpirvError::NoVulkan) => {
            let message = error.to_string();
            assert!(
                message.contains("mesa-vulkan-drivers libvulkan1")
                    && message.contains("vulkaninfo --summary"),
                "{message}"
            );
        }
        Err(other) => panic!("expected NoVulkan, got: {other}"),
        Ok(gpu) => panic!("expected no adapter, opened {}", gpu.adapter()),
    }
}
