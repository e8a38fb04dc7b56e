//! Builds `shader/` to one SPIR-V module on the pinned nightly and hands its path to the
//! crate as `SCRATCHWAVE_SHADER_SPV` (entry-point names in `SCRATCHWAVE_SHADER_ENTRY_POINTS`).
//!
//! The workspace itself stays on stable. Two things need the nightly:
//!
//! 1. `rustc_codegen_spirv`, the rust-gpu backend, compiled once per machine from
//!    `codegen/` (pinned lock, `use-installed-tools`) into the rust-gpu cache directory
//!    (`$XDG_CACHE_HOME/rust-gpu`, else `~/.cache/rust-gpu`). A few minutes, once.
//! 2. The shader crate itself, compiled by `cargo +nightly rustc` with that backend
//!    (spirv-builder does the driving). After a kernel edit this takes most of an hour on a
//!    2-core machine (rust-gpu codegen and `spirv-opt` are single-threaded), so the module
//!    is kept in a content-addressed cache (`build/shader_cache.rs`,
//!    `~/.cache/scratchwave/shader`): another checkout of the same kernel and shader, a
//!    fresh clone included, reuses it without running the nightly at all.
//!    `SCRATCHWAVE_SHADER_CACHE=off` always builds.
//!
//! Anything missing fails the build with a message naming `scripts/setup.sh`.

#[path = "build/shader_cache.rs"]
mod shader_cache;

use shader_cache::io_error;
use spirv_builder::{SpirvBuilder, cargo_cmd::CargoCmd};
use std::fs;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::Instant;

/// The toolchain rustc_codegen_spirv 0.11 is written against (see its build.rs).
const TOOLCHAIN: &str = "nightly-2026-08-15";
/// Components of [`TOOLCHAIN`] the codegen build and `-Zbuild-std=core` need.
const COMPONENTS: [&str; 3] = ["rust-src", "rustc-dev", "llvm-tools"];
/// Vulkan 1.2 SPIR-V: what lavapipe and every current desktop driver accept.
const TARGET: &str = "spirv-unknown-vulkan1.2";
const SETUP_HINT: &str = "run `scripts/setup.sh` (installs the Rust toolchain nightly-2026-08-15 \
     with rust-src, rustc-dev and llvm-tools, and the Debian packages spirv-tools, \
     mesa-vulkan-drivers and libvulkan1)";

type BuildResult<T> = Result<T, String>;

fn main() {
    if let Err(message) = build() {
        // Cargo prints a failing build script's stderr; keep the message first and plain.
        eprintln!("error: scratchwave-spirv cannot build its SPIR-V shader module:\n  {message}");
        std::process::exit(1);
    }
}

fn build() -> BuildResult<()> {
    let manifest_dir = PathBuf::from(env("CARGO_MANIFEST_DIR")?);
    let workspace = manifest_dir
        .parent()
        .ok_or("backend-spirv has no parent directory")?
        .to_path_buf();
    let shader_dir = manifest_dir.join("shader");
    let codegen_dir = manifest_dir.join("codegen");
    for path in ["codegen/Cargo.toml", "codegen/Cargo.lock"] {
        println!(
            "cargo::rerun-if-changed={}",
            manifest_dir.join(path).display()
        );
    }
    for path in shader_cache::HASHED.iter().chain(&["Cargo.lock"]) {
        println!("cargo::rerun-if-changed={}", workspace.join(path).display());
    }
    for var in ["XDG_CACHE_HOME", "SCRATCHWAVE_SHADER_CACHE"] {
        println!("cargo::rerun-if-env-changed={var}");
    }
    let features: Vec<String> = if std::env::var_os("CARGO_FEATURE_PORTABLE_MATH").is_some() {
        vec!["portable-math".to_owned()]
    } else {
        Vec::new()
    };

    // A module built before from the same inputs, by any checkout on this machine.
    let cache = shader_cache::directory();
    let key = shader_cache::key(&workspace, &build_config(&codegen_dir, &features)?)?;
    if let Some(entry) = cache
        .as_deref()
        .and_then(|dir| shader_cache::lookup(dir, &key))
    {
        return announce(&entry.module, &entry.entry_points);
    }

    check_toolchain()?;
    check_spirv_tools()?;
    let codegen = codegen_backend(&codegen_dir)?;

    let mut builder = SpirvBuilder::new(&shader_dir, TARGET);
    builder.rustc_codegen_spirv_location = Some(codegen);
    builder.toolchain_overwrite = Some(TOOLCHAIN.to_owned());
    // rerun-if-changed for every source file the shader depends on (the kernel included),
    // rustc warnings forwarded as cargo warnings.
    builder.build_script.defaults = true;
    builder = builder.shader_crate_features(features);
    let start = Instant::now();
    let result = builder
        .build()
        .map_err(|e| format!("building the shader crate {}: {e}", shader_dir.display()))?;
    let module = result.module.unwrap_single().to_path_buf();
    let Some(dir) = cache else {
        return announce(&module, &result.entry_points);
    };
    let outside = shader_cache::outside_inputs(&module.with_extension("d"), &workspace)?;
    if !outside.is_empty() {
        println!(
            "cargo::warning=the SPIR-V module is not cached: it read {} , which the cache key \
             (backend-spirv/build/shader_cache.rs) does not cover",
            outside.join(", ")
        );
        return announce(&module, &result.entry_points);
    }
    let entry = shader_cache::store(&dir, &key, &module, &result.entry_points)?;
    println!(
        "cargo::warning=built the SPIR-V module in {:.0} s; cached for every checkout on \
         this machine: {}",
        start.elapsed().as_secs_f64(),
        entry.module.display()
    );
    announce(&entry.module, &entry.entry_points)
}

/// Hands the module and its entry points to the crate.
fn announce(module: &Path, entry_points: &[String]) -> BuildResult<()> {
    println!(
        "cargo::rustc-env=SCRATCHWAVE_SHADER_SPV={}",
        module.display()
    );
    println!(
        "cargo::rustc-env=SCRATCHWAVE_SHADER_ENTRY_POINTS={}",
        entry_points.join(",")
    );
    Ok(())
}

/// What the module depends on besides its sources: toolchain, target, features, the codegen
/// backend's manifest and lock, and the versions of the SPIR-V tools it runs.
fn build_config(codegen_dir: &Path, features: &[String]) -> BuildResult<Vec<String>> {
    let mut config = vec![TOOLCHAIN.to_owned(), TARGET.to_owned(), features.join(",")];
    for file in ["Cargo.toml", "Cargo.lock"] {
        config.push(String::from_utf8_lossy(&read(&codegen_dir.join(file))?).into_owned());
    }
    for tool in ["spirv-opt", "spirv-val"] {
        let version = Command::new(tool)
            .arg("--version")
            .stderr(Stdio::null())
            .output()
            .map(|o| String::from_utf8_lossy(&o.stdout).into_owned())
            .unwrap_or_else(|_| "missing".to_owned());
        config.push(format!("{tool} {version}"));
    }
    Ok(config)
}

fn env(name: &str) -> BuildResult<String> {
    std::env::var(name).map_err(|e| format!("environment variable {name}: {e}"))
}

/// `cargo`/`rustc` children must not inherit the stable toolchain the outer cargo runs on.
fn rustup_command(program: &str) -> Command {
    let mut command = Command::new(program);
    for var in [
        "RUSTC",
        "RUSTC_WRAPPER",
        "RUSTC_WORKSPACE_WRAPPER",
        "RUSTUP_TOOLCHAIN",
        "CARGO",
    ] {
        command.env_remove(var);
    }
    command
}

fn check_toolchain() -> BuildResult<()> {
    let missing_toolchain =
        || format!("the Rust toolchain {TOOLCHAIN} is not installed: {SETUP_HINT}");
    let output = rustup_command("rustup")
        .args(["component", "list", "--installed", "--toolchain", TOOLCHAIN])
        .stderr(Stdio::null())
        .output()
        .map_err(|e| format!("running rustup ({e}); rust-gpu needs rustup: {SETUP_HINT}"))?;
    if !output.status.success() {
        return Err(missing_toolchain());
    }
    let installed = String::from_utf8_lossy(&output.stdout);
    let missing: Vec<&str> = COMPONENTS
        .into_iter()
        .filter(|c| !installed.lines().any(|line| line.starts_with(c)))
        .collect();
    if !missing.is_empty() {
        return Err(format!(
            "the toolchain {TOOLCHAIN} lacks the component(s) {}: {SETUP_HINT}",
            missing.join(", ")
        ));
    }
    Ok(())
}

/// `use-installed-tools`: the codegen backend runs these at every shader link.
fn check_spirv_tools() -> BuildResult<()> {
    for tool in ["spirv-opt", "spirv-val"] {
        let found = Command::new(tool)
            .arg("--version")
            .stdout(Stdio::null())
            .stderr(Stdio::null())
            .status()
            .is_ok_and(|s| s.success());
        if !found {
            return Err(format!(
                "`{tool}` (Debian package spirv-tools) is not on PATH: {SETUP_HINT}"
            ));
        }
    }
    Ok(())
}

/// Path of the cached `librustc_codegen_spirv.so`, building it first if this machine has
/// none for the current `codegen/` manifest, lock and toolchain.
fn codegen_backend(codegen_dir: &Path) -> BuildResult<PathBuf> {
    let manifest = read(&codegen_dir.join("Cargo.toml"))?;
    let lock = read(&codegen_dir.join("Cargo.lock"))?;
    let key = format!(
        "rust-gpu-0.11.0-{:016x}",
        fnv1a(&[&manifest, &lock, TOOLCHAIN.as_bytes()])
    );
    let cache = rust_gpu_cache_dir()?.join("scratchwave-codegen");
    let dylib_name = format!(
        "{}rustc_codegen_spirv{}",
        std::env::consts::DLL_PREFIX,
        std::env::consts::DLL_SUFFIX
    );
    let installed = cache.join(&key).join(&dylib_name);
    if installed.is_file() {
        return Ok(installed);
    }

    fs::create_dir_all(cache.join(&key)).map_err(|e| io_error("creating", &cache, e))?;
    // Two workspaces building at once must not both compile the backend.
    let lock_path = cache.join(format!("{key}.lock"));
    let lock_file =
        fs::File::create(&lock_path).map_err(|e| io_error("creating", &lock_path, e))?;
    lock_file
        .lock()
        .map_err(|e| io_error("locking", &lock_path, e))?;
    if installed.is_file() {
        return Ok(installed);
    }

    let target_dir = cache.join(&key).join("target");
    let start = Instant::now();
    let mut cargo = CargoCmd::new();
    // spirv-tools' build script skips its work when it believes it runs under clippy.
    cargo.env_remove("CLIPPY_ARGS");
    cargo
        .arg(format!("+{TOOLCHAIN}"))
        .args(["build", "--release", "--locked", "--lib", "--manifest-path"])
        .arg(codegen_dir.join("Cargo.toml"))
        .arg("--target-dir")
        .arg(&target_dir)
        // Build-script stdout is read by cargo as directives; keep the child's off it.
        .stdout(Stdio::null())
        .stderr(Stdio::inherit());
    let status = cargo
        .status()
        .map_err(|e| format!("running cargo +{TOOLCHAIN}: {e}: {SETUP_HINT}"))?;
    if !status.success() {
        return Err(format!(
            "building rustc_codegen_spirv from {} failed ({status}); see the output above. \
             If the toolchain or spirv-tools is missing: {SETUP_HINT}",
            codegen_dir.display()
        ));
    }
    let built = target_dir.join("release").join(&dylib_name);
    fs::rename(&built, &installed).map_err(|e| io_error("moving", &built, e))?;
    // The backend's dependency tree is large; only the dylib is needed from here on.
    fs::remove_dir_all(&target_dir).map_err(|e| io_error("removing", &target_dir, e))?;
    println!(
        "cargo::warning=built rustc_codegen_spirv once for this machine in {:.0} s: {}",
        start.elapsed().as_secs_f64(),
        installed.display()
    );
    Ok(installed)
}

/// The cache directory cargo-gpu uses too, so `rm -rf ~/.cache/rust-gpu` resets both.
fn rust_gpu_cache_dir() -> BuildResult<PathBuf> {
    if let Some(dir) = std::env::var_os("XDG_CACHE_HOME").filter(|d| !d.is_empty()) {
        return Ok(PathBuf::from(dir).join("rust-gpu"));
    }
    let home = std::env::var_os("HOME").ok_or("neither XDG_CACHE_HOME nor HOME is set")?;
    Ok(PathBuf::from(home).join(".cache").join("rust-gpu"))
}

fn read(path: &Path) -> BuildResult<Vec<u8>> {
    fs::read(path).map_err(|e| io_error("reading", path, e))
}

/// FNV-1a over the parts, separated: a cache key that is stable across Rust versions
/// (unlike `DefaultHasher`).
fn fnv1a(parts: &[&[u8]]) -> u64 {
    let mut hash = 0xcbf2_9ce4_8422_2325_u64;
    for part in parts {
        for &byte in part.iter().chain(&[0xff]) {
            hash ^= u64::from(byte);
            hash = hash.wrapping_mul(0x0000_0100_0000_01b3);
        }
    }
    hash
}
