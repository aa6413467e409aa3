//! `chasles tour`: a walk through both papers on built-in data, with every number computed
//! on the spot. The tour is the list of experiments in [`run`] — the core algebra (Dam et
//! al. App. A and B; Kavan et al. §3), interpolation (Dam et al. ch. 5–7), blending (Kavan
//! et al. §4, §5, Table 1, Figure 7), skinning (Kavan et al. §6) and the identities —
//! each returning a typed section, run in order and fed to the terminal renderer (stdout)
//! and to the report (`--out`, default `report/`: one HTML page with every claim, our
//! measurement, whether they agree, and the pictures; see [`crate::report`]).

mod blending;
mod clips;
mod figure_5;
mod skinning;

use crate::report::Report;
use chasles_paper::experiments::{
    algebra, beyond_the_blending_paper::beyond_the_blending_paper, beyond_the_report,
    blending_claims::blending_claims, dam_figures, identities::identities, interpolation,
    kavan_figures, squad_and_spring, table_1::table_1,
};
use chasles_paper::{render, Experiment, Figures};
use std::io::{IsTerminal, Write};
use std::path::PathBuf;

/// Options of `chasles tour`.
pub struct TourArgs {
    /// Random inputs per identity in the sweep.
    pub samples: usize,
    /// Seed of the random inputs.
    pub seed: u64,
    /// The report's folder.
    pub out: PathBuf,
}

/// Progress on a terminal (stderr), nothing when piped.
fn stage(what: &str) {
    let mut e = std::io::stderr();
    if e.is_terminal() {
        let _ = write!(e, "\r\x1b[2K  tour: {what} …");
        let _ = e.flush();
    }
}

/// Runs the tour, printing to stdout.
pub fn run(args: TourArgs) -> anyhow::Result<()> {
    let (samples, seed) = (args.samples, args.seed);
    // Dam et al. first, then Kavan et al., each in its own order (chapters, sections,
    // figures); the identities of both last.
    let tour = [
        Experiment::new("the Euler convention", algebra::euler_convention),
        Experiment::new("App. B.4 near 180°", algebra::b4_near_half_turn),
        Experiment::new("Figure 4.1", algebra::figure_4_1),
        Experiment::new("gimbal lock, Figure 4.3", algebra::gimbal_lock_figure),
        Experiment::new("gimbal lock", algebra::gimbal_lock),
        Experiment::new("exp, log and powers", algebra::exp_log),
        Experiment::new("Dam et al. Figures 5.1–5.3", || {
            dam_figures::chapter_5_section(Figures::Draw)
        }),
        Experiment::new("interpolation", || {
            interpolation::six_methods(Figures::Draw)
        }),
        Experiment::new("Squad's continuity", interpolation::squad_continuity),
        Experiment::new("Dam et al. Figures 6.1–6.20", || {
            dam_figures::chapter_6_section(Figures::Draw)
        }),
        Experiment::new("Dam et al. Figures 7.1–7.12", || {
            squad_and_spring::chapter_7_section(Figures::Draw)
        }),
        Experiment::new("beyond Dam et al. (§8.2)", || {
            beyond_the_report::beyond_the_report(Figures::Draw)
        }),
        Experiment::new("skinning: Figure 1(c)", skinning::figure_1c),
        Experiment::new("dual quaternions", algebra::dual_quaternion),
        Experiment::new("Kavan et al. Figure 2", kavan_figures::figure_2),
        Experiment::new("Kavan et al. Figure 3", kavan_figures::figure_3),
        Experiment::new("blending: Figure 4", kavan_figures::figure_4),
        Experiment::new("blending: two transforms", blending::two_transforms),
        Experiment::new("blending: the claims", || {
            blending_claims(100, 1, Figures::Draw)
        }),
        Experiment::new("blending: Table 1", || table_1(50, 2006, Figures::Draw)),
        Experiment::new("skinning: Figure 5's timings", figure_5::figure_5),
        Experiment::new("skinning: the candy wrapper", skinning::candy_wrapper),
        Experiment::new("skinning: Figure 6(c)–(d)", skinning::long_way),
        Experiment::new("skinning: the characters", skinning::characters),
        Experiment::new("beyond Kavan et al. (§7): clips", clips::clips),
        Experiment::new(
            "beyond Kavan et al. (§7): poses and rigid key frames",
            || beyond_the_blending_paper(Figures::Draw),
        ),
        Experiment::new("identities on random inputs", move || {
            identities(samples, seed)
        }),
    ];
    println!("chasles tour — rotations and rigid motions, with numbers computed now");
    println!("Papers: Dam, Koch & Lillholm 1998 (quaternions, interpolation, animation);");
    println!("        Kavan, Collins, Žára & O'Sullivan 2006 (dual quaternions, rigid blending).");
    let mut report = Report::new(&args.out)?;
    for experiment in tour {
        stage(experiment.name);
        let section = experiment.run();
        print!("{}", render::terminal::section(&section));
        report.add(section)?;
    }
    let path = report.finish()?;
    if std::io::stderr().is_terminal() {
        eprint!("\r\x1b[2K");
    }
    let (ok, n) = report.tally();
    println!("\nreport: {} ({ok} of {n} claims agree)", path.display());
    Ok(())
}
