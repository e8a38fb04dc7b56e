//! Stability: no NaN, no Inf, never negative, over 10^6 random light/scratch/view
//! configurations, a quarter of them degenerate on purpose (collinear or repeated polygon
//! vertices, zero-area polygons, vertices at the shading point, lights touching the horizon
//! from above and below, r → 0, grazing views, views along the scratch).

use scratchwave_kernel::lights::{Cone, Light, LightParams, LightQuery, light_integral};
use scratchwave_kernel::material::{FresnelAngle, Material};
use scratchwave_kernel::scratch::{Scratch, ScratchSlice};

struct Rng(u64);
impl Rng {
    fn u(&mut self) -> f32 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        ((z ^ (z >> 31)) >> 40) as f32 / (1u64 << 24) as f32
    }
    fn r(&mut self, a: f32, b: f32) -> f32 {
        a + (b - a) * self.u()
    }
    fn pick(&mut self, n: usize) -> usize {
        ((self.u() * n as f32) as usize).min(n - 1)
    }
    fn dir(&mut self) -> [f32; 3] {
        let z = self.r(-1.0, 1.0);
        let p = self.r(0.0, std::f32::consts::TAU);
        let s = (1.0 - z * z).max(0.0).sqrt();
        [s * p.cos(), s * p.sin(), z]
    }
}

fn random_light(rng: &mut Rng) -> Light {
    let d = 10f32.powf(rng.r(-2.0, 3.0));
    let mut c = rng.dir().map(|v| v * d);
    let special = rng.pick(8);
    if rng.u() < 0.5 {
        let mut r = d * 10f32.powf(rng.r(-6.0, 0.3));
        match special {
            0 => r = 0.0,
            1 => r = f32::MIN_POSITIVE * rng.u(),
            2 => c[2] = r,  // touching the horizon from above
            3 => c[2] = -r, // from below
            4 => c[2] = 0.0,
            _ => {}
        }
        let cone = if rng.u() < 0.5 {
            Cone::Asin
        } else {
            Cone::Atan
        };
        Light::sphere(c, r, cone)
    } else {
        let n = 3 + rng.pick(14);
        let size = d * 10f32.powf(rng.r(-6.0, 0.5));
        let mut vs: Vec<[f32; 3]> = (0..n)
            .map(|_| {
                let o = rng.dir();
                [c[0] + size * o[0], c[1] + size * o[1], c[2] + size * o[2]]
            })
            .collect();
        match special {
            0 => {
                // collinear
                let (a, b) = (vs[0], vs[1]);
                for (k, v) in vs.iter_mut().enumerate() {
                    let t = k as f32 * 0.37;
                    *v = [
                        a[0] + t * (b[0] - a[0]),
                        a[1] + t * (b[1] - a[1]),
                        a[2] + t * (b[2] - a[2]),
                    ];
                }
            }
            1 => {
                let v0 = vs[0];
                vs.iter_mut().for_each(|v| *v = v0);
            }
            2 => vs[rng.pick(n)] = [0.0; 3],
            3 => vs.iter_mut().for_each(|v| v[2] = 0.0), // in the tangent plane
            4 => vs.iter_mut().for_each(|v| v[2] = v[2].abs() * 1e-6), // grazing sliver
            5 => {
                let k = rng.pick(n - 1);
                vs[k + 1] = vs[k]; // repeated vertex
            }
            _ => {}
        }
        Light::polygon(&vs)
    }
}

#[test]
fn a_million_configurations_are_finite_and_non_negative() {
    let mut rng = Rng(2018);
    let n = 1_000_000;
    let mut lit = 0usize;
    for i in 0..n {
        let mut wo = rng.dir();
        wo[2] = wo[2].abs();
        match rng.pick(10) {
            0 => wo[2] = 1e-7,
            1 => wo = [0.0, 0.0, 1.0],
            _ => {}
        }
        let a = rng.r(0.0, std::f32::consts::PI);
        let len = if rng.u() < 0.1 {
            0.0
        } else {
            10f32.powf(rng.r(-1.0, 3.0))
        };
        let sb = rng.r(-30.0, 30.0);
        let (t, b) = ([a.cos(), a.sin()], [-a.sin(), a.cos()]);
        let scratch = Scratch {
            center: [sb * b[0], sb * b[1]],
            tangent: t,
            half_len: len,
            width: if rng.u() < 0.05 {
                0.0
            } else {
                10f32.powf(rng.r(-2.0, 1.5))
            },
            depth: rng.r(0.0, 2.0),
            profile: (rng.u() < 0.2) as u32,
        };
        let params = LightParams {
            sigma_um: 10f32.powf(rng.r(0.0, 2.0)),
            eta: rng.pick(2) as u32,
            depth_term: rng.pick(2) as u32,
            si_mode: rng.pick(3) as u32,
            bands: [1, 3, 5, 20][rng.pick(4)],
            ..LightParams::default()
        };
        let material = if rng.u() < 0.5 {
            Material::constant(rng.u())
        } else {
            Material::ior(rng.r(0.1, 3.0), rng.r(0.0, 5.0), FresnelAngle::ThetaD)
        };
        let light = random_light(&mut rng);
        if rng.u() < 0.5 {
            // Aim the band at the light's centre direction (so most of these are lit).
            let c = if light.kind == 0 {
                [light.sphere[0], light.sphere[1], light.sphere[2]]
            } else {
                let k = light.count as usize;
                light.vertices[..k]
                    .iter()
                    .fold([0.0f32; 3], |a, v| [a[0] + v[0], a[1] + v[1], a[2] + v[2]])
            };
            let l = (c[0] * c[0] + c[1] * c[1] + c[2] * c[2]).sqrt().max(1e-30);
            let ct = -(c[0] * t[0] + c[1] * t[1]) / l;
            let room = (1.0 - ct * ct).max(0.0).sqrt() * rng.u();
            let (wx, wy) = (ct * t[0] + room * b[0], ct * t[1] + room * b[1]);
            wo = [wx, wy, (1.0 - wx * wx - wy * wy).max(0.0).sqrt()];
        }
        let q = LightQuery {
            wo,
            lambda_nm: rng.r(300.0, 900.0),
            x: [rng.r(-5.0, 5.0), rng.r(-5.0, 5.0)],
            material,
            light,
            ..LightQuery::default()
        };
        let v = light_integral(
            &params,
            &q,
            &ScratchSlice {
                scratches: &[scratch],
            },
        );
        assert!(
            v.is_finite() && v >= 0.0,
            "config {i}: {v} for {q:?} {scratch:?} {params:?}"
        );
        lit += (v > 0.0) as usize;
    }
    println!("{lit} of {n} configurations lit");
    assert!(lit > n / 10, "the sweep must exercise lit bands, got {lit}");
}
