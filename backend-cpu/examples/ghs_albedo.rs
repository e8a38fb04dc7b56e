//! White-furnace chart of the GHS model: directional albedo `a(θi) = ∫ ρ cosθo dωo` over θi
//! for a perfect conductor (isolating the geometry and the energy split from colour), the
//! presets, and the two layer variants in their published and energy-conserving forms.
//!
//! `cargo run --release -p scratchwave-cpu --example ghs_albedo` writes
//! `docs/ghs-albedo.svg` and `docs/ghs-albedo.csv`.

use scratchwave_cpu::Backend;
use scratchwave_cpu::ghs::directional_albedo;
use scratchwave_kernel::ghs::{DiffColor, GhsParams, Layer, layers::LayerForm, presets};
use std::fmt::Write as _;

/// `n + ik` with F ≈ 1 at every angle.
const MIRROR: (f32, f32) = (0.001, 1000.0);

fn mirror(p: GhsParams) -> GhsParams {
    GhsParams {
        n: MIRROR.0,
        k: MIRROR.1,
        ..p
    }
}

fn curves() -> Vec<(&'static str, &'static str, GhsParams, f32)> {
    let gold_g = |p| presets::channel(p, &presets::GOLD, 1);
    vec![
        (
            "mirror, σs = 0 (Cook–Torrance, β 0.2, p 0.6)",
            "#000000",
            mirror(GhsParams::new(0.0, 0.2, 0.6, 2.0, 2.0, 0.0, 0.0)),
            0.526,
        ),
        (
            "mirror, polished preset",
            "#1f77b4",
            mirror(presets::POLISHED_METAL),
            0.526,
        ),
        (
            "mirror, rough preset (off scale: 1.50 at 0°, 49 at 89°)",
            "#ff7f0e",
            mirror(presets::ROUGH_METAL),
            0.526,
        ),
        (
            "mirror, rough preset, colour none",
            "#d62728",
            mirror(presets::ROUGH_METAL).with_diff_color(DiffColor::None),
            0.526,
        ),
        (
            "gold (526 nm), rough preset",
            "#bcbd22",
            gold_g(presets::ROUGH_METAL),
            0.526,
        ),
        (
            "gold (645 nm), polished preset",
            "#e377c2",
            presets::channel(presets::POLISHED_METAL, &presets::GOLD, 0),
            0.645,
        ),
        (
            "gold (444 nm), polished preset",
            "#000080",
            presets::channel(presets::POLISHED_METAL, &presets::GOLD, 2),
            0.444,
        ),
        (
            "N-BK7 (526 nm), polished preset, no layer",
            "#17becf",
            presets::channel(presets::POLISHED_METAL, &presets::BK7, 1),
            0.526,
        ),
        (
            "plastic ρd = 1, η 1.5, published (Eq. 49)",
            "#2ca02c",
            GhsParams::new(0.05, 0.1, 1.0, 3.0, 3.0, 1.5, 0.0).with_layer(
                Layer::Plastic,
                LayerForm::Published,
                1.0,
            ),
            0.526,
        ),
        (
            "plastic ρd = 1, η 1.5, energy-conserving",
            "#98df8a",
            GhsParams::new(0.05, 0.1, 1.0, 3.0, 3.0, 1.5, 0.0).with_layer(
                Layer::Plastic,
                LayerForm::EnergyConserving,
                1.0,
            ),
            0.526,
        ),
        (
            "subsurface α = 1, η 1.5, published (Eqs. 45–48)",
            "#9467bd",
            GhsParams::new(0.1, 0.15, 1.0, 2.0, 2.5, 1.5, 0.0).with_layer(
                Layer::Subsurface,
                LayerForm::Published,
                1.0,
            ),
            0.526,
        ),
        (
            "subsurface α = 0.9, η 1.5, published",
            "#c5b0d5",
            GhsParams::new(0.1, 0.15, 1.0, 2.0, 2.5, 1.5, 0.0).with_layer(
                Layer::Subsurface,
                LayerForm::Published,
                0.9,
            ),
            0.526,
        ),
        (
            "subsurface α = 0.9, η 1.5, energy-conserving (Jensen's A)",
            "#8c564b",
            GhsParams::new(0.1, 0.15, 1.0, 2.0, 2.5, 1.5, 0.0).with_layer(
                Layer::Subsurface,
                LayerForm::EnergyConserving,
                0.9,
            ),
            0.526,
        ),
    ]
}

fn main() {
    let thetas: Vec<f32> = (0..30)
        .map(|i| (i as f32 + 0.5) / 30.0 * 89.0_f32.to_radians())
        .collect();
    let n = 160;
    let mut csv = String::from("curve,theta_i_deg,albedo\n");
    let mut series = Vec::new();
    for (name, colour, p, lambda) in curves() {
        let a = directional_albedo(Backend::Simd, &p, lambda, &thetas, n);
        for (t, v) in thetas.iter().zip(&a) {
            writeln!(csv, "\"{name}\",{:.2},{v:.5}", t.to_degrees()).unwrap();
        }
        println!(
            "{name:60} a(0) = {:.4}  max = {:.4}  a(89°) = {:.4}",
            a[0],
            a.iter().cloned().fold(0.0f32, f32::max),
            a[a.len() - 1]
        );
        series.push((name, colour, a));
    }
    let root = concat!(env!("CARGO_MANIFEST_DIR"), "/../docs");
    std::fs::create_dir_all(root).unwrap();
    std::fs::write(format!("{root}/ghs-albedo.csv"), csv).unwrap();
    std::fs::write(format!("{root}/ghs-albedo.svg"), svg(&thetas, &series)).unwrap();
}

fn svg(thetas: &[f32], series: &[(&str, &str, Vec<f32>)]) -> String {
    let (w, h, l, r, t, b) = (900.0, 620.0, 60.0, 20.0, 30.0, 310.0);
    let (ymin, ymax) = (0.0f32, 1.4f32);
    let x = |deg: f32| l + (w - l - r) * deg / 90.0;
    let y = |v: f32| t + (h - t - b) * (1.0 - (v.clamp(ymin, ymax) - ymin) / (ymax - ymin));
    let mut s = format!(
        "<svg xmlns='http://www.w3.org/2000/svg' width='{w}' height='{h}' font-family='sans-serif' font-size='12'>\n<rect width='100%' height='100%' fill='white'/>\n<text x='{l}' y='18' font-size='14'>GHS directional albedo a(θi) = ∫ρ cosθo dωo (λ = 526 nm unless named; importance-sampled, 25.6k samples/point)</text>\n"
    );
    for k in 0..=7 {
        let v = k as f32 * 0.2;
        let yy = y(v);
        let stroke = if (v - 1.0).abs() < 1e-3 {
            "#888"
        } else {
            "#ddd"
        };
        writeln!(s, "<line x1='{l}' x2='{}' y1='{yy}' y2='{yy}' stroke='{stroke}'/><text x='{}' y='{}' text-anchor='end'>{v:.1}</text>", w - r, l - 5.0, yy + 4.0).unwrap();
    }
    for d in (0..=90).step_by(15) {
        let xx = x(d as f32);
        writeln!(s, "<line x1='{xx}' x2='{xx}' y1='{t}' y2='{}' stroke='#eee'/><text x='{xx}' y='{}' text-anchor='middle'>{d}°</text>", h - b, h - b + 16.0).unwrap();
    }
    writeln!(
        s,
        "<text x='{}' y='{}' text-anchor='middle'>θi</text>",
        (l + w - r) / 2.0,
        h - b + 32.0
    )
    .unwrap();
    for (i, (name, colour, a)) in series.iter().enumerate() {
        let pts: Vec<String> = thetas
            .iter()
            .zip(a)
            .map(|(t, v)| format!("{:.1},{:.1}", x(t.to_degrees()), y(*v)))
            .collect();
        writeln!(
            s,
            "<polyline fill='none' stroke='{colour}' stroke-width='2' points='{}'/>",
            pts.join(" ")
        )
        .unwrap();
        let ly = h - b + 50.0 + 18.0 * i as f32;
        writeln!(s, "<line x1='{l}' x2='{}' y1='{ly}' y2='{ly}' stroke='{colour}' stroke-width='3'/><text x='{}' y='{}'>{name}</text>", l + 30.0, l + 38.0, ly + 4.0).unwrap();
    }
    s.push_str("</svg>\n");
    s
}
