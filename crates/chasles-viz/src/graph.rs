//! The angular-velocity graph (Dam et al. 1998, §5.2): velocity against frame index as a
//! line, the key frames marked with asterisks; the first and last frame, which have no
//! centred velocity, are left out, as in the report. Written as a self-contained SVG, or
//! drawn into a PNG.

use crate::image::Image;
use std::fmt::Write;

/// The frames shown (not the first or last, finite) and the value range, from 0.
fn shown_and_range(velocity: &[f64]) -> (Vec<(usize, f64)>, f64, f64) {
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
    (shown, lo, hi)
}

/// An SVG (800 × 360) of `velocity` (one value per frame) with asterisks at `keys`.
pub fn velocity_svg(velocity: &[f64], keys: &[usize], title: &str) -> String {
    let (w, h, left, right, top, bottom) = (800.0, 360.0, 70.0, 20.0, 40.0, 50.0);
    let n = velocity.len();
    let (shown, lo, hi) = shown_and_range(velocity);
    let x = |i: usize| left + (w - left - right) * i as f64 / (n.max(2) - 1) as f64;
    let y = |v: f64| top + (h - top - bottom) * (1.0 - (v - lo) / (hi - lo));
    let mut s = crate::svg::open(w, h, title, w / 2.0);
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

/// The same graph as a `width × height` picture: axes, four value ticks, the curve, and
/// asterisks at the inner `keys`.
pub fn velocity_png(velocity: &[f64], keys: &[usize], width: usize, height: usize) -> Image {
    let (left, right, top, bottom) = (80.0, 20.0, 20.0, 40.0);
    let (w, h) = (width as f64, height as f64);
    let n = velocity.len();
    let (shown, lo, hi) = shown_and_range(velocity);
    let x = |i: usize| left + (w - left - right) * i as f64 / (n.max(2) - 1) as f64;
    let y = |v: f64| top + (h - top - bottom) * (1.0 - (v - lo) / (hi - lo));
    let mut img = Image::filled(width, height, [255, 255, 255]);
    let black = [0, 0, 0];
    for k in 0..=4 {
        let v = lo + (hi - lo) * k as f64 / 4.0;
        line(
            &mut img,
            [left, y(v)],
            [w - right, y(v)],
            [221, 221, 221],
            1.0,
        );
        text(&mut img, 4.0, y(v) - 5.0, &format!("{v:.4}"), black, 2);
    }
    for k in 0..=5 {
        let i = n.saturating_sub(1) * k / 5;
        text(
            &mut img,
            x(i) - 6.0,
            h - bottom + 8.0,
            &format!("{i}"),
            black,
            2,
        );
    }
    text(&mut img, w / 2.0 - 30.0, h - 16.0, "FRAME", black, 2);
    line(&mut img, [left, top], [left, h - bottom], black, 1.0);
    line(
        &mut img,
        [left, h - bottom],
        [w - right, h - bottom],
        black,
        1.0,
    );
    for pair in shown.windows(2) {
        let (a, b) = (pair[0], pair[1]);
        if b.0 == a.0 + 1 {
            line(
                &mut img,
                [x(a.0), y(a.1)],
                [x(b.0), y(b.1)],
                [31, 95, 191],
                2.0,
            );
        }
    }
    for k in keys.iter().filter(|k| **k > 0 && **k + 1 < n) {
        text(
            &mut img,
            x(*k) - 4.5,
            y(velocity[*k]) - 7.5,
            "*",
            [192, 57, 43],
            3,
        );
    }
    img
}

/// A line `thickness` pixels wide, drawn as a row of discs.
fn line(img: &mut Image, a: [f64; 2], b: [f64; 2], colour: [u8; 3], thickness: f64) {
    let len = ((b[0] - a[0]).powi(2) + (b[1] - a[1]).powi(2)).sqrt();
    let steps = (len * 2.0).ceil().max(1.0) as usize;
    let r = thickness / 2.0;
    for s in 0..=steps {
        let t = s as f64 / steps as f64;
        let (cx, cy) = (a[0] + (b[0] - a[0]) * t, a[1] + (b[1] - a[1]) * t);
        let (x0, x1) = ((cx - r).round() as i64, (cx + r).round() as i64);
        let (y0, y1) = ((cy - r).round() as i64, (cy + r).round() as i64);
        for py in y0..=y1.max(y0) {
            for px in x0..=x1.max(x0) {
                if px >= 0 && py >= 0 {
                    img.set(px as usize, py as usize, colour);
                }
            }
        }
    }
}

/// Text in the 3×5 font at `px` pixels a dot.
fn text(img: &mut Image, x: f64, y: f64, s: &str, colour: [u8; 3], px: usize) {
    for (dx, dy) in crate::font::dots(s) {
        for sy in 0..px {
            for sx in 0..px {
                let (px, py) = (x + (dx * px + sx) as f64, y + (dy * px + sy) as f64);
                if px >= 0.0 && py >= 0.0 {
                    img.set(px as usize, py as usize, colour);
                }
            }
        }
    }
}

/// The indices of the key frames among interpolated `frames` (where the asterisks go).
pub fn key_indices(frames: &[chasles::interp::Frame<f64>]) -> Vec<usize> {
    frames
        .iter()
        .enumerate()
        .filter_map(|(i, f)| f.key.map(|_| i))
        .collect()
}
