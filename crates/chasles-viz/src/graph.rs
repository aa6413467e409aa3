//! The angular-velocity graph (Dam et al. 1998, §5.2): velocity against frame index as a
//! line, the key frames marked with asterisks; the first and last frame, which have no
//! centred velocity, are left out, as in the report. Written as a self-contained SVG.

use std::fmt::Write;

/// An SVG (800 × 360) of `velocity` (one value per frame) with asterisks at `keys`.
pub fn velocity_svg(velocity: &[f64], keys: &[usize], title: &str) -> String {
    let (w, h, left, right, top, bottom) = (800.0, 360.0, 70.0, 20.0, 40.0, 50.0);
    let n = velocity.len();
    let shown: Vec<(usize, f64)> = velocity
        .iter()
        .copied()
        .enumerate()
        .filter(|(i, v)| *i > 0 && *i + 1 < n && v.is_finite())
        .collect();
    let (lo, hi) = shown
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), (_, v)| {
            (a.min(*v), b.max(*v))
        });
    let (lo, hi) = if lo.is_finite() {
        (0.0f64.min(lo), if hi > lo { hi * 1.05 } else { lo + 1.0 })
    } else {
        (0.0, 1.0)
    };
    let x = |i: usize| left + (w - left - right) * i as f64 / (n.max(2) - 1) as f64;
    let y = |v: f64| top + (h - top - bottom) * (1.0 - (v - lo) / (hi - lo));
    let mut s = String::new();
    let _ = writeln!(
        s,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{h}" viewBox="0 0 {w} {h}" font-family="sans-serif" font-size="12">"#
    );
    let _ = writeln!(s, r#"<rect width="{w}" height="{h}" fill="white"/>"#);
    let esc = title
        .replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;");
    let _ = writeln!(
        s,
        r#"<text x="{}" y="24" text-anchor="middle" font-size="15">{esc}</text>"#,
        w / 2.0
    );
    // Axes and ticks.
    let _ = writeln!(
        s,
        r#"<path d="M{left} {top} V{} H{}" stroke="black" fill="none"/>"#,
        h - bottom,
        w - right
    );
    for k in 0..=4 {
        let v = lo + (hi - lo) * k as f64 / 4.0;
        let _ = writeln!(
            s,
            r##"<line x1="{}" x2="{left}" y1="{y0}" y2="{y0}" stroke="black"/><text x="{}" y="{}" text-anchor="end">{v:.4}</text><line x1="{left}" x2="{}" y1="{y0}" y2="{y0}" stroke="#ddd"/>"##,
            left - 5.0,
            left - 8.0,
            y(v) + 4.0,
            w - right,
            y0 = y(v)
        );
    }
    for k in 0..=5 {
        let i = (n.saturating_sub(1)) * k / 5;
        let _ = writeln!(
            s,
            r#"<line x1="{0}" x2="{0}" y1="{1}" y2="{2}" stroke="black"/><text x="{0}" y="{3}" text-anchor="middle">{i}</text>"#,
            x(i),
            h - bottom,
            h - bottom + 5.0,
            h - bottom + 20.0
        );
    }
    let _ = writeln!(
        s,
        r#"<text x="{}" y="{}" text-anchor="middle">frame</text>"#,
        (left + w - right) / 2.0,
        h - 10.0
    );
    let _ = writeln!(
        s,
        r#"<text x="18" y="{}" text-anchor="middle" transform="rotate(-90 18 {})">angular velocity</text>"#,
        (top + h - bottom) / 2.0,
        (top + h - bottom) / 2.0
    );
    // The curve.
    let pts: Vec<String> = shown
        .iter()
        .map(|(i, v)| format!("{:.2},{:.2}", x(*i), y(*v)))
        .collect();
    let _ = writeln!(
        s,
        r##"<polyline points="{}" fill="none" stroke="#1f5fbf" stroke-width="1.5"/>"##,
        pts.join(" ")
    );
    // Asterisks at the inner key frames.
    for k in keys.iter().filter(|k| **k > 0 && **k + 1 < n) {
        let _ = writeln!(
            s,
            r##"<text class="key" x="{:.2}" y="{:.2}" text-anchor="middle" font-size="20" fill="#c0392b">*</text>"##,
            x(*k),
            y(velocity[*k]) + 9.0
        );
    }
    s.push_str("</svg>\n");
    s
}
