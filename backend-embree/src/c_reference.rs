//! The C reference program (`bench-c/embree_rays.c`): the same Embree library, mesh and rays
//! driven from plain C, to measure what this crate's wrapper costs and to prove that both
//! trace the same rays to the same hits.
//!
//! [`compile`] builds the program with the system C compiler (`$CC`, else `cc`) at run time;
//! [`write_workload`] writes a mesh and ray sets in the format the program reads;
//! [`CProgram`] starts it (it builds its scene once) and runs timed passes over one ray set
//! and [`QueryPath`] at a time, so a driver can interleave C and Rust runs;
//! [`run_rust`] runs the same path through [`Scene`]. Both report a [`Measurement`] with an
//! FNV-1a checksum of every hit ([`hash_hits`], [`hash_occluded`]; the C program hashes the
//! same words in the same order).
//!
//! Used by `tests/c_reference.rs` and the `embree_vs_c` example of `scratchwave-benches`.

use crate::Scene;
use scratchwave_host::Coherence;
use scratchwave_kernel::ray::{Hit, Ray};
use std::ffi::OsString;
use std::io::{BufRead, BufReader, BufWriter, Write};
use std::ops::Range;
use std::path::{Path, PathBuf};
use std::process::{Child, ChildStdin, ChildStdout, Command, Stdio};
use std::time::Instant;

/// The C source, embedded so the program can be built wherever the crate is used.
pub const SOURCE: &str = include_str!("../bench-c/embree_rays.c");

/// Magic bytes opening a workload file.
const MAGIC: &[u8; 8] = b"SWRAYS01";

/// One query path, the same Embree entry point on both sides.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum QueryPath {
    /// Closest hit of single rays: `rtcIntersect1` ([`Scene::intersect`]).
    Intersect1,
    /// Closest hits of packets of 8 consecutive rays: `rtcIntersect8`
    /// ([`Scene::intersect_many`] with width 8).
    Intersect8,
    /// Packets of 16: `rtcIntersect16` ([`Scene::intersect_many`] with width 16).
    Intersect16,
    /// Occlusion of single rays: `rtcOccluded1` ([`Scene::occluded`]).
    Occluded1,
}

impl QueryPath {
    /// Every path, in table order.
    pub const ALL: [QueryPath; 4] = [
        QueryPath::Intersect1,
        QueryPath::Intersect8,
        QueryPath::Intersect16,
        QueryPath::Occluded1,
    ];

    /// The Embree function's name, which is also the C program's name for the path.
    pub fn name(self) -> &'static str {
        match self {
            QueryPath::Intersect1 => "intersect1",
            QueryPath::Intersect8 => "intersect8",
            QueryPath::Intersect16 => "intersect16",
            QueryPath::Occluded1 => "occluded1",
        }
    }

    /// `rtcIntersect1`, `rtcIntersect8`, … as written in the C API.
    pub fn embree_function(self) -> &'static str {
        match self {
            QueryPath::Intersect1 => "rtcIntersect1",
            QueryPath::Intersect8 => "rtcIntersect8",
            QueryPath::Intersect16 => "rtcIntersect16",
            QueryPath::Occluded1 => "rtcOccluded1",
        }
    }
}

/// How long to time one path: passes over the whole ray set are repeated until both
/// minimums are reached. Each pass traces the rays in blocks of consecutive rays, each block
/// timed on its own.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Budget {
    /// Minimum total time of the timed passes, in seconds of thread CPU time.
    pub min_seconds: f64,
    /// Minimum number of passes.
    pub min_passes: u32,
    /// Rays per timed block; rounded up to a multiple of 16 (at least 16, at most 2³⁰), so
    /// packets are the same as without blocks.
    pub block: usize,
}

impl Budget {
    /// A single pass: enough to compare hits.
    pub const ONCE: Budget = Budget {
        min_seconds: 0.0,
        min_passes: 1,
        block: 4096,
    };

    /// The block length actually used: [`Budget::block`] clamped to 16…2³⁰ and rounded up
    /// to a multiple of 16.
    pub fn block_len(&self) -> usize {
        self.block.clamp(16, 1 << 30).next_multiple_of(16)
    }
}

/// The result of timing one path on one ray set.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Measurement {
    /// Rays per pass.
    pub rays: usize,
    /// Passes timed.
    pub passes: u32,
    /// The sum over blocks of each block's fastest time, in seconds of thread CPU time: the
    /// time of a pass undisturbed by other processes, as well as the passes can tell.
    pub best_seconds: f64,
    /// All passes together, in seconds of thread CPU time.
    pub total_seconds: f64,
    /// Rays that hit something (or were occluded) in the last pass.
    pub hits: u64,
    /// [`hash_hits`] or [`hash_occluded`] of the last pass.
    pub checksum: u64,
}

impl Measurement {
    /// Rays per second from [`Measurement::best_seconds`].
    pub fn rays_per_second(&self) -> f64 {
        self.rays as f64 / self.best_seconds
    }

    /// Combines two measurements of the same work (e.g. interleaved rounds): the better
    /// [`Measurement::best_seconds`] and the sums; hits and checksum of `self` (the caller
    /// checks they agree).
    pub fn merge(self, other: Measurement) -> Measurement {
        Measurement {
            passes: self.passes + other.passes,
            best_seconds: self.best_seconds.min(other.best_seconds),
            total_seconds: self.total_seconds + other.total_seconds,
            ..self
        }
    }
}

/// Why the C reference could not be built or run.
#[derive(Debug, thiserror::Error)]
pub enum CReferenceError {
    /// No C compiler could be started.
    #[error("no C compiler ({compiler:?}: {source}); set CC or install cc")]
    NoCompiler {
        /// The command tried.
        compiler: OsString,
        /// Why it could not be started.
        source: std::io::Error,
    },
    /// The compiler rejected the program.
    #[error("{compiler:?} failed on embree_rays.c:\n{stderr}")]
    Compile {
        /// The command run.
        compiler: OsString,
        /// Its diagnostics.
        stderr: String,
    },
    /// Reading or writing a file or the program's pipes failed.
    #[error("{what}: {source}")]
    Io {
        /// What was being done.
        what: String,
        /// The error.
        source: std::io::Error,
    },
    /// The program answered something unexpected or exited.
    #[error("C program: {0}")]
    Protocol(String),
    /// A workload does not fit the file format (more than `u32::MAX` items).
    #[error("workload too large: {0}")]
    TooLarge(&'static str),
}

fn io(what: impl Into<String>) -> impl FnOnce(std::io::Error) -> CReferenceError {
    let what = what.into();
    move |source| CReferenceError::Io { what, source }
}

/// Writes [`SOURCE`] into `dir` and compiles it with `$CC` (default `cc`) at `-O2`; returns
/// the executable's path. The program opens Embree with `dlopen`, like this crate.
pub fn compile(dir: &Path) -> Result<PathBuf, CReferenceError> {
    std::fs::create_dir_all(dir).map_err(io(format!("create {}", dir.display())))?;
    let source = dir.join("embree_rays.c");
    let exe = dir.join("embree_rays");
    std::fs::write(&source, SOURCE).map_err(io(format!("write {}", source.display())))?;
    let compiler = std::env::var_os("CC").unwrap_or_else(|| "cc".into());
    let output = Command::new(&compiler)
        .args(["-std=c11", "-O2", "-Wall", "-Wextra", "-o"])
        .arg(&exe)
        .arg(&source)
        .arg("-ldl")
        .output()
        .map_err(|source| CReferenceError::NoCompiler {
            compiler: compiler.clone(),
            source,
        })?;
    if !output.status.success() {
        return Err(CReferenceError::Compile {
            compiler,
            stderr: String::from_utf8_lossy(&output.stderr).into_owned(),
        });
    }
    Ok(exe)
}

fn count(n: usize, what: &'static str) -> Result<[u8; 4], CReferenceError> {
    u32::try_from(n)
        .map(u32::to_le_bytes)
        .map_err(|_| CReferenceError::TooLarge(what))
}

/// Writes one mesh and several ray sets in the program's workload format (see the comment
/// at the top of `bench-c/embree_rays.c`).
pub fn write_workload(
    path: &Path,
    vertices: &[[f32; 3]],
    indices: &[[u32; 3]],
    ray_sets: &[&[Ray]],
) -> Result<(), CReferenceError> {
    let what = || format!("write {}", path.display());
    let file = std::fs::File::create(path).map_err(io(what()))?;
    let mut out = BufWriter::new(file);
    let mut bytes: Vec<u8> = Vec::with_capacity(20);
    bytes.extend_from_slice(MAGIC);
    bytes.extend_from_slice(&count(vertices.len(), "vertices")?);
    bytes.extend_from_slice(&count(indices.len(), "triangles")?);
    bytes.extend_from_slice(&count(ray_sets.len(), "ray sets")?);
    out.write_all(&bytes).map_err(io(what()))?;
    for v in vertices.iter().flatten() {
        out.write_all(&v.to_le_bytes()).map_err(io(what()))?;
    }
    for i in indices.iter().flatten() {
        out.write_all(&i.to_le_bytes()).map_err(io(what()))?;
    }
    for rays in ray_sets {
        out.write_all(&count(rays.len(), "rays")?)
            .map_err(io(what()))?;
        for r in *rays {
            let words = [
                r.origin[0],
                r.origin[1],
                r.origin[2],
                r.t_near,
                r.dir[0],
                r.dir[1],
                r.dir[2],
                r.t_far,
            ];
            for w in words {
                out.write_all(&w.to_le_bytes()).map_err(io(what()))?;
            }
        }
    }
    out.flush().map_err(io(what()))
}

/// A running C reference program with its scene built.
pub struct CProgram {
    child: Child,
    stdin: Option<ChildStdin>,
    stdout: BufReader<ChildStdout>,
    version: isize,
    build_seconds: f64,
}

impl CProgram {
    /// Starts `exe` (from [`compile`]) on `workload` (from [`write_workload`]) with the Embree
    /// library this crate loads ([`crate::ffi::library_path`]) and the device configuration
    /// `device_config` (use the one the Rust [`crate::Device`] was made with), and waits until
    /// its scene is committed.
    pub fn start(
        exe: &Path,
        device_config: &str,
        workload: &Path,
    ) -> Result<CProgram, CReferenceError> {
        let mut child = Command::new(exe)
            .arg(crate::ffi::library_path())
            .arg(device_config)
            .arg(workload)
            .stdin(Stdio::piped())
            .stdout(Stdio::piped())
            .stderr(Stdio::inherit())
            .spawn()
            .map_err(io(format!("start {}", exe.display())))?;
        let (Some(stdin), Some(stdout)) = (child.stdin.take(), child.stdout.take()) else {
            return Err(CReferenceError::Protocol("no pipes".into()));
        };
        let mut program = CProgram {
            child,
            stdin: Some(stdin),
            stdout: BufReader::new(stdout),
            version: 0,
            build_seconds: 0.0,
        };
        let line = program.read_line()?;
        let fields: Vec<&str> = line.split_whitespace().collect();
        match fields.as_slice() {
            ["ready", version, build] => {
                program.version = parse(version, &line)?;
                program.build_seconds = parse(build, &line)?;
            }
            _ => return Err(CReferenceError::Protocol(format!("expected ready: {line}"))),
        }
        Ok(program)
    }

    /// The Embree version the program loaded (`major·10000 + minor·100 + patch`).
    pub fn version(&self) -> isize {
        self.version
    }

    /// CPU seconds the program's main thread took to read the workload and commit its
    /// scene.
    pub fn build_seconds(&self) -> f64 {
        self.build_seconds
    }

    fn read_line(&mut self) -> Result<String, CReferenceError> {
        let mut line = String::new();
        let n = self
            .stdout
            .read_line(&mut line)
            .map_err(io("read from the C program"))?;
        if n == 0 {
            let status = self.child.wait().map_err(io("wait for the C program"))?;
            return Err(CReferenceError::Protocol(format!(
                "exited ({status}); see its message above"
            )));
        }
        Ok(line.trim_end().to_owned())
    }

    /// Times `path` over ray set `set` (its index in [`write_workload`]'s `ray_sets`).
    /// `coherence` is the packet paths' query flag (single rays are traced incoherent, as by
    /// [`Scene::intersect`]).
    pub fn run(
        &mut self,
        set: usize,
        path: QueryPath,
        coherence: Coherence,
        budget: Budget,
    ) -> Result<Measurement, CReferenceError> {
        let coherent = u32::from(coherence == Coherence::Coherent);
        let stdin = self
            .stdin
            .as_mut()
            .ok_or_else(|| CReferenceError::Protocol("already closed".into()))?;
        writeln!(
            stdin,
            "run {set} {} {coherent} {} {} {}",
            path.name(),
            budget.min_seconds,
            budget.min_passes,
            budget.block_len()
        )
        .and_then(|()| stdin.flush())
        .map_err(io("write to the C program"))?;
        let line = self.read_line()?;
        let fields: Vec<&str> = line.split_whitespace().collect();
        let ["ok", rays, passes, best, total, hits, checksum] = fields.as_slice() else {
            return Err(CReferenceError::Protocol(format!("expected ok: {line}")));
        };
        Ok(Measurement {
            rays: parse(rays, &line)?,
            passes: parse(passes, &line)?,
            best_seconds: parse(best, &line)?,
            total_seconds: parse(total, &line)?,
            hits: parse(hits, &line)?,
            checksum: u64::from_str_radix(checksum, 16)
                .map_err(|e| CReferenceError::Protocol(format!("{e}: {line}")))?,
        })
    }
}

impl Drop for CProgram {
    fn drop(&mut self) {
        if let Some(mut stdin) = self.stdin.take() {
            // The program may already have exited; then there is nothing to tell it.
            let _ = writeln!(stdin, "quit");
        }
        // Closing stdin ends the program; reap it.
        let _ = self.child.wait();
    }
}

fn parse<T: std::str::FromStr>(field: &str, line: &str) -> Result<T, CReferenceError>
where
    T::Err: std::fmt::Display,
{
    field
        .parse()
        .map_err(|e| CReferenceError::Protocol(format!("{e} in {field:?}: {line}")))
}

/// CPU time of the calling thread, in seconds (`CLOCK_THREAD_CPUTIME_ID`, as in the C
/// program): unlike wall time it leaves out the time the thread waited for a core, which on a
/// shared machine is most of the noise.
#[cfg(target_os = "linux")]
pub fn thread_cpu_seconds() -> f64 {
    #[repr(C)]
    struct Timespec {
        tv_sec: i64,
        tv_nsec: i64,
    }
    unsafe extern "C" {
        fn clock_gettime(clock: i32, out: *mut Timespec) -> i32;
    }
    const CLOCK_THREAD_CPUTIME_ID: i32 = 3;
    let mut t = Timespec {
        tv_sec: 0,
        tv_nsec: 0,
    };
    // SAFETY: glibc's clock_gettime writes one `struct timespec` (two 64-bit words on 64-bit
    // Linux) and has no other effect.
    match unsafe { clock_gettime(CLOCK_THREAD_CPUTIME_ID, &mut t) } {
        0 => t.tv_sec as f64 + 1e-9 * t.tv_nsec as f64,
        _ => wall_seconds(),
    }
}

/// Wall time since first use, in seconds (the stand-in for thread CPU time off Linux).
#[cfg(not(target_os = "linux"))]
pub fn thread_cpu_seconds() -> f64 {
    wall_seconds()
}

fn wall_seconds() -> f64 {
    static START: std::sync::OnceLock<Instant> = std::sync::OnceLock::new();
    START.get_or_init(Instant::now).elapsed().as_secs_f64()
}

/// Times passes over `n` rays until `budget` is spent, calling `trace` on each block of ray
/// indices, exactly as the C program does; times are [`thread_cpu_seconds`]. Returns
/// `(passes, best_seconds, total_seconds)` with `best_seconds` the sum of each block's
/// fastest time.
pub fn time_passes(
    budget: Budget,
    n: usize,
    mut trace: impl FnMut(Range<usize>),
) -> (u32, f64, f64) {
    let block = budget.block_len();
    let mut block_best = vec![f64::INFINITY; n.div_ceil(block)];
    let (mut passes, mut total) = (0u32, 0.0);
    // An empty ray set takes no time: only the minimum number of passes then.
    while passes < budget.min_passes || (total < budget.min_seconds && n > 0) {
        for (b, best) in block_best.iter_mut().enumerate() {
            let range = b * block..n.min((b + 1) * block);
            let start = thread_cpu_seconds();
            trace(range);
            let elapsed = thread_cpu_seconds() - start;
            *best = best.min(elapsed);
            total += elapsed;
        }
        passes += 1;
    }
    (passes, block_best.iter().sum(), total)
}

/// Times `path` through the Rust wrapper on `rays`, exactly as [`CProgram::run`] times the C
/// program: the same passes, the same outputs (one hit record or flag per ray), hashed after
/// the last pass.
pub fn run_rust(
    scene: &Scene,
    rays: &[Ray],
    path: QueryPath,
    coherence: Coherence,
    budget: Budget,
) -> Measurement {
    let mut hits: Vec<Option<Hit>> = vec![None; rays.len()];
    let mut occluded = vec![false; rays.len()];
    let (passes, best_seconds, total_seconds) = time_passes(budget, rays.len(), |r| match path {
        QueryPath::Intersect1 => scene.intersect_many(&rays[r.clone()], &mut hits[r], 1, coherence),
        QueryPath::Intersect8 => scene.intersect_many(&rays[r.clone()], &mut hits[r], 8, coherence),
        QueryPath::Intersect16 => {
            scene.intersect_many(&rays[r.clone()], &mut hits[r], 16, coherence)
        }
        QueryPath::Occluded1 => {
            for (ray, o) in rays[r.clone()].iter().zip(&mut occluded[r]) {
                *o = scene.occluded(ray);
            }
        }
    });
    let (hit_count, checksum) = match path {
        QueryPath::Occluded1 => hash_occluded(&occluded),
        _ => hash_hits(&hits),
    };
    Measurement {
        rays: rays.len(),
        passes,
        best_seconds,
        total_seconds,
        hits: hit_count,
        checksum,
    }
}

const FNV_OFFSET: u64 = 0xcbf2_9ce4_8422_2325;
const FNV_PRIME: u64 = 0x0000_0100_0000_01b3;

/// FNV-1a over one 32-bit word, low byte first.
fn fnv_word(mut h: u64, w: u32) -> u64 {
    for b in w.to_le_bytes() {
        h ^= u64::from(b);
        h = h.wrapping_mul(FNV_PRIME);
    }
    h
}

/// `(hits, checksum)`: FNV-1a over, per ray, `geom_id, prim_id, t, u, v, ng` (bit patterns)
/// for a hit and the single word `u32::MAX` for a miss.
pub fn hash_hits(hits: &[Option<Hit>]) -> (u64, u64) {
    let mut h = FNV_OFFSET;
    let mut count = 0;
    for hit in hits {
        match hit {
            None => h = fnv_word(h, u32::MAX),
            Some(hit) => {
                count += 1;
                let words = [
                    hit.geom_id,
                    hit.prim_id,
                    hit.t.to_bits(),
                    hit.u.to_bits(),
                    hit.v.to_bits(),
                    hit.ng[0].to_bits(),
                    hit.ng[1].to_bits(),
                    hit.ng[2].to_bits(),
                ];
                h = words.into_iter().fold(h, fnv_word);
            }
        }
    }
    (count, h)
}

/// `(occluded rays, checksum)`: FNV-1a over one word per ray, 1 if occluded, else 0.
pub fn hash_occluded(occluded: &[bool]) -> (u64, u64) {
    let h = occluded
        .iter()
        .fold(FNV_OFFSET, |h, &o| fnv_word(h, u32::from(o)));
    (occluded.iter().filter(|&&o| o).count() as u64, h)
}
