//! Area lights that cannot add anything at a hit get no shadow ray
//! (`kernel::render::shading::area_light_is_dark`, called by `first_rays`). That is only
//! sound if the closed form it stands for is exactly 0 there: for every primary hit of a
//! scratched `velinov` plate under a sphere light and a triangle light (Gaussian, smooth
//! and no base; footprints on and off; RGB and 16-sample spectral), wherever the test says
//! dark, `velinov_area_light` must give +0.0 at every wavelength of the frame. The scene is
//! chosen so that most hits are dark and some are lit.

use scratchwave_kernel::bsdf::Lookup;
use scratchwave_kernel::render::pixel::sample_offset;
use scratchwave_kernel::render::radiance::{Tracer, hit_point};
use scratchwave_kernel::render::shading::{area_light_is_dark, velinov_area_light};
use scratchwave_render::per_pixel::FlatScene;
use scratchwave_render::{prepare, scene_file};
use serde_json::json;
use std::path::Path;

fn scene(base: &str, footprint: &str, spectrum: serde_json::Value) -> serde_json::Value {
    // Velinov's Gaussian base is an option of the model; a smooth base is a base material.
    let (option, base_material) = match base {
        "gaussian" => ("gaussian", None),
        "smooth" => ("none", Some("smooth")),
        _ => ("none", None),
    };
    let mut v = json!({
        "unit_um": 1000,
        "camera": {"type": "perspective", "eye": [0, -4, 3], "target": [0, 0, 0], "up": [0, 0, 1],
                   "fov_y_deg": 40, "width_px": 48, "height_px": 36},
        "materials": {
            "plate": {"model": "velinov", "sigma_um": 10, "material": {"ior": [1.2, 7.0]},
                "options": {"base": option},
                "scratches": [{"generate": {"seed": 7, "count": 3000,
                    "region": {"min": [0, 0], "max": [6000, 6000]},
                    "shape": {"type": "straight", "length": {"uniform": [200, 2000]}},
                    "orientation": {"type": "random"}, "width": {"uniform": [0.8, 6]},
                    "depth": {"uniform": [0.1, 0.5]}, "profile": "alternate"}}]}
        },
        "objects": [{"shape": "rectangle", "center": [0, 0, 0], "tangent": [1, 0, 0],
                     "normal": [0, 0, 1], "size": [6, 6], "material": "plate"}],
        "lights": [
            {"type": "sphere", "center": [0, 6, 4.5], "radius": 0.15, "radiance": 50},
            {"type": "polygon", "vertices": [[-3, 5, 5], [-2, 5, 5.5], [-2.5, 4, 5]], "radiance": 20}
        ],
        "spectrum": spectrum,
        "render": {"spp": 1, "footprint": footprint}
    });
    if let Some(b) = base_material {
        v["materials"]["plate"]["base"] = json!(b);
    }
    v
}

#[test]
fn dark_means_zero() {
    let (mut dark, mut lit, mut nonzero) = (0usize, 0usize, 0usize);
    for base in ["gaussian", "smooth", "none"] {
        for footprint in ["none", "ellipse"] {
            for spectrum in [
                json!({"mode": "rgb"}),
                json!({"mode": "spectral", "samples": 16}),
            ] {
                let v = scene(base, footprint, spectrum.clone());
                let s = scene_file::scene_from_value(&v, "dark_lights", Path::new("."))
                    .unwrap_or_else(|e| panic!("{base} {footprint}: {e}"));
                let prep = prepare::prepare(&s);
                let flat = FlatScene::new(&s, &prep).expect("flattens");
                let (frame, geo, tracer) = (flat.frame, prep.geometry(), flat.tracer());
                let cam = frame.camera;
                let lambda_max = frame.longest_wavelength_nm();
                for j in 0..cam.height_px {
                    for i in 0..cam.width_px {
                        let (ox, oy) = sample_offset(j * cam.width_px + i, 0, 1);
                        let rd = cam.ray(i as f32 + ox, j as f32 + oy);
                        let Some(hit) = tracer.closest_hit(&rd.ray) else {
                            continue;
                        };
                        let Some(hp) = hit_point(&geo, &rd, frame.footprint_scale(), &hit) else {
                            continue;
                        };
                        let mi = hp.material as usize;
                        let m = &prep.materials[mi];
                        let lk = Lookup::new(prep.scratch_set(mi));
                        for light in &prep.lights {
                            let is_dark = area_light_is_dark(
                                m, &hp.sp, hp.wo, light, &lk, &hp.fp, lambda_max,
                            );
                            let mut any = false;
                            let n = frame.wavelength_count();
                            let mut k0 = 0;
                            while k0 < n {
                                let wl = frame.wavelength_group(k0);
                                let c = wl.count as usize;
                                let l = velinov_area_light(
                                    m, &hp.sp, hp.wo, light, &wl.nm, c, &lk, &hp.fp,
                                );
                                for (k, x) in l[..c].iter().enumerate() {
                                    if is_dark {
                                        assert_eq!(
                                            x.to_bits(),
                                            0,
                                            "{base} {footprint} {spectrum}: pixel ({i}, {j}) \
                                             dark but {x} at {} nm",
                                            wl.nm[k]
                                        );
                                    }
                                    any |= *x != 0.0;
                                }
                                k0 += wl.count;
                            }
                            if is_dark {
                                dark += 1;
                            } else {
                                lit += 1;
                                nonzero += usize::from(any);
                            }
                        }
                    }
                }
            }
        }
    }
    println!("{dark} dark hit–light pairs, {lit} not ({nonzero} of them non-zero)");
    assert!(
        dark > lit,
        "{dark} dark, {lit} not: the scene should be mostly dark"
    );
    assert!(nonzero > 50, "only {nonzero} lit hit–light pairs");
}
