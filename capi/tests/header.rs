//! `include/scratchwave.h` is what cbindgen makes of `src/ffi.rs` now. Regenerate with
//! `SCRATCHWAVE_BLESS=1 cargo test -p scratchwave-capi --test header`.

use std::path::Path;

#[test]
fn header_is_current() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR"));
    let config = cbindgen::Config::from_file(dir.join("cbindgen.toml")).expect("cbindgen.toml");
    let mut made = Vec::new();
    cbindgen::Builder::new()
        .with_crate(dir)
        .with_config(config)
        .generate()
        .expect("cbindgen parses the crate")
        .write(&mut made);
    let made = String::from_utf8(made).expect("utf-8 header");
    let path = dir.join("include/scratchwave.h");
    if std::env::var_os("SCRATCHWAVE_BLESS").is_some() {
        std::fs::write(&path, &made).expect("write the header");
    }
    let committed = std::fs::read_to_string(&path).unwrap_or_default();
    assert!(
        committed == made,
        "{} is stale: regenerate it with SCRATCHWAVE_BLESS=1 cargo test -p scratchwave-capi \
         --test header",
        path.display()
    );
}
