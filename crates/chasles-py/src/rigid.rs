//! Key-frame curves of rigid motions, wrapping `chasles::interp::interpolate_rigid` (Dam et
//! al. 1998's constructions carried to unit dual quaternions through their log and exp;
//! Kavan et al. 2006, §7, "spatial keyframing"): piecewise ScLERP, the dual-quaternion
//! Squad and the rigid Spring through keys (..., K, 8), one curve per item of the leading
//! dimensions, on all cores; `chasles interp --rigid` on numpy arrays.

use crate::arrays::{array, dispatch, dq_in, dq_out, map, value_error, Fail, Num};
use chasles::interp::{interpolate_rigid, RigidEnergy, RigidKeys, RigidMethod, RigidSpringConfig};
use chasles::DualQuat;
use numpy::{PyArrayDyn, PyUntypedArrayMethods};
use pyo3::prelude::*;
use pyo3::types::PyTuple;

/// What [`interpolate_rigid_py`] is told besides the arrays, checked.
struct Curve {
    method: RigidMethod,
    frames: usize,
    full_output: bool,
    sf: bool,
}

impl Curve {
    /// Numbers a frame: the pose, and with `full_output` its parameter and key index.
    fn width(&self) -> usize {
        if self.full_output {
            10
        } else {
            8
        }
    }
}

/// A curve of ``frames`` rigid poses through key poses ``keys`` (..., K, 8 unit dual
/// quaternions, K ≥ 2; leading dimensions are a batch of key sets, one curve each, on all
/// cores). ``method`` is ``"sclerp"`` (piecewise ScLERP: the screw motion from key to key at
/// constant speed, the rigid Slerp), ``"squad"`` (Dam et al.'s Squad with ScLERP and the
/// dual-quaternion log and exp: C¹ at the keys) or ``"spring"`` (the curve of least
/// curvature energy through the keys: ``energy="split"``, the rotations' Spring energy plus
/// the translations' second differences — two separate problems, so ``length_scale``
/// changes nothing — or ``"screw"``, the dual-quaternion curve's own, with the length
/// ``length_scale`` that weighs as much as a radian; its Gauss–Newton steps stop when the
/// gradient has fallen to ``tolerance`` (in [0, 1), 1e-12 when None) of its start or after
/// ``max_iterations`` (1 to 10 000, 100 when None); the screw energy's solve grows faster
/// than the frames: 0.6 s at 10⁴, about 20 s at 10⁵). Every key is one of the frames; the
/// others are shared equally among the intervals, or by the key ``times`` (..., K) when
/// given. Keys are chained to one hemisphere. The dtype is the keys'; the times are read as
/// it. Returns (..., frames, 8); with
/// ``full_output`` also the curve parameter (..., frames) and each frame's key index
/// (..., frames), -1 between keys. A key that is not unit, too few frames or a bad
/// setting raise ``ValueError`` naming it.
///
/// >>> import chasles, numpy as np
/// >>> q = chasles.quat_from_axis_angle([0.0, 0.0, 1.0], [0.0, np.pi / 2])
/// >>> keys = chasles.dq_from_rt(q, [[0.0, 0.0, 0.0], [0.0, 0.0, 2.0]])
/// >>> curve = chasles.interpolate_rigid(keys, "sclerp", 5)
/// >>> r, t = chasles.dq_to_rt(curve[2])
/// >>> np.round(np.degrees(chasles.quat_to_rotvec(r)[2]), 9), np.round(t, 9)
/// (np.float64(45.0), array([0., 0., 1.]))
#[pyfunction]
#[pyo3(name = "interpolate_rigid")]
#[pyo3(signature = (keys, method = "sclerp", frames = 200, *, times = None, energy = "split",
    length_scale = 1.0, tolerance = None, max_iterations = None, full_output = false,
    scalar_first = true, max_frames = 1_000_000))]
#[allow(clippy::too_many_arguments)]
pub fn interpolate_rigid_py<'py>(
    keys: &Bound<'py, PyAny>,
    method: &str,
    frames: usize,
    times: Option<&Bound<'py, PyAny>>,
    energy: &str,
    length_scale: f64,
    tolerance: Option<f64>,
    max_iterations: Option<usize>,
    full_output: bool,
    scalar_first: bool,
    max_frames: usize,
) -> PyResult<Bound<'py, PyAny>> {
    crate::arrays::check_frames(frames, max_frames)?;
    crate::arrays::check_iterations(None, max_iterations)?;
    let spring_only =
        energy != "split" || length_scale != 1.0 || tolerance.is_some() || max_iterations.is_some();
    let method = match method {
        "sclerp" | "slerp" => RigidMethod::ScLerp,
        "squad" => RigidMethod::Squad,
        "spring" => {
            let defaults = RigidSpringConfig::default();
            RigidMethod::Spring(RigidSpringConfig {
                energy: match energy {
                    "split" => RigidEnergy::Split,
                    "screw" => RigidEnergy::Screw,
                    e => return Err(value_error(format!("unknown energy '{e}': split, screw"))),
                },
                length_scale,
                tolerance: tolerance.unwrap_or(defaults.tolerance),
                max_iterations: max_iterations.unwrap_or(defaults.max_iterations),
            })
        }
        m => {
            return Err(value_error(format!(
                "unknown rigid method '{m}': sclerp, squad, spring"
            )))
        }
    };
    if spring_only && !matches!(method, RigidMethod::Spring(_)) {
        return Err(value_error(
            "energy, length_scale, tolerance and max_iterations are Spring's: give method='spring'",
        ));
    }
    let c = Curve {
        method,
        frames,
        full_output,
        sf: scalar_first,
    };
    dispatch!([keys], curves(keys, times, &c))
}

/// One curve through the keys `k` (8 numbers each) with the key times `t`, into `out`.
fn one<T: Num>(k: &[T], t: Option<&[T]>, c: &Curve, out: &mut [T]) -> Result<(), Fail> {
    let keys: Vec<DualQuat<T>> = k.chunks_exact(8).map(|s| dq_in(s, c.sf)).collect();
    let rk = RigidKeys::new(&keys, t)?;
    let frames = interpolate_rigid(&c.method, &rk, c.frames)?;
    if frames.len() != c.frames {
        return Err(Fail(format!(
            "{} frames made, {} asked for",
            frames.len(),
            c.frames
        )));
    }
    for (f, o) in frames.iter().zip(out.chunks_exact_mut(c.width())) {
        dq_out(f.dq, &mut o[..8], c.sf);
        if c.full_output {
            o[8] = f.t;
            o[9] = f.key.map_or(-T::ONE, |k| T::from_f64(k as f64));
        }
    }
    Ok(())
}

fn curves<'py, T: Num>(
    keys: &Bound<'py, PyAny>,
    times: Option<&Bound<'py, PyAny>>,
    c: &Curve,
) -> PyResult<Bound<'py, PyAny>> {
    let py = keys.py();
    let k = array::<T>(keys, "keys")?;
    let shape = k.shape().to_vec();
    if shape.len() < 2 || shape[shape.len() - 1] != 8 {
        return Err(value_error(format!(
            "keys must have shape (..., K, 8) (unit dual quaternions), got {}",
            crate::arrays::shape_text(&shape)
        )));
    }
    let n = shape[shape.len() - 2];
    let work = match c.method {
        RigidMethod::Spring(_) => 1_000_000,
        _ => 200 * c.frames,
    };
    let core = [n, 8];
    let out_core = [c.frames, c.width()];
    let out = match times {
        Some(times) => {
            let t = array::<T>(times, "times")?;
            map(
                py,
                [("keys", &k, &core), ("times", &t, &[n])],
                &out_core,
                work,
                |[k, t], out| one(k, Some(t), c, out),
            )?
        }
        None => map(py, [("keys", &k, &core)], &out_core, work, |[k], out| {
            one(k, None, c, out)
        })?,
    };
    finish(out, c.full_output)
}

/// The poses, and with `full` the curve parameters and key indices.
fn finish<'py, T: Num>(out: Bound<'py, PyArrayDyn<T>>, full: bool) -> PyResult<Bound<'py, PyAny>> {
    let py = out.py();
    let out = out.into_any();
    if !full {
        return Ok(out);
    }
    let key = crate::arrays::column_as(&out, 9, "int64")?;
    Ok(PyTuple::new(
        py,
        [
            crate::arrays::part(&out, 0, 8)?,
            crate::arrays::column(&out, 8)?,
            key,
        ],
    )?
    .into_any())
}
