//! Skinning, wrapping `chasles_skin` (Kavan et al. 2006, §6): every pose goes through the
//! typed fast job — a rig laid out once (`fast::FastRig`, 4 or 8 influences), the
//! method's `fast::Palette` made from the pose's skinning matrices, and a
//! `fast::SkinningJob` writing straight into the numpy output (`fast::Output::Split`) —
//! the path `chasles skin --device cpu` takes (`fast::Skinner`), so the numbers are the
//! same; a rig with more than 8 influences on a vertex takes the reference path
//! (`skinning::skin_joints`), as the CLI's does. Whole clips are skinned one frame per
//! task on all cores; users' own arrays (positions, normals, joints, weights, joint
//! matrices) are made into a checked `Rig` first ([`rig_from_arrays`]): by [`skin`] on every
//! call, or once by `Rig.from_arrays`, whose `Rig.skin_with` then skins it by joint
//! matrices through the layout made with it ([`skin_by_matrices`], the same numbers).

use crate::arrays::{array, item_error, leading, value_error, Fail};
use chasles::{Mat4, Vec3};
use chasles_skin::fast::{FastRig, Output, Palette, SkinningJob};
use chasles_skin::pose::rigid_of;
use chasles_skin::{skin_joints, Influences, JointTransforms, Mesh, Method, Node, Rig, SkinError};
use numpy::{PyArrayDyn, PyArrayMethods, PyReadonlyArrayDyn, PyUntypedArrayMethods};
use pyo3::prelude::*;

/// A rig laid out for skinning: the fast path's layout, or the reference path for more
/// than 8 influences on a vertex (as `fast::Skinner` chooses).
#[derive(Debug)]
pub enum Layout {
    /// Up to 4 influences.
    Four(FastRig<4>),
    /// Up to 8.
    Eight(FastRig<8>),
    /// More: the reference path.
    Reference,
}

impl Layout {
    /// The layout of `rig`.
    pub fn of(rig: &Rig) -> Result<Self, SkinError> {
        Ok(match rig.influences.max_per_vertex() {
            0..=4 => Layout::Four(FastRig::new(rig)?),
            5..=8 => Layout::Eight(FastRig::new(rig)?),
            _ => Layout::Reference,
        })
    }
}

/// The method of a `chasles skin` name.
pub fn method(name: &str) -> PyResult<Method> {
    Method::from_name(name).ok_or_else(|| {
        let all: Vec<&str> = Method::ALL.iter().map(|m| m.name()).collect();
        value_error(format!("unknown method '{name}': {}", all.join(", ")))
    })
}

/// Where a rig is skinned (`chasles skin --device`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Device {
    /// The CPU: the fast path on all cores.
    Cpu,
    /// The GPU (wgpu compute), any adapter, a software one too; LBS, DQS and DIB only.
    Gpu,
    /// A hardware GPU when there is one and the method has a shader, else the CPU.
    Auto,
}

/// The device of a name: `cpu`, `gpu` or `auto`.
pub fn device(name: &str) -> PyResult<Device> {
    match name {
        "cpu" => Ok(Device::Cpu),
        "gpu" => Ok(Device::Gpu),
        "auto" => Ok(Device::Auto),
        other => Err(value_error(format!(
            "unknown device '{other}': cpu, gpu or auto"
        ))),
    }
}

/// One pose's skinning matrices `C_j` skinned by `method` into `pos` and `nrm` (one entry
/// per vertex), on all threads when `parallel`; a non-finite vertex is an error, as in
/// `fast::Skinner`.
pub fn skin_into(
    rig: &Rig,
    layout: &Layout,
    mats: &[Mat4<f32>],
    method: Method,
    pos: &mut [[f32; 3]],
    nrm: &mut [[f32; 3]],
    parallel: bool,
) -> Result<(), SkinError> {
    fn job<const K: usize>(
        f: &FastRig<K>,
        mats: &[Mat4<f32>],
        method: Method,
        pos: &mut [[f32; 3]],
        nrm: &mut [[f32; 3]],
        parallel: bool,
    ) -> Result<(), SkinError> {
        let palette = Palette::from_matrices(method, f, mats, parallel)?;
        SkinningJob {
            rig: f,
            palette: &palette,
            output: Output::Split {
                positions: pos,
                normals: nrm,
            },
            parallel,
        }
        .run()
    }
    match layout {
        Layout::Four(f) => job(f, mats, method, pos, nrm, parallel)?,
        Layout::Eight(f) => job(f, mats, method, pos, nrm, parallel)?,
        Layout::Reference => {
            let mut non_rigidity = 0f32;
            let dual_quats = mats
                .iter()
                .map(|m| {
                    let (d, off) = rigid_of(m);
                    non_rigidity = non_rigidity.max(off);
                    d
                })
                .collect();
            let jt = JointTransforms {
                matrices: mats.to_vec(),
                dual_quats,
                non_rigidity,
            };
            let s = skin_joints(rig, &jt, method)?;
            for (o, p) in pos.iter_mut().zip(&s.positions) {
                *o = p.to_array();
            }
            for (o, n) in nrm.iter_mut().zip(&s.normals) {
                *o = n.to_array();
            }
        }
    }
    if let Some(v) = pos
        .iter()
        .zip(nrm.iter())
        .position(|(p, n)| p.iter().chain(n).any(|x| !x.is_finite()))
    {
        return Err(SkinError::NonFiniteOutput {
            rig: rig.name.clone(),
            method: method.name(),
            vertex: v,
        });
    }
    Ok(())
}

/// Two float32 arrays of `frames` × V × 3 (no leading axis when `frames` is None), filled
/// frame by frame by `frame(f, positions, normals)`: one frame per task on all cores when
/// there are several, else the frame's job on all cores (`parallel` passed to `frame`).
pub fn frames_out<'py>(
    py: Python<'py>,
    lead: &[usize],
    vertices: usize,
    frame: impl Fn(usize, &mut [[f32; 3]], &mut [[f32; 3]], bool) -> Result<(), Fail> + Sync,
) -> PyResult<(Bound<'py, PyAny>, Bound<'py, PyAny>)> {
    let mut shape = lead.to_vec();
    shape.extend([vertices, 3]);
    let pos = PyArrayDyn::<f32>::zeros(py, shape.clone(), false);
    let nrm = PyArrayDyn::<f32>::zeros(py, shape, false);
    {
        let mut pw = pos.readwrite();
        let mut nw = nrm.readwrite();
        let p: &mut [[f32; 3]] =
            bytemuck::cast_slice_mut(pw.as_slice_mut().map_err(|e| value_error(e.to_string()))?);
        let n: &mut [[f32; 3]] =
            bytemuck::cast_slice_mut(nw.as_slice_mut().map_err(|e| value_error(e.to_string()))?);
        let count: usize = lead.iter().product();
        let by_frame = count > 1;
        py.detach(|| -> Result<(), (usize, String)> {
            use rayon::prelude::*;
            if vertices == 0 || count == 0 {
                return Ok(());
            }
            if by_frame {
                p.par_chunks_mut(vertices)
                    .zip(n.par_chunks_mut(vertices))
                    .enumerate()
                    .filter_map(|(f, (p, n))| frame(f, p, n, false).err().map(|e| (f, e.0)))
                    .min_by_key(|e| e.0)
                    .map_or(Ok(()), Err)
            } else {
                frame(0, p, n, true).map_err(|e| (0, e.0))
            }
        })
        .map_err(|(i, m)| item_error(i, m, lead))?;
    }
    Ok((pos.into_any(), nrm.into_any()))
}

/// Skins your own arrays: a mesh and its influences, posed by joint matrices.
///
/// ``positions`` and ``normals`` are (V, 3) bind-pose vertices; ``joints`` (V, K) integer
/// joint indices and ``weights`` (V, K) their weights (zero weights are ignored; each
/// vertex's are scaled to sum to 1; negative or non-finite weights, joints out of range
/// and vertices with no weight raise ``ValueError`` naming the vertex);
/// ``joint_matrices`` (..., J, 4, 4) are the skinning matrices ``C_j = World_j ·
/// InverseBind_j`` of one pose, or of a batch of poses. ``method`` is ``lbs``, ``dqs`` (the
/// default), ``dib``, ``log``, ``qlb`` or ``sbs``; ``centres`` (J, 3) are the joints'
/// bind-pose origins, about which QLB and SBS blend rotations (default: the origin).
/// Returns float32 ``(positions, normals)`` of shape (..., V, 3) — the skinning kernels
/// work in float32. Runs through the fast job (up to 8 influences) on all cores. Every
/// call checks the arrays and lays the rig out again: to skin one mesh by many poses, make
/// it once with :meth:`Rig.from_arrays` and call :meth:`Rig.skin_with`.
///
/// >>> import chasles, numpy as np
/// >>> p = np.array([[1.0, 0.0, 0.0]]); n = np.array([[0.0, 0.0, 1.0]])
/// >>> m = np.stack([np.eye(4), np.eye(4)]); m[1, :3, 3] = [0.0, 2.0, 0.0]
/// >>> pos, nrm = chasles.skin(p, n, [[0, 1]], [[0.5, 0.5]], m, "lbs")
/// >>> pos
/// array([[1., 1., 0.]], dtype=float32)
#[pyfunction]
#[pyo3(signature = (positions, normals, joints, weights, joint_matrices, method = "dqs", *,
    centres = None))]
pub fn skin<'py>(
    positions: &Bound<'py, PyAny>,
    normals: &Bound<'py, PyAny>,
    joints: &Bound<'py, PyAny>,
    weights: &Bound<'py, PyAny>,
    joint_matrices: &Bound<'py, PyAny>,
    method: &str,
    centres: Option<&Bound<'py, PyAny>>,
) -> PyResult<(Bound<'py, PyAny>, Bound<'py, PyAny>)> {
    let m = self::method(method)?;
    let mats = array::<f32>(joint_matrices, "joint_matrices")?;
    let ms = mats.shape();
    if ms.len() < 3 || ms[ms.len() - 2..] != [4, 4] {
        return Err(value_error(format!(
            "joint_matrices must have shape (..., J, 4, 4), got {}",
            crate::arrays::shape_text(ms)
        )));
    }
    let nj = Some(ms[ms.len() - 3]);
    let rig = rig_from_arrays(positions, normals, joints, weights, centres, nj, "arrays")?;
    let layout = Layout::of(&rig).map_err(crate::arrays::skin_error)?;
    skin_by_matrices(positions.py(), &rig, &layout, &mats, m)
}

/// `rig` (laid out as `layout`) skinned by `m` with the skinning matrices `mats`
/// (..., J, 4, 4), J the rig's joints: float32 (..., V, 3) positions and normals, a batch's
/// poses one per task on all cores (the free [`skin`]'s and `Rig.skin_with`'s last step).
pub fn skin_by_matrices<'py>(
    py: Python<'py>,
    rig: &Rig,
    layout: &Layout,
    mats: &PyReadonlyArrayDyn<'_, f32>,
    m: Method,
) -> PyResult<(Bound<'py, PyAny>, Bound<'py, PyAny>)> {
    let nj = rig.joints.len();
    let ms = mats.shape();
    if ms.len() < 3 || ms[ms.len() - 3..] != [nj, 4, 4] {
        return Err(value_error(format!(
            "joint_matrices must have shape (..., {nj}, 4, 4), one per joint, got {}",
            crate::arrays::shape_text(ms)
        )));
    }
    let lead = ms[..ms.len() - 3].to_vec();
    let md = mats.as_slice().map_err(|e| value_error(e.to_string()))?;
    frames_out(
        py,
        &lead,
        rig.mesh.positions.len(),
        |f, pos, nrm, parallel| {
            let mats: Vec<Mat4<f32>> = md[f * nj * 16..][..nj * 16]
                .chunks_exact(16)
                .map(|c| Mat4::from_row_major(c.try_into().unwrap_or([0.0; 16])))
                .collect();
            Ok(skin_into(rig, layout, &mats, m, pos, nrm, parallel)?)
        },
    )
}

/// Users' arrays made into a checked rig (the free [`skin`]'s and `Rig.from_arrays`'s):
/// `positions` and `normals` (V, 3), `joints` (V, K) integers and `weights` (V, K),
/// `centres` (J, 3) or none; J is `joint_count` when given, else the centres' count, else
/// the largest joint index of positive weight plus one (an index of weight 0 is ignored, as
/// padding). `name` names the rig in errors. The rig has one root node per joint, inverse
/// bind matrices that put each joint's bind origin at its centre, no triangles and no
/// clips, and is checked by `Rig::new`. A `ValueError` names the array and its shape, or
/// the vertex with bad influences.
pub fn rig_from_arrays(
    positions: &Bound<'_, PyAny>,
    normals: &Bound<'_, PyAny>,
    joints: &Bound<'_, PyAny>,
    weights: &Bound<'_, PyAny>,
    centres: Option<&Bound<'_, PyAny>>,
    joint_count: Option<usize>,
    name: &str,
) -> PyResult<Rig> {
    let p = array::<f32>(positions, "positions")?;
    let n = array::<f32>(normals, "normals")?;
    let j = crate::rig::int_array(joints, "joints")?;
    let w = array::<f32>(weights, "weights")?;
    let v = p.shape().first().copied().unwrap_or(0);
    leading(p.shape(), &[v, 3], "positions")?;
    let vl = leading(p.shape(), &[3], "positions")?;
    if vl.len() != 1 {
        return Err(value_error(format!(
            "positions must have shape (V, 3), got {}",
            crate::arrays::shape_text(p.shape())
        )));
    }
    if n.shape() != p.shape() {
        return Err(value_error(format!(
            "normals must have shape ({v}, 3) like positions, got {}",
            crate::arrays::shape_text(n.shape())
        )));
    }
    let k = j.shape().get(1).copied().unwrap_or(0);
    if j.shape() != [v, k] {
        return Err(value_error(format!(
            "joints must have shape ({v}, K), got {}",
            crate::arrays::shape_text(j.shape())
        )));
    }
    if w.shape() != [v, k] {
        return Err(value_error(format!(
            "weights must have shape ({v}, {k}) like joints, got {}",
            crate::arrays::shape_text(w.shape())
        )));
    }
    let c = centres.map(|c| array::<f32>(c, "centres")).transpose()?;
    let slice = |e: numpy::AsSliceError| value_error(e.to_string());
    let (js, ws) = (j.as_slice().map_err(slice)?, w.as_slice().map_err(slice)?);
    let nj = match (joint_count, &c) {
        (Some(nj), _) => nj,
        (None, Some(c)) => c.shape().first().copied().unwrap_or(0),
        (None, None) => js
            .iter()
            .zip(ws)
            .filter(|(_, w)| **w > 0.0)
            .map(|(j, _)| *j)
            .max()
            .map_or(0, |m| usize::try_from(m).map_or(0, |m| m.saturating_add(1))),
    };
    if let Some(c) = &c {
        if c.shape() != [nj, 3] {
            return Err(value_error(format!(
                "centres must have shape ({nj}, 3), one per joint, got {}",
                crate::arrays::shape_text(c.shape())
            )));
        }
    }
    let cs = c
        .as_ref()
        .map(|c| c.as_slice())
        .transpose()
        .map_err(slice)?;
    let err = crate::arrays::skin_error;
    // The influences row by row, with no list a vertex (`Influences::from_rows`).
    if let Some(at) = js.iter().position(|&joint| joint < 0) {
        return Err(err(SkinError::BadWeights {
            vertex: at / k.max(1),
            reason: format!("joint index {} is negative", js[at]),
        }));
    }
    let row = |vertex: usize| {
        let (j, w) = (&js[vertex * k..][..k], &ws[vertex * k..][..k]);
        j.iter()
            .zip(w)
            .map(|(&joint, &weight)| (joint as usize, weight))
    };
    let influences = Influences::from_rows((0..v).map(row), nj).map_err(err)?;
    let vecs = |a: &[f32]| -> Vec<Vec3<f32>> {
        a.chunks_exact(3)
            .map(|c| Vec3::new(c[0], c[1], c[2]))
            .collect()
    };
    let nodes = (0..nj)
        .map(|i| Node {
            name: format!("joint {i}"),
            parent: None,
            rest: Default::default(),
        })
        .collect();
    let inverse_bind = (0..nj)
        .map(|i| {
            let c = cs.map_or(Vec3::zero(), |c| {
                Vec3::new(c[3 * i], c[3 * i + 1], c[3 * i + 2])
            });
            Mat4::from_rotation_translation(&chasles::Mat3::identity(), -c)
        })
        .collect();
    Rig::new(
        name.to_string(),
        Mesh {
            positions: vecs(p.as_slice().map_err(slice)?),
            normals: vecs(n.as_slice().map_err(slice)?),
            triangles: Vec::new(),
        },
        nodes,
        (0..nj).collect(),
        inverse_bind,
        influences,
        Vec::new(),
    )
    .map_err(err)
}
