//! Dual numbers (Kavan et al. 2006, §3): arithmetic, inverse, sqrt and the dual functions,
//! whose dual part must be the derivative (checked against central differences).

mod common;
use chasles::{Dual, Error, Real};
use common::*;
use proptest::prelude::*;

fn d<T: Real>(a: f64, b: f64) -> Dual<T> {
    Dual::new(T::from_f64(a), T::from_f64(b))
}

fn field_laws<T: Tol>((a, b, c, e): (f64, f64, f64, f64), tol: f64) -> Result<(), TestCaseError> {
    let x = d::<T>(a, b);
    let y = d::<T>(c, e);
    // (a0 + εaε)(b0 + εbε) = a0b0 + ε(a0bε + aεb0)
    let p = x * y;
    close(
        &[p.re, p.du],
        &[x.re * y.re, x.re * y.du + x.du * y.re],
        tol,
    )?;
    let one = x * x.inverse().unwrap();
    close(&[one.re, one.du], &[T::ONE, T::ZERO], tol)?;
    let q = (x * y).checked_div(x).unwrap();
    close(&[q.re, q.du], &[y.re, y.du], tol * 10.0)?;
    let cj = x.conjugate();
    close(&[cj.re, cj.du], &[x.re, -x.du], 0.0)
}
both_precisions!(
    dual_number_arithmetic,
    field_laws,
    prop_oneof![-3.0f64..-0.1, 0.1f64..3.0],
    -3.0f64..3.0,
    -3.0f64..3.0,
    -3.0f64..3.0
);

fn sqrt_squares<T: Tol>((a, b): (f64, f64), tol: f64) -> Result<(), TestCaseError> {
    let x = d::<T>(a, b);
    let r = x.sqrt().unwrap();
    let sq = r * r;
    close(&[sq.re, sq.du], &[x.re, x.du], tol)?;
    // √(a0 + εaε) = √a0 + ε aε/(2√a0)
    close(&[r.du], &[x.du / (T::TWO * x.re.sqrt())], tol)
}
both_precisions!(
    dual_sqrt_squares_back,
    sqrt_squares,
    0.01f64..10.0,
    -5.0f64..5.0
);

fn functions_differentiate<T: Tol>((a, b): (f64, f64), tol: f64) -> Result<(), TestCaseError> {
    // The dual part is b·f'(a): compare with a central difference in f64.
    let h = 1e-6;
    let fd = |f: fn(f64) -> f64| b * (f(a + h) - f(a - h)) / (2.0 * h);
    let x = d::<T>(a, b);
    let loose = tol.max(1e-8); // the finite difference itself is only good to ~1e-9
    close(&[x.sin().du], &[T::from_f64(fd(f64::sin))], loose)?;
    close(&[x.cos().du], &[T::from_f64(fd(f64::cos))], loose)?;
    close(&[x.exp().du], &[T::from_f64(fd(f64::exp))], loose)?;
    close(&[x.ln().unwrap().du], &[T::from_f64(fd(f64::ln))], loose)?;
    let (s, c) = x.sin_cos();
    let one = s * s + c * c;
    close(&[one.re, one.du], &[T::ONE, T::ZERO], tol * 4.0)
}
both_precisions!(
    dual_functions_carry_the_derivative,
    functions_differentiate,
    0.1f64..3.0,
    -2.0f64..2.0
);

#[test]
fn purely_dual_and_non_positive_get_typed_errors() {
    let pure = Dual::<f64>::new(0.0, 2.0);
    assert_eq!(pure.inverse(), Err(Error::PurelyDual { re: 0.0, du: 2.0 }));
    assert!(pure
        .inverse()
        .unwrap_err()
        .to_string()
        .contains("purely dual"));
    assert!(matches!(
        Dual::<f64>::new(1.0, 1.0).checked_div(pure),
        Err(Error::PurelyDual { .. })
    ));
    assert!(matches!(
        Dual::<f64>::new(0.0, 1.0).sqrt(),
        Err(Error::NonPositiveSqrt { .. })
    ));
    assert!(matches!(
        Dual::<f32>::new(-1.0, 1.0).sqrt(),
        Err(Error::NonPositiveSqrt { .. })
    ));
    assert!(matches!(
        Dual::<f64>::new(f64::NAN, 1.0).sqrt(),
        Err(Error::NonFinite { .. })
    ));
    assert!(matches!(
        Dual::<f64>::new(-1.0, 0.0).ln(),
        Err(Error::NonPositiveLog { .. })
    ));
    assert!(matches!(
        Dual::<f64>::new(1.0, f64::INFINITY).inverse(),
        Err(Error::NonFinite { .. })
    ));
    // 1/(2 + 3ε) = 1/2 − ε 3/4
    assert_eq!(
        Dual::<f64>::new(2.0, 3.0).inverse(),
        Ok(Dual::new(0.5, -0.75))
    );
    // √(4 + 2ε) = 2 + ε/2
    assert_eq!(Dual::<f64>::new(4.0, 2.0).sqrt(), Ok(Dual::new(2.0, 0.5)));
}
