//! The experiments: each function runs one part of a paper and returns its outcome as a
//! [`Section`](crate::Section). A part whose operation fails adds its claim as
//! [`Failed`](crate::Verdict::Failed) and the section goes on.
//!
//! * [`algebra`]: Dam et al. App. A and B (Euler angles, B.4 near the half turn, gimbal
//!   lock), Definitions 14–16 (exp, log, powers); Kavan et al. eq. (1)–(2).
//! * [`interpolation`]: Dam et al. ch. 5–6 (six methods through Table 5.1's keys) and
//!   Proposition 30 (Squad is C¹).
//! * [`dam_figures`]: Dam et al. Figures 5.1–5.3, 6.1–6.20 and 7.1–7.12, each with its
//!   caption's parameters; [`captions`]: chapters 5 and 6's captions checked;
//!   [`squad_and_spring`]: chapter 7's outcomes by number.
//! * [`kavan_figures`]: Kavan et al. Figures 2 and 3 (a screw motion; q^t against (−q)^t).
//! * [`table_1`]: Kavan et al. Table 1 measured, with FLOP counts.
//! * [`blending_claims`]: Kavan et al. §4, §5, Lemmas 2–3, Appendix B / Figure 7.
//! * [`identities`]: both papers' identities on random inputs, f64 and f32.
//! * [`beyond_the_report`]: Dam et al. §8.2's future work (Spring solved to its optimum,
//!   §7.6's remark tested, angular velocities at keys).
//! * [`beyond_the_blending_paper`]: Kavan et al. §7's future work (averaging measured
//!   poses, plainly and robustly; with [`rigid_keyframes`], key-frame curves of rigid
//!   motions).

pub mod algebra;
pub mod beyond_the_blending_paper;
pub mod beyond_the_report;
pub mod blending_claims;
pub mod captions;
pub mod dam_figures;
pub mod identities;
pub mod interpolation;
pub mod kavan_figures;
pub mod rigid_keyframes;
pub mod squad_and_spring;
pub mod table_1;

/// Whether an experiment draws its pictures (the tour does; `chasles properties` does
/// not, having nowhere to put them).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Figures {
    /// Draw them and add them to the section.
    Draw,
    /// Leave them out.
    Skip,
}

/// `[+0.100000, +0.200000]`: numbers with sign and six decimals.
pub(crate) fn arr(xs: &[f64]) -> String {
    let parts: Vec<String> = xs.iter().map(|x| format!("{x:+.6}")).collect();
    format!("[{}]", parts.join(", "))
}
