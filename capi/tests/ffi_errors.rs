//! The C functions called from Rust with bad arguments: each returns its status and leaves
//! a message naming the argument or field; nothing is allocated on failure.

use scratchwave_capi::Status;
use scratchwave_capi::ffi::*;
use std::ffi::{CStr, CString};
use std::ptr;

fn last() -> String {
    // SAFETY: sw_last_error returns a valid NUL-terminated string.
    unsafe { CStr::from_ptr(sw_last_error()) }
        .to_string_lossy()
        .into_owned()
}

#[test]
fn bad_arguments_name_themselves() {
    let json = CString::new(r#"{"model": "werner", "sigma_um": 5}"#).unwrap();
    let mut b: *mut SwBsdf = ptr::null_mut();
    // SAFETY: valid arguments.
    let s = unsafe { sw_bsdf_from_json(json.as_ptr(), ptr::null(), ptr::null(), &mut b) };
    assert_eq!(s, Status::Ok);
    assert_eq!(last(), "");
    assert!(!b.is_null());

    let wo = [0.0f32, 0.0, 1.0];
    let mut out = [0.0f32; 4];
    let q = SwQueries {
        count: 1,
        wo: wo.as_ptr(),
        wi: wo.as_ptr(),
        x_um: ptr::null(),
        footprint: ptr::null(),
        lambda_nm: ptr::null(),
        lambda_count: 0,
        lambda_per_query: 0,
    };
    // SAFETY: live handle, valid arrays.
    assert_eq!(unsafe { sw_eval(b, &q, out.as_mut_ptr(), 3) }, Status::Ok);
    assert!(
        out[0] > 0.0,
        "a smooth Werner surface reflects at normal incidence"
    );

    // SAFETY: null queries are reported, not dereferenced.
    let s = unsafe { sw_eval(b, ptr::null(), out.as_mut_ptr(), 3) };
    assert_eq!(
        (s, last().as_str()),
        (Status::InvalidArgument, "queries: null")
    );
    // SAFETY: null handle.
    let s = unsafe { sw_pdf(ptr::null(), &q, out.as_mut_ptr(), 1) };
    assert_eq!(
        (s, last().as_str()),
        (Status::InvalidArgument, "bsdf: null")
    );
    let lambda = [500.0f32; 5];
    let q5 = SwQueries {
        lambda_nm: lambda.as_ptr(),
        lambda_count: 5,
        ..q
    };
    // SAFETY: valid arrays of the promised sizes.
    let s = unsafe { sw_eval(b, &q5, out.as_mut_ptr(), 4) };
    assert_eq!(s, Status::InvalidArgument);
    assert_eq!(last(), "lambda_count: expected 1 to 4, got 5");
    // A footprint semi-axis outside [1e-6, 1e9] µm (2.8e-27 gave a NaN Velinov average) or
    // a non-finite angle is named by its flat index, query and column.
    for (fp, want) in [
        (
            [2.828427e-27f32, 1.0, 0.0],
            "footprint[0] (query 0, a1): must be in [1e-6, 1e9] µm, got 0.000000000000000000000000002828427",
        ),
        (
            [1.0, 2e9, 0.0],
            "footprint[1] (query 0, a2): must be in [1e-6, 1e9] µm, got 2000000000",
        ),
        (
            [1.0, 1.0, f32::NAN],
            "footprint[2] (query 0, angle): must be finite, got NaN",
        ),
    ] {
        let bad = SwQueries {
            footprint: fp.as_ptr(),
            ..q
        };
        // SAFETY: valid arrays of the promised sizes.
        let s = unsafe { sw_eval(b, &bad, out.as_mut_ptr(), 3) };
        assert_eq!((s, last().as_str()), (Status::InvalidArgument, want));
    }
    let fp = [1e-6f32, 1e9, 0.5];
    let edge = SwQueries {
        footprint: fp.as_ptr(),
        ..q
    };
    // SAFETY: as above.
    assert_eq!(
        unsafe { sw_eval(b, &edge, out.as_mut_ptr(), 3) },
        Status::Ok
    );
    let no_wi = SwQueries {
        wi: ptr::null(),
        ..q
    };
    // SAFETY: as above.
    let s = unsafe { sw_eval(b, &no_wi, out.as_mut_ptr(), 3) };
    assert_eq!(
        (s, last().as_str()),
        (Status::InvalidArgument, "wi: required by eval and pdf")
    );

    // A bad scratch row names its row and column; the handle stays null.
    let rows = [0.0f64, 0.0, 10.0, f64::NAN, 1.0, 0.1];
    let mut set: *mut SwScratchSet = ptr::null_mut();
    // SAFETY: 6 doubles, null triangle flags.
    let s = unsafe { sw_scratch_set_from_rows(rows.as_ptr(), ptr::null(), 1, &mut set) };
    assert_eq!(s, Status::InvalidInput);
    assert_eq!(last(), "segments[0].y1: must be finite");
    assert!(set.is_null());
    // A good one, used as the material's scratches; JSON scratches too is an error.
    let rows = [0.0f64, 0.0, 10.0, 0.0, 1.0, 0.1];
    // SAFETY: as above.
    assert_eq!(
        unsafe { sw_scratch_set_from_rows(rows.as_ptr(), ptr::null(), 1, &mut set) },
        Status::Ok
    );
    // SAFETY: live handle.
    assert_eq!(unsafe { sw_scratch_set_len(set) }, 1);
    let both = CString::new(
        r#"{"model": "velinov", "scratches": [{"p0": [0, 0], "p1": [1, 0], "width": 1, "depth": 0.1}]}"#,
    )
    .unwrap();
    let mut b2: *mut SwBsdf = ptr::null_mut();
    // SAFETY: valid arguments.
    let s = unsafe { sw_bsdf_from_json(both.as_ptr(), ptr::null(), set, &mut b2) };
    assert_eq!(s, Status::InvalidArgument);
    assert!(last().starts_with("scratches: given both"));
    assert!(b2.is_null());
    // Not UTF-8.
    let bad = [0xffu8, 0];
    // SAFETY: NUL-terminated.
    let s = unsafe { sw_bsdf_from_json(bad.as_ptr().cast(), ptr::null(), set, &mut b2) };
    assert_eq!(
        (s, last().as_str()),
        (Status::InvalidArgument, "json: not UTF-8")
    );
    // SAFETY: live handles, freed once; null is accepted.
    unsafe {
        sw_scratch_set_free(set);
        sw_bsdf_free(b);
        sw_bsdf_free(ptr::null_mut());
    }
}

/// `"model": "auto"` needs a light to choose its model: the BSDF interface refuses it with
/// the field named.
#[test]
fn auto_model_is_refused_with_its_field() {
    let json = CString::new(r#"{"model": "auto", "tolerance": 0.01}"#).unwrap();
    let mut b: *mut SwBsdf = ptr::null_mut();
    // SAFETY: valid arguments.
    let s = unsafe { sw_bsdf_from_json(json.as_ptr(), ptr::null(), ptr::null(), &mut b) };
    assert_eq!(s, Status::InvalidInput);
    assert!(b.is_null());
    assert!(last().starts_with("material.model: "), "{}", last());
}
