//! f64 vector helpers for the light reference and Monte Carlo estimator (the kernel's own
//! geometry is f32; these exist only to compute references in f64).

use glam::DVec3;

/// `a / |a|` (a division, not a multiplication by `1/|a|`, so the sweeps replay their
/// published inputs bit for bit), or zero for a zero vector.
pub fn unit(a: DVec3) -> DVec3 {
    let l = a.length();
    if l > 0.0 { a / l } else { DVec3::ZERO }
}

/// Two unit vectors completing the unit `a` to a right-handed orthonormal basis
/// `(e1, e2, a)` (`e1` from `a × x̂`, or `a × ŷ` when `a` is near the x axis).
pub fn basis(a: DVec3) -> (DVec3, DVec3) {
    let helper = if a.x.abs() < 0.9 { DVec3::X } else { DVec3::Y };
    basis_from(a, helper)
}

/// The basis `(e1, e2)` about the unit `a` with `e1 ∥ a × helper` (`helper` not parallel
/// to `a`).
pub fn basis_from(a: DVec3, helper: DVec3) -> (DVec3, DVec3) {
    let e1 = unit(a.cross(helper));
    (e1, a.cross(e1))
}
