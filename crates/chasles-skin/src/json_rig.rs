//! A plain JSON rig format for scripts and tests, and JSON pose files.
//!
//! Rig (`.json`):
//!
//! ```json
//! {
//!   "positions": [[x, y, z], …],
//!   "normals": [[x, y, z], …],              // optional: computed from the triangles
//!   "triangles": [[a, b, c], …],             // vertex indices
//!   "joints": [                               // parents before children
//!     {"name": "hip", "parent": null, "translation": [x, y, z],
//!      "rotation": [w, x, y, z], "scale": [x, y, z]},   // all three optional
//!     {"name": "knee", "parent": 0, "translation": [0, -1, 0]}
//!   ],
//!   "inverse_bind": [[[r00, r01, r02, t0], …, [0, 0, 0, 1]], …],  // optional: the
//!                                             // inverse of each joint's rest world matrix
//!   "influences": [[[joint, weight], …], …]  // per vertex, any number
//! }
//! ```
//!
//! Pose (`--pose FILE.json`): `{"joints": {"knee": {"rotation": [w, x, y, z]}, "0":
//! {"translation": [x, y, z]}}}` — joints by name or index; what is not given stays at rest.
//! Quaternions are `[w, x, y, z]`, matrices row-major.
//!
//! Both are serde-derived types read through `serde_path_to_error`, so every error is a
//! [`SkinError::Field`] naming the file and the path of the bad field — `joints[2].rotation`,
//! `influences[17][0]`, `positions[3]` — whether the field has the wrong shape (serde's
//! message) or a value that cannot be used (not finite, a parent after its child, a vertex
//! out of range, weights that are negative or sum to zero). Unknown fields are errors too,
//! so a misspelt `"normal"` is not silently ignored.

use crate::error::{Result, SkinError};
use crate::pose::{world_of, Pose};
use crate::rig::{compute_normals, Influences, Mesh, Node, Rig, Trs};
use chasles::{Mat4, Quat, Vec3};
use serde::Deserialize;
use std::collections::BTreeMap;

/// A rig file as written.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RigFile {
    positions: Vec<[f64; 3]>,
    #[serde(default)]
    normals: Option<Vec<[f64; 3]>>,
    triangles: Vec<[u32; 3]>,
    joints: Vec<JointFile>,
    #[serde(default)]
    inverse_bind: Option<Vec<[[f64; 4]; 4]>>,
    influences: Vec<Vec<(usize, f64)>>,
}

/// One joint of a rig file: its rest transform relative to its parent.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct JointFile {
    #[serde(default)]
    name: String,
    #[serde(default)]
    parent: Option<usize>,
    #[serde(default)]
    translation: Option<[f64; 3]>,
    #[serde(default)]
    rotation: Option<[f64; 4]>,
    #[serde(default)]
    scale: Option<[f64; 3]>,
}

/// Translation, rotation `[w, x, y, z]` and scale, each optional: a pose file's joint.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct TrsFile {
    #[serde(default)]
    translation: Option<[f64; 3]>,
    #[serde(default)]
    rotation: Option<[f64; 4]>,
    #[serde(default)]
    scale: Option<[f64; 3]>,
}

/// A pose file: joints by name or index.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct PoseFile {
    joints: BTreeMap<String, TrsFile>,
}

/// The error for the field at `path` of `file`.
fn field(file: &str, path: impl Into<String>, reason: impl Into<String>) -> SkinError {
    SkinError::Field {
        file: file.to_string(),
        path: path.into(),
        reason: reason.into(),
    }
}

/// Reads `text` as `T`, naming the path of the field that does not fit.
fn read<'a, T: Deserialize<'a>>(text: &'a str, file: &str) -> Result<T> {
    let mut de = serde_json::Deserializer::from_str(text);
    let value = serde_path_to_error::deserialize(&mut de).map_err(|e| {
        let path = e.path().to_string();
        let inner = e.into_inner();
        let reason = if inner.is_syntax() || inner.is_eof() {
            format!("not valid JSON: {inner}")
        } else {
            inner.to_string()
        };
        field(file, path, reason)
    })?;
    // Nothing but white space may follow the document.
    de.end()
        .map_err(|e| field(file, ".", format!("not valid JSON: {e}")))?;
    Ok(value)
}

/// `a` in f32, every component finite there.
fn finite<const N: usize>(a: [f64; N], file: &str, path: impl Fn() -> String) -> Result<[f32; N]> {
    let out = a.map(|x| x as f32);
    match out.iter().position(|x| !x.is_finite()) {
        Some(k) => Err(field(
            file,
            format!("{}[{k}]", path()),
            format!("{:e} is not a finite f32", a[k]),
        )),
        None => Ok(out),
    }
}

impl TrsFile {
    /// `base` with what is given replaced; `at` is the path of this object.
    fn apply(&self, base: Trs, file: &str, at: &str) -> Result<Trs> {
        let mut t = base;
        if let Some(x) = self.translation {
            t.translation = Vec3::from_array(finite(x, file, || format!("{at}.translation"))?);
        }
        if let Some(x) = self.rotation {
            let q = finite(x, file, || format!("{at}.rotation"))?;
            t.rotation = Quat::from_array(q)
                .normalize()
                .map_err(|e| field(file, format!("{at}.rotation"), e.to_string()))?;
        }
        if let Some(x) = self.scale {
            t.scale = Vec3::from_array(finite(x, file, || format!("{at}.scale"))?);
        }
        Ok(t)
    }
}

/// Parses a JSON rig; `name` (the file) names it in errors.
pub fn parse_rig(text: &str, name: &str) -> Result<Rig> {
    let f: RigFile = read(text, name)?;
    let positions = f
        .positions
        .iter()
        .enumerate()
        .map(|(i, p)| finite(*p, name, || format!("positions[{i}]")).map(Vec3::from_array))
        .collect::<Result<Vec<_>>>()?;
    if let Some((i, t)) = f
        .triangles
        .iter()
        .enumerate()
        .find(|(_, t)| t.iter().any(|x| *x as usize >= positions.len()))
    {
        return Err(field(
            name,
            format!("triangles[{i}]"),
            format!(
                "{t:?} names a vertex out of range (there are {})",
                positions.len()
            ),
        ));
    }
    let mut nodes = Vec::with_capacity(f.joints.len());
    for (i, j) in f.joints.iter().enumerate() {
        let at = format!("joints[{i}]");
        if let Some(p) = j.parent.filter(|p| *p >= i) {
            return Err(field(
                name,
                format!("{at}.parent"),
                format!("{p}: parents must come before their children"),
            ));
        }
        nodes.push(Node {
            name: j.name.clone(),
            parent: j.parent,
            rest: TrsFile {
                translation: j.translation,
                rotation: j.rotation,
                scale: j.scale,
            }
            .apply(Trs::default(), name, &at)?,
        });
    }
    let nj = nodes.len();
    if f.influences.len() != positions.len() {
        return Err(field(
            name,
            "influences",
            format!(
                "{} influence lists for {} vertices",
                f.influences.len(),
                positions.len()
            ),
        ));
    }
    let lists: Vec<Vec<(usize, f32)>> = f
        .influences
        .iter()
        .map(|l| l.iter().map(|&(j, w)| (j, w as f32)).collect())
        .collect();
    let influences = Influences::from_lists(&lists, nj).map_err(|e| match e {
        SkinError::BadWeights { vertex, .. } | SkinError::JointOutOfRange { vertex, .. } => {
            field(name, format!("influences[{vertex}]"), e.to_string())
        }
        e => e,
    })?;
    let normals = match &f.normals {
        Some(n) => n
            .iter()
            .enumerate()
            .map(|(i, p)| {
                finite(*p, name, || format!("normals[{i}]")).map(|a| {
                    Vec3::from_array(a)
                        .normalize()
                        .unwrap_or(Vec3::new(0.0, 0.0, 1.0))
                })
            })
            .collect::<Result<Vec<_>>>()?,
        None => compute_normals(&positions, &f.triangles),
    };
    let inverse_bind = match &f.inverse_bind {
        Some(ib) => ib
            .iter()
            .enumerate()
            .map(|(i, m)| {
                let mut rows = [[0f32; 4]; 4];
                for (k, row) in m.iter().enumerate() {
                    rows[k] = finite(*row, name, || format!("inverse_bind[{i}][{k}]"))?;
                }
                Ok(Mat4::from_rows(rows))
            })
            .collect::<Result<Vec<_>>>()?,
        None => {
            let rest: Vec<Trs> = nodes.iter().map(|n| n.rest).collect();
            world_of(&nodes, &rest)
                .iter()
                .enumerate()
                .map(|(i, m)| {
                    let a = m.linear_part().inverse().ok_or_else(|| {
                        field(name, format!("joints[{i}]"), "a singular rest transform")
                    })?;
                    Ok(Mat4::from_rotation_translation(
                        &a,
                        -a.mul_vec(m.translation()),
                    ))
                })
                .collect::<Result<Vec<_>>>()?
        }
    };
    Rig::new(
        name.to_string(),
        Mesh {
            positions,
            normals,
            triangles: f.triangles,
        },
        nodes,
        (0..nj).collect(),
        inverse_bind,
        influences,
        Vec::new(),
    )
}

/// Parses a JSON pose for `rig`: joints by name or index, the rest at rest.
pub fn parse_pose(text: &str, rig: &Rig, name: &str) -> Result<Pose> {
    let f: PoseFile = read(text, name)?;
    let mut pose = Pose::rest(rig);
    for (key, t) in &f.joints {
        let at = format!("joints.{key}");
        let node = rig
            .joints
            .iter()
            .copied()
            .find(|n| rig.nodes[*n].name == *key)
            .or_else(|| {
                key.parse::<usize>()
                    .ok()
                    .and_then(|j| rig.joints.get(j).copied())
            })
            .ok_or_else(|| field(name, &at, format!("no joint named or numbered '{key}'")))?;
        pose.local[node] = t.apply(pose.local[node], name, &at)?;
    }
    Ok(pose)
}
