//! A table of measured deviations as a coloured grid (Kavan et al. 2006, Table 1): one row
//! per method, one column per property, each cell the worst deviation measured, green where
//! the property holds (below the tolerance) and red where it does not, lighter the closer
//! to the tolerance; a black frame marks a cell that disagrees with the paper. A cell of
//! exactly 0 is a yes/no property and is written so.

use crate::svg::{esc, open};
use std::fmt::Write;

/// One cell: the worst deviation, whether it holds, whether it agrees with the paper.
#[derive(Debug, Clone, Copy)]
pub struct GridCell {
    /// The worst deviation (NaN: not measured).
    pub value: f64,
    /// Whether the property holds.
    pub holds: bool,
    /// Whether the measured mark agrees with the paper's.
    pub agrees: bool,
}

/// An SVG grid of `cells[row][column]` with the given labels and title.
pub fn grid_svg(rows: &[&str], columns: &[&str], cells: &[Vec<GridCell>], title: &str) -> String {
    let (cw, ch, left, top) = (112.0, 30.0, 90.0, 70.0);
    let w = left + cw * columns.len() as f64 + 10.0;
    let h = top + ch * rows.len() as f64 + 30.0;
    let mut s = open(w, h, title, w / 2.0);
    for (j, c) in columns.iter().enumerate() {
        let _ = writeln!(
            s,
            r#"<text x="{}" y="{}" text-anchor="middle">{}</text>"#,
            left + cw * (j as f64 + 0.5),
            top - 10.0,
            esc(c)
        );
    }
    for (i, r) in rows.iter().enumerate() {
        let y = top + ch * i as f64;
        let _ = writeln!(
            s,
            r#"<text x="{}" y="{}" text-anchor="end">{}</text>"#,
            left - 8.0,
            y + ch / 2.0 + 4.0,
            esc(r)
        );
        for (j, cell) in cells
            .get(i)
            .map(|v| v.as_slice())
            .unwrap_or(&[])
            .iter()
            .enumerate()
        {
            let x = left + cw * j as f64;
            // Lightness from how many decades the value is from 1e-8 (the usual tolerance).
            let decades = if cell.value > 0.0 && cell.value.is_finite() {
                (cell.value.log10() + 8.0).abs().min(8.0) / 8.0
            } else {
                1.0
            };
            let fill = if cell.value.is_nan() {
                "#eeeeee".to_string()
            } else if cell.holds {
                let g = (230.0 - 90.0 * decades) as u8;
                format!("rgb({},{},{})", g / 2, g, g / 2)
            } else {
                let r = (240.0 - 60.0 * decades) as u8;
                format!("rgb({r},{},{})", r / 3, r / 3)
            };
            let stroke = if cell.agrees {
                r#"stroke="white""#
            } else {
                r#"stroke="black" stroke-width="3""#
            };
            let text = if cell.value.is_nan() {
                "—".to_string()
            } else if cell.value == 0.0 {
                // A yes/no property (e.g. "n > 2"), not a deviation.
                if cell.holds { "yes" } else { "no" }.to_string()
            } else {
                format!("{:.0e}", cell.value)
            };
            let _ = writeln!(
                s,
                r#"<rect class="cell" x="{x}" y="{y}" width="{cw}" height="{ch}" fill="{fill}" {stroke}/><text x="{}" y="{}" text-anchor="middle" fill="white">{text}</text>"#,
                x + cw / 2.0,
                y + ch / 2.0 + 4.0
            );
        }
    }
    let _ = writeln!(
        s,
        r#"<text x="{left}" y="{}">green: holds (below tolerance) · red: fails · framed: differs from the paper</text>"#,
        h - 10.0
    );
    s.push_str("</svg>\n");
    s
}
