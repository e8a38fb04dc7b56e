//! Finds the Embree 4 shared library and bakes its absolute path into the crate
//! (`SCRATCHWAVE_EMBREE_LIBRARY`), which loads it at run time. Every test, bench and binary of
//! every crate that depends on this one therefore finds Embree without `LD_LIBRARY_PATH`,
//! rpaths or build scripts of its own.
//!
//! Looks in `$EMBREE_DIR` if set, else in `<workspace>/.deps/embree` (filled by
//! `scripts/fetch-embree.sh`). A build script cannot download, so a missing library fails
//! the build with the command to run.

use std::env;
use std::path::{Path, PathBuf};

const LIBRARY: &str = "libembree4.so.4";

fn main() {
    println!("cargo:rerun-if-env-changed=EMBREE_DIR");
    let manifest_dir = PathBuf::from(env::var_os("CARGO_MANIFEST_DIR").expect("set by cargo"));
    let workspace = manifest_dir.parent().expect("crate lives in the workspace");
    let (dir, from_env) = match env::var_os("EMBREE_DIR") {
        Some(dir) => (PathBuf::from(dir), true),
        None => (workspace.join(".deps").join("embree"), false),
    };
    let candidates: Vec<PathBuf> = ["lib", "lib64", ""]
        .iter()
        .map(|sub| dir.join(sub).join(LIBRARY))
        .collect();
    let Some(library) = candidates.iter().find(|p| p.is_file()) else {
        // A failed build script runs again on the next build, so a library fetched later
        // is found then.
        fail(&dir, from_env, workspace);
    };
    // Watch only the library found: cargo treats a watched path that does not exist as
    // changed, which would rerun this script (and rebuild every dependent) on every build.
    println!("cargo:rerun-if-changed={}", library.display());
    let library = std::path::absolute(library).unwrap_or_else(|_| library.clone());
    println!(
        "cargo:rustc-env=SCRATCHWAVE_EMBREE_LIBRARY={}",
        library.display()
    );
}

fn fail(dir: &Path, from_env: bool, workspace: &Path) -> ! {
    let script = workspace.join("scripts").join("fetch-embree.sh");
    if from_env {
        eprintln!(
            "error: EMBREE_DIR={} contains no lib/{LIBRARY}.\n\
             Point EMBREE_DIR at an Embree 4 (>= 4.3) install, or unset it and run\n\n    {}\n",
            dir.display(),
            script.display()
        );
    } else {
        eprintln!(
            "error: Embree 4 is not installed for this checkout ({} is missing).\n\
             Fetch it (Embree 4.4.1 from the pinned PyPI wheel pyembree2==1.0.1, checksum verified) with\n\n    \
             {}\n\n\
             or set EMBREE_DIR to an Embree 4 (>= 4.3) install containing lib/{LIBRARY}.\n",
            dir.join("lib").join(LIBRARY).display(),
            script.display()
        );
    }
    std::process::exit(1);
}
