//! `chasles.Rig` and `chasles.Pose`, wrapping `chasles_skin::Rig` (loaded from glTF/glb,
//! the plain JSON format, bytes, or the built-in models of `chasles_models`) and
//! `chasles_skin::Pose` (clips sampled by the glTF rules). Both pickle, so they cross
//! processes (Dask): a rig as its bytes ([`crate::pickle`]), a pose as its arrays.
//!
//! `device="gpu"` skins through `chasles_skin::gpu::GpuSkinner` (wgpu compute shaders for
//! LBS, DQS and DIB, Kavan et al. §6's GPU implementation) — the mesh uploaded once per rig,
//! on the first call that asks for it, and the frames of a clip skinned one after another
//! on it; `device="auto"` takes a hardware GPU when there is one and the method has a
//! shader, the CPU otherwise, as `chasles skin --device auto`.

use crate::arrays::{array, skin_error, value_error};
use crate::skin::{
    device, frames_out, method, rig_from_arrays, skin_by_matrices, skin_into, Device, Layout,
};
use chasles::{Quat, Vec3};
use chasles_skin::gpu::GpuSkinner;
use chasles_skin::pose::skinning_matrices;
use chasles_skin::{gltf_load, joint_transforms, json_rig, Method, Pose, Rig, Trs};
use numpy::{
    PyArray1, PyArray2, PyArrayDyn, PyArrayMethods, PyReadonlyArrayDyn, PyUntypedArrayMethods,
};
use pyo3::prelude::*;
use pyo3::types::{PyBytes, PyType};
use std::path::PathBuf;
use std::sync::{Mutex, OnceLock};

/// `obj` as an int64 array; a `ValueError` unless its numbers are integers.
pub fn int_array<'py>(
    obj: &Bound<'py, PyAny>,
    name: &str,
) -> PyResult<PyReadonlyArrayDyn<'py, i64>> {
    let py = obj.py();
    let np = py.import("numpy")?;
    let a = np.call_method1("asarray", (obj,))?;
    let kind: String = a.getattr("dtype")?.getattr("kind")?.extract()?;
    if !matches!(kind.as_str(), "i" | "u") {
        let dt: String = a.getattr("dtype")?.getattr("name")?.extract()?;
        return Err(value_error(format!("{name} must be integers, got {dt}")));
    }
    let kw = pyo3::types::PyDict::new(py);
    kw.set_item("dtype", np.getattr("int64")?)?;
    kw.set_item("requirements", "CAE")?;
    let a = np.call_method("require", (a,), Some(&kw))?;
    Ok(a.cast_into::<PyArrayDyn<i64>>()?.readonly())
}

/// `pose` of `rig` skinned by `m` on the GPU `g` into `pos` and `nrm`; a vertex that is
/// not finite is an error, as on the CPU.
fn on_gpu(
    g: &Mutex<GpuSkinner>,
    rig: &Rig,
    pose: &Pose,
    m: Method,
    pos: &mut [[f32; 3]],
    nrm: &mut [[f32; 3]],
) -> Result<(), crate::arrays::Fail> {
    let jt = joint_transforms(rig, pose)?;
    let g = g
        .lock()
        .map_err(|_| "the GPU skinner was poisoned by an earlier panic".to_string())?;
    let s = g.skin(&jt, m).map_err(|e| e.to_string())?;
    for (i, (o, p)) in pos.iter_mut().zip(&s.positions).enumerate() {
        *o = p.to_array();
        if !o.iter().all(|x| x.is_finite()) {
            return Err(format!("vertex {i}: the GPU's skinned position is not finite").into());
        }
    }
    for (o, n) in nrm.iter_mut().zip(&s.normals) {
        *o = n.to_array();
    }
    Ok(())
}

/// The names of the built-in models (``CesiumMan``, ``Fox``, …): real rigged characters
/// (Khronos glTF samples) compiled into the package; load one with :meth:`Rig.model`.
/// Each carries its licence and credit, to be shown with any picture of it (CesiumMan:
/// CC-BY 4.0 with trademark limitations, © 2017 Cesium; see crates/chasles-models/README.md).
///
/// >>> import chasles
/// >>> "CesiumMan" in chasles.models()
/// True
#[pyfunction]
pub fn models() -> Vec<&'static str> {
    chasles_models::ALL.iter().map(|m| m.stem()).collect()
}

/// The file bytes of a built-in model (``.glb``, or ``.gltf`` with embedded buffers), to
/// write it to disk for tools that take paths (``chasles skin --rig``).
///
/// >>> import chasles
/// >>> chasles.model_bytes("CesiumMan")[:4]
/// b'glTF'
#[pyfunction]
pub fn model_bytes<'py>(py: Python<'py>, name: &str) -> PyResult<Bound<'py, PyBytes>> {
    Ok(PyBytes::new(py, model(name)?.bytes))
}

fn model(name: &str) -> PyResult<&'static chasles_models::Model> {
    chasles_models::ALL
        .iter()
        .find(|m| m.stem() == name || m.file == name)
        .ok_or_else(|| {
            value_error(format!(
                "no built-in model '{name}': {}",
                models().join(", ")
            ))
        })
}

/// A rigged mesh: bind-pose vertices, a node hierarchy with a skin (joints, inverse bind
/// matrices), up to any number of influences per vertex, and animation clips.
///
/// Make one with :meth:`Rig.load` (``.gltf``, ``.glb`` or the plain ``.json`` format),
/// :meth:`Rig.model` (the built-in characters) or :meth:`Rig.from_bytes`. Rigs pickle.
///
/// >>> import chasles
/// >>> rig = chasles.Rig.model("CesiumMan")
/// >>> rig.vertex_count, rig.joint_count, rig.clips
/// (3273, 19, ['0'])
#[pyclass(name = "Rig", module = "chasles", frozen)]
pub struct PyRig {
    /// The rig.
    pub rig: Rig,
    /// Laid out for skinning.
    pub layout: Layout,
    /// The mesh on the GPU, made by the first call that asks for it (the reason when
    /// there is no adapter); not pickled.
    gpu: OnceLock<Result<Mutex<GpuSkinner>, String>>,
}

/// The methods with a GPU shader.
fn has_shader(m: Method) -> bool {
    matches!(m, Method::Lbs | Method::Dqs | Method::Dib)
}

impl PyRig {
    fn of(rig: Rig) -> PyResult<Self> {
        let layout = Layout::of(&rig).map_err(skin_error)?;
        Ok(PyRig {
            rig,
            layout,
            gpu: OnceLock::new(),
        })
    }

    /// The GPU to skin on by `m` under `device`: None for the CPU; a `ValueError` when
    /// the GPU was asked for and cannot be had (no adapter, or no shader for `m`).
    fn gpu(
        &self,
        py: Python<'_>,
        device: Device,
        m: Method,
    ) -> PyResult<Option<&Mutex<GpuSkinner>>> {
        if device == Device::Cpu || (device == Device::Auto && !has_shader(m)) {
            return Ok(None);
        }
        if !has_shader(m) {
            return Err(value_error(format!(
                "device='gpu': {} has no GPU path (lbs, dqs and dib do); use device='cpu'",
                m.name()
            )));
        }
        let made = self.gpu.get_or_init(|| {
            py.detach(|| {
                GpuSkinner::new(&self.rig)
                    .map(Mutex::new)
                    .map_err(|e| e.to_string())
            })
        });
        match (made, device) {
            (Ok(g), Device::Gpu) => Ok(Some(g)),
            (Ok(g), _) => {
                let software = g.lock().map_or(true, |g| g.is_software());
                Ok((!software).then_some(g))
            }
            (Err(e), Device::Gpu) => Err(value_error(format!("device='gpu': {e}"))),
            (Err(_), _) => Ok(None),
        }
    }

    /// The adapter's name when skinning by `method` under `device` runs on a GPU.
    fn adapter_of(&self, py: Python<'_>, device: Device, m: Method) -> PyResult<Option<String>> {
        Ok(self
            .gpu(py, device, m)?
            .and_then(|g| g.lock().ok().map(|g| g.adapter().to_string())))
    }

    /// A clip by index (int), name, or index as text; the first when None.
    fn clip(&self, clip: Option<&Bound<'_, PyAny>>) -> PyResult<usize> {
        let r = &self.rig;
        let names = || r.clip_list();
        let Some(c) = clip else {
            if r.animations.is_empty() {
                return Err(value_error(format!("{}: has no animations", r.name)));
            }
            return Ok(0);
        };
        if let Ok(i) = c.extract::<i64>() {
            return usize::try_from(i)
                .ok()
                .filter(|i| *i < r.animations.len())
                .ok_or_else(|| {
                    value_error(format!(
                        "{}: no animation {i}; there are: {}",
                        r.name,
                        names()
                    ))
                });
        }
        let a: String = c
            .extract()
            .map_err(|_| value_error("clip must be a name or an index"))?;
        r.clip_index(&a).map_err(|_| {
            value_error(format!(
                "{}: no animation '{a}'; there are: {}",
                r.name,
                names()
            ))
        })
    }

    /// The pose asked for: a Pose, or clip/time (the rest pose when neither is given).
    fn chosen(
        &self,
        pose: Option<PyRef<'_, PyPose>>,
        clip: Option<&Bound<'_, PyAny>>,
        time: Option<f32>,
    ) -> PyResult<Pose> {
        match (pose, clip, time) {
            (Some(_), Some(_), _) | (Some(_), _, Some(_)) => {
                Err(value_error("give either pose or clip/time, not both"))
            }
            (Some(p), None, None) => Ok(p.pose.clone()),
            (None, None, None) => Ok(Pose::rest(&self.rig)),
            (None, c, t) => {
                let c = self.clip(c)?;
                Pose::animated(&self.rig, c, t.unwrap_or(0.0)).map_err(skin_error)
            }
        }
    }
}

fn vec3_array<'py>(py: Python<'py>, v: &[Vec3<f32>]) -> PyResult<Bound<'py, PyArray2<f32>>> {
    let flat: Vec<f32> = v.iter().flat_map(|p| p.to_array()).collect();
    PyArray1::from_vec(py, flat).reshape([v.len(), 3])
}

#[pymethods]
impl PyRig {
    /// Loads a rig from a ``.gltf`` (embedded or external buffers), ``.glb`` or ``.json``
    /// file (by extension). A file that cannot be read raises ``OSError``; a bad rig
    /// ``ValueError`` naming the file and the item.
    ///
    /// >>> import chasles, pathlib, tempfile
    /// >>> path = pathlib.Path(tempfile.mkdtemp()) / "CesiumMan.glb"
    /// >>> _ = path.write_bytes(chasles.model_bytes("CesiumMan"))
    /// >>> chasles.Rig.load(path).name
    /// 'CesiumMan.glb'
    #[classmethod]
    fn load(_cls: &Bound<'_, PyType>, py: Python<'_>, path: PathBuf) -> PyResult<Self> {
        let rig = py
            .detach(|| chasles_skin::load(&path))
            .map_err(skin_error)?;
        Self::of(rig)
    }

    /// A built-in model by name (see :func:`models`).
    ///
    /// >>> import chasles
    /// >>> chasles.Rig.model("Fox").clips
    /// ['Survey', 'Walk', 'Run']
    #[classmethod]
    fn model(_cls: &Bound<'_, PyType>, name: &str) -> PyResult<Self> {
        let m = model(name)?;
        Self::of(gltf_load::load_slice(m.bytes, m.file).map_err(skin_error)?)
    }

    /// A rig from the bytes of a ``.glb``, a ``.gltf`` with embedded buffers, or (``name``
    /// ending in ``.json``) the plain JSON format; ``name`` names it in messages.
    ///
    /// >>> import chasles
    /// >>> chasles.Rig.from_bytes(chasles.model_bytes("RiggedSimple"), "RiggedSimple.glb").joint_count
    /// 2
    #[classmethod]
    #[pyo3(signature = (data, name = "rig.glb"))]
    fn from_bytes(_cls: &Bound<'_, PyType>, data: &[u8], name: &str) -> PyResult<Self> {
        let rig = if name.to_ascii_lowercase().ends_with(".json") {
            let text = std::str::from_utf8(data)
                .map_err(|_| value_error(format!("{name}: not UTF-8 text")))?;
            json_rig::parse_rig(text, name)
        } else {
            gltf_load::load_slice(data, name)
        };
        Self::of(rig.map_err(skin_error)?)
    }

    /// A rig of your own arrays, laid out for skinning once: ``positions`` and ``normals``
    /// (V, 3) bind-pose vertices, ``joints`` (V, K) integer joint indices and ``weights``
    /// (V, K) their weights (checked as :func:`skin` checks them), ``centres`` (J, 3) the
    /// joints' bind-pose origins (about which QLB and SBS blend rotations; default the
    /// origin). J is ``joint_count`` when given, else the number of centres, else the
    /// largest joint index of positive weight plus one (indices of weight 0 are padding).
    /// Each joint is a root node with the identity rest transform; there are no triangles
    /// and no clips. Skin it by joint matrices with :meth:`skin_with`: :func:`skin` does the
    /// same but lays the rig out again on every call. Named ``name`` in messages; pickles as
    /// any rig.
    ///
    /// >>> import chasles, numpy as np
    /// >>> p = np.array([[1.0, 0.0, 0.0]]); n = np.array([[0.0, 0.0, 1.0]])
    /// >>> rig = chasles.Rig.from_arrays(p, n, [[0, 1]], [[0.5, 0.5]])
    /// >>> rig.vertex_count, rig.joint_count
    /// (1, 2)
    #[classmethod]
    #[pyo3(signature = (positions, normals, joints, weights, *, centres = None,
        joint_count = None, name = "arrays"))]
    #[allow(clippy::too_many_arguments)]
    fn from_arrays(
        _cls: &Bound<'_, PyType>,
        positions: &Bound<'_, PyAny>,
        normals: &Bound<'_, PyAny>,
        joints: &Bound<'_, PyAny>,
        weights: &Bound<'_, PyAny>,
        centres: Option<&Bound<'_, PyAny>>,
        joint_count: Option<i64>,
        name: &str,
    ) -> PyResult<Self> {
        let joint_count = joint_count
            .map(|n| {
                usize::try_from(n)
                    .map_err(|_| value_error(format!("joint_count must be 0 or more, got {n}")))
            })
            .transpose()?;
        let rig = rig_from_arrays(
            positions,
            normals,
            joints,
            weights,
            centres,
            joint_count,
            name,
        )?;
        Self::of(rig)
    }

    /// A rig from its pickled bytes (what pickling calls).
    #[classmethod]
    fn _from_state(_cls: &Bound<'_, PyType>, state: &[u8]) -> PyResult<Self> {
        Self::of(crate::pickle::rig_from_bytes(state).map_err(value_error)?)
    }

    fn __reduce__<'py>(
        slf: &Bound<'py, Self>,
    ) -> PyResult<(Bound<'py, PyAny>, (Bound<'py, PyBytes>,))> {
        let py = slf.py();
        let f = slf.get_type().getattr("_from_state")?;
        let bytes = crate::pickle::rig_to_bytes(&slf.get().rig);
        Ok((f, (PyBytes::new(py, &bytes),)))
    }

    fn __repr__(&self) -> String {
        let r = &self.rig;
        format!(
            "Rig('{}': {} vertices, {} joints, {} clips)",
            r.name,
            r.mesh.positions.len(),
            r.joints.len(),
            r.animations.len()
        )
    }

    /// The rig's name (its file name).
    #[getter]
    fn name(&self) -> &str {
        &self.rig.name
    }
    /// The clips' names (their index as text when unnamed).
    #[getter]
    fn clips(&self) -> Vec<String> {
        self.rig.clip_names()
    }
    /// The joints' node names, in skin order.
    #[getter]
    fn joint_names(&self) -> Vec<String> {
        self.rig
            .joints
            .iter()
            .map(|n| self.rig.nodes[*n].name.clone())
            .collect()
    }
    /// Every node's name (a pose has one transform per node).
    #[getter]
    fn node_names(&self) -> Vec<String> {
        self.rig.nodes.iter().map(|n| n.name.clone()).collect()
    }
    /// Number of vertices.
    #[getter]
    fn vertex_count(&self) -> usize {
        self.rig.mesh.positions.len()
    }
    /// Number of joints.
    #[getter]
    fn joint_count(&self) -> usize {
        self.rig.joints.len()
    }
    /// Bind-pose positions (V, 3), float32.
    #[getter]
    fn positions<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f32>>> {
        vec3_array(py, &self.rig.mesh.positions)
    }
    /// Bind-pose unit normals (V, 3), float32.
    #[getter]
    fn normals<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f32>>> {
        vec3_array(py, &self.rig.mesh.normals)
    }
    /// Triangles (T, 3) as vertex indices, uint32.
    #[getter]
    fn triangles<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<u32>>> {
        let t = &self.rig.mesh.triangles;
        PyArray1::from_vec(py, t.iter().flatten().copied().collect()).reshape([t.len(), 3])
    }
    /// The inverse bind matrices (J, 4, 4), float32.
    #[getter]
    fn inverse_bind<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let ib = &self.rig.inverse_bind;
        let flat: Vec<f32> = ib.iter().flat_map(|m| m.to_row_major()).collect();
        Ok(PyArray1::from_vec(py, flat)
            .reshape([ib.len(), 4, 4])?
            .into_any())
    }
    /// The influences padded to the most any vertex has (K): joint indices (V, K) int64
    /// and weights (V, K) float32 (summing to 1, heaviest first; padding has weight 0).
    ///
    /// >>> import chasles
    /// >>> j, w = chasles.Rig.model("CesiumMan").influences()
    /// >>> j.shape, w.dtype
    /// ((3273, 4), dtype('float32'))
    fn influences<'py>(&self, py: Python<'py>) -> PyResult<(Bound<'py, PyAny>, Bound<'py, PyAny>)> {
        let inf = &self.rig.influences;
        let (v, k) = (inf.vertices(), inf.max_per_vertex());
        let mut j = vec![0i64; v * k];
        let mut w = vec![0f32; v * k];
        for x in 0..v {
            for (s, (jj, ww)) in inf.of(x).enumerate() {
                j[x * k + s] = jj as i64;
                w[x * k + s] = ww;
            }
        }
        Ok((
            PyArray1::from_vec(py, j).reshape([v, k])?.into_any(),
            PyArray1::from_vec(py, w).reshape([v, k])?.into_any(),
        ))
    }
    /// The vertex order that groups the vertices by influence count (V,), int64: entry i
    /// is the vertex that comes i-th. Each window of 256 vertices is sorted by how many
    /// influences its vertices have (1, 2, 3, 4, …), rising and falling in turn, so
    /// that fewer of DIB's SIMD blocks pay for its iteration; :meth:`reordered` applies it.
    /// (The CPU's fast path groups DIB's vertices so by itself, on a copy; a rig reordered
    /// once needs no copy.)
    ///
    /// >>> import chasles
    /// >>> rig = chasles.Rig.model("Fox")
    /// >>> order = rig.vertex_order()
    /// >>> order.shape, sorted(order.tolist()) == list(range(rig.vertex_count))
    /// ((1728,), True)
    fn vertex_order<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray1<i64>>> {
        let order =
            chasles_skin::vertex_order::by_influence_count(&self.rig).map_err(skin_error)?;
        Ok(PyArray1::from_vec(
            py,
            order.into_iter().map(i64::from).collect(),
        ))
    }
    /// This rig with its vertices in ``order`` (entry i the vertex that becomes vertex i, as
    /// :meth:`vertex_order` gives it): positions, normals and influences moved, the
    /// triangles renumbered, the skeleton and clips as they are. Skinning it gives each
    /// vertex the same result at its new index. A ``ValueError`` unless ``order`` names
    /// each vertex once.
    ///
    /// >>> import chasles, numpy as np
    /// >>> rig = chasles.Rig.model("Fox")
    /// >>> order = rig.vertex_order()
    /// >>> p, _ = rig.skin(method="dib", time=0.5)
    /// >>> q, _ = rig.reordered(order).skin(method="dib", time=0.5)
    /// >>> bool(np.array_equal(q, p[order]))
    /// True
    fn reordered(&self, order: &Bound<'_, PyAny>) -> PyResult<PyRig> {
        let a = int_array(order, "order")?;
        if a.ndim() != 1 {
            return Err(value_error(format!(
                "order must have shape (V,), got {}",
                crate::arrays::shape_text(a.shape())
            )));
        }
        let o = a
            .as_slice()
            .map_err(|e| value_error(e.to_string()))?
            .iter()
            .enumerate()
            .map(|(i, &v)| {
                u32::try_from(v).map_err(|_| {
                    value_error(format!("order: entry {i} is {v}, not a vertex index"))
                })
            })
            .collect::<PyResult<Vec<u32>>>()?;
        PyRig::of(self.rig.reordered(&o).map_err(skin_error)?)
    }
    /// The length in seconds of a clip (by index or name; the first by default).
    ///
    /// >>> import chasles
    /// >>> round(chasles.Rig.model("CesiumMan").duration(), 3)
    /// 2.0
    #[pyo3(signature = (clip = None))]
    fn duration(&self, clip: Option<&Bound<'_, PyAny>>) -> PyResult<f32> {
        Ok(self.rig.animations[self.clip(clip)?].duration())
    }
    /// A pose: clip ``clip`` (index or name; the first when only ``time`` is given) at
    /// ``time`` seconds (default 0), sampled by the glTF rules; the rest pose when neither
    /// is given.
    ///
    /// >>> import chasles
    /// >>> rig = chasles.Rig.model("CesiumMan")
    /// >>> len(rig.pose(0, 0.5)) == len(rig.node_names)
    /// True
    #[pyo3(signature = (clip = None, time = None))]
    fn pose(&self, clip: Option<&Bound<'_, PyAny>>, time: Option<f32>) -> PyResult<PyPose> {
        Ok(PyPose {
            pose: self.chosen(None, clip, time)?,
        })
    }
    /// The skinning matrices ``C_j = World(joint_j) · InverseBind_j`` (J, 4, 4), float32, of
    /// a pose — what :func:`chasles.skin` takes as ``joint_matrices``.
    ///
    /// >>> import chasles
    /// >>> rig = chasles.Rig.model("CesiumMan")
    /// >>> rig.skinning_matrices(rig.pose(0, 0.5)).shape
    /// (19, 4, 4)
    fn skinning_matrices<'py>(
        &self,
        py: Python<'py>,
        pose: PyRef<'_, PyPose>,
    ) -> PyResult<Bound<'py, PyAny>> {
        let m = skinning_matrices(&self.rig, &pose.pose).map_err(skin_error)?;
        let flat: Vec<f32> = m.iter().flat_map(|m| m.to_row_major()).collect();
        Ok(PyArray1::from_vec(py, flat)
            .reshape([m.len(), 4, 4])?
            .into_any())
    }
    /// Where :meth:`skin` and :meth:`skin_clip` run for ``method`` under ``device``:
    /// ``"cpu"``, or the GPU adapter's name (``device="gpu"`` raises ``ValueError`` with
    /// the reason when there is no adapter or the method has no shader; ``"auto"`` takes a
    /// hardware GPU for ``lbs``, ``dqs`` and ``dib``, else the CPU).
    ///
    /// >>> import chasles
    /// >>> chasles.Rig.model("CesiumMan").skinning_device("sbs", "auto")
    /// 'cpu'
    #[pyo3(signature = (method = "dqs", device = "auto"))]
    fn skinning_device(&self, py: Python<'_>, method: &str, device: &str) -> PyResult<String> {
        let m = self::method(method)?;
        Ok(self
            .adapter_of(py, self::device(device)?, m)?
            .unwrap_or_else(|| "cpu".into()))
    }
    /// Skins one pose: ``pose`` (a :class:`Pose`), or ``clip``/``time`` as
    /// :meth:`pose` takes them (the rest pose when none is given), by ``method`` (``lbs``,
    /// ``dqs``, ``dib``, ``log``, ``qlb``, ``sbs``) — the numbers of ``chasles skin
    /// --device cpu`` — on ``device`` ``"cpu"`` (the default), ``"gpu"`` (LBS, DQS, DIB by
    /// compute shaders, any adapter; ``ValueError`` when there is none) or ``"auto"`` (see
    /// :meth:`skinning_device`). Returns float32 ``(positions, normals)``, each (V, 3).
    ///
    /// >>> import chasles
    /// >>> pos, nrm = chasles.Rig.model("CesiumMan").skin(clip=0, time=0.5, method="dqs")
    /// >>> pos.shape, nrm.dtype
    /// ((3273, 3), dtype('float32'))
    #[pyo3(signature = (pose = None, method = "dqs", device = "cpu", *, clip = None, time = None))]
    fn skin<'py>(
        &self,
        py: Python<'py>,
        pose: Option<PyRef<'_, PyPose>>,
        method: &str,
        device: &str,
        clip: Option<&Bound<'_, PyAny>>,
        time: Option<f32>,
    ) -> PyResult<(Bound<'py, PyAny>, Bound<'py, PyAny>)> {
        let m = self::method(method)?;
        let gpu = self.gpu(py, self::device(device)?, m)?;
        let pose = self.chosen(pose, clip, time)?;
        let v = self.rig.mesh.positions.len();
        frames_out(py, &[], v, |_, p, n, parallel| {
            if let Some(g) = gpu {
                return on_gpu(g, &self.rig, &pose, m, p, n);
            }
            let mats = skinning_matrices(&self.rig, &pose)?;
            Ok(skin_into(
                &self.rig,
                &self.layout,
                &mats,
                m,
                p,
                n,
                parallel,
            )?)
        })
    }
    /// Skins by your own skinning matrices ``joint_matrices`` (..., J, 4, 4), ``C_j =
    /// World_j · InverseBind_j`` of one pose or of a batch of poses (J the rig's joints),
    /// by ``method`` on the CPU, through the layout made when the rig was — the numbers of
    /// :func:`skin` on the same arrays, and of :meth:`skin` where the matrices are
    /// :meth:`skinning_matrices`'. A batch's poses run one per task on all cores. Returns
    /// float32 ``(positions, normals)`` of shape (..., V, 3).
    ///
    /// >>> import chasles, numpy as np
    /// >>> rig = chasles.Rig.model("CesiumMan")
    /// >>> m = rig.skinning_matrices(rig.pose(0, 0.5))
    /// >>> pos, nrm = rig.skin_with(m, "dib")
    /// >>> bool(np.array_equal(pos, rig.skin(clip=0, time=0.5, method="dib")[0]))
    /// True
    /// >>> rig.skin_with(np.stack([m, m, m]))[0].shape
    /// (3, 3273, 3)
    #[pyo3(signature = (joint_matrices, method = "dqs"))]
    fn skin_with<'py>(
        &self,
        joint_matrices: &Bound<'py, PyAny>,
        method: &str,
    ) -> PyResult<(Bound<'py, PyAny>, Bound<'py, PyAny>)> {
        let m = self::method(method)?;
        let mats = array::<f32>(joint_matrices, "joint_matrices")?;
        skin_by_matrices(joint_matrices.py(), &self.rig, &self.layout, &mats, m)
    }
    /// Skins a whole clip at ``fps`` frames a second — ``floor(duration · fps) + 1``
    /// frames at ``t = f / fps``, as ``chasles skin --all-frames`` — or at the given
    /// ``times`` (seconds), one frame per task on all cores (one after another on the GPU
    /// with ``device="gpu"``, see :meth:`skin`). Returns float32
    /// ``(positions, normals)``, each (F, V, 3). ``max_frames`` is a ceiling against a clip
    /// that lasts a week.
    ///
    /// >>> import chasles
    /// >>> pos, nrm = chasles.Rig.model("CesiumMan").skin_clip(0, fps=10, method="lbs")
    /// >>> pos.shape
    /// (21, 3273, 3)
    #[pyo3(signature = (clip = None, fps = 30.0, method = "dqs", *, times = None, device = "cpu",
        max_frames = 10_000))]
    #[allow(clippy::too_many_arguments)]
    fn skin_clip<'py>(
        &self,
        py: Python<'py>,
        clip: Option<&Bound<'_, PyAny>>,
        fps: f32,
        method: &str,
        times: Option<&Bound<'py, PyAny>>,
        device: &str,
        max_frames: usize,
    ) -> PyResult<(Bound<'py, PyAny>, Bound<'py, PyAny>)> {
        let m = self::method(method)?;
        let gpu = self.gpu(py, self::device(device)?, m)?;
        let c = self.clip(clip)?;
        let ts: Vec<f32> = match times {
            Some(t) => {
                let t = array::<f32>(t, "times")?;
                if t.ndim() != 1 {
                    return Err(value_error(format!(
                        "times must have shape (F,), got {}",
                        crate::arrays::shape_text(t.shape())
                    )));
                }
                t.as_slice()
                    .map_err(|e| value_error(e.to_string()))?
                    .to_vec()
            }
            None => {
                if !(fps > 0.0 && fps.is_finite() && fps <= 1000.0) {
                    return Err(value_error(format!("fps must be in (0, 1000], got {fps}")));
                }
                let duration = self.rig.animations[c].duration();
                let n = (f64::from(duration) * f64::from(fps)).floor() + 1.0;
                if !n.is_finite() || n > max_frames as f64 {
                    return Err(value_error(format!(
                        "clip {c} lasts {duration} s, {n} frames at {fps} fps: more than max_frames={max_frames}"
                    )));
                }
                (0..n as usize).map(|f| f as f32 / fps).collect()
            }
        };
        if ts.len() > max_frames {
            return Err(value_error(format!(
                "{} times: more than max_frames={max_frames}",
                ts.len()
            )));
        }
        let v = self.rig.mesh.positions.len();
        frames_out(py, &[ts.len()], v, |f, p, n, parallel| {
            let pose = Pose::animated(&self.rig, c, ts[f])?;
            if let Some(g) = gpu {
                return on_gpu(g, &self.rig, &pose, m, p, n);
            }
            let mats = skinning_matrices(&self.rig, &pose)?;
            Ok(skin_into(
                &self.rig,
                &self.layout,
                &mats,
                m,
                p,
                n,
                parallel,
            )?)
        })
    }
}

/// A pose of a rig: the local transform (translation, rotation, scale) of every node.
///
/// Made by :meth:`Rig.pose`, or from arrays: ``translations`` (N, 3), ``rotations``
/// (N, 4) quaternions (``[w, x, y, z]``; ``scalar_first=False``: ``[x, y, z, w]``; any
/// non-zero length) and ``scales`` (N, 3, default ones), N the rig's node count. Poses
/// pickle.
///
/// >>> import chasles, numpy as np
/// >>> rig = chasles.Rig.model("RiggedSimple")
/// >>> p = rig.pose(0, 1.0)
/// >>> q = chasles.Pose(p.translations, p.rotations, p.scales)
/// >>> bool(np.array_equal(q.rotations, p.rotations))
/// True
#[pyclass(name = "Pose", module = "chasles", frozen)]
pub struct PyPose {
    /// The pose.
    pub pose: Pose,
}

#[pymethods]
impl PyPose {
    #[new]
    #[pyo3(signature = (translations, rotations, scales = None, *, scalar_first = true))]
    fn new(
        translations: &Bound<'_, PyAny>,
        rotations: &Bound<'_, PyAny>,
        scales: Option<&Bound<'_, PyAny>>,
        scalar_first: bool,
    ) -> PyResult<Self> {
        let t = array::<f32>(translations, "translations")?;
        let r = array::<f32>(rotations, "rotations")?;
        let n = t.shape().first().copied().unwrap_or(0);
        let check = |a: &PyReadonlyArrayDyn<'_, f32>, name: &str, k: usize| {
            if a.shape() != [n, k] {
                return Err(value_error(format!(
                    "{name} must have shape ({n}, {k}), got {}",
                    crate::arrays::shape_text(a.shape())
                )));
            }
            Ok(())
        };
        check(&t, "translations", 3)?;
        check(&r, "rotations", 4)?;
        let s = scales.map(|s| array::<f32>(s, "scales")).transpose()?;
        if let Some(s) = &s {
            check(s, "scales", 3)?;
        }
        let sl = |a: &PyReadonlyArrayDyn<'_, f32>| {
            a.as_slice()
                .map(|s| s.to_vec())
                .map_err(|e| value_error(e.to_string()))
        };
        let (t, r) = (sl(&t)?, sl(&r)?);
        let s = s.as_ref().map(sl).transpose()?;
        let mut local = Vec::with_capacity(n);
        for i in 0..n {
            let q = crate::arrays::q_in(&r[4 * i..4 * i + 4], scalar_first);
            let v = |a: &[f32]| Vec3::new(a[3 * i], a[3 * i + 1], a[3 * i + 2]);
            let tr = Trs {
                translation: v(&t),
                rotation: q,
                scale: s.as_deref().map_or(Vec3::new(1.0, 1.0, 1.0), v),
            };
            let ok = q.normalize().is_ok() && tr.translation.is_finite() && tr.scale.is_finite();
            if !ok {
                return Err(value_error(format!(
                    "node {i}: the transform is not finite or its rotation is zero"
                )));
            }
            local.push(tr);
        }
        Ok(PyPose {
            pose: Pose { local },
        })
    }

    /// Node translations (N, 3), float32.
    #[getter]
    fn translations<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f32>>> {
        let v: Vec<Vec3<f32>> = self.pose.local.iter().map(|t| t.translation).collect();
        vec3_array(py, &v)
    }
    /// Node rotations (N, 4) ``[w, x, y, z]``, float32.
    #[getter]
    fn rotations<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f32>>> {
        let q: Vec<f32> = self
            .pose
            .local
            .iter()
            .flat_map(|t| Quat::to_array(t.rotation))
            .collect();
        PyArray1::from_vec(py, q).reshape([self.pose.local.len(), 4])
    }
    /// Node scales (N, 3), float32.
    #[getter]
    fn scales<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f32>>> {
        let v: Vec<Vec3<f32>> = self.pose.local.iter().map(|t| t.scale).collect();
        vec3_array(py, &v)
    }
    fn __len__(&self) -> usize {
        self.pose.local.len()
    }
    fn __repr__(&self) -> String {
        format!("Pose({} nodes)", self.pose.local.len())
    }
    fn __eq__(&self, other: &Bound<'_, PyAny>) -> bool {
        other
            .cast::<PyPose>()
            .is_ok_and(|o| o.get().pose == self.pose)
    }
    fn __reduce__<'py>(slf: &Bound<'py, Self>) -> PyResult<(Bound<'py, PyAny>, Bound<'py, PyAny>)> {
        let py = slf.py();
        let me = slf.get();
        let args = (me.translations(py)?, me.rotations(py)?, me.scales(py)?);
        Ok((
            slf.get_type().into_any(),
            args.into_pyobject(py)?.into_any(),
        ))
    }
}
