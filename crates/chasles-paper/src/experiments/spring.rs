//! Dam et al. 1998, chapter 7: Spring (§6.3.7) against Squad and Slerp on the chapter's
//! examples (§7.1–§7.6), 200 frames each, by curvature energy (eq. 6.23).

use super::interpolation::{energy, frames_of};
use crate::claim::Paper::Dam1998;
use crate::section::Section;
use crate::table::{Cell, Number, Table};
use chasles::interp::{examples, Hemisphere, KeyFrames, Method};

/// The curvature energy of Slerp, Squad and Spring on every chapter-7 example, and the
/// claim that Spring's curves are the smoother.
pub fn spring_vs_squad() -> Section {
    let mut s = Section::new(
        "Dam et al. ch. 7: Spring against Squad on the chapter's examples (200 frames)",
    );
    s.attempt(
        Dam1998,
        "ch. 7",
        "Spring's curves are smoother than Squad's (lower curvature energy, eq. 6.23) on the chapter's examples",
        |s| -> chasles::Result<_> {
            let mut t = Table::new(
                "curvature energy (eq. 6.23), 200 frames",
                &["set", "Slerp", "Squad", "Spring", "Spring / Squad"],
            );
            let mut worst = 0.0f64;
            for set in examples::all().into_iter().skip(1) {
                let keys = KeyFrames::new(&set.keys::<f64>(), None, Hemisphere::Chain)?;
                let sl = energy(&frames_of(Some(Method::Slerp), &keys, 200)?);
                let sq = energy(&frames_of(Some(Method::Squad), &keys, 200)?);
                let sp = energy(&frames_of(None, &keys, 200)?);
                worst = worst.max(sp / sq);
                t.row(vec![
                    Cell::text(format!("{} ({})", set.name, set.section)),
                    Cell::Number(Number::sci(sl, 4)),
                    Cell::Number(Number::sci(sq, 4)),
                    Cell::Number(Number::sci(sp, 4)),
                    Cell::Number(Number::fixed(sp / sq, 3)),
                ]);
            }
            s.table(t);
            Ok((
                format!("largest Spring / Squad energy ratio over the examples: {worst:.3}"),
                worst < 1.0,
            ))
        },
    );
    s
}
