//! Counting floating-point operations exactly (for the FLOPS row of Kavan et al. 2006,
//! Table 1, §5): [`Flop`] is an `f64` that implements [`Real`] and counts every operation it
//! takes part in, per thread. Run any generic routine with `T = Flop` inside [`count`].
//!
//! Counted: `+ − × ÷` (one each), and the special functions `sqrt, sin, cos, asin, acos,
//! atan2, exp, ln` (one each; `sin_cos` is two). Not counted: negation, `abs`,
//! comparisons, `max`/`min` and conversions — sign flips and selections, not arithmetic.

use chasles::Real;
use core::cell::Cell;
use core::fmt;
use core::ops::{Add, AddAssign, Div, DivAssign, Mul, MulAssign, Neg, Sub, SubAssign};

/// Operation counts by kind.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Counts {
    /// Additions and subtractions.
    pub add: u64,
    /// Multiplications.
    pub mul: u64,
    /// Divisions.
    pub div: u64,
    /// Square roots and transcendental functions.
    pub special: u64,
}

impl Counts {
    /// All of them.
    pub fn total(&self) -> u64 {
        self.add + self.mul + self.div + self.special
    }
}

thread_local! {
    static COUNTS: Cell<Counts> = const { Cell::new(Counts { add: 0, mul: 0, div: 0, special: 0 }) };
}

fn bump(f: impl FnOnce(&mut Counts)) {
    COUNTS.with(|c| {
        let mut v = c.get();
        f(&mut v);
        c.set(v);
    });
}

/// Runs `f` and returns its result with the operations [`Flop`] counted meanwhile.
pub fn count<R>(f: impl FnOnce() -> R) -> (R, Counts) {
    let before = COUNTS.with(|c| c.replace(Counts::default()));
    let r = f();
    let counted = COUNTS.with(|c| c.replace(before));
    (r, counted)
}

/// An `f64` that counts its arithmetic (see the module docs).
#[derive(Debug, Clone, Copy, PartialEq, PartialOrd, Default)]
pub struct Flop(pub f64);

impl fmt::Display for Flop {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        fmt::Display::fmt(&self.0, f)
    }
}

macro_rules! binop {
    ($tr:ident, $m:ident, $atr:ident, $am:ident, $op:tt, $field:ident) => {
        impl $tr for Flop {
            type Output = Flop;
            #[inline]
            #[allow(clippy::suspicious_arithmetic_impl)] // counting, then the real operation
            fn $m(self, o: Flop) -> Flop {
                bump(|c| c.$field += 1);
                Flop(self.0 $op o.0)
            }
        }
        impl $atr for Flop {
            #[inline]
            fn $am(&mut self, o: Flop) {
                *self = *self $op o;
            }
        }
    };
}
binop!(Add, add, AddAssign, add_assign, +, add);
binop!(Sub, sub, SubAssign, sub_assign, -, add);
binop!(Mul, mul, MulAssign, mul_assign, *, mul);
binop!(Div, div, DivAssign, div_assign, /, div);

impl Neg for Flop {
    type Output = Flop;
    #[inline]
    fn neg(self) -> Flop {
        Flop(-self.0)
    }
}

fn special(v: f64) -> Flop {
    bump(|c| c.special += 1);
    Flop(v)
}

impl Real for Flop {
    const ZERO: Self = Flop(0.0);
    const ONE: Self = Flop(1.0);
    const TWO: Self = Flop(2.0);
    const HALF: Self = Flop(0.5);
    const PI: Self = Flop(core::f64::consts::PI);
    const EPSILON: Self = Flop(f64::EPSILON);
    const MIN_POSITIVE: Self = Flop(f64::MIN_POSITIVE);
    fn from_f64(v: f64) -> Self {
        Flop(v)
    }
    fn to_f64(self) -> f64 {
        self.0
    }
    fn sqrt(self) -> Self {
        special(self.0.sqrt())
    }
    fn sin(self) -> Self {
        special(self.0.sin())
    }
    fn cos(self) -> Self {
        special(self.0.cos())
    }
    fn asin(self) -> Self {
        special(self.0.asin())
    }
    fn acos(self) -> Self {
        special(self.0.acos())
    }
    fn atan2(self, x: Self) -> Self {
        special(self.0.atan2(x.0))
    }
    fn exp(self) -> Self {
        special(self.0.exp())
    }
    fn ln(self) -> Self {
        special(self.0.ln())
    }
    fn abs(self) -> Self {
        Flop(self.0.abs())
    }
    fn is_finite(self) -> bool {
        self.0.is_finite()
    }
    fn max(self, o: Self) -> Self {
        Flop(self.0.max(o.0))
    }
    fn min(self, o: Self) -> Self {
        Flop(self.0.min(o.0))
    }
}
