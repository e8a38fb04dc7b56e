//! Empty: this package exists only to build `rustc_codegen_spirv` as a dependency.
