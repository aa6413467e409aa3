//! # chasles-paper — the two papers' experiments, by number
//!
//! Everything that reproduces Dam, Koch & Lillholm 1998 (*Quaternions, Interpolation and
//! Animation*) and Kavan, Collins, Žára & O'Sullivan 2006 (*Dual Quaternions for Rigid
//! Transformation Blending*) rather than implementing them: the core crate `chasles` keeps
//! the algebra, interpolation, blending and the measures an algorithm needs (curvature,
//! velocity); this crate holds
//!
//! * the measurements: Kavan et al.'s Table 1 ([`properties`], with exact FLOP counts by
//!   [`flops`]) and its claims of §4, §5 and Appendix B ([`claims`]), on random inputs
//!   ([`random`]);
//! * the experiments ([`experiments`]): functions that run one measurement and return its
//!   outcome as a typed [`Section`] — [`Claim`]s (the paper's words, where they stand, our
//!   number, a [`Verdict`]; a failed operation gives [`Verdict::Failed`], never a skipped
//!   claim), [`Table`]s of typed [`Cell`]s, [`Figure`]s with their captions, paragraphs —
//!   all `serde::Serialize`;
//! * one renderer per format ([`render`]): terminal, Markdown, JSON and the HTML report.
//!
//! `chasles tour` is a short list of [`Experiment`]s fed to the terminal and HTML
//! renderers; `chasles properties` feeds Table 1 and the claims to Markdown or JSON.

#![forbid(unsafe_code)]
#![warn(missing_docs)]

pub mod claim;
pub mod claims;
pub mod error;
pub mod experiments;
pub mod flops;
pub mod properties;
pub mod random;
pub mod render;
pub mod section;
pub mod table;

pub use claim::{Claim, Paper, Verdict};
pub use error::{Error, Result};
pub use experiments::Figures;
pub use section::{tally, Experiment, Figure, Item, PaperFigure, Section};
pub use table::{Cell, Number, Style, Table};
