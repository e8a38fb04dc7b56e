//! The `Lanes<8>` operations give the bits of the `f32` ones, lane by lane, over the whole
//! `f32` range: the SIMD backends' lanes and the scalar backend (and SPIR-V) share one
//! formula only if every operation it is built from agrees.

use scratchwave_kernel::lane::{Lanes, Real};

/// Every 4 099th bit pattern (both signs, subnormals, infinities, NaNs) and the edge values
/// of the integer conversions and the rounding tricks.
fn sample() -> Vec<f32> {
    let mut v: Vec<f32> = (0..=u32::MAX / 4_099)
        .map(|i| f32::from_bits(i.wrapping_mul(4_099)))
        .collect();
    for x in [
        0.0_f32,
        0.5,
        0.49999997,
        1.0,
        1.5,
        2.5,
        8_388_607.5,
        8_388_608.0,
        8_388_609.0,
        16_777_215.0,
        2_147_483_520.0,
        2_147_483_648.0,
        4_294_967_296.0,
        f32::MAX,
        f32::MIN_POSITIVE,
        1.0e-45,
        f32::INFINITY,
        f32::NAN,
    ] {
        v.push(x);
        v.push(-x);
        v.push(f32::from_bits(x.to_bits().wrapping_add(1)));
        v.push(f32::from_bits(x.to_bits().wrapping_sub(1)));
    }
    v
}

fn same_bits(name: &str, lanes: impl Fn(Lanes<8>) -> Lanes<8>, one: impl Fn(f32) -> f32) {
    let xs = sample();
    let mut checked = 0;
    for chunk in xs.chunks(8) {
        let mut a = [0.0_f32; 8];
        a[..chunk.len()].copy_from_slice(chunk);
        let r = lanes(Lanes(a));
        for (x, got) in a.iter().zip(r.0) {
            let want = one(*x);
            let equal = got.to_bits() == want.to_bits() || (got.is_nan() && want.is_nan());
            assert!(equal, "{name}({x:e}): lanes {got:e}, f32 {want:e}");
            checked += 1;
        }
    }
    assert!(checked > 1_000_000, "{checked}");
}

#[test]
fn trunc_is_the_f32_trunc() {
    same_bits("trunc", Real::trunc, Real::trunc);
}

#[test]
fn floor_is_the_f32_floor() {
    same_bits("floor", Real::floor, Real::floor);
}

#[test]
fn sqrt_is_the_f32_sqrt() {
    same_bits("sqrt", Real::sqrt, Real::sqrt);
}

#[test]
fn abs_is_the_f32_abs() {
    same_bits("abs", Real::abs, Real::abs);
}
