//! A bar chart of counts, for DIB's iteration counts (Kavan et al. 2006, §5: "typically 1
//! to 4 iterations"): one bar per label, its count written above it.

use crate::svg::{esc, open};
use std::fmt::Write;

/// An SVG bar chart (640 × 300) of `counts` under `labels`.
pub fn bars_svg(labels: &[String], counts: &[usize], title: &str, x_label: &str) -> String {
    let (w, h, left, right, top, bottom) = (640.0, 300.0, 50.0, 20.0, 40.0, 50.0);
    let n = labels.len().min(counts.len()).max(1);
    let max = counts.iter().copied().max().unwrap_or(0).max(1) as f64;
    let bw = (w - left - right) / n as f64;
    let mut s = open(w, h, title, w / 2.0);
    for (i, (l, c)) in labels.iter().zip(counts).enumerate() {
        let bh = (h - top - bottom) * *c as f64 / max;
        let x = left + bw * i as f64;
        let y = h - bottom - bh;
        let _ = writeln!(
            s,
            r##"<rect class="bar" x="{:.2}" y="{y:.2}" width="{:.2}" height="{bh:.2}" fill="#1f5fbf"/><text x="{:.2}" y="{:.2}" text-anchor="middle">{c}</text><text x="{:.2}" y="{}" text-anchor="middle">{}</text>"##,
            x + bw * 0.15,
            bw * 0.7,
            x + bw / 2.0,
            y - 4.0,
            x + bw / 2.0,
            h - bottom + 16.0,
            esc(l)
        );
    }
    let _ = writeln!(
        s,
        r#"<path d="M{left} {} H{}" stroke="black"/><text x="{}" y="{}" text-anchor="middle">{}</text>"#,
        h - bottom,
        w - right,
        (left + w - right) / 2.0,
        h - 12.0,
        esc(x_label)
    );
    s.push_str("</svg>\n");
    s
}
