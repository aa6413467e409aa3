//! `chasles blend`: blend rigid transformations given as JSON (Kavan et al. 2006, §2–5).
//!
//! Input: one case or an array of cases. A case is
//! `{"transforms": [T, …], "weights": [w, …]}` (optional `"center": [x, y, z]` for dec and
//! qlb, `"precision"` and `"max_iterations"` for the iterative methods), or for sclerp
//! `{"from": T, "to": T, "t": x}`. A transform T is `{"rotation": [w,x,y,z],
//! "translation": [x,y,z]}`, `{"matrix": [[r00,r01,r02,t0],…,[0,0,0,1]]}` (row-major),
//! `{"dq": [8 numbers]}` or any other object form of `chasles convert --jsonl`
//! ([`crate::repr::MotionFields`]). Output: a JSON array, one object per case in order, with
//! `rotation`, `translation`, `matrix`, `dq`, `rigid` and, for dec, log-iter and dib,
//! `iterations` (and `"capped": true`, with a note on stderr, when it ran all
//! `max_iterations` updates without its stopping rule stopping it). `--plot`, `--render` and `--gif` draw the first case
//! ([`crate::blend_pictures`]).
//!
//! The input is read by [`crate::blend_case`]; every output (the JSON and the pictures) is
//! made and checked before any is written.

use crate::blend_case::blend_all;
use crate::blend_pictures;
use crate::output::Pending;
use crate::picture_args::Pictures;
use anyhow::{anyhow, Context, Result};
use chasles::blend::Method;

/// Runs `chasles blend`; `pictures` are the `--plot` (SVG), `--render` (PNG), `--gif`
/// (GIF) and `--sphere` (PNG) paths, drawn for the first case (see
/// [`crate::blend_pictures`]).
pub fn run(m: Method, input: &str, pictures: &Pictures) -> Result<()> {
    pictures.check(&["svg"])?;
    use chasles_skin::bounded::{read_capped, read_text, MAX_TEXT_BYTES};
    let text = if input == "-" {
        let bytes = read_capped(std::io::stdin().lock(), MAX_TEXT_BYTES, "stdin")?;
        String::from_utf8(bytes).context("stdin is not UTF-8 text")?
    } else {
        read_text(std::path::Path::new(input), MAX_TEXT_BYTES)
            .with_context(|| format!("cannot read {input}"))?
    };
    let b = blend_all(m, &text)?;
    // Every output made and checked before any is written: the JSON, then each picture.
    let json = serde_json::to_string_pretty(&b.out)?;
    let mut files = Pending::default();
    if pictures.any() {
        let (x, w, opt) = b
            .first
            .as_ref()
            .ok_or_else(|| anyhow!("no cases to draw"))?;
        let c = blend_pictures::Case { x, w, opt };
        let Pictures {
            plot,
            render,
            gif,
            sphere,
        } = pictures;
        if let Some(p) = plot {
            files.add(
                p,
                blend_pictures::plot(&c)?.into_bytes(),
                Some(String::new()),
            );
        }
        if let Some(p) = render {
            files.add(p, blend_pictures::render(&c)?.png(), Some(String::new()));
        }
        if let Some(p) = gif {
            let frames = blend_pictures::animate(&c, m, 40)?;
            files.add(p, chasles_viz::gif(&frames, 5)?, Some(String::new()));
        }
        if let Some(p) = sphere {
            files.add(p, blend_pictures::sphere(&c, m)?.png(), Some(String::new()));
        }
    }
    let said = files.write()?;
    for n in &b.notes {
        eprintln!("note: {n}");
    }
    println!("{json}");
    for line in said {
        eprintln!("{line}");
    }
    Ok(())
}
