//! Line plots for the measured claims (Kavan et al. 2006, §4 and Appendix B / Figure 7):
//! several named series of (x, y) points on shared axes, as a self-contained SVG with a
//! legend. Non-finite points are left out.

use crate::svg::{esc, open};
use std::fmt::Write;

/// One curve: its legend, colour (CSS) and points.
pub struct Series<'a> {
    /// The legend entry.
    pub name: &'a str,
    /// A CSS colour, e.g. `#1f5fbf`.
    pub colour: &'a str,
    /// Whether to draw it dashed.
    pub dashed: bool,
    /// The points, in x order.
    pub points: Vec<(f64, f64)>,
}

/// An SVG (720 × 340) of `series` with a title and axis labels. The y range starts at 0
/// when the data come near it (their minimum under half their maximum); otherwise it is
/// zoomed to the data, so that a small variation (Figure 7's) shows.
pub fn lines_svg(series: &[Series], title: &str, x_label: &str, y_label: &str) -> String {
    let (w, h, left, right, top, bottom) = (720.0, 340.0, 80.0, 170.0, 40.0, 50.0);
    let finite = || {
        series
            .iter()
            .flat_map(|s| s.points.iter())
            .filter(|p| p.0.is_finite() && p.1.is_finite())
    };
    let (mut x0, mut x1) = (f64::INFINITY, f64::NEG_INFINITY);
    let (mut y0, mut y1) = (f64::INFINITY, f64::NEG_INFINITY);
    for p in finite() {
        x0 = x0.min(p.0);
        x1 = x1.max(p.0);
        y0 = y0.min(p.1);
        y1 = y1.max(p.1);
    }
    if !y0.is_finite() {
        (y0, y1) = (0.0, 1.0);
    } else if y0 >= 0.0 && y0 < 0.5 * y1 {
        y0 = 0.0;
    } else {
        let pad = (y1 - y0).max(1e-12 * y1.abs()) * 0.05;
        y0 -= pad;
    }
    if x0 >= x1 {
        (x0, x1) = (0.0, 1.0);
    }
    if y0 >= y1 {
        y1 = y0 + 1.0;
    }
    let y1 = y1 + (y1 - y0) * 0.05;
    let x = |v: f64| left + (w - left - right) * (v - x0) / (x1 - x0);
    let y = |v: f64| top + (h - top - bottom) * (1.0 - (v - y0) / (y1 - y0));
    let mut s = open(w, h, title, (left + w - right) / 2.0);
    for k in 0..=4 {
        let v = y0 + (y1 - y0) * k as f64 / 4.0;
        let _ = writeln!(
            s,
            r##"<line x1="{left}" x2="{}" y1="{yy}" y2="{yy}" stroke="#ddd"/><text x="{}" y="{}" text-anchor="end">{v:.4}</text>"##,
            w - right,
            left - 6.0,
            y(v) + 4.0,
            yy = y(v)
        );
        let u = x0 + (x1 - x0) * k as f64 / 4.0;
        let _ = writeln!(
            s,
            r#"<text x="{}" y="{}" text-anchor="middle">{u:.3}</text>"#,
            x(u),
            h - bottom + 18.0
        );
    }
    let _ = writeln!(
        s,
        r#"<path d="M{left} {top} V{} H{}" stroke="black" fill="none"/>"#,
        h - bottom,
        w - right
    );
    let _ = writeln!(
        s,
        r#"<text x="{}" y="{}" text-anchor="middle">{}</text>"#,
        (left + w - right) / 2.0,
        h - 10.0,
        esc(x_label)
    );
    let my = (top + h - bottom) / 2.0;
    let _ = writeln!(
        s,
        r#"<text x="16" y="{my}" text-anchor="middle" transform="rotate(-90 16 {my})">{}</text>"#,
        esc(y_label)
    );
    for (i, se) in series.iter().enumerate() {
        let pts: Vec<String> = se
            .points
            .iter()
            .filter(|p| p.0.is_finite() && p.1.is_finite())
            .map(|p| format!("{:.2},{:.2}", x(p.0), y(p.1)))
            .collect();
        let dash = if se.dashed {
            r#" stroke-dasharray="6 4""#
        } else {
            ""
        };
        let _ = writeln!(
            s,
            r#"<polyline class="series" points="{}" fill="none" stroke="{}" stroke-width="2"{dash}/>"#,
            pts.join(" "),
            se.colour
        );
        let ly = top + 10.0 + 20.0 * i as f64;
        let _ = writeln!(
            s,
            r#"<line x1="{}" x2="{}" y1="{ly}" y2="{ly}" stroke="{}" stroke-width="2"{dash}/><text x="{}" y="{}">{}</text>"#,
            w - right + 10.0,
            w - right + 34.0,
            se.colour,
            w - right + 40.0,
            ly + 4.0,
            esc(se.name)
        );
    }
    s.push_str("</svg>\n");
    s
}
