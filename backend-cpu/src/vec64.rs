//! f64 3-vector helpers for the std-side light reference and Monte Carlo estimator (the
//! kernel's own geometry is f32 glam; these exist only to compute references in f64).

/// A 3-vector in f64.
pub type V3 = [f64; 3];

/// `a − b`.
pub fn sub(a: V3, b: V3) -> V3 {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

/// `a · b`.
pub fn dot(a: V3, b: V3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// `a × b`.
pub fn cross(a: V3, b: V3) -> V3 {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// `a / |a|`, or zero for a zero vector.
pub fn norm(a: V3) -> V3 {
    let l = dot(a, a).sqrt();
    if l > 0.0 {
        [a[0] / l, a[1] / l, a[2] / l]
    } else {
        [0.0; 3]
    }
}

/// Two unit vectors completing the unit `a` to a right-handed orthonormal basis
/// `(e1, e2, a)` (`e1` from `a × x̂`, or `a × ŷ` when `a` is near the x axis).
pub fn basis(a: V3) -> (V3, V3) {
    let helper = if a[0].abs() < 0.9 {
        [1.0, 0.0, 0.0]
    } else {
        [0.0, 1.0, 0.0]
    };
    basis_from(a, helper)
}

/// The basis `(e1, e2)` about the unit `a` with `e1 ∥ a × helper` (`helper` not parallel
/// to `a`).
pub fn basis_from(a: V3, helper: V3) -> (V3, V3) {
    let e1 = norm(cross(a, helper));
    (e1, cross(a, e1))
}
