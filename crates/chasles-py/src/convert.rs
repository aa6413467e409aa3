//! Conversions between rotation representations, wrapping `chasles::convert` (Dam et al.
//! 1998, App. B): Euler angles in all 24 conventions (`chasles::EulerOrder`, scipy's
//! naming: lower case extrinsic, upper case intrinsic), rotation matrices (Shepperd's
//! method, checked), rotation vectors and axis–angle pairs. Every function is batched over
//! leading dimensions; quaternions are `[w, x, y, z]` (`scalar_first=False`: scipy's
//! `[x, y, z, w]`). Quaternion → Euler angles and matrix → quaternion run the library's
//! batch functions (`quats_to_euler`, `quats_from_rotation_matrices`, in their AVX2 build
//! where the processor has it, see [`crate::simd`]) over each thread's share of the items,
//! and so does quaternion → matrix (`quats_to_rotation_matrices`).

use crate::arrays::{
    array, column, dispatch, finite, lib_error, map, map_runs, part, q_in, q_out, v_in, v_out,
    Fail, Num,
};
use crate::simd::{quats_from_rotation_matrices, quats_to_euler, quats_to_rotation_matrices};
use chasles::convert::BatchError;
use chasles::{EulerOrder, Mat3, Quat};
use numpy::PyUntypedArrayMethods;
use pyo3::prelude::*;

/// Items converted at a time through the library's batch functions (their inputs copied to
/// the stack as the library's types, in scalar-first order).
const BLOCK: usize = 256;

/// A batch function's failure at `index` of block `b` as [`map_runs`] reports it.
fn at_block(b: usize, e: BatchError) -> (usize, Fail) {
    (b * BLOCK + e.index, e.error.into())
}

/// Parses an Euler order by the library's rules (`ValueError` with its message).
pub fn order(s: &str) -> PyResult<EulerOrder> {
    s.parse::<EulerOrder>().map_err(lib_error)
}

/// The unit quaternions of Euler angles (radians) in ``order``.
///
/// ``angles`` is (..., 3): the three angles in the order's axis sequence. ``order`` is
/// three of ``x``, ``y``, ``z`` with no two neighbours equal: lower case for extrinsic
/// (fixed axes: ``"xyz"`` is ``R = Rz(γ) Ry(β) Rx(α)``), upper case for intrinsic
/// (``"XYZ"`` is ``R = Rx(α) Ry(β) Rz(γ)``) — scipy's naming, all 24 conventions.
/// Returns (..., 4) quaternions ``[w, x, y, z]`` (``scalar_first=False``: ``[x, y, z, w]``).
///
/// >>> import chasles, numpy as np
/// >>> q = chasles.quat_from_euler([0.0, 0.0, np.pi / 2], "xyz")
/// >>> np.round(q, 6)
/// array([0.707107, 0.      , 0.      , 0.707107])
#[pyfunction]
#[pyo3(signature = (angles, order, *, scalar_first = true))]
pub fn quat_from_euler<'py>(
    angles: &Bound<'py, PyAny>,
    order: &str,
    scalar_first: bool,
) -> PyResult<Bound<'py, PyAny>> {
    let o = self::order(order)?;
    dispatch!([angles], from_euler(angles, o, scalar_first))
}

fn from_euler<'py, T: Num>(
    a: &Bound<'py, PyAny>,
    o: EulerOrder,
    sf: bool,
) -> PyResult<Bound<'py, PyAny>> {
    let a = array::<T>(a, "angles")?;
    let out = map(a.py(), [("angles", &a, &[3])], &[4], 40, |[a], out| {
        finite(a, "Euler angles")?;
        q_out(Quat::from_euler(o, [a[0], a[1], a[2]]), out, sf);
        Ok(())
    })?;
    Ok(out.into_any())
}

/// Euler angles (radians) of quaternions in ``order`` (see :func:`quat_from_euler`).
///
/// ``q`` is (..., 4), any non-zero scale or sign. Returns (..., 3): first and third angle
/// in [-π, π], the middle one in [-π/2, π/2] (Tait–Bryan) or [0, π] (proper Euler). At
/// gimbal lock the third angle is 0 (Dam et al. App. B.2). Zero or non-finite
/// quaternions raise ``ValueError``.
///
/// >>> import chasles, numpy as np
/// >>> q = chasles.quat_from_euler([0.1, 0.2, 0.3], "ZYX")
/// >>> np.round(chasles.quat_to_euler(q, "ZYX"), 12)
/// array([0.1, 0.2, 0.3])
#[pyfunction]
#[pyo3(signature = (q, order, *, scalar_first = true))]
pub fn quat_to_euler<'py>(
    q: &Bound<'py, PyAny>,
    order: &str,
    scalar_first: bool,
) -> PyResult<Bound<'py, PyAny>> {
    let o = self::order(order)?;
    dispatch!([q], to_euler(q, o, scalar_first))
}

fn to_euler<'py, T: Num>(
    q: &Bound<'py, PyAny>,
    o: EulerOrder,
    sf: bool,
) -> PyResult<Bound<'py, PyAny>> {
    let q = array::<T>(q, "q")?;
    // chasles::convert::euler::quats_to_euler: Quat::to_euler's angles to a few ulp (exactly
    // at gimbal lock), vectorized.
    let out = map_runs(q.py(), [("q", &q, &[4])], &[3], 15, |[q], out| {
        let mut buf = [Quat::<T>::zero(); BLOCK];
        let (q, out) = (q.as_chunks::<4>().0, out.as_chunks_mut::<3>().0);
        for (b, (qs, os)) in q.chunks(BLOCK).zip(out.chunks_mut(BLOCK)).enumerate() {
            for (d, s) in buf.iter_mut().zip(qs) {
                *d = q_in(s, sf);
            }
            quats_to_euler(&buf[..qs.len()], o, os).map_err(|e| at_block(b, e))?;
        }
        Ok(())
    })?;
    Ok(out.into_any())
}

/// Unit quaternions (``w ≥ 0``) of rotation matrices, by Shepperd's method (exact at 180°).
///
/// ``m`` is (..., 3, 3) rotation matrices or (..., 4, 4) homogeneous rotations (no
/// translation), row-major, acting on column vectors. A matrix that is not a rotation
/// (reflection, scale, shear past the library's tolerance) raises ``ValueError``.
///
/// >>> import chasles, numpy as np
/// >>> chasles.quat_from_matrix(np.diag([1.0, -1.0, -1.0]))
/// array([0., 1., 0., 0.])
#[pyfunction]
#[pyo3(signature = (m, *, scalar_first = true))]
pub fn quat_from_matrix<'py>(
    m: &Bound<'py, PyAny>,
    scalar_first: bool,
) -> PyResult<Bound<'py, PyAny>> {
    dispatch!([m], from_matrix(m, scalar_first))
}

fn from_matrix<'py, T: Num>(m: &Bound<'py, PyAny>, sf: bool) -> PyResult<Bound<'py, PyAny>> {
    let m = array::<T>(m, "m")?;
    let four = m.shape().ends_with(&[4, 4]);
    let out = if four {
        map(m.py(), [("m", &m, &[4, 4])], &[4], 40, |[m], out| {
            let m = crate::dualquat::mat4(m)?;
            q_out(Quat::from_matrix4(&m)?, out, sf);
            Ok(())
        })?
    } else {
        // chasles::convert::matrix::quats_from_rotation_matrices: Quat::from_rotation_matrix
        // bit for bit, without branches.
        map_runs(m.py(), [("m", &m, &[3, 3])], &[4], 15, |[m], out| {
            let mut ms = [Mat3::<T>::identity(); BLOCK];
            let mut qs = [Quat::<T>::zero(); BLOCK];
            let (m, out) = (m.as_chunks::<9>().0, out.as_chunks_mut::<4>().0);
            for (b, (mb, ob)) in m.chunks(BLOCK).zip(out.chunks_mut(BLOCK)).enumerate() {
                for (d, s) in ms.iter_mut().zip(mb) {
                    *d = Mat3::from_row_major(*s);
                }
                let (ms, qs) = (&ms[..mb.len()], &mut qs[..mb.len()]);
                quats_from_rotation_matrices(ms, qs).map_err(|e| at_block(b, e))?;
                for (q, o) in qs.iter().zip(ob) {
                    q_out(*q, o, sf);
                }
            }
            Ok(())
        })?
    };
    Ok(out.into_any())
}

/// Rotation matrices (..., 3, 3) of quaternions (any non-zero scale: ``q/|q|`` is used).
///
/// Zero or non-finite quaternions raise ``ValueError``.
///
/// >>> import chasles, numpy as np
/// >>> np.round(chasles.quat_to_matrix([0.0, 0.0, 0.0, 1.0]), 12) + 0.0
/// array([[-1.,  0.,  0.],
///        [ 0., -1.,  0.],
///        [ 0.,  0.,  1.]])
#[pyfunction]
#[pyo3(signature = (q, *, scalar_first = true))]
pub fn quat_to_matrix<'py>(
    q: &Bound<'py, PyAny>,
    scalar_first: bool,
) -> PyResult<Bound<'py, PyAny>> {
    dispatch!([q], to_matrix(q, scalar_first))
}

fn to_matrix<'py, T: Num>(q: &Bound<'py, PyAny>, sf: bool) -> PyResult<Bound<'py, PyAny>> {
    let q = array::<T>(q, "q")?;
    // chasles::convert::matrix::quats_to_rotation_matrices: Quat::to_rotation_matrix bit
    // for bit (normalized first where |q|² is not a normal number), eight in lanes.
    let out = map_runs(q.py(), [("q", &q, &[4])], &[3, 3], 5, |[q], out| {
        let mut buf = [Quat::<T>::zero(); BLOCK];
        let (q, out) = (q.as_chunks::<4>().0, out.as_chunks_mut::<9>().0);
        for (b, (qs, os)) in q.chunks(BLOCK).zip(out.chunks_mut(BLOCK)).enumerate() {
            for (d, s) in buf.iter_mut().zip(qs) {
                *d = q_in(s, sf);
            }
            quats_to_rotation_matrices(&buf[..qs.len()], os).map_err(|e| at_block(b, e))?;
        }
        Ok(())
    })?;
    Ok(out.into_any())
}

/// Unit quaternions of rotation vectors (..., 3): angle ``|r|`` about ``r/|r|``, exact for
/// tiny ``r``. Non-finite vectors raise ``ValueError``.
///
/// >>> import chasles, numpy as np
/// >>> np.round(chasles.quat_from_rotvec([np.pi, 0.0, 0.0]), 12)
/// array([0., 1., 0., 0.])
#[pyfunction]
#[pyo3(signature = (rotvec, *, scalar_first = true))]
pub fn quat_from_rotvec<'py>(
    rotvec: &Bound<'py, PyAny>,
    scalar_first: bool,
) -> PyResult<Bound<'py, PyAny>> {
    dispatch!([rotvec], from_rotvec(rotvec, scalar_first))
}

fn from_rotvec<'py, T: Num>(r: &Bound<'py, PyAny>, sf: bool) -> PyResult<Bound<'py, PyAny>> {
    let r = array::<T>(r, "rotvec")?;
    let out = map(r.py(), [("rotvec", &r, &[3])], &[4], 40, |[r], out| {
        q_out(Quat::from_rotation_vector(v_in(r))?, out, sf);
        Ok(())
    })?;
    Ok(out.into_any())
}

/// Rotation vectors (..., 3) of quaternions: axis times angle, the angle in [0, π] (the
/// shorter way). Zero or non-finite quaternions raise ``ValueError``.
///
/// >>> import chasles
/// >>> chasles.quat_to_rotvec([1.0, 0.0, 0.0, 0.0])
/// array([0., 0., 0.])
#[pyfunction]
#[pyo3(signature = (q, *, scalar_first = true))]
pub fn quat_to_rotvec<'py>(
    q: &Bound<'py, PyAny>,
    scalar_first: bool,
) -> PyResult<Bound<'py, PyAny>> {
    dispatch!([q], to_rotvec(q, scalar_first))
}

fn to_rotvec<'py, T: Num>(q: &Bound<'py, PyAny>, sf: bool) -> PyResult<Bound<'py, PyAny>> {
    let q = array::<T>(q, "q")?;
    let out = map(q.py(), [("q", &q, &[4])], &[3], 40, |[q], out| {
        v_out(q_in(q, sf).to_rotation_vector()?, out);
        Ok(())
    })?;
    Ok(out.into_any())
}

/// Unit quaternions rotating by ``angle`` (radians, counter-clockwise) about ``axis``.
///
/// ``axis`` is (..., 3), normalized here; ``angle`` is (...); they broadcast. A zero or
/// non-finite axis or angle raises ``ValueError``.
///
/// >>> import chasles, numpy as np
/// >>> np.round(chasles.quat_from_axis_angle([0.0, 0.0, 2.0], np.pi), 12)
/// array([0., 0., 0., 1.])
#[pyfunction]
#[pyo3(signature = (axis, angle, *, scalar_first = true))]
pub fn quat_from_axis_angle<'py>(
    axis: &Bound<'py, PyAny>,
    angle: &Bound<'py, PyAny>,
    scalar_first: bool,
) -> PyResult<Bound<'py, PyAny>> {
    dispatch!([axis, angle], from_axis_angle(axis, angle, scalar_first))
}

fn from_axis_angle<'py, T: Num>(
    axis: &Bound<'py, PyAny>,
    angle: &Bound<'py, PyAny>,
    sf: bool,
) -> PyResult<Bound<'py, PyAny>> {
    let a = array::<T>(axis, "axis")?;
    let t = array::<T>(angle, "angle")?;
    let out = map(
        a.py(),
        [("axis", &a, &[3]), ("angle", &t, &[])],
        &[4],
        40,
        |[a, t], out| {
            q_out(Quat::from_axis_angle(v_in(a), t[0])?, out, sf);
            Ok(())
        },
    )?;
    Ok(out.into_any())
}

/// Unit axes (..., 3) and angles (...) in [0, 2π] of quaternions: ``q/|q| = [cos(a/2),
/// sin(a/2) axis]`` — the sign of ``q`` is kept (``-q`` turns the long way). The identity
/// gives the x axis and angle 0. Zero or non-finite quaternions raise ``ValueError``.
///
/// >>> import chasles, numpy as np
/// >>> axis, angle = chasles.quat_to_axis_angle([0.0, 0.0, 1.0, 0.0])
/// >>> axis, round(float(angle), 12)
/// (array([0., 1., 0.]), 3.14159265359)
#[pyfunction]
#[pyo3(signature = (q, *, scalar_first = true))]
pub fn quat_to_axis_angle<'py>(
    q: &Bound<'py, PyAny>,
    scalar_first: bool,
) -> PyResult<(Bound<'py, PyAny>, Bound<'py, PyAny>)> {
    dispatch!([q], to_axis_angle(q, scalar_first))
}

fn to_axis_angle<'py, T: Num>(
    q: &Bound<'py, PyAny>,
    sf: bool,
) -> PyResult<(Bound<'py, PyAny>, Bound<'py, PyAny>)> {
    let q = array::<T>(q, "q")?;
    let out = map(q.py(), [("q", &q, &[4])], &[4], 60, |[q], out| {
        let (axis, angle) = q_in(q, sf).to_axis_angle()?;
        v_out(axis, out);
        out[3] = angle;
        Ok(())
    })?
    .into_any();
    Ok((part(&out, 0, 3)?, column(&out, 3)?))
}
