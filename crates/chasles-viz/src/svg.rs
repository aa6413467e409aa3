//! What every SVG picture starts with: the document element, a white ground and a centred
//! title; and text escaping.

use std::fmt::Write;

/// `s` with `& < >` escaped for SVG text.
pub(crate) fn esc(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
}

/// The opening of a `w × h` SVG document: white ground, `title` centred on `title_x`.
pub(crate) fn open(w: f64, h: f64, title: &str, title_x: f64) -> String {
    let mut s = String::new();
    let _ = writeln!(
        s,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{h}" viewBox="0 0 {w} {h}" font-family="sans-serif" font-size="12">"#
    );
    let _ = writeln!(s, r#"<rect width="{w}" height="{h}" fill="white"/>"#);
    let _ = writeln!(
        s,
        r#"<text x="{title_x}" y="24" text-anchor="middle" font-size="15">{}</text>"#,
        esc(title)
    );
    s
}
