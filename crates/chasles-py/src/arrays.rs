//! Arrays in, arrays out: the machinery every function of the package shares.
//!
//! * [`wants_f32`] picks the precision of a call: float32 when the arrays given are float32,
//!   float64 otherwise (lists, integers, float64), as numpy would promote them.
//! * [`array`] reads an argument as a C-contiguous, aligned array of that type (`numpy.require`),
//!   naming the argument when it cannot.
//! * [`map`] checks each argument's trailing "core" shape (a quaternion's 4, a matrix's
//!   (4, 4)), broadcasts the leading dimensions as numpy does, allocates the output and
//!   runs the library once per item with the GIL released — on all cores (rayon) when the
//!   batch is large. A failing item raises `ValueError` with the library's message and the
//!   item's index; the first failing index is reported whatever the thread order.
//! * [`map_runs`] does the same for the library's batch functions (`quats_to_euler`,
//!   `dlb_batch`, …): when no argument is broadcast, each thread's share of the items is
//!   handed over as plain slices of the arrays — no index arithmetic and no call per item.
//! * Outputs are allocated by numpy's `empty`: every function writes every element of every
//!   item before it returns, and an array whose filling failed is never returned. (`zeros`
//!   clears outputs up to 32 MB, which glibc serves from memory it reuses: 0.4 ms for 10⁶
//!   Euler triples, 0.8 ms for 10⁶ quaternions on the development machine.)
//! * [`q_in`], [`q_out`] and friends read and write `[w, x, y, z]`, or scipy's
//!   `[x, y, z, w]` when `scalar_first` is false.

use chasles::{DualQuat, Quat, Real, Vec3};
use numpy::{Element, PyArrayDyn, PyArrayMethods, PyReadonlyArrayDyn, PyUntypedArrayMethods};
use pyo3::exceptions::{PyOSError, PyValueError};
use pyo3::intern;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyEllipsis, PySlice, PyTuple};
use rayon::prelude::*;

/// The element types a call runs in: `f32` and `f64`.
pub trait Num: Real + Element + Send + Sync + crate::simd::Dlb {}
impl Num for f32 {}
impl Num for f64 {}

/// Why one item failed: the library's message.
#[derive(Debug)]
pub struct Fail(pub String);

impl From<chasles::Error> for Fail {
    fn from(e: chasles::Error) -> Self {
        Fail(e.to_string())
    }
}

impl From<chasles_skin::SkinError> for Fail {
    fn from(e: chasles_skin::SkinError) -> Self {
        Fail(e.to_string())
    }
}

impl From<String> for Fail {
    fn from(e: String) -> Self {
        Fail(e)
    }
}

/// A `ValueError` with this message.
pub fn value_error(msg: impl Into<String>) -> PyErr {
    PyValueError::new_err(msg.into())
}

/// A skinning error as Python sees it: `OSError` for a file that cannot be read,
/// `ValueError` for everything else, with the library's message.
pub fn skin_error(e: chasles_skin::SkinError) -> PyErr {
    use chasles_skin::SkinError;
    match e {
        SkinError::Io { .. } | SkinError::NotAFile { .. } => PyOSError::new_err(e.to_string()),
        _ => value_error(e.to_string()),
    }
}

/// A library error as a `ValueError` with its message.
pub fn lib_error(e: chasles::Error) -> PyErr {
    value_error(e.to_string())
}

/// Whether a call with these arguments runs in float32: some argument is a float32 array
/// (or numpy float32 scalar) and no argument is an array of any other dtype. Lists and
/// Python numbers follow the arrays; without arrays the call runs in float64.
pub fn wants_f32(args: &[&Bound<'_, PyAny>]) -> PyResult<bool> {
    let mut seen = false;
    for a in args {
        let py = a.py();
        if a.is_none() {
            continue;
        }
        let Ok(dt) = a.getattr(intern!(py, "dtype")) else {
            continue;
        };
        let Ok(name) = dt.getattr(intern!(py, "name")) else {
            continue;
        };
        if name.extract::<String>().ok().as_deref() == Some("float32") {
            seen = true;
        } else {
            return Ok(false);
        }
    }
    Ok(seen)
}

/// Runs `$f::<f32>(…)` or `$f::<f64>(…)` by [`wants_f32`] of the arrays listed.
macro_rules! dispatch {
    ([$($a:expr),* $(,)?], $f:ident ( $($p:expr),* $(,)? )) => {
        if $crate::arrays::wants_f32(&[$($a),*])? {
            $f::<f32>($($p),*)
        } else {
            $f::<f64>($($p),*)
        }
    };
}
pub(crate) use dispatch;

/// A setting that must be positive and finite, checked: the error names it.
pub fn positive(what: &str, v: f64) -> PyResult<()> {
    if v > 0.0 && v.is_finite() {
        Ok(())
    } else {
        Err(value_error(format!(
            "{what} must be positive and finite, got {v}"
        )))
    }
}

/// The iterative methods' `precision` (positive and finite) and `max_iterations` (at most
/// 10 000: they converge in tens, and the cap bounds a call's time), checked.
pub fn check_iterations(precision: Option<f64>, max_iterations: Option<usize>) -> PyResult<()> {
    if let Some(p) = precision {
        positive("precision", p)?;
    }
    if let Some(n) = max_iterations {
        if n > 10_000 {
            return Err(value_error(format!(
                "max_iterations must be at most 10000 (the iterations converge in tens; a cap, not a goal), got {n}"
            )));
        }
    }
    Ok(())
}

/// A curve's frame count, checked: none (an empty output would skip every check of the
/// keys), or more than `max_frames`.
pub fn check_frames(frames: usize, max_frames: usize) -> PyResult<()> {
    if frames == 0 {
        return Err(value_error(
            "frames must be at least the number of keys, got 0",
        ));
    }
    if frames > max_frames {
        return Err(value_error(format!(
            "{frames} frames is more than max_frames={max_frames} (raise it to make longer curves)"
        )));
    }
    Ok(())
}

/// `obj` as a C-contiguous, aligned array of T (numpy's `require`); a `ValueError` naming
/// the argument when it is not numbers.
pub fn array<'py, T: Num>(
    obj: &Bound<'py, PyAny>,
    name: &str,
) -> PyResult<PyReadonlyArrayDyn<'py, T>> {
    let py = obj.py();
    let np = py.import(intern!(py, "numpy"))?;
    // C-contiguous, aligned (arrays unpickled from out-of-band buffers may not be) and a
    // base-class ndarray.
    let kw = PyDict::new(py);
    kw.set_item(intern!(py, "dtype"), numpy::dtype::<T>(py))?;
    kw.set_item(intern!(py, "requirements"), "CAE")?;
    let a = np
        .call_method(intern!(py, "require"), (obj,), Some(&kw))
        .map_err(|e| {
            value_error(format!(
                "{name}: cannot be read as an array of {}: {e}",
                type_name::<T>()
            ))
        })?;
    let a = a
        .cast_into::<PyArrayDyn<T>>()
        .map_err(|e| value_error(format!("{name}: {e}")))?;
    Ok(a.readonly())
}

/// "float32" or "float64".
pub fn type_name<T: Num>() -> &'static str {
    if T::EPSILON > T::from_f64(1e-10) {
        "float32"
    } else {
        "float64"
    }
}

/// `(3, 4)`, `(3,)`, `()`.
pub fn shape_text(s: &[usize]) -> String {
    match s {
        [] => "()".into(),
        [a] => format!("({a},)"),
        _ => format!(
            "({})",
            s.iter()
                .map(usize::to_string)
                .collect::<Vec<_>>()
                .join(", ")
        ),
    }
}

/// `(..., 4, 4)` for a core shape; `(...)` for none.
pub fn core_text(core: &[usize]) -> String {
    let mut parts = vec!["...".to_string()];
    parts.extend(core.iter().map(usize::to_string));
    format!("({})", parts.join(", "))
}

/// The leading dimensions of `shape`, whose trailing dimensions must be `core`.
pub fn leading<'a>(shape: &'a [usize], core: &[usize], name: &str) -> PyResult<&'a [usize]> {
    let n = shape.len();
    if n < core.len() || shape[n - core.len()..] != *core {
        return Err(value_error(format!(
            "{name} must have shape {}, got {}",
            core_text(core),
            shape_text(shape)
        )));
    }
    Ok(&shape[..n - core.len()])
}

/// numpy's broadcasting of the leading shapes; an error naming every argument's.
pub fn broadcast(leads: &[(&str, &[usize])]) -> PyResult<Vec<usize>> {
    let nd = leads.iter().map(|l| l.1.len()).max().unwrap_or(0);
    let mut out = vec![1usize; nd];
    for (_, s) in leads {
        for (k, &d) in s.iter().rev().enumerate() {
            let o = &mut out[nd - 1 - k];
            if *o == 1 {
                *o = d;
            } else if d != 1 && d != *o {
                let all: Vec<String> = leads
                    .iter()
                    .map(|(n, s)| format!("{n} {}", shape_text(s)))
                    .collect();
                return Err(value_error(format!(
                    "the leading dimensions do not broadcast together: {}",
                    all.join(", ")
                )));
            }
        }
    }
    Ok(out)
}

/// Where item i of the broadcast output reads its input.
#[derive(Debug, Clone)]
pub struct Index {
    dims: Vec<usize>,
    strides: Vec<usize>,
    kind: Kind,
}

#[derive(Debug, Clone, Copy)]
enum Kind {
    Same,
    One,
    General,
}

impl Index {
    /// For an input of leading shape `input` broadcast to `out`.
    pub fn new(input: &[usize], out: &[usize]) -> Self {
        let kind = if input == out {
            Kind::Same
        } else if input.iter().product::<usize>() == 1 {
            Kind::One
        } else {
            Kind::General
        };
        let pad = out.len() - input.len();
        let mut strides = vec![0; out.len()];
        let mut s = 1;
        for k in (0..input.len()).rev() {
            strides[pad + k] = if input[k] == 1 { 0 } else { s };
            s *= input[k];
        }
        Index {
            dims: out.to_vec(),
            strides,
            kind,
        }
    }
    /// Whether every output item `i` reads input item `i` (no broadcasting).
    pub fn is_identity(&self) -> bool {
        matches!(self.kind, Kind::Same)
    }
    /// The input item of output item `i`.
    #[inline]
    pub fn at(&self, mut i: usize) -> usize {
        match self.kind {
            Kind::Same => i,
            Kind::One => 0,
            Kind::General => {
                let mut off = 0;
                for k in (0..self.dims.len()).rev() {
                    let d = self.dims[k];
                    off += (i % d) * self.strides[k];
                    i /= d;
                }
                off
            }
        }
    }
}

/// The multi-index of item `i` in `dims`, as text: `(2, 5)`.
pub fn index_text(mut i: usize, dims: &[usize]) -> String {
    let mut idx = vec![0; dims.len()];
    for k in (0..dims.len()).rev() {
        idx[k] = i % dims[k].max(1);
        i /= dims[k].max(1);
    }
    shape_text(&idx)
}

/// One argument of [`map`]: its name, the array and its core (trailing) shape.
pub type Arg<'a, 'py, T> = (&'a str, &'a PyReadonlyArrayDyn<'py, T>, &'a [usize]);

/// Items below this many nanoseconds of work in all stay on the caller's thread.
const PARALLEL_NS: usize = 200_000;

/// Runs `f(i, out)` for every item `i` of `out` (items of `size` numbers), on all threads
/// when there are enough (`work`: rough nanoseconds an item); the failure of the lowest
/// index, if any.
pub fn for_items<T: Send>(
    out: &mut [T],
    size: usize,
    work: usize,
    f: &(impl Fn(usize, &mut [T]) -> Result<(), Fail> + Sync),
) -> Result<(), (usize, String)> {
    for_runs(out, size, work, 64, &|start, run: &mut [T]| {
        for (j, oi) in run.chunks_mut(size).enumerate() {
            f(start + j, oi).map_err(|e| (start + j, e.0))?;
        }
        Ok(())
    })
}

/// A failure at item `i` of a batch of leading shape `lead`, as a `ValueError`.
pub fn item_error(i: usize, msg: String, lead: &[usize]) -> PyErr {
    if lead.is_empty() {
        value_error(msg)
    } else {
        value_error(format!("at index {}: {msg}", index_text(i, lead)))
    }
}

/// What [`map`] and [`map_runs`] share: the checked and broadcast arguments and the
/// output, allocated.
struct Prepared<'a, 'py, T: Num, const N: usize> {
    lead: Vec<usize>,
    index: [Index; N],
    sizes: [usize; N],
    data: [&'a [T]; N],
    out: Bound<'py, PyArrayDyn<T>>,
    size: usize,
}

fn prepare<'a, 'py, T: Num, const N: usize>(
    py: Python<'py>,
    args: &[Arg<'a, 'py, T>; N],
    out_core: &[usize],
) -> PyResult<Prepared<'a, 'py, T, N>> {
    let mut leads = Vec::with_capacity(N);
    for (name, a, core) in args {
        leads.push((*name, leading(a.shape(), core, name)?));
    }
    let lead = broadcast(&leads)?;
    let index = std::array::from_fn(|k| Index::new(leads[k].1, &lead));
    let sizes = std::array::from_fn(|k| args[k].2.iter().product());
    let mut data = [&[][..]; N];
    for (d, a) in data.iter_mut().zip(args) {
        *d = a.1.as_slice().map_err(|e| value_error(e.to_string()))?;
    }
    let mut shape = lead.clone();
    shape.extend_from_slice(out_core);
    Ok(Prepared {
        lead,
        index,
        sizes,
        data,
        out: empty(py, &shape)?,
        size: out_core.iter().product(),
    })
}

/// `numpy.empty(shape, T)`: the callers write every element of every item before the array
/// is returned and read none before it is written (on a failure it is dropped unread).
pub fn empty<'py, T: Num>(py: Python<'py>, shape: &[usize]) -> PyResult<Bound<'py, PyArrayDyn<T>>> {
    let np = py.import(intern!(py, "numpy"))?;
    let a = np.call_method1(
        intern!(py, "empty"),
        (PyTuple::new(py, shape)?, numpy::dtype::<T>(py)),
    )?;
    Ok(a.cast_into::<PyArrayDyn<T>>()?)
}

/// Checks each argument's core shape, broadcasts their leading dimensions, allocates the
/// output (leading dimensions + `out_core`) and fills it item by item with `f(inputs,
/// out)`, the GIL released; `f` must write all of `out` when it succeeds. `work` is a rough
/// cost of one item in nanoseconds (it decides when to use all cores).
pub fn map<'py, T: Num, const N: usize>(
    py: Python<'py>,
    args: [Arg<'_, 'py, T>; N],
    out_core: &[usize],
    work: usize,
    f: impl Fn(&[&[T]; N], &mut [T]) -> Result<(), Fail> + Sync,
) -> PyResult<Bound<'py, PyArrayDyn<T>>> {
    let p = prepare(py, &args, out_core)?;
    {
        let mut rw = p.out.readwrite();
        let o = rw.as_slice_mut().map_err(|e| value_error(e.to_string()))?;
        let item = |i: usize, oi: &mut [T]| {
            let ins: [&[T]; N] = std::array::from_fn(|k| {
                let at = p.index[k].at(i) * p.sizes[k];
                &p.data[k][at..at + p.sizes[k]]
            });
            f(&ins, oi)
        };
        py.detach(|| for_items(o, p.size, work, &item))
            .map_err(|(i, m)| item_error(i, m, &p.lead))?;
    }
    Ok(p.out)
}

/// [`map`] for functions of runs of consecutive items (the library's batch functions):
/// `f(inputs, out)` gets each argument's numbers for some `k` items and the `k` items'
/// output, writes all of it when it succeeds, and otherwise returns the first failing
/// item's offset in the run with its message. When no argument is broadcast, each thread's
/// share of the batch is one run of plain slices of the arrays; otherwise `f` sees runs of
/// one item, gathered as [`map`] does.
pub fn map_runs<'py, T: Num, const N: usize>(
    py: Python<'py>,
    args: [Arg<'_, 'py, T>; N],
    out_core: &[usize],
    work: usize,
    f: impl Fn(&[&[T]; N], &mut [T]) -> Result<(), (usize, Fail)> + Sync,
) -> PyResult<Bound<'py, PyArrayDyn<T>>> {
    let p = prepare(py, &args, out_core)?;
    {
        let mut rw = p.out.readwrite();
        let o = rw.as_slice_mut().map_err(|e| value_error(e.to_string()))?;
        let result = if p.index.iter().all(Index::is_identity) {
            let run = |start: usize, oi: &mut [T]| {
                let count = oi.len() / p.size.max(1);
                let ins: [&[T]; N] = std::array::from_fn(|k| {
                    &p.data[k][start * p.sizes[k]..(start + count) * p.sizes[k]]
                });
                f(&ins, oi).map_err(|(j, e)| (start + j, e.0))
            };
            py.detach(|| for_runs(o, p.size, work, 1024, &run))
        } else {
            let item = |i: usize, oi: &mut [T]| {
                let ins: [&[T]; N] = std::array::from_fn(|k| {
                    let at = p.index[k].at(i) * p.sizes[k];
                    &p.data[k][at..at + p.sizes[k]]
                });
                f(&ins, oi).map_err(|(_, e)| e)
            };
            py.detach(|| for_items(o, p.size, work, &item))
        };
        result.map_err(|(i, m)| item_error(i, m, &p.lead))?;
    }
    Ok(p.out)
}

/// Runs `f(start, out)` over runs of consecutive items of `out` (items of `size` numbers;
/// `start` is the run's first item): one run on the caller's thread for small batches
/// (`work`: rough nanoseconds an item), else runs of an eighth of a thread's share (at
/// least `min_run` items) on all threads. The failure of the lowest index, if any.
fn for_runs<T: Send>(
    out: &mut [T],
    size: usize,
    work: usize,
    min_run: usize,
    f: &(impl Fn(usize, &mut [T]) -> Result<(), (usize, String)> + Sync),
) -> Result<(), (usize, String)> {
    let n = out.len() / size.max(1);
    if size == 0 || n == 0 {
        return Ok(());
    }
    let threads = rayon::current_num_threads();
    if threads > 1 && n.saturating_mul(work) >= PARALLEL_NS && n > 1 {
        let per = (n / (threads * 8)).max(min_run).min(n);
        out.par_chunks_mut(per * size)
            .enumerate()
            .filter_map(|(c, o)| f(c * per, o).err())
            .min_by_key(|e| e.0)
            .map_or(Ok(()), Err)
    } else {
        f(0, out)
    }
}

/// `a[..., start:end]`.
pub fn part<'py>(a: &Bound<'py, PyAny>, start: isize, end: isize) -> PyResult<Bound<'py, PyAny>> {
    let py = a.py();
    let key = PyTuple::new(
        py,
        [
            PyEllipsis::get(py).to_owned().into_any(),
            PySlice::new(py, start, end, 1).into_any(),
        ],
    )?;
    a.get_item(key)
}

/// `a[..., k]` as numpy's `dtype` (`"int64"`, `"bool_"`): a count or flag that travelled
/// in a float output.
pub fn column_as<'py>(a: &Bound<'py, PyAny>, k: isize, dtype: &str) -> PyResult<Bound<'py, PyAny>> {
    let np = a.py().import(intern!(a.py(), "numpy"))?;
    column(a, k)?.call_method1(intern!(a.py(), "astype"), (np.getattr(dtype)?,))
}

/// `a[..., k]`.
pub fn column<'py>(a: &Bound<'py, PyAny>, k: isize) -> PyResult<Bound<'py, PyAny>> {
    let py = a.py();
    let key = PyTuple::new(
        py,
        [
            PyEllipsis::get(py).to_owned().into_any(),
            k.into_pyobject(py)?.into_any(),
        ],
    )?;
    a.get_item(key)
}

/// A quaternion from 4 numbers, `[w, x, y, z]` or (not `sf`) `[x, y, z, w]`.
#[inline(always)]
pub fn q_in<T: Num>(s: &[T], sf: bool) -> Quat<T> {
    if sf {
        Quat::new(s[0], s[1], s[2], s[3])
    } else {
        Quat::new(s[3], s[0], s[1], s[2])
    }
}

/// Writes a quaternion as [`q_in`] reads it.
#[inline(always)]
pub fn q_out<T: Num>(q: Quat<T>, o: &mut [T], sf: bool) {
    if sf {
        o[..4].copy_from_slice(&[q.w, q.x, q.y, q.z]);
    } else {
        o[..4].copy_from_slice(&[q.x, q.y, q.z, q.w]);
    }
}

/// A dual quaternion from 8 numbers, each half as [`q_in`] reads it.
#[inline(always)]
pub fn dq_in<T: Num>(s: &[T], sf: bool) -> DualQuat<T> {
    DualQuat::new(q_in(&s[..4], sf), q_in(&s[4..8], sf))
}

/// Writes a dual quaternion as [`dq_in`] reads it.
#[inline(always)]
pub fn dq_out<T: Num>(d: DualQuat<T>, o: &mut [T], sf: bool) {
    q_out(d.real, &mut o[..4], sf);
    q_out(d.dual, &mut o[4..8], sf);
}

/// A vector from 3 numbers.
#[inline(always)]
pub fn v_in<T: Num>(s: &[T]) -> Vec3<T> {
    Vec3::new(s[0], s[1], s[2])
}

/// Writes a vector.
#[inline(always)]
pub fn v_out<T: Num>(v: Vec3<T>, o: &mut [T]) {
    o[..3].copy_from_slice(&[v.x, v.y, v.z]);
}

/// The library's `NonFinite` error unless every value is finite.
#[inline]
pub fn finite<T: Num>(values: &[T], what: &'static str) -> Result<(), Fail> {
    if values.iter().all(|v| v.is_finite()) {
        Ok(())
    } else {
        Err(chasles::Error::NonFinite { what }.into())
    }
}
