//! The C ABI (`include/scratchwave.h`, generated from this file by cbindgen;
//! `tests/header.rs` checks it is current). Every function returns a [`Status`] and, on
//! failure, leaves a message naming the bad argument or JSON field for
//! [`sw_last_error`]. Panics are caught at the boundary and reported as
//! [`Status::Internal`]; handles are freed with their `_free` function (null is accepted).

use crate::batch::{Bsdf, Queries, ScratchSet};
use crate::error::{Error, Status};
use std::cell::RefCell;
use std::ffi::{CStr, CString, c_char};
use std::panic::{AssertUnwindSafe, catch_unwind};
use std::path::Path;

/// A material with its scratch lookup (opaque).
pub struct SwBsdf(Bsdf);

/// A set of scratch segments (opaque).
pub struct SwScratchSet(ScratchSet);

/// One batch of queries as flat arrays; see `Queries` in the Rust docs and
/// `docs/bindings.md`. Directions are local (`z` normal, `x` tangent), pointing away from
/// the surface.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct SwQueries {
    /// Number of queries `n`.
    pub count: usize,
    /// `3n` floats: direction towards the viewer.
    pub wo: *const f32,
    /// `3n` floats: direction towards the light (`sw_eval`, `sw_pdf`; ignored by
    /// `sw_sample`, may be null there).
    pub wi: *const f32,
    /// `2n` floats: scratch-space position (µm), or null for the origin.
    pub x_um: *const f32,
    /// `3n` floats: pixel footprint `(a1, a2, angle)` (µm, µm, radians), or null for none.
    /// Semi-axes in [1e-6, 1e9] µm and a finite angle; otherwise `SW_STATUS_INVALID_ARGUMENT`
    /// naming the first bad value.
    pub footprint: *const f32,
    /// Wavelengths (nm): `lambda_count` floats, or `lambda_count` per query when
    /// `lambda_per_query` is non-zero; null for 700, 520, 440 nm.
    pub lambda_nm: *const f32,
    /// Wavelengths per query, 1 to 4 (ignored when `lambda_nm` is null; then 3).
    pub lambda_count: u32,
    /// Non-zero: `lambda_nm` holds `lambda_count` values per query.
    pub lambda_per_query: u32,
}

thread_local! {
    static LAST_ERROR: RefCell<CString> = RefCell::new(CString::default());
}

fn set_error(msg: String) {
    let c = CString::new(msg.replace('\0', " ")).unwrap_or_default();
    LAST_ERROR.with(|e| *e.borrow_mut() = c);
}

/// Runs `f`, catching panics; records the message of a failure for [`sw_last_error`].
fn guard(f: impl FnOnce() -> Result<(), Error>) -> Status {
    let r = match catch_unwind(AssertUnwindSafe(f)) {
        Ok(r) => r,
        Err(p) => {
            let what = p
                .downcast_ref::<&str>()
                .map(|s| s.to_string())
                .or_else(|| p.downcast_ref::<String>().cloned())
                .unwrap_or_else(|| "panic".into());
            Err(Error::Internal(what))
        }
    };
    match r {
        Ok(()) => {
            set_error(String::new());
            Status::Ok
        }
        Err(e) => {
            let s = e.status();
            set_error(e.to_string());
            s
        }
    }
}

/// A non-null C string argument as UTF-8.
///
/// # Safety
/// `p` is null or a NUL-terminated string.
unsafe fn text<'a>(p: *const c_char, name: &str) -> Result<&'a str, Error> {
    if p.is_null() {
        return Err(Error::arg(format!("{name}: null")));
    }
    // SAFETY: non-null and NUL-terminated by the caller's contract.
    unsafe { CStr::from_ptr(p) }
        .to_str()
        .map_err(|_| Error::arg(format!("{name}: not UTF-8")))
}

/// An optional directory argument.
///
/// # Safety
/// As [`text`].
unsafe fn dir<'a>(p: *const c_char) -> Result<Option<&'a Path>, Error> {
    if p.is_null() {
        return Ok(None);
    }
    // SAFETY: forwarded contract.
    Ok(Some(Path::new(unsafe { text(p, "base_dir") }?)))
}

/// `len` values at `p`; null is an error unless `len` is 0.
///
/// # Safety
/// `p` is null or points to `len` readable values.
unsafe fn slice<'a, T>(p: *const T, len: usize, name: &str) -> Result<&'a [T], Error> {
    if len == 0 {
        return Ok(&[]);
    }
    if p.is_null() {
        return Err(Error::arg(format!("{name}: null")));
    }
    // SAFETY: non-null, `len` values by the caller's contract.
    Ok(unsafe { std::slice::from_raw_parts(p, len) })
}

/// As [`slice`], writable.
///
/// # Safety
/// `p` is null or points to `len` writable values not aliased elsewhere.
unsafe fn slice_mut<'a, T>(p: *mut T, len: usize, name: &str) -> Result<&'a mut [T], Error> {
    if len == 0 {
        return Ok(&mut []);
    }
    if p.is_null() {
        return Err(Error::arg(format!("{name}: null")));
    }
    // SAFETY: non-null, `len` writable values by the caller's contract.
    Ok(unsafe { std::slice::from_raw_parts_mut(p, len) })
}

/// The optional array of `per` values per query.
///
/// # Safety
/// `p` is null or points to `len` readable values.
unsafe fn optional<'a>(p: *const f32, len: usize) -> Option<&'a [f32]> {
    if p.is_null() {
        None
    } else {
        // SAFETY: non-null, `len` values by the caller's contract.
        Some(unsafe { std::slice::from_raw_parts(p, len) })
    }
}

/// The Rust view of a C batch.
///
/// # Safety
/// `q` is null or valid, and its arrays hold the counts its fields promise.
unsafe fn queries<'a>(q: *const SwQueries) -> Result<Queries<'a>, Error> {
    if q.is_null() {
        return Err(Error::arg("queries: null"));
    }
    // SAFETY: non-null and valid by the caller's contract.
    let q = unsafe { *q };
    let n = q.count;
    let by = |per: usize| {
        n.checked_mul(per)
            .ok_or_else(|| Error::arg(format!("count: {n} queries overflow the address space")))
    };
    // Every per-query array (at most 4 values per query) fits the address space.
    by(4)?;
    let k = q.lambda_count as usize;
    let lambda_len = if q.lambda_per_query != 0 { by(k)? } else { k };
    // SAFETY: each array holds the count the caller promised.
    unsafe {
        Ok(Queries {
            wo: slice(q.wo, by(3)?, "queries.wo")?,
            wi: optional(q.wi, by(3)?),
            x_um: optional(q.x_um, by(2)?),
            footprint: optional(q.footprint, by(3)?),
            lambda_nm: optional(q.lambda_nm, lambda_len),
            lambda_count: k,
        })
    }
}

/// Stores a new handle at `out`.
///
/// # Safety
/// `out` is null or writable.
unsafe fn put<T>(out: *mut *mut T, v: T) -> Result<(), Error> {
    if out.is_null() {
        return Err(Error::arg("out: null"));
    }
    // SAFETY: non-null and writable by the caller's contract.
    unsafe { *out = Box::into_raw(Box::new(v)) };
    Ok(())
}

/// The message of the last failed call on this thread ("" after a success). Valid until
/// the next call on this thread.
#[unsafe(no_mangle)]
pub extern "C" fn sw_last_error() -> *const c_char {
    LAST_ERROR.with(|e| e.borrow().as_ptr())
}

/// The library version (`major.minor.patch`), a static string.
#[unsafe(no_mangle)]
pub extern "C" fn sw_version() -> *const c_char {
    concat!(env!("CARGO_PKG_VERSION"), "\0").as_ptr().cast()
}

/// A scratch set from a JSON array of scratch sources (as a scene material's
/// `"scratches"`, `docs/scratches.md`); files are resolved against `base_dir` (null: the
/// working directory).
///
/// # Safety
/// `json` and `base_dir` are null or NUL-terminated; `out` is null or writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sw_scratch_set_from_json(
    json: *const c_char,
    base_dir: *const c_char,
    out: *mut *mut SwScratchSet,
) -> Status {
    guard(|| {
        // SAFETY: forwarded contract.
        let s = unsafe { ScratchSet::from_json(text(json, "json")?, dir(base_dir)?) }?;
        // SAFETY: forwarded contract.
        unsafe { put(out, SwScratchSet(s)) }
    })
}

/// A scratch set from `count` rows of 6 doubles `x0, y0, x1, y1, width, depth` (µm);
/// `triangle` (null: all rectangular) marks triangular profiles with non-zero bytes.
///
/// # Safety
/// `rows` holds `6·count` doubles, `triangle` is null or holds `count` bytes, `out` is
/// null or writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sw_scratch_set_from_rows(
    rows: *const f64,
    triangle: *const u8,
    count: usize,
    out: *mut *mut SwScratchSet,
) -> Status {
    guard(|| {
        let len = count
            .checked_mul(6)
            .ok_or_else(|| Error::arg("count: overflows the address space"))?;
        // SAFETY: forwarded contract.
        let flat = unsafe { slice(rows, len, "rows") }?;
        let rows: Vec<[f64; 6]> = flat
            .chunks_exact(6)
            .map(|r| [r[0], r[1], r[2], r[3], r[4], r[5]])
            .collect();
        let tri: Vec<bool> = if triangle.is_null() {
            vec![false; count]
        } else {
            // SAFETY: forwarded contract.
            unsafe { slice(triangle, count, "triangle") }?
                .iter()
                .map(|b| *b != 0)
                .collect()
        };
        let s = ScratchSet::from_rows(&rows, &tri)?;
        // SAFETY: forwarded contract.
        unsafe { put(out, SwScratchSet(s)) }
    })
}

/// Number of segments of a scratch set (0 for null).
///
/// # Safety
/// `set` is null or a live handle.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sw_scratch_set_len(set: *const SwScratchSet) -> usize {
    // SAFETY: null or live by the caller's contract.
    unsafe { set.as_ref() }.map_or(0, |s| s.0.len())
}

/// Frees a scratch set (null is accepted).
///
/// # Safety
/// `set` is null or a live handle not used afterwards.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sw_scratch_set_free(set: *mut SwScratchSet) {
    if !set.is_null() {
        // SAFETY: a handle made by `put`, freed once.
        drop(unsafe { Box::from_raw(set) });
    }
}

/// A material from the scene file's material JSON (`docs/render.md`, "materials"):
/// `{"model": "werner" | "werner_blended" | "velinov" | "ghs", ...}`. `scratches` (null:
/// none) gives its scratches, unless the JSON has its own `"scratches"` (then it must be
/// null). Files are resolved against `base_dir` (null: the working directory).
///
/// # Safety
/// `json`, `base_dir` are null or NUL-terminated; `scratches` is null or live; `out` is
/// null or writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sw_bsdf_from_json(
    json: *const c_char,
    base_dir: *const c_char,
    scratches: *const SwScratchSet,
    out: *mut *mut SwBsdf,
) -> Status {
    guard(|| {
        // SAFETY: forwarded contract.
        let (t, d, s) = unsafe { (text(json, "json")?, dir(base_dir)?, scratches.as_ref()) };
        let b = Bsdf::from_json(t, d, s.map(|s| &s.0))?;
        // SAFETY: forwarded contract.
        unsafe { put(out, SwBsdf(b)) }
    })
}

/// Number of scratch segments of a material (0 for null).
///
/// # Safety
/// `bsdf` is null or a live handle.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sw_bsdf_scratch_count(bsdf: *const SwBsdf) -> usize {
    // SAFETY: null or live by the caller's contract.
    unsafe { bsdf.as_ref() }.map_or(0, |b| b.0.scratch_count())
}

/// Frees a material (null is accepted).
///
/// # Safety
/// `bsdf` is null or a live handle not used afterwards.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sw_bsdf_free(bsdf: *mut SwBsdf) {
    if !bsdf.is_null() {
        // SAFETY: a handle made by `put`, freed once.
        drop(unsafe { Box::from_raw(bsdf) });
    }
}

/// The live material behind a handle.
///
/// # Safety
/// `bsdf` is null or a live handle.
unsafe fn bsdf_ref<'a>(bsdf: *const SwBsdf) -> Result<&'a Bsdf, Error> {
    // SAFETY: null or live by the caller's contract.
    unsafe { bsdf.as_ref() }
        .map(|b| &b.0)
        .ok_or_else(|| Error::arg("bsdf: null"))
}

/// Runs a batch call with one output array (`eval`, `pdf`) behind the guard.
///
/// # Safety
/// As [`sw_eval`].
unsafe fn one_output(
    bsdf: *const SwBsdf,
    queries: *const SwQueries,
    out: *mut f32,
    out_len: usize,
    call: fn(&Bsdf, &Queries<'_>, &mut [f32]) -> Result<(), Error>,
) -> Status {
    guard(|| {
        // SAFETY: forwarded contract.
        let (b, q, o) = unsafe {
            (
                bsdf_ref(bsdf)?,
                self::queries(queries)?,
                slice_mut(out, out_len, "out")?,
            )
        };
        call(b, &q, o)
    })
}

/// The BRDF (1/sr, without the cosine) of each query: `out` receives `k` floats per query
/// (`k` = wavelengths per query), `out_len` = `k·count`.
///
/// # Safety
/// `bsdf` is a live handle, `queries` valid with arrays of the promised sizes, `out` holds
/// `out_len` writable floats.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sw_eval(
    bsdf: *const SwBsdf,
    queries: *const SwQueries,
    out: *mut f32,
    out_len: usize,
) -> Status {
    // SAFETY: forwarded contract.
    unsafe { one_output(bsdf, queries, out, out_len, Bsdf::eval) }
}

/// The solid-angle pdf of sampling each query's `wi` given its `wo`: one float per query.
///
/// # Safety
/// As [`sw_eval`]; `out` holds `out_len` = `count` floats.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sw_pdf(
    bsdf: *const SwBsdf,
    queries: *const SwQueries,
    out: *mut f32,
    out_len: usize,
) -> Status {
    // SAFETY: forwarded contract.
    unsafe { one_output(bsdf, queries, out, out_len, Bsdf::pdf) }
}

/// Draws `wi` given `wo` for each query from `u` (3 uniform floats per query). Writes
/// `wi_out` (3 per query), `weight_out` (`f·cosθi/pdf`, `k` per query) and `pdf_out` (1
/// per query); all three are 0 where nothing can be drawn.
///
/// # Safety
/// `bsdf` is a live handle, `queries` valid, `u` holds `3·count` floats, the outputs hold
/// `3·count`, `k·count` and `count` writable floats.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sw_sample(
    bsdf: *const SwBsdf,
    queries: *const SwQueries,
    u: *const f32,
    wi_out: *mut f32,
    weight_out: *mut f32,
    pdf_out: *mut f32,
) -> Status {
    guard(|| {
        // SAFETY: forwarded contract.
        let (b, q) = unsafe { (bsdf_ref(bsdf)?, self::queries(queries)?) };
        let n = q.len();
        let k = q.wavelengths_per_query();
        // SAFETY: forwarded contract.
        let (u, wi, w, p) = unsafe {
            (
                slice(u, 3 * n, "u")?,
                slice_mut(wi_out, 3 * n, "wi_out")?,
                slice_mut(weight_out, k * n, "weight_out")?,
                slice_mut(pdf_out, n, "pdf_out")?,
            )
        };
        b.sample(&q, u, wi, w, p)
    })
}
