//! Quaternion algebra on arrays, wrapping `chasles::Quat` (Dam et al. 1998, §3.3): the
//! Hamilton product, conjugate, inverse, normalization, `exp`/`log` of any quaternion,
//! real powers, rotation of vectors and the angle between rotations. Batched over leading
//! dimensions (which broadcast); `[w, x, y, z]`, or scipy's `[x, y, z, w]` with
//! `scalar_first=False`.

use crate::arrays::{array, dispatch, map, q_in, q_out, v_in, v_out, Fail, Num};
use chasles::Quat;
use pyo3::prelude::*;

/// The rotation matrix of a non-zero, finite quaternion (`to_rotation_matrix` treats a
/// non-unit q as `q/|q|`, with one division and no square root); the library's error for
/// a zero or non-finite one (and the normalized route where `|q|²` overflows or is
/// subnormal, as `chasles::convert::matrix::quats_to_rotation_matrices` does).
#[inline(always)]
pub fn unit_matrix<T: Num>(q: Quat<T>) -> Result<chasles::Mat3<T>, Fail> {
    let n2 = q.norm_squared();
    if n2.is_finite() && n2 >= T::MIN_POSITIVE {
        Ok(q.to_rotation_matrix())
    } else {
        Ok(q.normalize()?.to_rotation_matrix())
    }
}

/// Quaternion → quaternion, item by item.
fn unary<'py, T: Num>(
    q: &Bound<'py, PyAny>,
    sf: bool,
    work: usize,
    f: impl Fn(Quat<T>) -> Result<Quat<T>, Fail> + Sync,
) -> PyResult<Bound<'py, PyAny>> {
    let q = array::<T>(q, "q")?;
    let out = map(q.py(), [("q", &q, &[4])], &[4], work, |[q], out| {
        q_out(f(q_in(q, sf))?, out, sf);
        Ok(())
    })?;
    Ok(out.into_any())
}

/// The Hamilton product ``a b`` of (..., 4) quaternions (Dam et al. App. B.3); the
/// leading dimensions broadcast. ``a b`` rotates by ``b`` first, then by ``a``.
///
/// >>> import chasles
/// >>> chasles.quat_mul([0.0, 1.0, 0.0, 0.0], [0.0, 0.0, 1.0, 0.0])
/// array([0., 0., 0., 1.])
#[pyfunction]
#[pyo3(signature = (a, b, *, scalar_first = true))]
pub fn quat_mul<'py>(
    a: &Bound<'py, PyAny>,
    b: &Bound<'py, PyAny>,
    scalar_first: bool,
) -> PyResult<Bound<'py, PyAny>> {
    dispatch!([a, b], mul(a, b, scalar_first))
}

fn mul<'py, T: Num>(
    a: &Bound<'py, PyAny>,
    b: &Bound<'py, PyAny>,
    sf: bool,
) -> PyResult<Bound<'py, PyAny>> {
    let (a, b) = (array::<T>(a, "a")?, array::<T>(b, "b")?);
    let out = map(
        a.py(),
        [("a", &a, &[4]), ("b", &b, &[4])],
        &[4],
        10,
        |[a, b], out| {
            q_out(q_in(a, sf) * q_in(b, sf), out, sf);
            Ok(())
        },
    )?;
    Ok(out.into_any())
}

/// The conjugate ``[w, -x, -y, -z]`` of (..., 4) quaternions.
///
/// >>> import chasles
/// >>> chasles.quat_conj([1.0, 2.0, 3.0, 4.0])
/// array([ 1., -2., -3., -4.])
#[pyfunction]
#[pyo3(signature = (q, *, scalar_first = true))]
pub fn quat_conj<'py>(q: &Bound<'py, PyAny>, scalar_first: bool) -> PyResult<Bound<'py, PyAny>> {
    dispatch!([q], conj(q, scalar_first))
}

fn conj<'py, T: Num>(q: &Bound<'py, PyAny>, sf: bool) -> PyResult<Bound<'py, PyAny>> {
    unary::<T>(q, sf, 5, |q| Ok(q.conjugate()))
}

/// The inverse ``q* / |q|²`` of (..., 4) quaternions. Zero or non-finite quaternions raise
/// ``ValueError``.
///
/// >>> import chasles
/// >>> chasles.quat_inv([0.0, 0.0, 2.0, 0.0])
/// array([ 0. , -0. , -0.5, -0. ])
#[pyfunction]
#[pyo3(signature = (q, *, scalar_first = true))]
pub fn quat_inv<'py>(q: &Bound<'py, PyAny>, scalar_first: bool) -> PyResult<Bound<'py, PyAny>> {
    dispatch!([q], inv(q, scalar_first))
}

fn inv<'py, T: Num>(q: &Bound<'py, PyAny>, sf: bool) -> PyResult<Bound<'py, PyAny>> {
    unary::<T>(q, sf, 10, |q| Ok(q.inverse()?))
}

/// ``q / |q|`` for (..., 4) quaternions (no overflow for huge components). Zero or
/// non-finite quaternions raise ``ValueError``.
///
/// >>> import chasles
/// >>> chasles.quat_normalize([0.0, 3.0, 0.0, 4.0])
/// array([0. , 0.6, 0. , 0.8])
#[pyfunction]
#[pyo3(signature = (q, *, scalar_first = true))]
pub fn quat_normalize<'py>(
    q: &Bound<'py, PyAny>,
    scalar_first: bool,
) -> PyResult<Bound<'py, PyAny>> {
    dispatch!([q], normalize(q, scalar_first))
}

fn normalize<'py, T: Num>(q: &Bound<'py, PyAny>, sf: bool) -> PyResult<Bound<'py, PyAny>> {
    unary::<T>(q, sf, 10, |q| Ok(q.normalize()?))
}

/// The logarithm ``[ln|q|, atan2(|v|, w) v/|v|]`` of any non-zero quaternion (Dam et al.
/// Def. 14, extended): for a unit ``q = [cos θ, sin θ n]`` it is ``[0, θ n]``, θ the
/// *half* angle. Exact near the identity. Zero or non-finite input raises ``ValueError``.
///
/// >>> import chasles, numpy as np
/// >>> np.round(chasles.quat_log([0.0, 0.0, 0.0, 1.0]), 6)
/// array([0.      , 0.      , 0.      , 1.570796])
#[pyfunction]
#[pyo3(signature = (q, *, scalar_first = true))]
pub fn quat_log<'py>(q: &Bound<'py, PyAny>, scalar_first: bool) -> PyResult<Bound<'py, PyAny>> {
    dispatch!([q], log(q, scalar_first))
}

fn log<'py, T: Num>(q: &Bound<'py, PyAny>, sf: bool) -> PyResult<Bound<'py, PyAny>> {
    unary::<T>(q, sf, 40, |q| Ok(q.log()?))
}

/// The exponential ``e^w [cos|v|, sin|v| v/|v|]`` of any quaternion (Dam et al. Def. 15,
/// extended); ``quat_exp(quat_log(q)) == q``. Exact at ``v = 0``.
///
/// >>> import chasles, numpy as np
/// >>> np.round(chasles.quat_exp([0.0, 0.0, 0.0, np.pi / 2]), 12)
/// array([0., 0., 0., 1.])
#[pyfunction]
#[pyo3(signature = (q, *, scalar_first = true))]
pub fn quat_exp<'py>(q: &Bound<'py, PyAny>, scalar_first: bool) -> PyResult<Bound<'py, PyAny>> {
    dispatch!([q], exp(q, scalar_first))
}

fn exp<'py, T: Num>(q: &Bound<'py, PyAny>, sf: bool) -> PyResult<Bound<'py, PyAny>> {
    unary::<T>(q, sf, 40, |q| Ok(q.exp()))
}

/// Real powers ``q^t = exp(t log q)`` (Dam et al. Def. 16): for a unit ``q``, the rotation
/// ``t`` times as far about the same axis (``q`` and ``-q`` give the two arcs). ``q`` is
/// (..., 4), ``t`` is (...); they broadcast. Zero or non-finite ``q`` raises ``ValueError``.
///
/// >>> import chasles, numpy as np
/// >>> np.round(chasles.quat_pow([0.0, 0.0, 0.0, 1.0], 0.5), 6)
/// array([0.707107, 0.      , 0.      , 0.707107])
#[pyfunction]
#[pyo3(signature = (q, t, *, scalar_first = true))]
pub fn quat_pow<'py>(
    q: &Bound<'py, PyAny>,
    t: &Bound<'py, PyAny>,
    scalar_first: bool,
) -> PyResult<Bound<'py, PyAny>> {
    dispatch!([q, t], pow(q, t, scalar_first))
}

fn pow<'py, T: Num>(
    q: &Bound<'py, PyAny>,
    t: &Bound<'py, PyAny>,
    sf: bool,
) -> PyResult<Bound<'py, PyAny>> {
    let (q, t) = (array::<T>(q, "q")?, array::<T>(t, "t")?);
    let out = map(
        q.py(),
        [("q", &q, &[4]), ("t", &t, &[])],
        &[4],
        80,
        |[q, t], out| {
            q_out(q_in(q, sf).powf(t[0])?, out, sf);
            Ok(())
        },
    )?;
    Ok(out.into_any())
}

/// Vectors ``v`` (..., 3) rotated by quaternions ``q`` (..., 4): ``q v q⁻¹`` (Dam et al.
/// Prop. 18/21; the scale of ``q`` does not matter), by ``q``'s rotation matrix. Leading dimensions broadcast. Zero or
/// non-finite ``q`` raises ``ValueError``.
///
/// >>> import chasles, numpy as np
/// >>> q = chasles.quat_from_axis_angle([0.0, 0.0, 1.0], np.pi / 2)
/// >>> np.round(chasles.rotate(q, [1.0, 0.0, 0.0]), 12)
/// array([0., 1., 0.])
#[pyfunction]
#[pyo3(signature = (q, v, *, scalar_first = true))]
pub fn rotate<'py>(
    q: &Bound<'py, PyAny>,
    v: &Bound<'py, PyAny>,
    scalar_first: bool,
) -> PyResult<Bound<'py, PyAny>> {
    dispatch!([q, v], rotate_t(q, v, scalar_first))
}

fn rotate_t<'py, T: Num>(
    q: &Bound<'py, PyAny>,
    v: &Bound<'py, PyAny>,
    sf: bool,
) -> PyResult<Bound<'py, PyAny>> {
    let (q, v) = (array::<T>(q, "q")?, array::<T>(v, "v")?);
    let out = map(
        q.py(),
        [("q", &q, &[4]), ("v", &v, &[3])],
        &[3],
        20,
        |[q, v], out| {
            v_out(unit_matrix(q_in(q, sf))?.mul_vec(v_in(v)), out);
            Ok(())
        },
    )?;
    Ok(out.into_any())
}

/// The angle in [0, π] of the rotation taking ``a`` to ``b`` (``q`` and ``-q`` are the
/// same rotation), accurate also for nearly equal rotations. (..., 4) each, broadcast;
/// returns (...). Zero or non-finite input raises ``ValueError``.
///
/// >>> import chasles, numpy as np
/// >>> b = chasles.quat_from_axis_angle([1.0, 0.0, 0.0], 0.25)
/// >>> round(float(chasles.quat_angle([1.0, 0.0, 0.0, 0.0], b)), 12)
/// 0.25
#[pyfunction]
#[pyo3(signature = (a, b, *, scalar_first = true))]
pub fn quat_angle<'py>(
    a: &Bound<'py, PyAny>,
    b: &Bound<'py, PyAny>,
    scalar_first: bool,
) -> PyResult<Bound<'py, PyAny>> {
    dispatch!([a, b], angle(a, b, scalar_first))
}

fn angle<'py, T: Num>(
    a: &Bound<'py, PyAny>,
    b: &Bound<'py, PyAny>,
    sf: bool,
) -> PyResult<Bound<'py, PyAny>> {
    let (a, b) = (array::<T>(a, "a")?, array::<T>(b, "b")?);
    let out = map(
        a.py(),
        [("a", &a, &[4]), ("b", &b, &[4])],
        &[],
        60,
        |[a, b], out| {
            out[0] = q_in(a, sf).angle_to(q_in(b, sf))?;
            Ok(())
        },
    )?;
    // A 0-d result comes back as a numpy scalar, as numpy's own reductions do.
    let py = out.py();
    out.into_any().get_item(pyo3::types::PyTuple::empty(py))
}
