//! Averaging measured rigid poses, wrapping `chasles::blend::average` (Kavan et al. 2006,
//! §7 names "averaging of measured positions and orientations in computer vision" among
//! the blends' uses): the rigid mean — DIB's fixed point, §4 — and the robust means with
//! Huber's or Tukey's weights, of poses (..., n, 8), one mean per item of the leading
//! dimensions, on all cores; `chasles average` on numpy arrays.

use crate::arrays::{array, dispatch, dq_in, dq_out, finite, map, value_error, Num};
use chasles::blend::average::{mean, robust_mean, Average, Loss, Robust, Scale};
use chasles::blend::Options;
use chasles::DualQuat;
use numpy::{PyArrayDyn, PyUntypedArrayMethods};
use pyo3::prelude::*;
use pyo3::types::PyTuple;

/// What [`average`] is told besides the arrays, checked.
struct Settings {
    loss: Option<Loss>,
    tuning: Option<f64>,
    scale: Option<f64>,
    length_scale: f64,
    precision: Option<f64>,
    max_iterations: Option<usize>,
    full_output: bool,
    sf: bool,
}

/// The mean of rigid poses ``poses`` (..., n, 8 unit dual quaternions) with optional
/// ``weights`` (..., n; uniform when None), one mean per item of the leading dimensions:
/// ``loss=None`` gives the rigid mean — the pose DIB converges to, whose rotation is the
/// geodesic mean of the rotations, bi-invariant — and ``"huber"`` or ``"tukey"`` a robust
/// mean that discounts outliers by their distance to it (the turn in radians and the move
/// over ``length_scale``, in quadrature), with the tuning constant ``tuning`` (1.345 and
/// 4.685 when None) and the scale ``scale`` (re-estimated each step as 1.4826 × the median
/// distance when None). ``precision`` and ``max_iterations`` bound the updates (when None:
/// 1.5e-10 / 1.2e-5 for f64 / f32, and at most 50 updates for the rigid mean, 200 for a
/// robust one, as ``chasles average``; at most 10 000). The dtype is the poses'; the
/// weights are read as it. With ``full_output`` it returns ``(mean,
/// weights, distances, scale, iterations, capped)``: each pose's final weight and distance
/// to the mean, the last scale (NaN for the rigid mean), the updates made and whether it
/// stopped at the cap. A pose that is not finite or not unit, bad weights or settings, and
/// poses so far apart that their distances overflow raise ``ValueError`` naming them.
///
/// The translations' mean is not their average: the mean is of screw motions, and the
/// three poses turn as they move (the fourth, 50 away, is an outlier that Tukey's weights
/// drop).
///
/// >>> import chasles, numpy as np
/// >>> q = chasles.quat_from_axis_angle([0.0, 0.0, 1.0], [0.0, 0.2, 0.4, 3.0])
/// >>> poses = chasles.dq_from_rt(q, [[0.0, 0, 0], [1.0, 0, 0], [2.0, 0, 0], [50.0, 0, 0]])
/// >>> m = chasles.average(poses[:3])
/// >>> r, t = chasles.dq_to_rt(m)
/// >>> np.round(chasles.quat_to_rotvec(r), 9), np.round(t, 3)
/// (array([0. , 0. , 0.2]), array([ 1.   , -0.067,  0.   ]))
/// >>> m, w, d, s, it, capped = chasles.average(poses, loss="tukey", full_output=True)
/// >>> np.round(w, 3), bool(capped)
/// (array([0.329, 0.343, 0.329, 0.   ]), False)
#[pyfunction]
#[pyo3(signature = (poses, weights = None, loss = None, *, tuning = None, scale = None,
    length_scale = 1.0, precision = None, max_iterations = None, full_output = false,
    scalar_first = true))]
#[allow(clippy::too_many_arguments)]
pub fn average<'py>(
    poses: &Bound<'py, PyAny>,
    weights: Option<&Bound<'py, PyAny>>,
    loss: Option<&str>,
    tuning: Option<f64>,
    scale: Option<f64>,
    length_scale: f64,
    precision: Option<f64>,
    max_iterations: Option<usize>,
    full_output: bool,
    scalar_first: bool,
) -> PyResult<Bound<'py, PyAny>> {
    let loss = match loss {
        None => None,
        Some(name) => Some(
            Loss::ALL
                .into_iter()
                .find(|l| l.name() == name)
                .ok_or_else(|| value_error(format!("unknown loss '{name}': huber, tukey")))?,
        ),
    };
    crate::arrays::check_iterations(precision, max_iterations)?;
    for (what, v) in [("tuning", tuning), ("scale", scale)] {
        if let Some(v) = v {
            crate::arrays::positive(what, v)?;
        }
    }
    crate::arrays::positive("length_scale", length_scale)?;
    if loss.is_none() && (tuning.is_some() || scale.is_some() || length_scale != 1.0) {
        return Err(value_error(
            "tuning, scale and length_scale are a robust mean's: give loss='huber' or 'tukey'",
        ));
    }
    let set = Settings {
        loss,
        tuning,
        scale,
        length_scale,
        precision,
        max_iterations,
        full_output,
        sf: scalar_first,
    };
    dispatch!([poses], average_t(poses, weights, &set))
}

/// One mean of the `n` poses in `x` (8 numbers each) with the weights `w` (or uniform).
fn one<T: Num>(x: &[T], w: Option<&[T]>, s: &Settings) -> Result<Average<T>, crate::arrays::Fail> {
    let q: Vec<DualQuat<T>> = x.chunks_exact(8).map(|p| dq_in(p, s.sf)).collect();
    // `chasles average`'s settings: the library's defaults for the rigid mean (50 updates
    // at most), `Robust::new`'s for a robust one (200).
    let mut opt = Options::<T>::default();
    if let Some(p) = s.precision {
        opt.precision = T::from_f64(p);
    }
    let a = match s.loss {
        None => {
            opt.max_iterations = s.max_iterations.unwrap_or(opt.max_iterations);
            mean(&q, w, &opt)?
        }
        Some(loss) => {
            let mut robust = Robust::<T>::new(loss);
            robust.tuning = s.tuning.map(T::from_f64);
            robust.scale = s.scale.map_or(Scale::Mad, |v| Scale::Fixed(T::from_f64(v)));
            robust.length_scale = T::from_f64(s.length_scale);
            robust.options.precision = opt.precision;
            robust.options.max_iterations =
                s.max_iterations.unwrap_or(robust.options.max_iterations);
            robust_mean(&q, w, &robust)?
        }
    };
    finite(
        &a.distances,
        "a pose's distance to the mean (the poses are beyond the range of this precision)",
    )?;
    Ok(a)
}

fn average_t<'py, T: Num>(
    poses: &Bound<'py, PyAny>,
    weights: Option<&Bound<'py, PyAny>>,
    s: &Settings,
) -> PyResult<Bound<'py, PyAny>> {
    let py = poses.py();
    let x = array::<T>(poses, "poses")?;
    let shape = x.shape().to_vec();
    if shape.len() < 2 || shape[shape.len() - 1] != 8 {
        return Err(value_error(format!(
            "poses must have shape (..., n, 8) (unit dual quaternions), got {}",
            crate::arrays::shape_text(&shape)
        )));
    }
    let n = shape[shape.len() - 2];
    let width = 8 + if s.full_output { 2 * n + 3 } else { 0 };
    // A robust mean starts from a least-median pose: 64 n distances, then tens of updates.
    let work = 300 * n
        + if s.loss.is_some() {
            2_000 * n.min(64)
        } else {
            0
        };
    let write = |a: Average<T>, out: &mut [T]| -> Result<(), crate::arrays::Fail> {
        dq_out(a.pose, &mut out[..8], s.sf);
        finite(
            &out[..8],
            "the mean (the input is beyond the range of this precision)",
        )?;
        if s.full_output {
            out[8..8 + n].copy_from_slice(&a.weights);
            out[8 + n..8 + 2 * n].copy_from_slice(&a.distances);
            out[8 + 2 * n] = a.scale.unwrap_or(T::from_f64(f64::NAN));
            out[9 + 2 * n] = T::from_f64(a.iterations as f64);
            out[10 + 2 * n] = if a.capped { T::ONE } else { T::ZERO };
        }
        Ok(())
    };
    let core = [n, 8];
    let out = match weights {
        Some(weights) => {
            let w = array::<T>(weights, "weights")?;
            map(
                py,
                [("poses", &x, &core), ("weights", &w, &[n])],
                &[width],
                work,
                |[x, w], out| write(one(x, Some(w), s)?, out),
            )?
        }
        None => map(py, [("poses", &x, &core)], &[width], work, |[x], out| {
            write(one(x, None, s)?, out)
        })?,
    };
    finish(out, n, s.full_output)
}

/// The means, and with `full` the weights, distances, scales, iteration counts and flags.
fn finish<'py, T: Num>(
    out: Bound<'py, PyArrayDyn<T>>,
    n: usize,
    full: bool,
) -> PyResult<Bound<'py, PyAny>> {
    let py = out.py();
    let out = out.into_any();
    let mean = crate::arrays::part(&out, 0, 8)?;
    if !full {
        return Ok(mean);
    }
    let n = n as isize;
    let weights = crate::arrays::part(&out, 8, 8 + n)?;
    let distances = crate::arrays::part(&out, 8 + n, 8 + 2 * n)?;
    let scale = crate::arrays::column(&out, 8 + 2 * n)?;
    let iterations = crate::arrays::column_as(&out, 9 + 2 * n, "int64")?;
    let capped = crate::arrays::column_as(&out, 10 + 2 * n, "bool_")?;
    Ok(PyTuple::new(py, [mean, weights, distances, scale, iterations, capped])?.into_any())
}
