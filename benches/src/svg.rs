//! A minimal log–log scatter chart in SVG (no plotting dependency).

use std::fmt::Write;

/// One series: label, colour, points `(x, y_median, y_p90, y_max)`.
pub struct Series {
    /// Legend text.
    pub label: String,
    /// CSS colour.
    pub color: String,
    /// `(cost, median, p90, max)` per point; drawn as a marker at the median, a bar to p90
    /// and a tick at the max; consecutive points joined.
    pub points: Vec<(f64, f64, f64, f64)>,
    /// Join consecutive points with a line.
    pub line: bool,
}

/// A text placed next to a data point `(x, y)` (data coordinates).
pub struct PointLabel {
    /// Data x.
    pub x: f64,
    /// Data y.
    pub y: f64,
    /// The text.
    pub text: String,
    /// CSS colour.
    pub color: String,
}

/// A dashed horizontal line across the plot at data `y`, labelled at its right end.
pub struct HLine {
    /// Data y.
    pub y: f64,
    /// The label.
    pub label: String,
    /// CSS colour.
    pub color: String,
}

/// What [`loglog_with`] draws besides the series.
pub struct Extras {
    /// Texts next to points.
    pub labels: Vec<PointLabel>,
    /// Horizontal reference lines (included in the y range).
    pub hlines: Vec<HLine>,
    /// Lines of small text under the legend.
    pub notes: Vec<String>,
    /// Draw each point's bar to p90 and dashed line to the max (off: a marker only).
    pub whiskers: bool,
    /// The largest y is multiplied by this before the top decade is chosen (room for labels
    /// above the highest point).
    pub y_headroom: f64,
}

impl Default for Extras {
    /// What [`loglog`] draws: whiskers and their explanation.
    fn default() -> Self {
        Extras {
            labels: Vec::new(),
            hlines: Vec::new(),
            notes: vec![
                "dot: median, bar: 90th pct,".into(),
                "dashed to tick: max".into(),
            ],
            whiskers: true,
            y_headroom: 1.0,
        }
    }
}

/// Renders a log–log chart.
pub fn loglog(title: &str, xlabel: &str, ylabel: &str, series: &[Series]) -> String {
    loglog_with(title, xlabel, ylabel, series, &Extras::default())
}

/// [`loglog`] with point labels, horizontal lines, notes and optional whiskers.
pub fn loglog_with(
    title: &str,
    xlabel: &str,
    ylabel: &str,
    series: &[Series],
    extras: &Extras,
) -> String {
    let (w, h, l, r, t, b) = (900.0, 600.0, 90.0, 260.0, 50.0, 70.0);
    let all = series.iter().flat_map(|s| s.points.iter());
    let (mut x0, mut x1, mut y0, mut y1) = (f64::MAX, f64::MIN, f64::MAX, f64::MIN);
    for p in all {
        x0 = x0.min(p.0);
        x1 = x1.max(p.0);
        y0 = y0.min(p.1.max(1e-9));
        y1 = y1.max(p.3);
    }
    for hl in &extras.hlines {
        y0 = y0.min(hl.y.max(1e-9));
        y1 = y1.max(hl.y);
    }
    y1 *= extras.y_headroom;
    let (lx0, lx1) = (x0.log10().floor(), x1.log10().ceil());
    let (ly0, ly1) = (
        y0.log10().floor(),
        y1.log10().ceil().max(y0.log10().floor() + 1.0),
    );
    let px = |x: f64| l + (x.log10() - lx0) / (lx1 - lx0) * (w - l - r);
    let py = |y: f64| t + (ly1 - y.max(1e-9).log10()) / (ly1 - ly0) * (h - t - b);
    let mut s = String::new();
    let _ = write!(
        s,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{h}" font-family="sans-serif" font-size="13">
<rect width="100%" height="100%" fill="white"/>
<text x="{}" y="28" text-anchor="middle" font-size="16">{title}</text>
"#,
        (w - r + l) / 2.0
    );
    for k in lx0 as i32..=lx1 as i32 {
        let x = px(10f64.powi(k));
        let _ = writeln!(
            s,
            r##"<line x1="{x}" y1="{t}" x2="{x}" y2="{}" stroke="#ddd"/><text x="{x}" y="{}" text-anchor="middle">1e{k}</text>"##,
            h - b,
            h - b + 18.0
        );
    }
    for k in ly0 as i32..=ly1 as i32 {
        let y = py(10f64.powi(k));
        let _ = writeln!(
            s,
            r##"<line x1="{l}" y1="{y}" x2="{}" y2="{y}" stroke="#ddd"/><text x="{}" y="{}" text-anchor="end">1e{k}</text>"##,
            w - r,
            l - 6.0,
            y + 4.0
        );
    }
    let _ = writeln!(
        s,
        r#"<text x="{}" y="{}" text-anchor="middle">{xlabel}</text><text transform="translate(22,{}) rotate(-90)" text-anchor="middle">{ylabel}</text>"#,
        (w - r + l) / 2.0,
        h - 20.0,
        (h - b + t) / 2.0
    );
    for (i, se) in series.iter().enumerate() {
        let c = &se.color;
        let path: Vec<String> = se
            .points
            .iter()
            .map(|p| format!("{:.1},{:.1}", px(p.0), py(p.1)))
            .collect();
        if se.line && path.len() > 1 {
            let _ = writeln!(
                s,
                r#"<polyline points="{}" fill="none" stroke="{c}" stroke-width="1.5"/>"#,
                path.join(" ")
            );
        }
        let rad = if se.line || se.points.len() < 3 {
            4.5
        } else {
            2.5
        };
        for p in &se.points {
            let (x, ym, y9, yx) = (px(p.0), py(p.1), py(p.2), py(p.3));
            if !extras.whiskers {
                let _ = writeln!(
                    s,
                    r#"<circle cx="{x:.1}" cy="{ym:.1}" r="{rad}" fill="{c}" fill-opacity="0.8"/>"#
                );
                continue;
            }
            let _ = writeln!(
                s,
                r#"<circle cx="{x:.1}" cy="{ym:.1}" r="{rad}" fill="{c}" fill-opacity="0.8"/><line x1="{x:.1}" y1="{ym:.1}" x2="{x:.1}" y2="{y9:.1}" stroke="{c}" stroke-width="2.5"/><line x1="{x:.1}" y1="{ym:.1}" x2="{x:.1}" y2="{yx:.1}" stroke="{c}" stroke-width="0.8" stroke-dasharray="3,2"/><line x1="{:.1}" y1="{yx:.1}" x2="{:.1}" y2="{yx:.1}" stroke="{c}"/>"#,
                x - 4.0,
                x + 4.0
            );
        }
        let ly = t + 20.0 + 22.0 * i as f64;
        let _ = writeln!(
            s,
            r#"<circle cx="{}" cy="{}" r="4.5" fill="{c}"/><text x="{}" y="{}">{}</text>"#,
            w - r + 20.0,
            ly - 4.0,
            w - r + 32.0,
            ly,
            se.label
        );
    }
    for hl in &extras.hlines {
        let (y, c) = (py(hl.y), &hl.color);
        let _ = writeln!(
            s,
            r#"<line x1="{l}" y1="{y:.1}" x2="{}" y2="{y:.1}" stroke="{c}" stroke-width="1.2" stroke-dasharray="6,4"/><text x="{}" y="{:.1}" text-anchor="end" font-size="11" fill="{c}">{}</text>"#,
            w - r,
            w - r - 4.0,
            y - 5.0,
            hl.label
        );
    }
    // Labels right of their point, moved up or down in steps of a line where they would
    // overlap one already placed (a thin leader line then joins them to the point).
    let mut placed: Vec<(f64, f64, f64)> = Vec::new();
    for lb in &extras.labels {
        let (x, y) = (px(lb.x), py(lb.y));
        let width = 6.2 * lb.text.chars().count() as f64;
        let overlaps = |ty: f64| {
            placed.iter().any(|&(px0, px1, py0)| {
                x + 7.0 < px1 && px0 < x + 7.0 + width && (ty - py0).abs() < 12.0
            })
        };
        let ty = (0..12)
            .map(|k| y - 5.0 + 13.0 * f64::from((k + 1) / 2) * if k % 2 == 1 { -1.0 } else { 1.0 })
            .find(|&ty| !overlaps(ty))
            .unwrap_or(y - 5.0);
        placed.push((x + 7.0, x + 7.0 + width, ty));
        if (ty - (y - 5.0)).abs() > 1.0 {
            let _ = writeln!(
                s,
                r#"<line x1="{x:.1}" y1="{y:.1}" x2="{:.1}" y2="{:.1}" stroke="{}" stroke-width="0.6"/>"#,
                x + 6.0,
                ty - 4.0,
                lb.color
            );
        }
        let _ = writeln!(
            s,
            r#"<text x="{:.1}" y="{ty:.1}" font-size="11" fill="{}">{}</text>"#,
            x + 7.0,
            lb.color,
            lb.text
        );
    }
    let mut notes = String::new();
    for (k, n) in extras.notes.iter().enumerate() {
        let _ = write!(
            notes,
            r#"<text x="{}" y="{}" font-size="11">{n}</text>"#,
            w - r + 12.0,
            t + 40.0 + 14.0 * k as f64 + 22.0 * series.len() as f64
        );
    }
    let _ = writeln!(s, "{notes}</svg>");
    s
}
