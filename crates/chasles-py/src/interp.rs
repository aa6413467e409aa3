//! Interpolation of rotations, wrapping `chasles::interp` (Dam et al. 1998, chapters 5–7):
//! Slerp between pairs (batched, broadcast), and whole curves through key frames — every
//! method of `chasles interp` by the same names (`lineuler`, `linmat`, `lerp`, `slerp`,
//! `squad`, `spring`, `slerpsvupti`, `squadsvupti`, `justdoit`, and the curves past the
//! report: `tcb`, `catmull-rom`, `bezier`, `c2`), with the Spring controls of its command
//! line ([`crate::spring`]), Kochanek–Bartels' tension, continuity and bias, and a stable
//! horizon for camera paths (`chasles::interp::horizon`). Key sets are batched: keys (..., K, 4) give curves (..., frames, 4), one
//! per item, on all cores.

use crate::arrays::{
    array, column, dispatch, finite, item_error, leading, part, q_in, q_out, value_error, Fail, Num,
};
use crate::spring::{spring_config, SpringOptions, DEFAULT_FRAMES};
use chasles::interp::horizon::{check_keys, level_frames};
use chasles::interp::slerp::{slerp as slerp_as_given, slerp_shortest};
use chasles::interp::tcb::check_parameter;
use chasles::interp::{
    interpolate as lib_interpolate, spring as lib_spring, Hemisphere, KeyFrames, Method,
    SpringConfig, Tcb, Timing, Up,
};
use chasles::{EulerOrder, Quat};
use numpy::{PyArrayDyn, PyArrayMethods, PyUntypedArrayMethods};
use pyo3::prelude::*;
use pyo3::types::PyTuple;

/// Spherical linear interpolation (Dam et al. eq. 6.13) from ``q0`` to ``q1`` at ``t``.
///
/// ``q0``, ``q1`` are (..., 4) (normalized here), ``t`` is (...); all three broadcast, so
/// one pair at many times is ``slerp(q0, q1, np.linspace(0, 1, 50)[:, None])``… or simply
/// ``t`` of shape (N,) against (4,) keys. With ``shortest=True`` (the default, as scipy's
/// ``Slerp``) the shorter rotation is taken (``-q1`` when ``q0·q1 < 0``); with ``False``
/// the great arc between the two 4D points as given. ``t`` outside [0, 1] extrapolates.
/// Exact for nearly equal keys; zero or non-finite input raises ``ValueError``.
///
/// >>> import chasles, numpy as np
/// >>> q1 = chasles.quat_from_axis_angle([0.0, 0.0, 1.0], np.pi / 2)
/// >>> q = chasles.slerp([1.0, 0.0, 0.0, 0.0], q1, [0.0, 0.5, 1.0])
/// >>> np.round(chasles.quat_to_rotvec(q)[:, 2], 6)
/// array([0.      , 0.785398, 1.570796])
#[pyfunction]
#[pyo3(signature = (q0, q1, t, *, shortest = true, scalar_first = true))]
pub fn slerp<'py>(
    q0: &Bound<'py, PyAny>,
    q1: &Bound<'py, PyAny>,
    t: &Bound<'py, PyAny>,
    shortest: bool,
    scalar_first: bool,
) -> PyResult<Bound<'py, PyAny>> {
    dispatch!([q0, q1, t], slerp_t(q0, q1, t, shortest, scalar_first))
}

fn slerp_t<'py, T: Num>(
    q0: &Bound<'py, PyAny>,
    q1: &Bound<'py, PyAny>,
    t: &Bound<'py, PyAny>,
    shortest: bool,
    sf: bool,
) -> PyResult<Bound<'py, PyAny>> {
    let (a, b) = (array::<T>(q0, "q0")?, array::<T>(q1, "q1")?);
    let t = array::<T>(t, "t")?;
    let out = crate::arrays::map(
        a.py(),
        [("q0", &a, &[4]), ("q1", &b, &[4]), ("t", &t, &[])],
        &[4],
        30,
        |[a, b, t], out| {
            finite(t, "interpolation parameter")?;
            let (p, q) = (q_in(a, sf).normalize()?, q_in(b, sf).normalize()?);
            let r = if shortest {
                slerp_shortest(p, q, t[0])
            } else {
                slerp_as_given(p, q, t[0])
            };
            q_out(r, out, sf);
            Ok(())
        },
    )?;
    Ok(out.into_any())
}

/// What a method name of `chasles interp` runs.
#[derive(Debug, Clone)]
enum Plan {
    Piecewise(Method),
    /// A Spring preset, and whether it runs the converged solver unless told otherwise.
    Spring(SpringConfig, bool),
}

/// The methods' names, for errors.
const METHODS: &str = "lineuler, linmat, lerp, slerp, squad, spring, slerpsvupti, squadsvupti, justdoit, tcb, catmull-rom, bezier or c2";

/// The plan of a method name; LinEuler in `order`.
fn plan(method: &str, order: EulerOrder) -> PyResult<Plan> {
    Ok(match method {
        "lineuler" => Plan::Piecewise(Method::LinEuler(order)),
        "linmat" => Plan::Piecewise(Method::LinMat),
        "lerp" => Plan::Piecewise(Method::Nlerp),
        "slerp" => Plan::Piecewise(Method::Slerp),
        "squad" => Plan::Piecewise(Method::Squad),
        "spring" => Plan::Spring(SpringConfig::spring(), true),
        "slerpsvupti" => Plan::Spring(SpringConfig::slerpsvupti(), false),
        "squadsvupti" => Plan::Spring(SpringConfig::squadsvupti(), false),
        "justdoit" => Plan::Spring(SpringConfig::justdoit(), false),
        "tcb" => Plan::Piecewise(Method::KochanekBartels(Tcb::CATMULL_ROM)),
        "catmull-rom" => Plan::Piecewise(Method::CatmullRom),
        "bezier" => Plan::Piecewise(Method::Bezier),
        "c2" => Plan::Piecewise(Method::C2),
        other => return Err(value_error(format!("unknown method '{other}': {METHODS}"))),
    })
}

/// Everything [`interpolate`] is told besides the keys.
#[derive(Debug, Clone)]
pub struct Curve {
    /// The method's name.
    pub method: String,
    /// Frames asked for.
    pub frames: Option<usize>,
    /// `uniform` or `angle`.
    pub timing: String,
    /// Keep the keys' signs instead of chaining hemispheres.
    pub keep_signs: bool,
    /// LinEuler's order.
    pub order: String,
    /// Also return the parameter and key index of each frame.
    pub full_output: bool,
    /// Quaternion layout.
    pub scalar_first: bool,
    /// The ceiling on frames.
    pub max_frames: usize,
    /// Spring's controls.
    pub spring: SpringOptions,
    /// Kochanek–Bartels' tension, continuity and bias (`tcb` only).
    pub tcb: [Option<f64>; 3],
    /// `"Z"` or `"Y"`: a camera path levelled about this up axis.
    pub horizon: Option<String>,
}

impl Curve {
    /// A curve by `method` with no options past the common ones.
    fn plain(method: &str, frames: Option<usize>, timing: &str) -> Self {
        Curve {
            method: method.into(),
            frames,
            timing: timing.into(),
            keep_signs: false,
            order: "xyz".into(),
            full_output: false,
            scalar_first: true,
            max_frames: 1_000_000,
            spring: SpringOptions::default(),
            tcb: [None; 3],
            horizon: None,
        }
    }
}

/// The names of Kochanek–Bartels' parameters, in [`Curve::tcb`]'s order.
const TCB_NAMES: [&str; 3] = ["tension", "continuity", "bias"];

/// Kochanek–Bartels' parameters checked (each named in its error), 0 where not given.
fn tcb_params(given: &[Option<f64>; 3]) -> PyResult<Tcb> {
    let mut t = Tcb::CATMULL_ROM;
    let slots = [&mut t.tension, &mut t.continuity, &mut t.bias];
    for ((name, v), slot) in TCB_NAMES.iter().zip(given).zip(slots) {
        if let Some(v) = *v {
            if check_parameter("", v).is_err() {
                return Err(value_error(format!(
                    "{name} must be a finite number in [-1, 1], got {v}"
                )));
            }
            *slot = v;
        }
    }
    Ok(t)
}

/// The up axis named by `horizon`.
fn up_axis(horizon: Option<&str>) -> PyResult<Option<Up>> {
    match horizon {
        None => Ok(None),
        Some("Z" | "z") => Ok(Some(Up::Z)),
        Some("Y" | "y") => Ok(Some(Up::Y)),
        Some(other) => Err(value_error(format!(
            "horizon must be 'Z' or 'Y' (the world's up axis), got '{other}'"
        ))),
    }
}

/// Curves through key frames (..., K, 4) by `c.method`; see the Python docstring.
pub fn curves<'py>(
    keys: &Bound<'py, PyAny>,
    times: Option<&Bound<'py, PyAny>>,
    c: &Curve,
) -> PyResult<Bound<'py, PyAny>> {
    let mut arrays = vec![keys];
    arrays.extend(times);
    if crate::arrays::wants_f32(&arrays)? {
        curves_t::<f32>(keys, times, c)
    } else {
        curves_t::<f64>(keys, times, c)
    }
}

fn curves_t<'py, T: Num>(
    keys: &Bound<'py, PyAny>,
    times: Option<&Bound<'py, PyAny>>,
    c: &Curve,
) -> PyResult<Bound<'py, PyAny>> {
    let py = keys.py();
    let order: EulerOrder = crate::convert::order(&c.order)?;
    let timing = match c.timing.as_str() {
        "uniform" => Timing::Uniform,
        "angle" => Timing::Angle,
        other => {
            return Err(value_error(format!(
                "timing must be 'uniform' or 'angle', got '{other}'"
            )))
        }
    };
    let hemisphere = if c.keep_signs {
        Hemisphere::AsGiven
    } else {
        Hemisphere::Chain
    };
    let k_arr = array::<T>(keys, "keys")?;
    let shape = k_arr.shape().to_vec();
    if shape.len() < 2 || shape[shape.len() - 1] != 4 {
        return Err(value_error(format!(
            "keys must have shape (..., K, 4), got {}",
            crate::arrays::shape_text(&shape)
        )));
    }
    let k = shape[shape.len() - 2];
    let up = up_axis(c.horizon.as_deref())?;
    let mut plan = plan(&c.method, order)?;
    match &mut plan {
        Plan::Piecewise(Method::KochanekBartels(p)) => *p = tcb_params(&c.tcb)?,
        _ => {
            if let Some(i) = c.tcb.iter().position(Option::is_some) {
                return Err(value_error(format!(
                    "{} is a Kochanek-Bartels control: it applies to tcb, not {}",
                    TCB_NAMES[i], c.method
                )));
            }
        }
    }
    let (plan, frames) = match plan {
        Plan::Piecewise(m) => {
            if let Some(name) = c.spring.given().first() {
                return Err(value_error(format!(
                    "{name} is a Spring control: it applies to spring, slerpsvupti, squadsvupti and justdoit, not {}",
                    c.method
                )));
            }
            (Plan::Piecewise(m), c.frames.unwrap_or(DEFAULT_FRAMES))
        }
        Plan::Spring(preset, converged) => {
            let (cfg, total) = spring_config(preset, converged, &c.spring, c.frames, k)?;
            (Plan::Spring(cfg, converged), total)
        }
    };
    crate::arrays::check_frames(frames, c.max_frames)?;
    let t_arr = times.map(|t| array::<T>(t, "times")).transpose()?;
    let mut leads = vec![("keys", leading(&shape, &[k, 4], "keys")?)];
    if let Some(t) = &t_arr {
        leads.push(("times", leading(t.shape(), &[k], "times")?));
    }
    let lead = crate::arrays::broadcast(&leads)?;
    let kidx = crate::arrays::Index::new(leads[0].1, &lead);
    let tidx = t_arr
        .as_ref()
        .map(|_| crate::arrays::Index::new(leads[1].1, &lead));
    let kd = k_arr.as_slice().map_err(|e| value_error(e.to_string()))?;
    let td = match &t_arr {
        Some(t) => Some(t.as_slice().map_err(|e| value_error(e.to_string()))?),
        None => None,
    };
    let width = if c.full_output { 6 } else { 4 };
    let mut out_shape = lead.clone();
    out_shape.extend([frames, width]);
    let out = PyArrayDyn::<T>::zeros(py, out_shape, false);
    let sf = c.scalar_first;
    let work = match &plan {
        Plan::Piecewise(_) => frames * 60,
        Plan::Spring(..) => 1_000_000,
    };
    {
        let mut rw = out.readwrite();
        let o = rw.as_slice_mut().map_err(|e| value_error(e.to_string()))?;
        let item = |i: usize, out: &mut [T]| -> Result<(), Fail> {
            let ks = &kd[kidx.at(i) * k * 4..][..k * 4];
            // Normalized once here as `chasles interp`'s key files are, so that the curves
            // are the CLI's bit for bit (a second normalization may move a last bit, and
            // the converged Spring stops where the rounding says); a key that cannot be
            // normalized is left for KeyFrames to report with its index.
            let q: Vec<Quat<T>> = ks
                .chunks_exact(4)
                .map(|s| {
                    let q = q_in(s, sf);
                    q.normalize().unwrap_or(q)
                })
                .collect();
            let ts = match (&tidx, td) {
                (Some(ix), Some(td)) => Some(&td[ix.at(i) * k..][..k]),
                _ => None,
            };
            let kf = KeyFrames::new(&q, ts, hemisphere)?;
            if let Some(up) = up {
                check_keys(&kf, up)?;
            }
            let mut fr = match &plan {
                Plan::Piecewise(m) => lib_interpolate(*m, &kf, frames, timing)?,
                Plan::Spring(cfg, _) => lib_spring(&kf, frames, timing, cfg, &mut |_| {})?.frames,
            };
            if let Some(up) = up {
                level_frames(&mut fr, up);
            }
            if fr.len() != frames {
                return Err(Fail(format!(
                    "{} frames made, {frames} asked for",
                    fr.len()
                )));
            }
            for (f, o) in fr.iter().zip(out.chunks_exact_mut(width)) {
                q_out(f.q, o, sf);
                if width == 6 {
                    o[4] = f.t;
                    o[5] = f.key.map_or(-T::ONE, |k| T::from_f64(k as f64));
                }
            }
            Ok(())
        };
        py.detach(|| crate::arrays::for_items(o, frames * width, work, &item))
            .map_err(|(i, m)| item_error(i, m, &lead))?;
    }
    let out = out.into_any();
    if !c.full_output {
        return Ok(out);
    }
    let key = crate::arrays::column_as(&out, 5, "int64")?;
    Ok(PyTuple::new(py, [part(&out, 0, 4)?, column(&out, 4)?, key])?.into_any())
}

/// A curve of ``frames`` rotations through key frames by any method of ``chasles interp``.
///
/// ``keys`` is (..., K, 4), K ≥ 2 unit quaternions (normalized here); leading dimensions
/// are a batch of key sets, one curve each, on all cores. ``method`` is ``lineuler``
/// (Euler angles in ``order``, Dam et al. eq. 6.1), ``linmat`` (matrices, eq. 6.2),
/// ``lerp`` (normalized, eq. 6.3), ``slerp`` (eq. 6.13), ``squad`` (Definition 17),
/// Spring — ``spring`` (§6.3.7 solved to its optimum by Newton's method, §8.2),
/// ``slerpsvupti``, ``squadsvupti``, ``justdoit`` (App. C presets, the report's gradient
/// descent) — or a curve past the report: ``tcb`` (Kochanek–Bartels with ``tension``,
/// ``continuity`` and ``bias`` in [-1, 1], 0 by default), ``catmull-rom``, ``bezier``
/// (Shoemake) or ``c2`` (C² at the keys, as scipy's ``RotationSpline``).
///
/// Spring's controls are the keywords ``solver`` (``"converged"``, the default of
/// ``spring``, or ``"report"``, the presets'), ``tolerance`` (the converged solver's
/// gradient fall, 1e-10), the report's ``levels``, ``iterations``, ``step``
/// (``"fixed:0.02"``, ``"normalized:E"``, ``"adaptive:E"``, ``"accelerated:E"``) and
/// ``penalty``, and for both ``width`` (``one``, ``chord``, ``angle``), ``key_weight``,
/// ``velocity_weight`` and ``start`` (``slerp``, ``squad``), as on the command line.
/// ``horizon="Z"`` (or ``"Y"``) makes a camera path: keys looking along their x axis with
/// no roll about that world up axis, every frame turned back to roll 0.
///
/// Every key is one of the frames; ``timing`` shares the others among the intervals
/// (``"angle"``, the default, in proportion to each interval's angle; ``"uniform"``
/// equally, or by the key ``times`` (K,) when given). Keys are chained into one hemisphere
/// unless ``keep_signs``. Returns (..., frames, 4); with ``full_output`` also the curve
/// parameter (..., frames) and the key index of each frame (..., frames), -1 between keys.
///
/// >>> import chasles, numpy as np
/// >>> keys = chasles.quat_from_euler([[0, 0, 0], [0, 0, 1.0], [0, 1.0, 1.0]], "xyz")
/// >>> q = chasles.interpolate(keys, "squad", 9)
/// >>> q.shape, bool(np.allclose(q[0], keys[0]))
/// ((9, 4), True)
/// >>> chasles.interpolate(keys, "tcb", 9, tension=0.5).shape
/// (9, 4)
#[pyfunction]
#[pyo3(signature = (keys, method = "slerp", frames = None, *, timing = "angle", times = None,
    keep_signs = false, order = "xyz", full_output = false, scalar_first = true,
    max_frames = 1_000_000, solver = None, tolerance = None, levels = None,
    iterations = None, step = None, penalty = None, width = None, key_weight = None,
    velocity_weight = None, start = None, tension = None, continuity = None, bias = None,
    horizon = None))]
#[allow(clippy::too_many_arguments)]
pub fn interpolate<'py>(
    keys: &Bound<'py, PyAny>,
    method: &str,
    frames: Option<usize>,
    timing: &str,
    times: Option<&Bound<'py, PyAny>>,
    keep_signs: bool,
    order: &str,
    full_output: bool,
    scalar_first: bool,
    max_frames: usize,
    solver: Option<String>,
    tolerance: Option<f64>,
    levels: Option<Vec<usize>>,
    iterations: Option<Vec<usize>>,
    step: Option<String>,
    penalty: Option<f64>,
    width: Option<String>,
    key_weight: Option<f64>,
    velocity_weight: Option<f64>,
    start: Option<String>,
    tension: Option<f64>,
    continuity: Option<f64>,
    bias: Option<f64>,
    horizon: Option<String>,
) -> PyResult<Bound<'py, PyAny>> {
    let c = Curve {
        keep_signs,
        order: order.to_string(),
        full_output,
        scalar_first,
        max_frames,
        spring: SpringOptions {
            levels,
            iterations,
            step,
            penalty,
            width,
            key_weight,
            velocity_weight,
            start,
            solver,
            tolerance,
        },
        tcb: [tension, continuity, bias],
        horizon,
        ..Curve::plain(method, frames, timing)
    };
    curves(keys, times, &c)
}

/// Squad through key frames (Dam et al. Definition 17: C¹ at every key): ``frames``
/// rotations (..., frames, 4) through keys (..., K, 4); see :func:`interpolate` for
/// ``timing`` (default ``"angle"``, §6.2), ``times``, ``keep_signs`` and ``full_output``.
///
/// >>> import chasles, numpy as np
/// >>> keys = chasles.quat_from_euler([[0, 0, 0], [0, 0, 1.0], [0, 1.0, 1.0]], "xyz")
/// >>> chasles.squad(keys, 50).shape
/// (50, 4)
#[pyfunction]
#[pyo3(signature = (keys, frames, *, timing = "angle", times = None, keep_signs = false,
    full_output = false, scalar_first = true, max_frames = 1_000_000))]
#[allow(clippy::too_many_arguments)]
pub fn squad<'py>(
    keys: &Bound<'py, PyAny>,
    frames: usize,
    timing: &str,
    times: Option<&Bound<'py, PyAny>>,
    keep_signs: bool,
    full_output: bool,
    scalar_first: bool,
    max_frames: usize,
) -> PyResult<Bound<'py, PyAny>> {
    let c = Curve {
        keep_signs,
        full_output,
        scalar_first,
        max_frames,
        ..Curve::plain("squad", Some(frames), timing)
    };
    curves(keys, times, &c)
}

/// Spring (Dam et al. §6.3.7): the curve through key frames (..., K, 4) of least
/// curvature. ``preset`` ``spring`` (the default) solves eq. 6.23 to its optimum by
/// Newton's method (``solver="converged"``, §8.2's "more robust numerical solution"; the
/// gradient falls by ``tolerance``, 1e-10); the report's presets ``slerpsvupti``,
/// ``squadsvupti`` and ``justdoit`` run its gradient descent (App. C), as does
/// ``solver="report"`` for ``spring`` (``justdoit`` with key weight 1.3 and the
/// accelerated step). The keywords adjust the run as ``chasles interp``'s flags do
/// (the descent's ``levels``: frames at each step, the last the total; ``iterations`` per
/// step; ``step``; ``penalty``; for both ``width``, ``key_weight``, ``velocity_weight``,
/// ``start``). ``frames`` defaults to the last of ``levels``, else 200. See
/// :func:`interpolate` for the rest.
///
/// >>> import chasles, numpy as np
/// >>> keys = chasles.quat_from_euler([[0, 0, 0], [0, 0, 1.0], [0, 1.0, 1.0]], "xyz")
/// >>> q = chasles.spring(keys, 40)
/// >>> q.shape, bool(np.allclose(np.linalg.norm(q, axis=-1), 1.0))
/// ((40, 4), True)
/// >>> chasles.spring(keys, 40, solver="report", iterations=[20, 20, 20]).shape
/// (40, 4)
#[pyfunction]
#[pyo3(signature = (keys, frames = None, *, preset = "spring", timing = "angle", times = None,
    keep_signs = false, full_output = false, scalar_first = true, max_frames = 1_000_000,
    solver = None, tolerance = None, levels = None, iterations = None, step = None,
    penalty = None, width = None, key_weight = None, velocity_weight = None, start = None))]
#[allow(clippy::too_many_arguments)]
pub fn spring<'py>(
    keys: &Bound<'py, PyAny>,
    frames: Option<usize>,
    preset: &str,
    timing: &str,
    times: Option<&Bound<'py, PyAny>>,
    keep_signs: bool,
    full_output: bool,
    scalar_first: bool,
    max_frames: usize,
    solver: Option<String>,
    tolerance: Option<f64>,
    levels: Option<Vec<usize>>,
    iterations: Option<Vec<usize>>,
    step: Option<String>,
    penalty: Option<f64>,
    width: Option<String>,
    key_weight: Option<f64>,
    velocity_weight: Option<f64>,
    start: Option<String>,
) -> PyResult<Bound<'py, PyAny>> {
    if !matches!(
        preset,
        "spring" | "slerpsvupti" | "squadsvupti" | "justdoit"
    ) {
        return Err(value_error(format!(
            "unknown preset '{preset}': spring, slerpsvupti, squadsvupti or justdoit"
        )));
    }
    let c = Curve {
        keep_signs,
        full_output,
        scalar_first,
        max_frames,
        spring: SpringOptions {
            levels,
            iterations,
            step,
            penalty,
            width,
            key_weight,
            velocity_weight,
            start,
            solver,
            tolerance,
        },
        ..Curve::plain(preset, frames, timing)
    };
    curves(keys, times, &c)
}
