//! A content-addressed cache of the built SPIR-V module, shared by every checkout on a
//! machine.
//!
//! Cargo decides whether to rebuild the shader from file modification times and absolute
//! paths, so a fresh clone of an unchanged kernel recompiled it (tens of minutes: rust-gpu
//! codegen and `spirv-opt` are single-threaded). The key here is a hash of everything the
//! module is built from instead:
//!
//! - the build configuration (toolchain, target, features, codegen backend, SPIR-V tools);
//! - the shader crate and the kernel: `backend-spirv/shader/**`, `kernel/src/**`,
//!   `kernel/Cargo.toml`, and `backend-spirv/build.rs` (how the shader is built; this file
//!   only keys and stores, and a change to the key's meaning bumps its version string);
//! - the workspace manifest, less what cannot reach the shader (the member list, and the
//!   workspace dependencies outside the shader's dependency tree);
//! - the `Cargo.lock` entries of the shader's dependency tree (the kernel's and the shader's
//!   dev-dependencies excluded).
//!
//! After a build, [`outside_inputs`] reads the compiler's dep-info: a workspace file the
//! shader read that the key does not cover makes the build uncacheable (and says so) rather
//! than letting a later build reuse a module that file would have changed.

use std::collections::{BTreeMap, BTreeSet};
use std::fs;
use std::path::{Path, PathBuf};

/// Source trees and files of the workspace that the key hashes, relative to its root.
pub const HASHED: [&str; 5] = [
    "kernel/src",
    "kernel/Cargo.toml",
    "backend-spirv/shader",
    "backend-spirv/build.rs",
    "Cargo.toml",
];

/// The package whose dependency tree the key covers.
const SHADER_PACKAGE: &str = "scratchwave-spirv-shader";

/// Manifests whose `[dev-dependencies]` are left out of the dependency tree.
const DEV_MANIFESTS: [&str; 2] = ["kernel/Cargo.toml", "backend-spirv/shader/Cargo.toml"];

/// The cache key: 32 hex digits (FNV-1a, 128 bits) over `config` and the inputs above.
pub fn key(workspace: &Path, config: &[String]) -> Result<String, String> {
    let mut hash = Fnv128::new();
    hash.part(b"scratchwave shader cache v1");
    for item in config {
        hash.part(item.as_bytes());
    }
    let lock = read_text(&workspace.join("Cargo.lock"))?;
    let mut dev_only = BTreeSet::new();
    for manifest in DEV_MANIFESTS {
        let text = read_text(&workspace.join(manifest))?;
        dev_only.extend(section_keys(&text, "dev-dependencies"));
    }
    let tree = lock_tree(&lock, SHADER_PACKAGE, &dev_only)?;
    // Each block names its package, version, source and checksum.
    for block in tree.values() {
        hash.part(block.as_bytes());
    }
    let names: BTreeSet<&str> = tree.keys().map(|(name, _)| name.as_str()).collect();
    for relative in HASHED {
        let path = workspace.join(relative);
        if relative == "Cargo.toml" {
            let text = read_text(&path)?;
            hash.part(relative.as_bytes());
            hash.part(workspace_manifest_for(&text, &names).as_bytes());
            continue;
        }
        for file in files_under(&path)? {
            let name = file
                .strip_prefix(workspace)
                .unwrap_or(&file)
                .to_string_lossy()
                .replace('\\', "/");
            hash.part(name.as_bytes());
            hash.part(&fs::read(&file).map_err(|e| io_error("reading", &file, e))?);
        }
    }
    Ok(format!("{:032x}", hash.finish()))
}

/// Workspace files that the compiler read for the shader (its dep-info `depfile`, and the
/// dep-info beside every library it linked, recursively) and that no [`HASHED`] path covers.
pub fn outside_inputs(depfile: &Path, workspace: &Path) -> Result<Vec<String>, String> {
    let covered: Vec<PathBuf> = HASHED.iter().map(|h| workspace.join(h)).collect();
    let mut outside = BTreeSet::new();
    let mut seen = BTreeSet::new();
    let mut pending = vec![depfile.to_path_buf()];
    while let Some(file) = pending.pop() {
        if !seen.insert(file.clone()) {
            continue;
        }
        let text = read_text(&file)?;
        for line in text.lines() {
            let Some((_, deps)) = line.split_once(": ") else {
                continue;
            };
            for dep in split_escaped(deps) {
                // rustc writes workspace members' files relative to the workspace.
                let path = workspace.join(&dep);
                if is_library(&dep) {
                    // A compiled library (a proc macro is a shared object) is a build
                    // output, wherever the target directory lies: what it was built from
                    // is in the dep-info beside it.
                    pending.extend(depfiles_beside(&path));
                } else if path.starts_with(workspace)
                    && !covered.iter().any(|c| path.starts_with(c))
                {
                    outside.insert(dep);
                }
            }
        }
    }
    Ok(outside.into_iter().collect())
}

/// Whether a dep-info entry is a compiled library: an `rlib`, `rmeta` or a shared object
/// (proc macros, the codegen backend).
fn is_library(dep: &str) -> bool {
    [".rlib", ".rmeta", ".so", ".dylib", ".dll"]
        .iter()
        .any(|ext| dep.ends_with(ext))
}

/// The dep-info files in the directory of a compiled library.
fn depfiles_beside(library: &Path) -> Vec<PathBuf> {
    let Some(listing) = library.parent().and_then(|dir| fs::read_dir(dir).ok()) else {
        return Vec::new();
    };
    listing
        .flatten()
        .map(|e| e.path())
        .filter(|p| p.extension().is_some_and(|x| x == "d"))
        .collect()
}

/// The cache directory: `$SCRATCHWAVE_SHADER_CACHE` when set (empty or `off`: no cache),
/// else `scratchwave/shader` in `$XDG_CACHE_HOME` or `~/.cache`.
pub fn directory() -> Option<PathBuf> {
    if let Some(dir) = std::env::var_os("SCRATCHWAVE_SHADER_CACHE") {
        return (!dir.is_empty() && dir != "off").then(|| PathBuf::from(dir));
    }
    let base = match std::env::var_os("XDG_CACHE_HOME").filter(|d| !d.is_empty()) {
        Some(dir) => PathBuf::from(dir),
        None => PathBuf::from(std::env::var_os("HOME")?).join(".cache"),
    };
    Some(base.join("scratchwave").join("shader"))
}

/// A cached module: its file and its entry-point names.
pub struct Entry {
    pub module: PathBuf,
    pub entry_points: Vec<String>,
}

const MODULE_FILE: &str = "shader.spv";
const ENTRY_POINTS_FILE: &str = "entry-points.txt";
/// Entries kept; the least recently used beyond this are removed when one is stored.
const KEEP: usize = 8;

/// The entry for `key`, if a complete one is stored; marks it as used.
pub fn lookup(dir: &Path, key: &str) -> Option<Entry> {
    let entry_dir = dir.join(key);
    let names = fs::read_to_string(entry_dir.join(ENTRY_POINTS_FILE)).ok()?;
    let module = entry_dir.join(MODULE_FILE);
    if !module.is_file() {
        return None;
    }
    // Recency for eviction; failing to record it costs nothing but eviction order.
    let _ = fs::File::open(&entry_dir).and_then(|f| f.set_modified(std::time::SystemTime::now()));
    Some(Entry {
        module,
        entry_points: names.lines().map(str::to_owned).collect(),
    })
}

/// Stores a built module under `key` (written aside, then renamed into place, so a reader
/// never sees half an entry) and returns the stored entry.
pub fn store(
    dir: &Path,
    key: &str,
    module: &Path,
    entry_points: &[String],
) -> Result<Entry, String> {
    let staging = dir.join(format!("{key}.partial-{}", std::process::id()));
    fs::create_dir_all(&staging).map_err(|e| io_error("creating", &staging, e))?;
    let copy = staging.join(MODULE_FILE);
    fs::copy(module, &copy).map_err(|e| io_error("copying", module, e))?;
    let names = staging.join(ENTRY_POINTS_FILE);
    fs::write(&names, entry_points.join("\n")).map_err(|e| io_error("writing", &names, e))?;
    let final_dir = dir.join(key);
    if fs::rename(&staging, &final_dir).is_err() {
        // Another build stored the same key first: its entry is as good as ours.
        let _ = fs::remove_dir_all(&staging);
    }
    evict(dir, key);
    lookup(dir, key).ok_or_else(|| format!("the cache entry {} is unreadable", final_dir.display()))
}

/// Removes the least recently used entries beyond [`KEEP`], never `current`.
fn evict(dir: &Path, current: &str) {
    let Ok(listing) = fs::read_dir(dir) else {
        return;
    };
    let mut entries: Vec<(std::time::SystemTime, PathBuf)> = listing
        .flatten()
        .filter(|e| e.file_type().is_ok_and(|t| t.is_dir()))
        .filter(|e| {
            let name = e.file_name().to_string_lossy().into_owned();
            name != current && !name.contains(".partial-")
        })
        .filter_map(|e| Some((e.metadata().ok()?.modified().ok()?, e.path())))
        .collect();
    entries.sort();
    let excess = (entries.len() + 1).saturating_sub(KEEP);
    for (_, path) in entries.into_iter().take(excess) {
        let _ = fs::remove_dir_all(path);
    }
}

/// Every regular file under `path` (or `path` itself), sorted.
fn files_under(path: &Path) -> Result<Vec<PathBuf>, String> {
    let meta = fs::metadata(path).map_err(|e| io_error("reading", path, e))?;
    if meta.is_file() {
        return Ok(vec![path.to_path_buf()]);
    }
    let mut files = Vec::new();
    let mut pending = vec![path.to_path_buf()];
    while let Some(dir) = pending.pop() {
        for entry in fs::read_dir(&dir).map_err(|e| io_error("listing", &dir, e))? {
            let entry = entry.map_err(|e| io_error("listing", &dir, e))?;
            let kind = entry
                .file_type()
                .map_err(|e| io_error("reading", &entry.path(), e))?;
            if kind.is_dir() {
                pending.push(entry.path());
            } else {
                files.push(entry.path());
            }
        }
    }
    files.sort();
    Ok(files)
}

/// The dependency tree of `root` in a `Cargo.lock`: each package's `[[package]]` block by
/// (name, version). Dependencies of `root`'s workspace members named in `dev_only` are not
/// followed (the lock file does not tell dev-dependencies apart).
pub fn lock_tree(
    lock: &str,
    root: &str,
    dev_only: &BTreeSet<String>,
) -> Result<BTreeMap<(String, String), String>, String> {
    struct Package {
        version: String,
        local: bool,
        dependencies: Vec<String>,
        block: String,
    }
    let mut packages: BTreeMap<String, Vec<Package>> = BTreeMap::new();
    for block in lock.split("[[package]]").skip(1) {
        let field = |name: &str| {
            block.lines().find_map(|line| {
                line.strip_prefix(name)?
                    .trim_start()
                    .strip_prefix('=')
                    .map(|v| v.trim().trim_matches('"').to_owned())
            })
        };
        let name = field("name").ok_or("Cargo.lock: a [[package]] without a name")?;
        let version = field("version").unwrap_or_default();
        let local = field("source").is_none();
        let dependencies = match block.split_once("dependencies = [") {
            Some((_, rest)) => rest
                .split(']')
                .next()
                .unwrap_or("")
                .split(',')
                .map(|d| d.trim().trim_matches('"').to_owned())
                .filter(|d| !d.is_empty())
                .collect(),
            None => Vec::new(),
        };
        packages.entry(name).or_default().push(Package {
            version,
            local,
            dependencies,
            block: block.trim().to_owned(),
        });
    }
    let mut tree = BTreeMap::new();
    let mut pending = vec![root.to_owned()];
    while let Some(spec) = pending.pop() {
        // "name", "name version" or "name version (source)".
        let mut words = spec.split_whitespace();
        let name = words.next().unwrap_or("");
        let version = words.next();
        let candidates = packages
            .get(name)
            .ok_or_else(|| format!("Cargo.lock: no package {name} (needed by the shader)"))?;
        let package = match version {
            Some(v) => candidates.iter().find(|p| p.version == v),
            None => candidates.first(),
        }
        .ok_or_else(|| format!("Cargo.lock: no package {spec}"))?;
        let id = (name.to_owned(), package.version.clone());
        if tree.contains_key(&id) {
            continue;
        }
        tree.insert(id, package.block.clone());
        for dependency in &package.dependencies {
            let dep_name = dependency.split_whitespace().next().unwrap_or("");
            if package.local && dev_only.contains(dep_name) {
                continue;
            }
            pending.push(dependency.clone());
        }
    }
    Ok(tree)
}

/// The keys of a `[section]` of a manifest (`name = ...` or `name.workspace = true`).
pub fn section_keys(manifest: &str, section: &str) -> Vec<String> {
    let header = format!("[{section}]");
    let mut inside = false;
    let mut keys = Vec::new();
    for line in manifest.lines() {
        let line = line.trim();
        if line.starts_with('[') {
            inside = line == header;
        } else if inside && !line.is_empty() && !line.starts_with('#') {
            let key = line.split(['=', '.', ' ']).next().unwrap_or("");
            keys.push(key.trim_matches('"').to_owned());
        }
    }
    keys
}

/// The workspace manifest without what cannot change the shader: the `members` and
/// `exclude` lists, comments, and `[workspace.dependencies]` entries for packages outside
/// the shader's tree (`names`).
pub fn workspace_manifest_for(manifest: &str, names: &BTreeSet<&str>) -> String {
    let mut kept = String::new();
    let mut section = String::new();
    let mut in_list = false;
    for line in manifest.lines() {
        let trimmed = line.trim();
        if in_list {
            in_list = !trimmed.starts_with(']');
            continue;
        }
        if trimmed.is_empty() || trimmed.starts_with('#') {
            continue;
        }
        if trimmed.starts_with('[') {
            section = trimmed.to_owned();
        } else if section == "[workspace]"
            && (trimmed.starts_with("members") || trimmed.starts_with("exclude"))
        {
            in_list = trimmed.contains('[') && !trimmed.contains(']');
            continue;
        } else if section == "[workspace.dependencies]" {
            let name = trimmed.split(['=', '.', ' ']).next().unwrap_or("");
            if !names.contains(name.trim_matches('"')) {
                continue;
            }
        }
        kept.push_str(trimmed);
        kept.push('\n');
    }
    kept
}

/// Paths of a dep-info line's right-hand side (spaces inside a path are `\ `).
fn split_escaped(deps: &str) -> Vec<String> {
    let mut paths = Vec::new();
    let mut current = String::new();
    let mut chars = deps.chars();
    while let Some(c) = chars.next() {
        match c {
            '\\' => current.extend(chars.next()),
            ' ' => {
                if !current.is_empty() {
                    paths.push(std::mem::take(&mut current));
                }
            }
            _ => current.push(c),
        }
    }
    if !current.is_empty() {
        paths.push(current);
    }
    paths
}

fn read_text(path: &Path) -> Result<String, String> {
    fs::read_to_string(path).map_err(|e| io_error("reading", path, e))
}

pub fn io_error(action: &str, path: &Path, error: std::io::Error) -> String {
    format!("{action} {}: {error}", path.display())
}

/// FNV-1a with 128-bit state; each part is followed by its length, so parts cannot run
/// into each other.
struct Fnv128(u128);

impl Fnv128 {
    fn new() -> Self {
        Fnv128(0x6c62_272e_07bb_0142_62b8_2175_6295_c58d)
    }

    fn part(&mut self, bytes: &[u8]) {
        let length = (bytes.len() as u64).to_le_bytes();
        for &byte in bytes.iter().chain(&length) {
            self.0 ^= u128::from(byte);
            self.0 = self
                .0
                .wrapping_mul(0x0000_0000_0100_0000_0000_0000_0000_013b);
        }
    }

    fn finish(&self) -> u128 {
        self.0
    }
}
