//! Method names on the command line as clap value enums: `--method` is checked by clap,
//! which lists the choices in `--help` and in its error. The libraries' own method enums
//! (`chasles::blend::Method`, `chasles_skin::Method`) keep their names and lists; the CLI
//! wraps them here rather than making the libraries depend on clap.

use clap::builder::PossibleValue;
use clap::ValueEnum;
use std::sync::LazyLock;

/// A clap value enum over a library enum with `ALL` and `name()`.
macro_rules! choice {
    ($(#[$doc:meta])* $name:ident, $inner:ty) => {
        $(#[$doc])*
        #[derive(Clone, Copy, Debug, PartialEq, Eq)]
        pub struct $name(pub $inner);

        impl ValueEnum for $name {
            fn value_variants<'a>() -> &'a [Self] {
                static ALL: LazyLock<Vec<$name>> =
                    LazyLock::new(|| <$inner>::ALL.into_iter().map($name).collect());
                &ALL
            }
            fn to_possible_value(&self) -> Option<PossibleValue> {
                Some(PossibleValue::new(self.0.name()))
            }
        }
    };
}

choice!(
    /// A blending method of Kavan et al. 2006 (`lin`, `dec`, `log`, `log-iter`, `qlb`,
    /// `sclerp`, `dlb`, `dib`).
    BlendMethod,
    chasles::blend::Method
);

choice!(
    /// A skinning method (`lbs`, `dqs`, `dib`, `log`, `qlb`, `sbs`).
    SkinMethod,
    chasles_skin::Method
);

/// An interpolation method of Dam et al. 1998 by its name in the report and App. C: the
/// five piecewise methods, Spring, and the App. C presets of Spring; then the curves past
/// the report (issue 21): Kochanek–Bartels, Catmull–Rom, Bézier and the C² spline.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum InterpMethod {
    /// LinEuler (§6.1.1): Euler angles interpolated linearly.
    #[value(name = "lineuler")]
    LinEuler,
    /// LinMat (§6.1.2): matrices interpolated linearly.
    #[value(name = "linmat")]
    LinMat,
    /// Lerp (§6.1.3), normalized (Figure 6.3).
    Lerp,
    /// Slerp (§6.1.5, eq. 6.13); with --rigid, piecewise ScLERP (also named sclerp).
    #[value(alias = "sclerp")]
    Slerp,
    /// Squad (§6.2.1, Definition 17).
    Squad,
    /// Spring (§6.3.7): curvature minimized by gradient descent; `justdoit` with c_k = 1.3
    /// (Figure 6.20) and the accelerated step.
    Spring,
    /// App. C's `slerpsvupti`: gradient descent from Slerp, one step (Figure 6.15).
    #[value(name = "slerpsvupti")]
    SlerpSvupti,
    /// App. C's `squadsvupti`: gradient descent from Squad, one step.
    #[value(name = "squadsvupti")]
    SquadSvupti,
    /// App. C's `justdoit`: gradient descent applied three times from Slerp, 22 → 110 →
    /// 550 frames of 550 (Figures 6.16–6.17).
    #[value(name = "justdoit")]
    JustDoIt,
    /// Kochanek–Bartels (1984): tension, continuity and bias (`--tension`, `--continuity`,
    /// `--bias`, or per key in the key file); all 0 is Catmull–Rom.
    Tcb,
    /// Schlag's spherical Catmull–Rom spline (C¹).
    #[value(name = "catmull-rom")]
    CatmullRom,
    /// Shoemake's spherical Bézier spline, de Casteljau by Slerp (1985).
    Bezier,
    /// A C² spline: continuous angular acceleration (SciPy's `RotationSpline`).
    C2,
}

impl InterpMethod {
    /// Its name on the command line.
    pub fn name(self) -> &'static str {
        match self {
            InterpMethod::LinEuler => "lineuler",
            InterpMethod::LinMat => "linmat",
            InterpMethod::Lerp => "lerp",
            InterpMethod::Slerp => "slerp",
            InterpMethod::Squad => "squad",
            InterpMethod::Spring => "spring",
            InterpMethod::SlerpSvupti => "slerpsvupti",
            InterpMethod::SquadSvupti => "squadsvupti",
            InterpMethod::JustDoIt => "justdoit",
            InterpMethod::Tcb => "tcb",
            InterpMethod::CatmullRom => "catmull-rom",
            InterpMethod::Bezier => "bezier",
            InterpMethod::C2 => "c2",
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_library_method_is_a_choice_by_its_name() {
        for m in chasles::blend::Method::ALL {
            assert_eq!(BlendMethod::from_str(m.name(), false), Ok(BlendMethod(m)));
        }
        for m in chasles_skin::Method::ALL {
            assert_eq!(SkinMethod::from_str(m.name(), false), Ok(SkinMethod(m)));
        }
        assert!(SkinMethod::from_str("nope", false).is_err());
        for m in InterpMethod::value_variants() {
            assert_eq!(InterpMethod::from_str(m.name(), false), Ok(*m));
        }
    }
}
