//! The content key of the SPIR-V module cache (`build/shader_cache.rs`, used by the build
//! script): what changes it, what does not, and the check that a build read nothing the key
//! misses. Runs on copies of the real workspace files in a temporary directory.

#[allow(dead_code)]
#[path = "../build/shader_cache.rs"]
mod shader_cache;

use std::collections::BTreeSet;
use std::fs;
use std::path::{Path, PathBuf};

fn workspace() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .unwrap()
        .to_path_buf()
}

/// A fresh directory under the system temporary directory.
fn scratch_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!(
        "scratchwave-shader-cache-{name}-{}",
        std::process::id()
    ));
    let _ = fs::remove_dir_all(&dir);
    fs::create_dir_all(&dir).unwrap();
    dir
}

fn copy_tree(from: &Path, to: &Path) {
    if from.is_file() {
        fs::create_dir_all(to.parent().unwrap()).unwrap();
        fs::copy(from, to).unwrap();
        return;
    }
    for entry in fs::read_dir(from).unwrap() {
        let entry = entry.unwrap();
        copy_tree(&entry.path(), &to.join(entry.file_name()));
    }
}

/// A copy of everything the key reads, in another directory.
fn copy_of_workspace(name: &str) -> PathBuf {
    let dir = scratch_dir(name);
    let source = workspace();
    for path in shader_cache::HASHED
        .iter()
        .chain(&["Cargo.lock", "backend-spirv/shader/Cargo.toml"])
    {
        copy_tree(&source.join(path), &dir.join(path));
    }
    dir
}

fn config() -> Vec<String> {
    vec!["nightly".to_owned(), "spirv-unknown-vulkan1.2".to_owned()]
}

fn key(dir: &Path) -> String {
    shader_cache::key(dir, &config()).unwrap()
}

fn edit(path: &Path, from: &str, to: &str) {
    let text = fs::read_to_string(path).unwrap();
    assert!(text.contains(from), "{} lacks {from:?}", path.display());
    fs::write(path, text.replacen(from, to, 1)).unwrap();
}

#[test]
fn the_key_depends_on_content_not_on_the_checkout_path() {
    let copy = copy_of_workspace("path");
    assert_eq!(key(&workspace()), key(&copy));
    assert_eq!(key(&copy).len(), 32);
    let mut other = config();
    other.push("portable-math".to_owned());
    assert_ne!(key(&copy), shader_cache::key(&copy, &other).unwrap());
    fs::remove_dir_all(copy).unwrap();
}

#[test]
fn kernel_and_shader_sources_change_the_key() {
    let copy = copy_of_workspace("sources");
    let before = key(&copy);
    fs::write(copy.join("kernel/src/lib.rs"), {
        let mut text = fs::read_to_string(copy.join("kernel/src/lib.rs")).unwrap();
        text.push('\n');
        text
    })
    .unwrap();
    let after_kernel = key(&copy);
    assert_ne!(before, after_kernel);
    fs::write(copy.join("backend-spirv/shader/src/new.rs"), "// new\n").unwrap();
    assert_ne!(after_kernel, key(&copy));
    fs::remove_dir_all(copy).unwrap();
}

#[test]
fn what_cannot_reach_the_shader_leaves_the_key_alone() {
    let copy = copy_of_workspace("unrelated");
    let before = key(&copy);
    // Kernel tests, a new workspace member, a host-only dependency and its lock entry.
    fs::create_dir_all(copy.join("kernel/tests")).unwrap();
    fs::write(copy.join("kernel/tests/new.rs"), "#[test]\nfn t() {}\n").unwrap();
    edit(
        &copy.join("Cargo.toml"),
        "members = [\n",
        "members = [\n    \"bindings\",\n",
    );
    edit(
        &copy.join("Cargo.toml"),
        "rayon = \"1\"",
        "rayon = \"1.10\"\n# a comment",
    );
    edit(
        &copy.join("Cargo.lock"),
        "name = \"rayon\"",
        "name = \"rayon\"\n",
    );
    assert_eq!(before, key(&copy));
    fs::remove_dir_all(copy).unwrap();
}

#[test]
fn manifests_and_locked_versions_of_the_shader_tree_change_the_key() {
    for (file, from, to) in [
        (
            "Cargo.toml",
            "[profile.release]",
            "[profile.release]\nlto = true",
        ),
        ("Cargo.toml", "libm = \"0.2\"", "libm = \"0.2.1\""),
        (
            "kernel/Cargo.toml",
            "portable-math = []",
            "portable-math = []\nother = []",
        ),
        (
            "Cargo.lock",
            "name = \"libm\"\nversion = \"",
            "name = \"libm\"\nversion = \"9",
        ),
    ] {
        let copy = copy_of_workspace("manifests");
        let before = key(&copy);
        edit(&copy.join(file), from, to);
        assert_ne!(before, key(&copy), "{file}: {to}");
        fs::remove_dir_all(copy).unwrap();
    }
}

#[test]
fn the_lock_tree_is_the_shaders_dependencies_without_dev_dependencies() {
    let lock = fs::read_to_string(workspace().join("Cargo.lock")).unwrap();
    let dev_only: BTreeSet<String> = ["proptest", "serde_json"].map(str::to_owned).into();
    let tree = shader_cache::lock_tree(&lock, "scratchwave-spirv-shader", &dev_only).unwrap();
    let names: BTreeSet<&str> = tree.keys().map(|(name, _)| name.as_str()).collect();
    for needed in [
        "scratchwave-kernel",
        "spirv-std",
        "glam",
        "libm",
        "num-complex",
        "bytemuck",
    ] {
        assert!(names.contains(needed), "{needed} missing from {names:?}");
    }
    for unrelated in [
        "proptest",
        "serde_json",
        "wgpu",
        "rayon",
        "scratchwave-host",
    ] {
        assert!(!names.contains(unrelated), "{unrelated} in {names:?}");
    }
    let kernel_dev = shader_cache::section_keys(
        &fs::read_to_string(workspace().join("kernel/Cargo.toml")).unwrap(),
        "dev-dependencies",
    );
    assert_eq!(kernel_dev, ["serde_json", "proptest"]);
}

/// An empty library file `lib` (its directories made) and the dep-info `depfile` beside it
/// that lists `deps` as what it was built from.
fn library_with_depinfo(lib: &Path, depfile: &Path, deps: &str) {
    fs::create_dir_all(lib.parent().unwrap()).unwrap();
    fs::write(lib, b"").unwrap();
    fs::write(depfile, format!("{}: {deps}\n", lib.display())).unwrap();
}

/// The shader's dep-info in `dir`, listing `deps`; [`shader_cache::outside_inputs`] of it.
fn outside_inputs_of_shader(dir: &Path, deps: &str) -> Vec<String> {
    let top = dir.join("shader.d");
    fs::write(&top, format!("{}/shader.spv: {deps}\n", dir.display())).unwrap();
    shader_cache::outside_inputs(&top, dir).unwrap()
}

#[test]
fn a_workspace_file_outside_the_key_is_reported() {
    let dir = scratch_dir("depinfo");
    let lib = dir.join("deps/libdep-1.rlib");
    let d = dir.display();
    library_with_depinfo(
        &lib,
        &dir.join("deps/dep-1.d"),
        &format!("kernel/src/lib.rs {d}/render/src/scene.rs /usr/lib/x.rs"),
    );
    let outside = outside_inputs_of_shader(
        &dir,
        &format!(
            "backend-spirv/shader/src/lib.rs host/src/with\\ space.rs {}",
            lib.display()
        ),
    );
    let render = format!("{d}/render/src/scene.rs");
    assert_eq!(outside, [render.as_str(), "host/src/with space.rs"]);
    fs::remove_dir_all(dir).unwrap();
}

#[test]
fn a_proc_macro_built_inside_the_workspace_is_followed_not_reported() {
    // A checkout whose target directory lies inside it: the shader's dependencies list the
    // proc macros they were expanded by, as shared objects under `target/`.
    let dir = scratch_dir("depinfo-proc-macro");
    let out = dir.join("target/spirv-builder/release/build/derive/1/out");
    let so = out.join("libderive-1.so");
    library_with_depinfo(
        &so,
        &out.join("derive-1.d"),
        &format!(
            "/registry/derive/src/lib.rs {}/render/src/macro_input.rs",
            dir.display()
        ),
    );
    let outside = outside_inputs_of_shader(
        &dir,
        &format!("backend-spirv/shader/src/lib.rs {}", so.display()),
    );
    // The library itself is a build output; a workspace source it was built from is not
    // covered by the key and is still reported.
    let input = format!("{}/render/src/macro_input.rs", dir.display());
    assert_eq!(outside, [input.as_str()]);
    fs::remove_dir_all(dir).unwrap();
}

#[test]
fn a_stored_module_is_found_by_its_key_and_old_entries_are_evicted() {
    let dir = scratch_dir("store");
    let module = dir.join("built.spv");
    fs::write(&module, [3u8, 2, 35, 7]).unwrap();
    let cache = dir.join("cache");
    assert!(shader_cache::lookup(&cache, "k0").is_none());
    let names = ["a".to_owned(), "b".to_owned()];
    let stored = shader_cache::store(&cache, "k0", &module, &names).unwrap();
    assert_eq!(fs::read(&stored.module).unwrap(), [3, 2, 35, 7]);
    let found = shader_cache::lookup(&cache, "k0").unwrap();
    assert_eq!(found.entry_points, names);
    for i in 1..12 {
        shader_cache::store(&cache, &format!("k{i}"), &module, &names).unwrap();
    }
    let kept = fs::read_dir(&cache).unwrap().count();
    assert_eq!(kept, 8);
    assert!(shader_cache::lookup(&cache, "k11").is_some());
    fs::remove_dir_all(dir).unwrap();
}
