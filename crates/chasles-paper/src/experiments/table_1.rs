//! Kavan et al. 2006, Table 1 measured ([`crate::properties`]): one typed table, a column
//! per method and a row per property — each cell the measured mark, the worst deviation
//! and the paper's mark — with the FLOPS rows; the FLOP counts in full; the claim that the
//! measured marks are the paper's; and with [`Figures::Draw`] the deviations as a grid.

use super::Figures;
use crate::claim::Paper::Kavan2006;
use crate::properties::{self, PropertyCell, Table1, TOLERANCE};
use crate::section::Section;
use crate::table::{Cell, Number, Table};
use chasles_viz::grid::{grid_svg, GridCell};

fn check(c: &PropertyCell) -> Cell {
    Cell::Check {
        holds: c.holds,
        worst: (!c.worst.is_nan()).then(|| Number::sci(c.worst, 1)),
        note: c.note.clone(),
        paper: c.paper,
    }
}

/// The measured table as a typed table: property rows, method columns, the FLOPS rows.
pub fn typed(t: &Table1) -> Table {
    let mut header = vec!["property".to_string()];
    header.extend(t.rows.iter().map(|r| r.method.name().to_string()));
    let mut out = Table {
        caption: format!(
            "Table 1 measured: each cell the measured mark ('+': worst deviation below {TOLERANCE:.0e}) and the worst deviation, the paper's mark in parentheses"
        ),
        header,
        rows: Vec::new(),
    };
    let names = t.rows.first().map(|r| r.cells().map(|c| c.0));
    for (i, name) in names.into_iter().flatten().enumerate() {
        let mut row = vec![Cell::text(name)];
        row.extend(t.rows.iter().map(|r| check(r.cells()[i].1)));
        out.row(row);
    }
    let mut flops = vec![Cell::text("FLOPS")];
    flops.extend(t.rows.iter().map(|r| match r.flops.agrees() {
        Some(agrees) => Cell::Compared {
            ours: r.flops.ours(),
            paper: r.flops.paper.to_string(),
            agrees,
        },
        None => Cell::text(format!("{} (not in the paper)", r.flops.ours())),
    }));
    out.row(flops);
    out
}

/// Every FLOP count, per method and n.
fn flop_counts(t: &Table1) -> Table {
    let mut out = Table::new(
        "FLOPs of one blend, 4×4 matrices in and out (special: square roots and trigonometric functions, one each)",
        &["method", "n", "+ −", "×", "÷", "special", "total", "iterations"],
    );
    for r in &t.rows {
        for (n, c, it) in &r.flops.measured {
            out.row(vec![
                Cell::text(r.method.name()),
                Cell::Number(Number::integer(*n as u64)),
                Cell::Number(Number::integer(c.add)),
                Cell::Number(Number::integer(c.mul)),
                Cell::Number(Number::integer(c.div)),
                Cell::Number(Number::integer(c.special)),
                Cell::Number(Number::integer(c.total())),
                it.map_or(Cell::text("—"), |k| {
                    Cell::Number(Number::integer(k as u64))
                }),
            ]);
        }
    }
    out
}

/// The deviations as a grid picture.
fn grid(t: &Table1, samples: usize) -> Vec<u8> {
    let names: Vec<&str> = t.rows.iter().map(|r| r.method.name()).collect();
    let columns: Vec<&str> = t
        .rows
        .first()
        .map_or(Vec::new(), |r| r.cells().iter().map(|c| c.0).collect());
    let cells: Vec<Vec<GridCell>> = t
        .rows
        .iter()
        .map(|r| {
            r.cells()
                .iter()
                .map(|(_, c)| GridCell {
                    value: c.worst,
                    holds: c.holds,
                    agrees: c.agrees(),
                })
                .collect()
        })
        .collect();
    grid_svg(
        &names,
        &columns,
        &cells,
        &format!(
            "Table 1 measured: worst deviation per method and property ({samples} random cases)"
        ),
    )
    .into_bytes()
}

/// Table 1 measured on `samples` random cases per property from `seed`: the property
/// cells and the FLOPS cells, each compared with the paper as two claims.
pub fn table_1(samples: usize, seed: u64, figures: Figures) -> Section {
    let mut s = Section::new(format!(
        "Kavan et al. Table 1: properties of the blending methods, measured on {samples} random cases per property (seed {seed})"
    ));
    let measured = properties::measure(samples, seed).map_err(|e| e.to_string());
    s.attempt(
        Kavan2006,
        "Table 1",
        "which methods are rigid, bi-invariant, coordinate-invariant, blend more than two transforms, move at constant speed and take the shortest path",
        |s| -> Result<_, String> {
            let t = measured.as_ref().map_err(Clone::clone)?;
            s.text("Each cell: measured mark, worst deviation; the paper's mark in parentheses; \"differs\" where they disagree. The FLOPS row: our count (the same a + b n form, or the counts per n for an iterative method), the paper's in parentheses.");
            s.table(typed(t));
            s.table(flop_counts(t));
            if figures == Figures::Draw {
                s.figure(
                    "table1.svg",
                    grid(t, samples),
                    &format!("Table 1 as measured: each cell the worst deviation over {samples} random cases; green holds, red fails, a frame marks a disagreement with the paper"),
                );
            }
            let listed: usize = t
                .rows
                .iter()
                .map(|r| r.cells().iter().filter(|c| c.1.paper.is_some()).count())
                .sum();
            let dis = t.disagreements();
            let ours = if dis.is_empty() {
                format!("All {listed} property cells the paper lists agree with it.")
            } else {
                let which: Vec<String> =
                    dis.iter().map(|(m, p)| format!("{}: {p}", m.name())).collect();
                format!(
                    "{} of {listed} property cells the paper lists agree with it; differing: {}.",
                    listed - dis.len(),
                    which.join(", ")
                )
            };
            Ok((ours, dis.is_empty()))
        },
    );
    s.attempt(
        Kavan2006,
        "Table 1, FLOPS",
        "number of FLOPS for blending n rigid transformations (4×4 matrices in and out): Lin. 23n, Log. 160+104n, ScLERP 240, DLB 65+49n; Dec. and DIB N/A (iterative)",
        |_| -> Result<_, String> {
            let t = measured.as_ref().map_err(Clone::clone)?;
            let (n, dis) = (t.flop_cells(), t.flop_disagreements());
            let which: Vec<String> = t
                .rows
                .iter()
                .filter(|r| dis.contains(&r.method))
                .map(|r| format!("{} {} (paper {})", r.method.name(), r.flops.ours(), r.flops.paper))
                .collect();
            Ok((
                if dis.is_empty() {
                    format!("all {n} FLOPS cells agree")
                } else {
                    format!(
                        "{} of {n} FLOPS cells agree; differing: {} — we count our code as it runs: Shepperd's matrix → dual quaternion conversion, DLB's antipodality fix, ScLERP's polynomial angle and sine (see the FLOP table)",
                        n - dis.len(),
                        which.join("; ")
                    )
                },
                dis.is_empty(),
            ))
        },
    );
    s
}
