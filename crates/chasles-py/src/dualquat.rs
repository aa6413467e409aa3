//! Dual quaternions and rigid motions on arrays, wrapping `chasles::DualQuat` and
//! `chasles::Screw` (Kavan et al. 2006, §3, eq. 1–2): rotation + translation ↔ unit dual
//! quaternion ↔ 4×4 matrix, point transforms, products, inverses, powers and screw
//! parameters. A dual quaternion is 8 numbers `[w, x, y, z, wε, xε, yε, zε]` (each half
//! `[x, y, z, w]` with `scalar_first=False`); batched over leading dimensions.

use crate::arrays::{
    array, column, dispatch, dq_in, dq_out, map, part, q_in, q_out, v_in, v_out, Fail, Num,
};
use chasles::{DualQuat, Mat4, Screw};
use pyo3::prelude::*;

/// Unit dual quaternions ``q0 + ε ½ t q0`` (Kavan et al. eq. 1) of rotations ``q``
/// (..., 4, normalized here) followed by translations ``t`` (..., 3); they broadcast.
/// Returns (..., 8). A zero or non-finite ``q`` raises ``ValueError``.
///
/// >>> import chasles
/// >>> chasles.dq_from_rt([1.0, 0.0, 0.0, 0.0], [2.0, 4.0, 6.0])
/// array([1., 0., 0., 0., 0., 1., 2., 3.])
#[pyfunction]
#[pyo3(signature = (q, t, *, scalar_first = true))]
pub fn dq_from_rt<'py>(
    q: &Bound<'py, PyAny>,
    t: &Bound<'py, PyAny>,
    scalar_first: bool,
) -> PyResult<Bound<'py, PyAny>> {
    dispatch!([q, t], from_rt(q, t, scalar_first))
}

fn from_rt<'py, T: Num>(
    q: &Bound<'py, PyAny>,
    t: &Bound<'py, PyAny>,
    sf: bool,
) -> PyResult<Bound<'py, PyAny>> {
    let (q, t) = (array::<T>(q, "q")?, array::<T>(t, "t")?);
    let out = map(
        q.py(),
        [("q", &q, &[4]), ("t", &t, &[3])],
        &[8],
        20,
        |[q, t], out| {
            crate::arrays::finite(t, "translation")?;
            let d = DualQuat::from_rotation_translation(q_in(q, sf).normalize()?, v_in(t));
            dq_out(d, out, sf);
            Ok(())
        },
    )?;
    Ok(out.into_any())
}

/// The rotation ``q`` (..., 4) and translation ``t`` (..., 3) of dual quaternions (..., 8),
/// normalized first (``t = 2 qε q0*``). A zero or non-finite real part raises ``ValueError``.
///
/// >>> import chasles
/// >>> q, t = chasles.dq_to_rt([1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 2.0, 3.0])
/// >>> q, t
/// (array([1., 0., 0., 0.]), array([2., 4., 6.]))
#[pyfunction]
#[pyo3(signature = (dq, *, scalar_first = true))]
pub fn dq_to_rt<'py>(
    dq: &Bound<'py, PyAny>,
    scalar_first: bool,
) -> PyResult<(Bound<'py, PyAny>, Bound<'py, PyAny>)> {
    dispatch!([dq], to_rt(dq, scalar_first))
}

fn to_rt<'py, T: Num>(
    dq: &Bound<'py, PyAny>,
    sf: bool,
) -> PyResult<(Bound<'py, PyAny>, Bound<'py, PyAny>)> {
    let d = array::<T>(dq, "dq")?;
    let out = map(d.py(), [("dq", &d, &[8])], &[7], 20, |[d], out| {
        let d = dq_in(d, sf).normalize()?;
        q_out(d.rotation(), &mut out[..4], sf);
        v_out(d.translation(), &mut out[4..]);
        Ok(())
    })?
    .into_any();
    Ok((part(&out, 0, 4)?, part(&out, 4, 7)?))
}

/// Unit dual quaternions (..., 8) of rigid 4×4 matrices (..., 4, 4), row-major, acting on
/// column vectors. A matrix that is not rigid (last row, reflection, scale) raises
/// ``ValueError``.
///
/// >>> import chasles, numpy as np
/// >>> m = np.eye(4); m[:3, 3] = [2.0, 4.0, 6.0]
/// >>> chasles.dq_from_matrix(m)
/// array([1., 0., 0., 0., 0., 1., 2., 3.])
#[pyfunction]
#[pyo3(signature = (m, *, scalar_first = true))]
pub fn dq_from_matrix<'py>(
    m: &Bound<'py, PyAny>,
    scalar_first: bool,
) -> PyResult<Bound<'py, PyAny>> {
    dispatch!([m], from_matrix(m, scalar_first))
}

/// A 4×4 matrix from 16 row-major numbers.
pub fn mat4<T: Num>(s: &[T]) -> Result<Mat4<T>, Fail> {
    let a: [T; 16] = s
        .try_into()
        .map_err(|_| Fail("a 4x4 matrix needs 16 numbers".into()))?;
    Ok(Mat4::from_row_major(a))
}

fn from_matrix<'py, T: Num>(m: &Bound<'py, PyAny>, sf: bool) -> PyResult<Bound<'py, PyAny>> {
    let m = array::<T>(m, "m")?;
    let out = map(m.py(), [("m", &m, &[4, 4])], &[8], 40, |[m], out| {
        dq_out(DualQuat::from_matrix4(&mat4(m)?)?, out, sf);
        Ok(())
    })?;
    Ok(out.into_any())
}

/// Rigid 4×4 matrices (..., 4, 4) of dual quaternions (..., 8), normalized first. A zero
/// or non-finite real part raises ``ValueError``.
///
/// >>> import chasles
/// >>> chasles.dq_to_matrix([1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 2.0, 3.0])[:3, 3]
/// array([2., 4., 6.])
#[pyfunction]
#[pyo3(signature = (dq, *, scalar_first = true))]
pub fn dq_to_matrix<'py>(
    dq: &Bound<'py, PyAny>,
    scalar_first: bool,
) -> PyResult<Bound<'py, PyAny>> {
    dispatch!([dq], to_matrix(dq, scalar_first))
}

fn to_matrix<'py, T: Num>(dq: &Bound<'py, PyAny>, sf: bool) -> PyResult<Bound<'py, PyAny>> {
    let d = array::<T>(dq, "dq")?;
    let out = map(d.py(), [("dq", &d, &[8])], &[4, 4], 30, |[d], out| {
        out.copy_from_slice(&dq_in(d, sf).normalize()?.to_matrix4().to_row_major());
        Ok(())
    })?;
    Ok(out.into_any())
}

/// Points (..., 3) moved by the rigid motions ``dq`` (..., 8, normalized first): rotation,
/// then translation (the closed form DQS uses). Leading dimensions broadcast. A zero or
/// non-finite real part raises ``ValueError``.
///
/// >>> import chasles
/// >>> dq = chasles.dq_from_rt([0.0, 0.0, 0.0, 1.0], [1.0, 0.0, 0.0])
/// >>> chasles.dq_transform(dq, [1.0, 0.0, 0.0]).round(12)
/// array([0., 0., 0.])
#[pyfunction]
#[pyo3(signature = (dq, points, *, scalar_first = true))]
pub fn dq_transform<'py>(
    dq: &Bound<'py, PyAny>,
    points: &Bound<'py, PyAny>,
    scalar_first: bool,
) -> PyResult<Bound<'py, PyAny>> {
    dispatch!([dq, points], transform(dq, points, scalar_first))
}

fn transform<'py, T: Num>(
    dq: &Bound<'py, PyAny>,
    p: &Bound<'py, PyAny>,
    sf: bool,
) -> PyResult<Bound<'py, PyAny>> {
    let (d, p) = (array::<T>(dq, "dq")?, array::<T>(p, "points")?);
    let out = map(
        d.py(),
        [("dq", &d, &[8]), ("points", &p, &[3])],
        &[3],
        25,
        |[d, p], out| {
            v_out(dq_in(d, sf).normalize()?.transform_point(v_in(p)), out);
            Ok(())
        },
    )?;
    Ok(out.into_any())
}

/// The product ``a b`` of dual quaternions (..., 8): the motion ``b`` first, then ``a``.
///
/// >>> import chasles
/// >>> a = chasles.dq_from_rt([1.0, 0.0, 0.0, 0.0], [1.0, 0.0, 0.0])
/// >>> chasles.dq_to_rt(chasles.dq_mul(a, a))[1]
/// array([2., 0., 0.])
#[pyfunction]
#[pyo3(signature = (a, b, *, scalar_first = true))]
pub fn dq_mul<'py>(
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
        [("a", &a, &[8]), ("b", &b, &[8])],
        &[8],
        20,
        |[a, b], out| {
            dq_out(dq_in(a, sf) * dq_in(b, sf), out, sf);
            Ok(())
        },
    )?;
    Ok(out.into_any())
}

/// Dual quaternion → dual quaternion, item by item.
fn unary<'py, T: Num>(
    dq: &Bound<'py, PyAny>,
    sf: bool,
    f: impl Fn(DualQuat<T>) -> Result<DualQuat<T>, Fail> + Sync,
) -> PyResult<Bound<'py, PyAny>> {
    let d = array::<T>(dq, "dq")?;
    let out = map(d.py(), [("dq", &d, &[8])], &[8], 40, |[d], out| {
        dq_out(f(dq_in(d, sf))?, out, sf);
        Ok(())
    })?;
    Ok(out.into_any())
}

/// The inverse ``q̂* / |q̂|²`` of dual quaternions (..., 8) (Kavan et al. §3). A zero or
/// non-finite real part raises ``ValueError``.
///
/// >>> import chasles
/// >>> d = chasles.dq_from_rt([0.0, 0.0, 0.0, 1.0], [1.0, 2.0, 3.0])
/// >>> chasles.dq_mul(d, chasles.dq_inv(d)).round(12) + 0.0
/// array([1., 0., 0., 0., 0., 0., 0., 0.])
#[pyfunction]
#[pyo3(signature = (dq, *, scalar_first = true))]
pub fn dq_inv<'py>(dq: &Bound<'py, PyAny>, scalar_first: bool) -> PyResult<Bound<'py, PyAny>> {
    dispatch!([dq], inv(dq, scalar_first))
}

fn inv<'py, T: Num>(dq: &Bound<'py, PyAny>, sf: bool) -> PyResult<Bound<'py, PyAny>> {
    unary::<T>(dq, sf, |d| Ok(d.inverse()?))
}

/// The nearest unit dual quaternions (real part to unit length, dual part made orthogonal
/// to it). A zero or non-finite real part raises ``ValueError``.
///
/// >>> import chasles
/// >>> chasles.dq_normalize([2.0, 0.0, 0.0, 0.0, 0.0, 2.0, 0.0, 0.0])
/// array([1., 0., 0., 0., 0., 1., 0., 0.])
#[pyfunction]
#[pyo3(signature = (dq, *, scalar_first = true))]
pub fn dq_normalize<'py>(
    dq: &Bound<'py, PyAny>,
    scalar_first: bool,
) -> PyResult<Bound<'py, PyAny>> {
    dispatch!([dq], normalize(dq, scalar_first))
}

fn normalize<'py, T: Num>(dq: &Bound<'py, PyAny>, sf: bool) -> PyResult<Bound<'py, PyAny>> {
    unary::<T>(dq, sf, |d| Ok(d.normalize()?))
}

/// Real powers ``q̂^t = exp(t log q̂)`` of dual quaternions (..., 8): the screw motion with
/// angle and slide times ``t`` about the same axis. ``t`` is (...); they broadcast. A zero
/// or non-finite real part raises ``ValueError``.
///
/// >>> import chasles
/// >>> d = chasles.dq_from_rt([1.0, 0.0, 0.0, 0.0], [2.0, 0.0, 0.0])
/// >>> chasles.dq_to_rt(chasles.dq_pow(d, 0.5))[1]
/// array([1., 0., 0.])
#[pyfunction]
#[pyo3(signature = (dq, t, *, scalar_first = true))]
pub fn dq_pow<'py>(
    dq: &Bound<'py, PyAny>,
    t: &Bound<'py, PyAny>,
    scalar_first: bool,
) -> PyResult<Bound<'py, PyAny>> {
    dispatch!([dq, t], pow(dq, t, scalar_first))
}

fn pow<'py, T: Num>(
    dq: &Bound<'py, PyAny>,
    t: &Bound<'py, PyAny>,
    sf: bool,
) -> PyResult<Bound<'py, PyAny>> {
    let (d, t) = (array::<T>(dq, "dq")?, array::<T>(t, "t")?);
    let out = map(
        d.py(),
        [("dq", &d, &[8]), ("t", &t, &[])],
        &[8],
        150,
        |[d, t], out| {
            dq_out(dq_in(d, sf).powf(t[0])?, out, sf);
            Ok(())
        },
    )?;
    Ok(out.into_any())
}

/// Screw parameters of rigid motions (Chasles' theorem; Kavan et al. Figure 2): returns
/// ``(axis, point, angle, translation)`` — the unit axis (..., 3), the point of the axis
/// nearest the origin (..., 3), the turn (...) in [0, 2π] for the sign given and the slide
/// along the axis (...). A pure translation has its direction as axis; the identity the
/// x axis. A zero or non-finite input raises ``ValueError``.
///
/// >>> import chasles, numpy as np
/// >>> d = chasles.dq_from_rt(chasles.quat_from_axis_angle([0.0, 0.0, 1.0], np.pi), [0.0, 0.0, 1.0])
/// >>> axis, point, angle, slide = chasles.screw(d)
/// >>> axis.round(12) + 0.0, round(float(angle), 12), round(float(slide), 12)
/// (array([0., 0., 1.]), 3.14159265359, 1.0)
#[pyfunction]
#[pyo3(signature = (dq, *, scalar_first = true))]
pub fn screw<'py>(dq: &Bound<'py, PyAny>, scalar_first: bool) -> PyResult<Bound<'py, PyTuple>> {
    dispatch!([dq], screw_t(dq, scalar_first))
}

use pyo3::types::PyTuple;

fn screw_t<'py, T: Num>(dq: &Bound<'py, PyAny>, sf: bool) -> PyResult<Bound<'py, PyTuple>> {
    let d = array::<T>(dq, "dq")?;
    let py = d.py();
    let out = map(py, [("dq", &d, &[8])], &[8], 120, |[d], out| {
        let s = dq_in(d, sf).to_screw()?;
        v_out(s.axis, &mut out[..3]);
        v_out(s.point(), &mut out[3..6]);
        out[6] = s.angle;
        out[7] = s.translation;
        Ok(())
    })?
    .into_any();
    PyTuple::new(
        py,
        [
            part(&out, 0, 3)?,
            part(&out, 3, 6)?,
            column(&out, 6)?,
            column(&out, 7)?,
        ],
    )
}

/// Unit dual quaternions ``cos(θ̂/2) + ŝ sin(θ̂/2)`` (Kavan et al. eq. 2) of screws: an
/// ``axis`` direction (..., 3, normalized here), a ``point`` on it (..., 3), the turn
/// ``angle`` (...) and the ``translation`` along the axis (...); they broadcast. A zero or
/// non-finite axis raises ``ValueError``.
///
/// >>> import chasles, numpy as np
/// >>> d = chasles.dq_from_screw([0.0, 0.0, 1.0], [0.0, 0.0, 0.0], 0.0, 2.0)
/// >>> chasles.dq_to_rt(d)[1]
/// array([0., 0., 2.])
#[pyfunction]
#[pyo3(signature = (axis, point, angle, translation, *, scalar_first = true))]
pub fn dq_from_screw<'py>(
    axis: &Bound<'py, PyAny>,
    point: &Bound<'py, PyAny>,
    angle: &Bound<'py, PyAny>,
    translation: &Bound<'py, PyAny>,
    scalar_first: bool,
) -> PyResult<Bound<'py, PyAny>> {
    dispatch!(
        [axis, point, angle, translation],
        from_screw(axis, point, angle, translation, scalar_first)
    )
}

fn from_screw<'py, T: Num>(
    axis: &Bound<'py, PyAny>,
    point: &Bound<'py, PyAny>,
    angle: &Bound<'py, PyAny>,
    translation: &Bound<'py, PyAny>,
    sf: bool,
) -> PyResult<Bound<'py, PyAny>> {
    let a = array::<T>(axis, "axis")?;
    let p = array::<T>(point, "point")?;
    let g = array::<T>(angle, "angle")?;
    let t = array::<T>(translation, "translation")?;
    let out = map(
        a.py(),
        [
            ("axis", &a, &[3]),
            ("point", &p, &[3]),
            ("angle", &g, &[]),
            ("translation", &t, &[]),
        ],
        &[8],
        120,
        |[a, p, g, t], out| {
            let s = Screw::from_point(v_in(a), v_in(p), g[0], t[0])?;
            dq_out(DualQuat::from_screw(&s)?, out, sf);
            Ok(())
        },
    )?;
    Ok(out.into_any())
}
