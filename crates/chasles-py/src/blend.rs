//! Blending rigid transformations, wrapping `chasles::blend` (Kavan et al. 2006, §2–5):
//! every method of `chasles blend` by the same names (`lin`, `dec`, `log`, `log-iter`,
//! `qlb`, `sclerp`, `dlb`, `dib`) with its options (`center`, `precision`,
//! `max_iterations`), on dual quaternions (..., n, 8) or rigid matrices (..., n, 4, 4)
//! with weights (..., n) — one blend per item of the leading dimensions, on all cores —
//! and ScLERP between pairs.

use crate::arrays::{
    array, dispatch, dq_in, dq_out, finite, map, map_runs, value_error, Fail, Num,
};
use crate::dualquat::mat4;
use chasles::blend::{blend_dual_quats, blend_matrices, dlb, Method, Options};
use chasles::{DualQuat, Mat4, Real, Vec3};
use numpy::{PyArrayDyn, PyUntypedArrayMethods};
use pyo3::prelude::*;
use pyo3::types::PyTuple;

/// The method of a `chasles blend` name.
fn method(name: &str) -> PyResult<Method> {
    Method::from_name(name).ok_or_else(|| {
        let all: Vec<&str> = Method::ALL.iter().map(|m| m.name()).collect();
        value_error(format!("unknown method '{name}': {}", all.join(", ")))
    })
}

/// DLB of `q` with weights `w`, exactly as `chasles::blend::dlb::dlb` (the weights scaled
/// by their sum, summed in the same order) but without its allocation when the weights are
/// good; bad weights get the library's own error from `weights::convex_weights`.
fn dlb_item<T: Real>(q: &[DualQuat<T>], w: &[T]) -> Result<DualQuat<T>, Fail> {
    const N: usize = 16;
    let mut sum = T::ZERO;
    let good = w.len() == q.len() && w.len() <= N && {
        let mut ok = true;
        for v in w {
            ok &= v.is_finite() && *v >= T::ZERO;
            sum += *v;
        }
        ok && sum > T::ZERO && sum.is_finite()
    };
    if !good {
        return Ok(dlb::dlb(q, w)?);
    }
    let mut c = [T::ZERO; N];
    for (c, v) in c.iter_mut().zip(w) {
        *c = *v / sum;
    }
    Ok(dlb::dlb_convex(q, &c[..w.len()])?)
}

/// DLB of the (at most N) dual quaternions in `x` (8 numbers each), held on the stack.
#[inline(always)]
fn dlb_on<T: Num, const N: usize>(x: &[T], w: &[T], sf: bool) -> Result<DualQuat<T>, Fail> {
    let mut buf = [DualQuat::new(chasles::Quat::zero(), chasles::Quat::zero()); N];
    let n = x.len() / 8;
    for (b, s) in buf.iter_mut().zip(x.chunks_exact(8)) {
        *b = dq_in(s, sf);
    }
    dlb_item(&buf[..n], w)
}

/// Items blended at a time by [`dlb_run`] when their numbers are reordered first.
const BLOCK: usize = 128;

/// DLB of a run of blends of N dual quaternions each (`x`: 8 N numbers a blend, `w`: N),
/// into `out` (8 numbers a blend, and with `full` the rigid flag and -1): through
/// `chasles::blend::dlb::dlb_batch` (in its AVX2 build where the processor has it), which
/// gives `dlb`'s results bit for bit. Scalar-first input and plain output are read and
/// written where they are; otherwise blocks are reordered through the stack. The first
/// failure — the library's, or a blend that is not finite — with its offset.
fn dlb_run<T: Num, const N: usize>(
    x: &[T],
    w: &[T],
    out: &mut [T],
    sf: bool,
    full: bool,
) -> Result<(), (usize, Fail)> {
    let x = x.as_chunks::<8>().0.as_chunks::<N>().0;
    let w = w.as_chunks::<N>().0;
    if sf && !full {
        let out = out.as_chunks_mut::<8>().0;
        let failed = crate::simd::dlb_batch(x, w, out).err();
        return checked(out, failed, 0);
    }
    let width = if full { 10 } else { 8 };
    let mut qs = [[[T::ZERO; 8]; N]; BLOCK];
    let mut ds = [[T::ZERO; 8]; BLOCK];
    for (b, (xs, ws)) in x.chunks(BLOCK).zip(w.chunks(BLOCK)).enumerate() {
        for (q, s) in qs.iter_mut().zip(xs) {
            for (d, s) in q.iter_mut().zip(s) {
                *d = dq_in(s, sf).to_array();
            }
        }
        let (qs, ds) = (&qs[..xs.len()], &mut ds[..xs.len()]);
        let failed = crate::simd::dlb_batch(qs, ws, ds).err();
        let os = out[b * BLOCK * width..].chunks_exact_mut(width);
        for (d, o) in ds.iter().zip(os) {
            dq_out(DualQuat::from_array(*d), &mut o[..8], sf);
            if full {
                o[8] = T::ONE;
                o[9] = -T::ONE;
            }
        }
        checked(ds, failed, b * BLOCK)?;
    }
    Ok(())
}

/// The first failure of a DLB batch written to `out` (`failed`: the library's, which stopped
/// it), or of a blend in `out` before it that is not finite, offset by `start`.
fn checked<T: Num>(
    out: &[[T; 8]],
    failed: Option<chasles::convert::BatchError>,
    start: usize,
) -> Result<(), (usize, Fail)> {
    let written = &out[..failed.as_ref().map_or(out.len(), |e| e.index)];
    // One pass without branches (0·x is 0 for finite x, NaN otherwise; one running sum per
    // number, so the loop vectorizes); the search only when something is not finite.
    let mut acc = [T::ZERO; 8];
    for d in written {
        for (a, v) in acc.iter_mut().zip(d) {
            *a += *v * T::ZERO;
        }
    }
    if acc.iter().any(|a| *a != T::ZERO) {
        for (k, d) in written.iter().enumerate() {
            finite(
                d,
                "the blend (the input is beyond the range of this precision)",
            )
            .map_err(|e| (start + k, e))?;
        }
    }
    match failed {
        Some(e) => Err((start + e.index, e.error.into())),
        None => Ok(()),
    }
}

/// Blends of rigid transformations with convex weights, every method of ``chasles blend``.
///
/// ``transforms`` is (..., n, 8) unit dual quaternions or (..., n, 4, 4) rigid matrices
/// (row-major, acting on column vectors); ``weights`` is (..., n): finite, not negative,
/// with a positive sum (they are scaled to sum to 1); leading dimensions broadcast, one
/// blend per item. ``method`` is ``lin``, ``dec``, ``log``, ``log-iter``, ``qlb``,
/// ``sclerp`` (n = 2), ``dlb`` (the default) or ``dib`` (Kavan et al. 2006). ``center``
/// (3,) is the centre of Dec and QLB (default the origin); ``precision`` and
/// ``max_iterations`` (at most 10⁴) stop the iterative methods (dec, log-iter, dib).
/// Returns the blends in the form given: (..., 8) or (..., 4, 4) — Lin's matrix may not be
/// rigid; its dual quaternion is of the nearest rotation. With ``full_output`` also
/// whether each result is rigid (...) and the updates made (...), -1 for the methods that
/// do not iterate.
///
/// >>> import chasles, numpy as np
/// >>> a = chasles.dq_from_rt([1.0, 0.0, 0.0, 0.0], [0.0, 0.0, 0.0])
/// >>> b = chasles.dq_from_rt(chasles.quat_from_axis_angle([0.0, 0.0, 1.0], np.pi / 2), [2.0, 0.0, 0.0])
/// >>> d = chasles.blend(np.stack([a, b]), [0.5, 0.5], "dlb")
/// >>> np.round(np.degrees(chasles.quat_to_rotvec(d[:4])[2]), 9)
/// np.float64(45.0)
#[pyfunction]
#[pyo3(signature = (transforms, weights, method = "dlb", *, center = None, precision = None,
    max_iterations = None, full_output = false, scalar_first = true))]
#[allow(clippy::too_many_arguments)]
pub fn blend<'py>(
    transforms: &Bound<'py, PyAny>,
    weights: &Bound<'py, PyAny>,
    method: &str,
    center: Option<[f64; 3]>,
    precision: Option<f64>,
    max_iterations: Option<usize>,
    full_output: bool,
    scalar_first: bool,
) -> PyResult<Bound<'py, PyAny>> {
    let m = self::method(method)?;
    crate::arrays::check_iterations(precision, max_iterations)?;
    if let Some(c) = center {
        if c.iter().any(|v| !v.is_finite()) {
            return Err(value_error("center is not finite"));
        }
    }
    let set = Settings {
        method: m,
        center,
        precision,
        max_iterations,
        full_output,
        sf: scalar_first,
    };
    dispatch!([transforms, weights], blend_t(transforms, weights, &set))
}

/// What [`blend`] is told besides the arrays.
struct Settings {
    method: Method,
    center: Option<[f64; 3]>,
    precision: Option<f64>,
    max_iterations: Option<usize>,
    full_output: bool,
    sf: bool,
}

fn blend_t<'py, T: Num>(
    transforms: &Bound<'py, PyAny>,
    weights: &Bound<'py, PyAny>,
    s: &Settings,
) -> PyResult<Bound<'py, PyAny>> {
    let py = transforms.py();
    let x = array::<T>(transforms, "transforms")?;
    let w = array::<T>(weights, "weights")?;
    let shape = x.shape().to_vec();
    let matrices = shape.len() >= 3 && shape[shape.len() - 2..] == [4, 4];
    let core: Vec<usize> = if matrices {
        vec![shape[shape.len() - 3], 4, 4]
    } else if shape.len() >= 2 && shape[shape.len() - 1] == 8 {
        vec![shape[shape.len() - 2], 8]
    } else {
        return Err(value_error(format!(
            "transforms must have shape (..., n, 8) (dual quaternions) or (..., n, 4, 4) (matrices), got {}",
            crate::arrays::shape_text(&shape)
        )));
    };
    let n = core[0];
    let mut opt = Options::<T>::default();
    if let Some([a, b, c]) = s.center {
        opt.center = Vec3::new(T::from_f64(a), T::from_f64(b), T::from_f64(c));
    }
    if let Some(p) = s.precision {
        opt.precision = T::from_f64(p);
    }
    if let Some(i) = s.max_iterations {
        opt.max_iterations = i;
    }
    let each = if matrices { 16 } else { 8 };
    let width = each + if s.full_output { 2 } else { 0 };
    let (m, sf, full) = (s.method, s.sf, s.full_output);
    if m == Method::Dlb && !matrices {
        // chasles::blend::dlb::dlb_batch for up to 8 transforms a blend.
        macro_rules! batch {
            ($($n:literal)*) => {
                match n {
                    $($n => {
                        let out = map_runs(
                            py,
                            [("transforms", &x, &core), ("weights", &w, &[n])],
                            &[width],
                            20 * n + 10,
                            |[x, w], out| dlb_run::<T, $n>(x, w, out, sf, full),
                        )?;
                        return finish(out, false, full);
                    })*
                    _ => {}
                }
            };
        }
        batch!(1 2 3 4 5 6 7 8);
    }
    let work = match m {
        Method::Dlb | Method::Lin | Method::Qlb | Method::ScLerp => 20 * n + 40,
        _ => 400 * n,
    };
    let out = map(
        py,
        [("transforms", &x, &core), ("weights", &w, &[n])],
        &[width],
        work,
        |[x, w], out| {
            let b = if matrices {
                let ms: Vec<Mat4<T>> = x.chunks_exact(16).map(mat4).collect::<Result<_, _>>()?;
                let b = blend_matrices(m, &ms, w, &opt)?;
                out[..16].copy_from_slice(&b.matrix.to_row_major());
                (b.rigid, b.iterations)
            } else if m == Method::Dlb {
                let d = match n {
                    0..=4 => dlb_on::<T, 4>(x, w, sf)?,
                    5..=16 => dlb_on::<T, 16>(x, w, sf)?,
                    _ => dlb_item(
                        &x.chunks_exact(8).map(|s| dq_in(s, sf)).collect::<Vec<_>>(),
                        w,
                    )?,
                };
                dq_out(d, &mut out[..8], sf);
                (true, None)
            } else {
                let q: Vec<DualQuat<T>> = x.chunks_exact(8).map(|s| dq_in(s, sf)).collect();
                let b = blend_dual_quats(m, &q, w, &opt)?;
                dq_out(b.dq, &mut out[..8], sf);
                (b.rigid, b.iterations)
            };
            finite(
                &out[..each],
                "the blend (the input is beyond the range of this precision)",
            )?;
            if full {
                out[each] = if b.0 { T::ONE } else { T::ZERO };
                out[each + 1] = b.1.map_or(-T::ONE, |i| T::from_f64(i as f64));
            }
            Ok(())
        },
    )?;
    finish(out, matrices, full)
}

/// The blends in their form, and with `full` the rigid flags and iteration counts.
fn finish<'py, T: Num>(
    out: Bound<'py, PyArrayDyn<T>>,
    matrices: bool,
    full: bool,
) -> PyResult<Bound<'py, PyAny>> {
    let py = out.py();
    let lead = out.shape()[..out.ndim() - 1].to_vec();
    let out = out.into_any();
    let each = if matrices { 16 } else { 8 };
    let mut result = crate::arrays::part(&out, 0, each as isize)?;
    if matrices {
        let mut shape = lead.clone();
        shape.extend([4, 4]);
        result = result.call_method1("reshape", (shape,))?;
    }
    if !full {
        return Ok(result);
    }
    let rigid = crate::arrays::column_as(&out, each as isize, "bool_")?;
    let iters = crate::arrays::column_as(&out, each as isize + 1, "int64")?;
    Ok(PyTuple::new(py, [result, rigid, iters])?.into_any())
}

/// Screw linear interpolation (Kavan et al. §2.2: constant speed, shortest path) from
/// ``a`` to ``b`` (..., 8 dual quaternions, normalized here) at ``t`` (...); they
/// broadcast. Exact at ``t = 0`` and ``1`` and for pure translations. Zero or non-finite
/// input raises ``ValueError``.
///
/// >>> import chasles
/// >>> a = chasles.dq_from_rt([1.0, 0.0, 0.0, 0.0], [0.0, 0.0, 0.0])
/// >>> b = chasles.dq_from_rt([1.0, 0.0, 0.0, 0.0], [2.0, 0.0, 0.0])
/// >>> chasles.dq_to_rt(chasles.sclerp(a, b, 0.25))[1]
/// array([0.5, 0. , 0. ])
#[pyfunction]
#[pyo3(signature = (a, b, t, *, scalar_first = true))]
pub fn sclerp<'py>(
    a: &Bound<'py, PyAny>,
    b: &Bound<'py, PyAny>,
    t: &Bound<'py, PyAny>,
    scalar_first: bool,
) -> PyResult<Bound<'py, PyAny>> {
    dispatch!([a, b, t], sclerp_t(a, b, t, scalar_first))
}

fn sclerp_t<'py, T: Num>(
    a: &Bound<'py, PyAny>,
    b: &Bound<'py, PyAny>,
    t: &Bound<'py, PyAny>,
    sf: bool,
) -> PyResult<Bound<'py, PyAny>> {
    let (a, b) = (array::<T>(a, "a")?, array::<T>(b, "b")?);
    let t = array::<T>(t, "t")?;
    let out = map(
        a.py(),
        [("a", &a, &[8]), ("b", &b, &[8]), ("t", &t, &[])],
        &[8],
        80,
        |[a, b, t], out| {
            let (p, q) = (dq_in(a, sf).normalize()?, dq_in(b, sf).normalize()?);
            dq_out(chasles::blend::sclerp::sclerp(p, q, t[0])?, out, sf);
            Ok(())
        },
    )?;
    Ok(out.into_any())
}
