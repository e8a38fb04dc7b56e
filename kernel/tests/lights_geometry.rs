//! Geometric invariants of the closed-form light integrals: additivity of polygons, winding,
//! sphere vs inscribed polygon (also across the horizon), asin vs atan cone, the corner
//! cases of Velinov §3.4.1–3.4.2 (grazing, partly/fully below the horizon, a band through a
//! vertex: "a crossing on two arcs") and degenerate lights.

use scratchwave_kernel::lights::band_circle::Breakpoints;
use scratchwave_kernel::lights::{
    BandRule, Cone, Light, LightParams, LightQuery, LightRegion, SiMode, light_integral,
};
use scratchwave_kernel::material::Material;
use scratchwave_kernel::scratch::{Scratch, ScratchSlice};

/// From (−150, 2) to (150, 2) µm, W = 1 µm, D = 0.1 µm.
const SCRATCH: Scratch = Scratch {
    center: [0.0, 2.0],
    tangent: [1.0, 0.0],
    half_len: 150.0,
    width: 1.0,
    depth: 0.1,
    profile: 0,
};

fn eval_with(light: Light, wo: [f32; 3], bands: u32) -> f32 {
    let params = LightParams {
        sigma_um: 10.0,
        eta: 1,
        si_mode: SiMode::Exact as u32,
        bands,
        ..LightParams::default()
    };
    let q = LightQuery {
        wo,
        lambda_nm: 550.0,
        material: Material::constant(1.0),
        light,
        ..LightQuery::default()
    };
    light_integral(
        &params,
        &q,
        &ScratchSlice {
            scratches: &[SCRATCH],
        },
    )
}

fn eval(light: Light, wo: [f32; 3]) -> f32 {
    eval_with(light, wo, 1)
}

fn rel(a: f32, b: f32) -> f32 {
    (a - b).abs() / b.abs().max(1e-30)
}

const WO: [f32; 3] = [0.05, 0.1, 1.0];

#[test]
fn polygon_is_additive_and_winding_free() {
    let quad = [
        [-1.0, -1.5, 5.0],
        [1.2, -1.0, 5.0],
        [1.0, 1.0, 4.0],
        [-1.0, 1.3, 5.5],
    ];
    let whole = eval(Light::polygon(&quad), WO);
    let t1 = eval(Light::polygon(&[quad[0], quad[1], quad[2]]), WO);
    let t2 = eval(Light::polygon(&[quad[0], quad[2], quad[3]]), WO);
    assert!(whole > 0.0);
    assert!(rel(t1 + t2, whole) < 1e-4, "{t1} + {t2} vs {whole}");
    let mut rev = quad;
    rev.reverse();
    assert!(rel(eval(Light::polygon(&rev), WO), whole) < 1e-6);
}

/// A regular n-gon inscribed in the sphere's silhouette circle.
fn inscribed(center: [f32; 3], r: f32, n: usize) -> Light {
    let c = glam::Vec3::from_array(center);
    let d = c.length();
    let axis = c / d;
    let sin_a = r / d;
    let cos_a = (1.0 - sin_a * sin_a).sqrt();
    let e1 = axis.cross(glam::Vec3::X).normalize();
    let e2 = axis.cross(e1);
    let rim = r * cos_a; // silhouette circle radius, at distance d cos²α along the axis
    let mid = axis * d * cos_a * cos_a;
    let vs: Vec<[f32; 3]> = (0..n)
        .map(|k| {
            let p = std::f32::consts::TAU * (k as f32 + 0.5) / n as f32;
            (mid + rim * (p.cos() * e1 + p.sin() * e2)).to_array()
        })
        .collect();
    Light::polygon(&vs)
}

#[test]
fn sphere_matches_inscribed_polygon_above_and_across_the_horizon() {
    // The 16-gon reaches cos(π/16) = 98.1 % of the radius between its vertices; where the
    // band runs into that gap at the bright end of the sinc² lobe, or only a sliver is above
    // the horizon, the deficit is larger (both sides checked against the quadrature
    // reference: 0.924 for the sliver case, matching it to 3e-4).
    for (center, wo) in [
        ([0.5f32, 0.2, 10.0], WO),
        ([0.0, 8.0, 0.0], [0.0, -0.6, 0.8]),
        ([0.0, 8.0, -1.0], [0.0, -0.6, 0.8]),
        ([3.0, -6.0, 0.8], [-0.44, 0.3, 0.85]),
    ] {
        let s = eval(Light::sphere(center, 2.0, Cone::Asin), wo);
        let p = eval(inscribed(center, 2.0, 16), wo);
        println!("{center:?}: sphere {s:.5e} polygon {p:.5e}");
        assert!(s > 0.0 && p > 0.0);
        assert!(p <= s * 1.001 && p >= s * 0.9, "{center:?}: {p} vs {s}");
    }
}

#[test]
fn atan_disk_is_narrower_than_the_sphere() {
    // Eq. 31's disk subtends atan(r/d) < asin(r/d): 0.588 vs 0.730 rad here.
    let (c, r) = ([0.0, 0.0, 3.0], 2.0);
    let a = eval(Light::sphere(c, r, Cone::Asin), WO);
    let b = eval(Light::sphere(c, r, Cone::Atan), WO);
    assert!(b < a * 0.995, "{b} vs {a}");
    // A sphere around the shading point (asin) lights the whole hemisphere.
    let inside = eval(Light::sphere([0.0, 0.0, 0.5], 1.0, Cone::Asin), WO);
    let huge = eval(Light::sphere([0.0, 0.0, 1.0e-3], 1.0e3, Cone::Atan), WO);
    assert!(
        inside > 0.0 && rel(inside, huge) < 1e-3,
        "{inside} vs {huge}"
    );
}

#[test]
fn horizon_cases() {
    // Fully below (touching from below) → 0; touching from above → finite, positive.
    assert_eq!(
        eval(
            Light::sphere([0.0, 5.0, -1.0], 1.0, Cone::Asin),
            [0.0, -0.5, 0.8]
        ),
        0.0
    );
    let above = eval(
        Light::sphere([0.0, 5.0, 1.0], 1.0, Cone::Asin),
        [0.0, -0.5, 0.8],
    );
    assert!(above.is_finite() && above >= 0.0);
    // Partly below: between nothing and the whole light lifted above.
    let half = eval(
        Light::sphere([0.0, 5.0, 0.0], 1.0, Cone::Asin),
        [0.0, -0.9, 0.43],
    );
    let lifted = eval(
        Light::sphere([0.0, 5.0, 1.2], 1.0, Cone::Asin),
        [0.0, -0.9, 0.43],
    );
    assert!(
        half > 0.0 && half.is_finite() && lifted.is_finite(),
        "{half} {lifted}"
    );
    // A polygon entirely below the horizon.
    let below = Light::polygon(&[[0.0, 1.0, -0.1], [1.0, 1.0, -0.2], [0.0, 2.0, -0.3]]);
    assert_eq!(eval(below, WO), 0.0);
}

#[test]
fn band_through_a_vertex_is_continuous() {
    // The band for wo = (0, 0, 1) and t = x is wi·x = 0. Put a vertex of a diamond on it.
    let mk = |e: f32| {
        Light::polygon(&[
            [e, -1.0, 5.0],
            [1.0, 0.0, 5.0],
            [e, 1.0, 5.0],
            [-1.0, 0.0, 5.0],
        ])
    };
    let wo = [0.0, 0.0, 1.0];
    let v0 = eval(mk(0.0), wo);
    for e in [1e-4f32, -1e-4] {
        assert!(rel(eval(mk(e), wo), v0) < 1e-3, "{e}");
    }
    assert!(v0 > 0.0);
}

#[test]
fn degenerate_lights_give_zero() {
    let collinear = Light::polygon(&[[0.0, 0.0, 5.0], [1.0, 0.0, 5.0], [2.0, 0.0, 5.0]]);
    let repeated = Light::polygon(&[[0.0, 0.0, 5.0], [0.0, 0.0, 5.0], [1.0, 1.0, 5.0]]);
    let two = Light::polygon(&[[0.0, 0.0, 5.0], [1.0, 0.0, 5.0]]);
    let point = Light::sphere([0.0, 0.0, 5.0], 0.0, Cone::Asin);
    for l in [collinear, repeated, two, point] {
        assert_eq!(eval(l, WO), 0.0);
    }
    // r → 0: finite, tends to 0.
    let mut last = f32::INFINITY;
    for r in [1e-1f32, 1e-3, 1e-5, 1e-8, 1e-20] {
        let v = eval(
            Light::sphere([0.0, 0.0, 5.0], r, Cone::Asin),
            [0.0, 0.0, 1.0],
        );
        assert!(v.is_finite() && v >= 0.0 && v <= last, "{r}: {v}");
        last = v;
    }
    // Edge-on polygon (its plane through the shading point).
    let edge_on = Light::polygon(&[[1.0, 0.0, 1.0], [2.0, 0.0, 2.0], [1.0, 0.0, 3.0]]);
    assert_eq!(eval(edge_on, WO), 0.0);
}

#[test]
fn grazing_views_are_finite() {
    for wo in [[0.9999f32, 0.0, 1e-4], [0.0, 1.0, 1e-6], [0.6, 0.8, 1e-5]] {
        for rule in [1, 3, 5] {
            let v = eval_with(Light::sphere([0.0, -3.0, 1.0], 1.0, Cone::Asin), wo, rule);
            assert!(v.is_finite() && v >= 0.0, "{wo:?}: {v}");
        }
    }
}

#[test]
fn band_rules_agree_for_a_large_light() {
    let l = Light::sphere([0.0, 0.0, 3.0], 1.5, Cone::Asin);
    let one = eval_with(l, WO, 1);
    for rule in [3, 5] {
        assert!(rel(eval_with(l, WO, rule), one) < 1e-3);
    }
    assert_eq!(BandRule::from_u32(7), BandRule::Single);
}

/// `SphereCap::dot_bound`, the band test's cheap first step, must contain `dot_range` for
/// every cone and direction, or a lit scratch would be skipped as dark: 200 000 seeded
/// cones (half-angles 1e-6 rad to the whole sphere, both cone kinds, centres from the
/// zenith to below the horizon) and unit directions in the plane, as the band test passes.
#[test]
fn sphere_dot_bound_contains_dot_range() {
    use scratchwave_kernel::lights::SphereCap;
    let mut next = uniform(0x9e37_79b9_7f4a_7c15_u64);
    let mut checked = 0;
    for i in 0..200_000 {
        let (theta, phi) = (next() * 1.7, next() * std::f64::consts::TAU);
        let d = 10f64.powf(next() * 6.0);
        let r = d * 10f64.powf(-6.0 * next()) * if i % 50 == 0 { 2.0 } else { 1.0 };
        let c = [
            (d * theta.sin() * phi.cos()) as f32,
            (d * theta.sin() * phi.sin()) as f32,
            (d * theta.cos()) as f32,
        ];
        let cone = if i % 2 == 0 { Cone::Asin } else { Cone::Atan };
        let Some(cap) = SphereCap::new(c.into(), r as f32, cone) else {
            continue;
        };
        let a = next() * std::f64::consts::TAU;
        let u = glam::Vec3::new(a.cos() as f32, a.sin() as f32, 0.0);
        let (range, bound) = (cap.dot_range(u), cap.dot_bound(u));
        assert!(
            bound.0 <= range.0 && bound.1 >= range.1,
            "cap {cap:?}, u {u}: bound {bound:?} misses range {range:?}"
        );
        checked += 1;
    }
    assert!(checked > 150_000, "only {checked} caps above the horizon");
}

/// The chord of a small sphere light across a band, `s₁ − s₀`, where both ends are the two
/// crossings of the cone's plane: the kernel takes it from the crossing formula's two roots
/// (`ArcPoints::chord`), not from the two rounded `s`, so it stays accurate when the chord
/// is far shorter than `|s|`. Reference: the same circle and cone (the kernel's f32 band
/// and cap, each normalised) in f64, `2 m_z √(R² − g²)/R²` with `R − g` in the angle form,
/// over 20 000 seeded caps of 1e-5 – 1e-2 rad centred near the band at |s| 0.3 – 0.95. What
/// is left is the rounding of the angle between the cap's axis and the band (a few ulps of
/// an O(1) quantity, as one ulp of an input moves it), so the assertion is relative to the
/// difference of the rounded ends: median error below a quarter of its, 99th percentile
/// and worst below half (measured: 8.2e-6 / 1.2e-3 / 3.3e-3 against 4.3e-5 / 3.9e-3 /
/// 1.2e-2; without the roots' difference the test fails).
#[test]
fn small_sphere_chord_is_the_difference_of_the_roots() {
    use glam::{Vec2, Vec3};
    use scratchwave_kernel::lights::band_circle::BandCircle;
    use scratchwave_kernel::lights::integrate::{LightRegion, lit_intervals};
    let mut next = uniform(0x2545_f491_4f6c_dd1d_u64);
    let (mut errs, mut errs_plain) = (Vec::new(), Vec::new());
    for _ in 0..20_000 {
        let a = next() * std::f64::consts::TAU;
        let t = Vec2::new(a.cos() as f32, a.sin() as f32);
        let b = Vec2::new(-t.y, t.x);
        let th = 0.05 + 1.2 * next();
        let wo = Vec3::new(
            (th.sin() * (a + 0.3).cos()) as f32,
            (th.sin() * (a + 0.3).sin()) as f32,
            th.cos() as f32,
        );
        let Some(band) = BandCircle::new(t, b, wo) else {
            continue;
        };
        // A point of the band at |s| 0.3 – 0.95, the light's centre moved off it by up to
        // 0.7 of its angular radius.
        let s = (0.3 + 0.65 * next()) * if next() < 0.5 { -1.0 } else { 1.0 };
        let (c, rho) = (band.c as f64, band.rho as f64);
        let (t3, b3) = (f64s(band.family.t3), f64s(band.family.b3));
        let z = (1.0 - s * s).sqrt();
        let alpha = 10f64.powf(-5.0 + 3.0 * next());
        let off = 0.7 * alpha * (2.0 * next() - 1.0);
        // The band point, moved by `off` along t₃ (across the band), at 1 m.
        let p: [f64; 3] = std::array::from_fn(|i| {
            c * t3[i] + rho * s * b3[i] + off * t3[i] + [0.0, 0.0, rho * z][i]
        });
        let len = dot(p, p).sqrt();
        let centre = p.map(|v| (1000.0 * v / len) as f32);
        let light = Light::sphere(centre, (1000.0 * alpha.sin()) as f32, Cone::Asin);
        let Some(region) = LightRegion::new(&light) else {
            continue;
        };
        // The reference chord on the kernel's own (f32) band and cone, each normalised in
        // f64, in the angle form (the cone's cos α is 1 − 5e-11 at 1e-5 rad).
        let axis = f64s(region.sphere.axis);
        let axis = axis.map(|v| v / dot(axis, axis).sqrt());
        let t_len = dot(t3, t3).sqrt();
        let (t3, b3) = (t3.map(|v| v / t_len), b3.map(|v| v / t_len));
        let (c, rho) = (c / c.hypot(rho), rho / c.hypot(rho));
        let (mt, mb, mz) = (dot(axis, t3), dot(axis, b3), axis[2]);
        let r = mb.hypot(mz);
        let beta = (r.atan2(mt) - rho.atan2(c)).abs();
        let alpha = region.sphere.alpha as f64;
        let slack = 2.0 * (0.5 * (alpha + beta)).sin() * (0.5 * (alpha - beta)).sin() / rho;
        if !(slack > 0.0) {
            continue;
        }
        let want = 2.0 * mz.abs() * (slack * (2.0 * r - slack)).sqrt() / (r * r);
        let mut got = Vec::new();
        lit_intervals(&region, &band, |p0, p1, ds| got.push((ds, p1.s - p0.s)));
        let [(ds, plain)] = got[..] else {
            continue;
        };
        errs.push((ds as f64 / want - 1.0).abs());
        errs_plain.push((plain as f64 / want - 1.0).abs());
    }
    assert!(errs.len() > 15_000, "only {} chords", errs.len());
    let q = |e: &mut Vec<f64>, p: f64| {
        e.sort_by(f64::total_cmp);
        e[((e.len() - 1) as f64 * p) as usize]
    };
    let (p50, p99, worst) = (q(&mut errs, 0.5), q(&mut errs, 0.99), q(&mut errs, 1.0));
    let (plain50, plain99, plain_worst) = (
        q(&mut errs_plain, 0.5),
        q(&mut errs_plain, 0.99),
        q(&mut errs_plain, 1.0),
    );
    println!(
        "{} chords, relative error median / 99 % / worst: {p50:.2e} / {p99:.2e} / {worst:.2e}; \
         of s1 − s0: {plain50:.2e} / {plain99:.2e} / {plain_worst:.2e}",
        errs.len()
    );
    assert!(
        p50 < 0.25 * plain50 && p99 < 0.5 * plain99 && worst < 0.5 * plain_worst,
        "the roots' difference is not well below s1 − s0's error"
    );
}

/// A seeded xorshift stream of uniform numbers in [0, 1).
/// The extent rule integrates over `LightRegion::offset_range`, so for a sphere its ends
/// must be where the chords `lit_intervals` forms begin: over 4 000 seeded caps of 1e-5 –
/// 1e-2 rad above the horizon, centred within 1e-3 of the band's centre line, seen from
/// random views across random scratches, the bands 1e-3 of the range inside either end are
/// lit and those 1e-3 outside are not. The ends as
/// `dot_range` gives them (`cos(θ ∓ α)`, shifted by `wo_xy · t`) are good to an ulp of
/// `u · w`, ~6e-8, up to 0.4 % of a 2.7e-4-rad cap's range, and fail this
/// (`docs/stability.md` *Small spheres*).
#[test]
fn sphere_offset_range_meets_its_chords() {
    use glam::Vec3;
    use scratchwave_kernel::lights::LightRegion;
    use scratchwave_kernel::lights::band_circle::BandCircle;
    use scratchwave_kernel::lights::integrate::lit_intervals;
    let mut next = uniform(0x0ff5_e7a9_3c21_d6b5);
    let (mut checked, mut misses) = (0usize, Vec::new());
    for _ in 0..4000 {
        let a = std::f64::consts::TAU * next();
        let scratch = Scratch {
            tangent: [a.cos() as f32, a.sin() as f32],
            ..SCRATCH
        };
        let frame = scratch.frame().expect("a valid scratch");
        let (th, az) = (0.05 + 1.4 * next(), std::f64::consts::TAU * next());
        let wo = Vec3::new(
            (th.sin() * az.cos()) as f32,
            (th.sin() * az.sin()) as f32,
            th.cos() as f32,
        );
        // The centre on the band `offset` within 1e-3 of the band's centre line (as the
        // extent rule meets a light within a few standard deviations of it), at `s`.
        let (t3, b3) = ([a.cos(), a.sin(), 0.0], [-a.sin(), a.cos(), 0.0]);
        let c = 2.0e-3 * (next() - 0.5) - (wo.x as f64 * t3[0] + wo.y as f64 * t3[1]);
        let rho = (1.0 - c * c).sqrt();
        let s = 1.8 * (next() - 0.5);
        let z = (1.0 - s * s).sqrt();
        let alpha = 10f64.powf(-5.0 + 3.0 * next());
        if rho * z < 0.05 {
            continue;
        }
        let centre: [f32; 3] = std::array::from_fn(|i| {
            (1000.0 * (c * t3[i] + rho * s * b3[i] + [0.0, 0.0, rho * z][i])) as f32
        });
        let light = Light::sphere(centre, (1000.0 * alpha.sin()) as f32, Cone::Asin);
        let Some(region) = LightRegion::new(&light) else {
            continue;
        };
        let lit = |offset: f32| {
            let mut total = 0.0;
            if let Some(band) = BandCircle::new_offset(frame.tangent, frame.bitangent, wo, offset) {
                lit_intervals(&region, &band, |_, _, ds| total += ds);
            }
            total > 0.0
        };
        let (lo, hi) = region.offset_range(&region.family(&frame, wo));
        let step = 1.0e-3 * (hi - lo);
        for (end, inward) in [(lo, step), (hi, -step)] {
            checked += 1;
            if !lit(end + inward) || lit(end - inward) {
                misses.push(format!(
                    "α {alpha:.2e}, end {end:e} of [{lo:e}, {hi:e}]: inside lit {}, outside lit {} \
                     (tangent {:?}, wo {wo:?}, centre {centre:?})",
                    lit(end + inward),
                    lit(end - inward),
                    frame.tangent,
                ));
            }
        }
    }
    println!(
        "{checked} range ends, {} not where the chords begin",
        misses.len()
    );
    assert!(checked > 7000, "only {checked} ends");
    assert!(
        misses.is_empty(),
        "{}",
        misses[..misses.len().min(10)].join("\n")
    );
}

fn uniform(mut state: u64) -> impl FnMut() -> f64 {
    move || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 11) as f64 / (1u64 << 53) as f64
    }
}

fn f64s(v: glam::Vec3) -> [f64; 3] {
    [v.x as f64, v.y as f64, v.z as f64]
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// `LightRegion::kinks` of a polygon holds, besides its corners, every band `u · w = c`
/// that touches an edge above the horizon from anywhere in the range: the interior extrema
/// of `u · w` along each edge's great-circle arc, found here in f64 by sampling the arc
/// densely and refining by golden section. At a grazing view the band is a small circle
/// that can touch an edge from inside the light; the extent rule must cut its range there
/// (`docs/stability.md` *Bands tangent to an edge*).
#[test]
fn polygon_kinks_include_bands_tangent_to_an_edge() {
    use scratchwave_kernel::lights::LightRegion;
    use scratchwave_kernel::lights::band_circle::Breakpoints;
    let mut next = uniform(0x7a9e_51d3);
    let (mut tangencies, mut worst) = (0usize, 0.0f64);
    for _ in 0..400 {
        // A convex n-gon around a direction above the horizon, 0.05–1 rad across.
        let n = 3 + (next() * 6.0) as usize;
        let (el, az) = (0.1 + 1.3 * next(), std::f64::consts::TAU * next());
        let c = [el.cos() * az.cos(), el.cos() * az.sin(), el.sin()];
        let e1 = normalise(cross(c, [0.0, 0.0, 1.0]));
        let e2 = cross(c, e1);
        let r = (0.05 + 0.95 * next()).tan() * 0.5;
        let phase = std::f64::consts::TAU * next();
        let verts: Vec<[f32; 3]> = (0..n)
            .map(|k| {
                let a = phase + std::f64::consts::TAU * (k as f64 + 0.4 * next()) / n as f64;
                let (ca, sa) = (a.cos() * r, a.sin() * r);
                [0, 1, 2].map(|i| (3.0 * (c[i] + ca * e1[i] + sa * e2[i])) as f32)
            })
            .collect();
        let Some(region) = LightRegion::new(&Light::polygon(&verts)) else {
            continue;
        };
        let u_az = std::f64::consts::TAU * next();
        let u = glam::Vec3::new(u_az.cos() as f32, u_az.sin() as f32, 0.0);
        let mut kinks = Breakpoints::empty();
        region.kinks(u, &mut kinks);
        let kinks = &kinks.s[..kinks.len];
        let u64s = f64s(u);
        let unit: Vec<[f64; 3]> = verts.iter().map(|v| normalise(v.map(f64::from))).collect();
        for m in 0..n {
            let (a, b) = (unit[m], unit[(m + 1) % n]);
            let on_arc = |t: f64| normalise([0, 1, 2].map(|i| a[i] + t * (b[i] - a[i])));
            let f = |t: f64| dot(u64s, on_arc(t));
            let steps = 4000;
            for i in 1..steps {
                let (t0, t1, t2) = (
                    (i - 1) as f64 / steps as f64,
                    i as f64 / steps as f64,
                    (i + 1) as f64 / steps as f64,
                );
                let sign = if f(t1) > f(t0) && f(t1) >= f(t2) {
                    1.0
                } else if f(t1) < f(t0) && f(t1) <= f(t2) {
                    -1.0
                } else {
                    continue;
                };
                // Golden section on [t0, t2] for the extremum of sign · f.
                let (mut lo, mut hi) = (t0, t2);
                for _ in 0..80 {
                    let g = 0.381_966_011_250_105;
                    let (p, q) = (lo + g * (hi - lo), hi - g * (hi - lo));
                    if sign * f(p) > sign * f(q) {
                        hi = q;
                    } else {
                        lo = p;
                    }
                }
                let t = 0.5 * (lo + hi);
                if on_arc(t)[2] < 1e-6 {
                    continue;
                }
                let value = f(t);
                let miss = kinks
                    .iter()
                    .map(|&k| (f64::from(k) - value).abs())
                    .fold(f64::INFINITY, f64::min);
                assert!(
                    miss < 1e-5,
                    "edge {m} of {verts:?}: tangent band at u·w = {value} (t = {t}) not among the kinks {kinks:?}"
                );
                tangencies += 1;
                worst = worst.max(miss);
            }
        }
    }
    println!("{tangencies} tangent bands found among the kinks, worst offset {worst:.2e}");
    assert!(tangencies > 50, "too few tangencies drawn: {tangencies}");
}

/// Where a sphere's cone holds `−u` or `u` (a large light near the horizon, seen along a
/// scratch), the bands `u · w = c` around that pole lie wholly inside the cone until one
/// touches its boundary from inside: a kink of the lit chord inside the light's range, not
/// at its ends. Both extremes of `u · w` along the cone's boundary circle above the horizon,
/// found here in f64 from the circle's own parametrisation, must be among the kinks or the
/// range's ends (`docs/stability.md` *Bands tangent to a sphere's cone*).
#[test]
fn sphere_kinks_include_bands_tangent_inside_the_cone() {
    let mut next = uniform(0x51e3_c0a7);
    let (mut checked, mut inside, mut worst) = (0usize, 0usize, 0.0f64);
    for _ in 0..2000 {
        // A cone around a direction from 0.4 rad below to 0.6 above the horizon, 0.1–1.5
        // rad wide, seen along a horizontal `u`.
        let (el, az) = (-0.4 + next(), std::f64::consts::TAU * next());
        let d = [el.cos() * az.cos(), el.cos() * az.sin(), el.sin()];
        let alpha = 0.1 + 1.4 * next();
        let Some((region, centre, radius, u, kinks)) = cone_seen_along(d, alpha, 5.0, &mut next)
        else {
            continue;
        };
        let (lo, hi) = region.dot_range(u);
        let mut known: Vec<f32> = kinks.s[..kinks.len].to_vec();
        known.extend([lo, hi]);
        // The cone's boundary circle w(t) = cos α d̂ + sin α (cos t e₁ + sin t e₂), with the
        // f32 axis and half-angle the kernel holds; u · w is extreme at t* and t* + π.
        let axis = normalise(centre.map(f64::from));
        let alpha =
            (f64::from(radius) / dot(centre.map(f64::from), centre.map(f64::from)).sqrt()).asin();
        let e1 = normalise(cross(axis, [0.0, 0.0, 1.0]));
        let e2 = cross(axis, e1);
        let u64s = f64s(u);
        let t_star = dot(u64s, e2).atan2(dot(u64s, e1));
        for t in [t_star, t_star + std::f64::consts::PI] {
            let w: [f64; 3] = [0, 1, 2]
                .map(|i| alpha.cos() * axis[i] + alpha.sin() * (t.cos() * e1[i] + t.sin() * e2[i]));
            if w[2] < 1e-6 {
                continue;
            }
            let value = dot(u64s, w);
            let miss = known
                .iter()
                .map(|&k| (f64::from(k) - value).abs())
                .fold(f64::INFINITY, f64::min);
            assert!(
                miss < 1e-5,
                "cone {centre:?}, α {alpha}: band tangent at u·w = {value} not among the kinks \
                 and range ends {known:?}"
            );
            checked += 1;
            if value > f64::from(lo) + 1e-4 && value < f64::from(hi) - 1e-4 {
                inside += 1;
            }
            worst = worst.max(miss);
        }
    }
    println!(
        "{checked} tangencies above the horizon ({inside} inside the range), worst offset {worst:.2e}"
    );
    assert!(
        inside > 50,
        "too few tangencies inside the range drawn: {inside}"
    );
}

/// `SphereCap::kinks` holds where the cone's boundary meets the horizon, for cones of
/// 1e-5 – 1 rad whose centre lies within ±α of the horizon: the two directions
/// `w = (cos ψ, sin ψ, 0)` at `ψ = φ ± δ`, `cos δ = cos α / cos e` (`e` the axis's
/// elevation, `φ` its azimuth), found here in f64 by bisection on the angle from the axis
/// (no closed form shared with the kernel). Each `u · w` must be among the kinks within
/// 1e-3 of the light's range in `u · w`, or 3e-7 (a few ulps of a value near 1). With
/// `acos(cos α / cos e)` in f32 a 5e-4-rad sphere's crossings were 30 % of the light off,
/// and this fails (`docs/stability.md` *Small spheres*).
#[test]
fn sphere_kinks_include_its_horizon_crossings() {
    let mut next = uniform(0x7a3d_22c1_9e05_b1f3);
    let (mut checked, mut worst) = (0usize, 0.0f64);
    for _ in 0..2000 {
        let alpha = 10f64.powf(-5.0 + 5.0 * next());
        let (el, az) = (alpha * (2.0 * next() - 1.0), std::f64::consts::TAU * next());
        let d = [el.cos() * az.cos(), el.cos() * az.sin(), el.sin()];
        let Some((region, centre, _, u, kinks)) = cone_seen_along(d, alpha, 1000.0, &mut next)
        else {
            continue;
        };
        let known: Vec<f64> = kinks.s[..kinks.len].iter().map(|&k| f64::from(k)).collect();
        let (lo, hi) = region.dot_range(u);
        let tol = (1.0e-3 * f64::from(hi - lo)).max(3.0e-7);
        // The kernel's cone: its f32 axis (normalised here) and half-angle.
        let axis = normalise(f64s(region.sphere.axis));
        let alpha = f64::from(region.sphere.alpha);
        let phi = axis[1].atan2(axis[0]);
        let angle = |psi: f64| {
            let w = [psi.cos(), psi.sin(), 0.0];
            dot(cross(w, axis), cross(w, axis))
                .sqrt()
                .atan2(dot(w, axis))
        };
        if angle(phi) >= alpha {
            continue;
        }
        for side in [1.0, -1.0] {
            // From the azimuth nearest the axis (inside) to a quarter turn away (outside).
            let (mut a, mut b) = (0.0f64, std::f64::consts::FRAC_PI_2);
            for _ in 0..200 {
                let m = 0.5 * (a + b);
                if angle(phi + side * m) < alpha {
                    a = m;
                } else {
                    b = m;
                }
            }
            let psi = phi + side * 0.5 * (a + b);
            let value = dot(f64s(u), [psi.cos(), psi.sin(), 0.0]);
            let miss = known
                .iter()
                .map(|k| (k - value).abs())
                .fold(f64::INFINITY, f64::min);
            assert!(
                miss <= tol,
                "cone {centre:?}, α {alpha:e}: the horizon crossing at u·w = {value} is {miss:e} \
                 from the nearest kink of {known:?} (tolerance {tol:e})"
            );
            checked += 1;
            worst = worst.max(miss / tol);
        }
    }
    println!("{checked} horizon crossings among the kinks, worst {worst:.2} of the tolerance");
    assert!(checked > 2000, "only {checked} crossings");
}

/// The sphere light of half-angle `alpha` at `dist` in the unit direction `d`, its region
/// (`None` if below the horizon or degenerate), centre and radius, and a horizontal `u`
/// drawn from `next` with the region's kinks along it.
fn cone_seen_along(
    d: [f64; 3],
    alpha: f64,
    dist: f64,
    next: &mut impl FnMut() -> f64,
) -> Option<(LightRegion, [f32; 3], f32, glam::Vec3, Breakpoints)> {
    let centre = d.map(|v| (dist * v) as f32);
    let radius = (dist * alpha.sin()) as f32;
    let region =
        scratchwave_kernel::lights::LightRegion::new(&Light::sphere(centre, radius, Cone::Asin))?;
    let u_az = std::f64::consts::TAU * next();
    let u = glam::Vec3::new(u_az.cos() as f32, u_az.sin() as f32, 0.0);
    let mut kinks = Breakpoints::empty();
    region.kinks(u, &mut kinks);
    Some((region, centre, radius, u, kinks))
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn normalise(v: [f64; 3]) -> [f64; 3] {
    let l = dot(v, v).sqrt();
    v.map(|x| x / l)
}

/// A small polygon crosses the bands in local form (`lights::polygon`): its chord is the
/// difference of two crossings formed relative to the light, not of two `s` values rounded
/// to ~ε each, and its vertices keep their offsets from each other rather than ~ε of their
/// unit directions. Over 4 000 seeded regular hexagons of angular radius 5e-5 – 2e-2 at
/// 1 – 1e4 units, centred on the band of a random scratch and view (`|s| ≤ 0.95`), the
/// chord through the centre against f64 crossings of the kernel's own band with the f64
/// edge planes of the same f32 vertices: within 1e-5 relative, median below 1e-6. The chord
/// crosses two opposite edges, parallel but for the f32 rounding of the vertices (~ε of the
/// light's distance, 1e-3 of a 5e-5-rad light), so a shift of the whole light by ~ε (the
/// local form's once-rounded common terms) moves it only to second order; smaller lights
/// are not asymmetric enough to tell the two apart. Before the local form the worst was
/// 1.0 (a chord lost entirely; median 1.2e-5, here 7e-8).
#[test]
fn small_polygon_chords_keep_their_relative_accuracy() {
    use glam::{Vec2, Vec3};
    use scratchwave_kernel::lights::band_circle::BandCircle;
    use scratchwave_kernel::lights::integrate::lit_intervals;
    let mut next = uniform(0x9e37_79b9_7f4a_7c15_u64);
    let mut errs = Vec::new();
    for _ in 0..4_000 {
        let a = next() * std::f64::consts::TAU;
        let t = Vec2::new(a.cos() as f32, a.sin() as f32);
        let b = Vec2::new(-t.y, t.x);
        let th = (0.1 + 0.9 * next()).acos();
        let az = next() * std::f64::consts::TAU;
        let wo = Vec3::new(
            (th.sin() * az.cos()) as f32,
            (th.sin() * az.sin()) as f32,
            th.cos() as f32,
        );
        let Some(band) = BandCircle::new(t, b, wo) else {
            continue;
        };
        // The kernel's band, normalised in f64.
        let (c, rho) = (band.c as f64, band.rho as f64);
        let (c, rho) = (c / c.hypot(rho), rho / c.hypot(rho));
        let (t3, b3) = (
            normalise(f64s(band.family.t3)),
            normalise(f64s(band.family.b3)),
        );
        let s = 0.95 * (2.0 * next() - 1.0);
        let z = (1.0 - s * s).sqrt();
        let at = |s: f64, z: f64| -> [f64; 3] {
            std::array::from_fn(|i| c * t3[i] + rho * s * b3[i] + [0.0, 0.0, rho * z][i])
        };
        let p = at(s, z);
        if p[2] < 0.05 {
            continue;
        }
        let e1 = normalise(std::array::from_fn(|i| t3[i] - dot(t3, p) * p[i]));
        let e2 = cross(p, e1);
        let alpha = 10f64.powf(-4.3 + 2.6 * next());
        let dist = 10f64.powf(4.0 * next());
        // Edges turned so that the band (along e2) crosses two opposite ones within 0.13
        // rad of square-on, far from a corner, where a shift of the light by ~ε would move
        // a crossing onto the next edge.
        let phase = std::f64::consts::FRAC_PI_3 + 0.25 * (next() - 0.5);
        let vertices: Vec<[f32; 3]> = (0..6)
            .map(|k| {
                let q = phase + k as f64 * std::f64::consts::FRAC_PI_3;
                std::array::from_fn(|i| {
                    (dist * (p[i] + alpha * (q.cos() * e1[i] + q.sin() * e2[i]))) as f32
                })
            })
            .collect();
        let light = Light::polygon(&vertices);
        let Some(region) = LightRegion::new(&light) else {
            continue;
        };
        // f64 crossings of the band with each edge's plane that lie on the edge.
        let u: Vec<[f64; 3]> = vertices
            .iter()
            .map(|v| normalise(v.map(f64::from)))
            .collect();
        let mut ends = Vec::new();
        for k in 0..6 {
            let (ua, ub) = (u[k], u[(k + 1) % 6]);
            let n = cross(ua, std::array::from_fn(|i| ub[i] - ua[i]));
            let (nt, nb, nz) = (dot(n, t3), dot(n, b3), n[2]);
            let r2 = nb * nb + nz * nz;
            let g = -c * nt / rho;
            let disc = r2 - g * g;
            if disc < 0.0 {
                continue;
            }
            for sign in [1.0, -1.0] {
                let (s, z) = (
                    (g * nb + sign * nz * disc.sqrt()) / r2,
                    (g * nz - sign * nb * disc.sqrt()) / r2,
                );
                let w = at(s, z);
                if dot(cross(ua, w), n) >= 0.0 && dot(cross(w, ub), n) >= 0.0 {
                    ends.push(s);
                }
            }
        }
        let [s0, s1] = ends[..] else {
            continue;
        };
        let want = (s1 - s0).abs();
        let mut got = 0.0f64;
        lit_intervals(&region, &band, |_, _, ds| got += ds as f64);
        let err = (got / want - 1.0).abs();
        errs.push(err);
    }
    assert!(errs.len() > 3_500, "only {} chords", errs.len());
    errs.sort_by(f64::total_cmp);
    let (median, worst) = (errs[errs.len() / 2], errs[errs.len() - 1]);
    println!(
        "{} chords through small hexagons, relative error median {median:.2e}, worst {worst:.2e}",
        errs.len()
    );
    assert!(
        median < 1e-6 && worst < 1e-5,
        "median {median:.2e}, worst {worst:.2e}"
    );
}
