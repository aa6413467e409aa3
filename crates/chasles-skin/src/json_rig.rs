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
//! Quaternions are `[w, x, y, z]`, matrices row-major. Errors name the field, e.g.
//! `joints[2].rotation` or `influences[17]`.

use crate::error::{invalid, Result, SkinError};
use crate::pose::{world, Pose};
use crate::rig::{compute_normals, Influences, Mesh, Node, Rig, Trs};
use chasles::{Mat4, Quat, Vec3};
use serde_json::Value;

fn numbers<const N: usize>(v: &Value, at: &str) -> Result<[f32; N]> {
    let a = v
        .as_array()
        .ok_or_else(|| SkinError::Invalid(format!("{at}: expected an array of {N} numbers")))?;
    if a.len() != N {
        return invalid(format!("{at}: expected {N} numbers, got {}", a.len()));
    }
    let mut out = [0f32; N];
    for (k, x) in a.iter().enumerate() {
        let f = x.as_f64().ok_or_else(|| {
            SkinError::Invalid(format!("{at}[{k}]: expected a number, found {x}"))
        })?;
        if !f.is_finite() {
            return invalid(format!("{at}[{k}]: not finite"));
        }
        out[k] = f as f32;
    }
    Ok(out)
}

fn array<'a>(v: &'a Value, field: &str) -> Result<&'a Vec<Value>> {
    v.get(field)
        .ok_or_else(|| SkinError::Invalid(format!("missing field '{field}'")))?
        .as_array()
        .ok_or_else(|| SkinError::Invalid(format!("field '{field}': expected an array")))
}

fn trs(v: &Value, at: &str, base: Trs) -> Result<Trs> {
    let mut t = base;
    if let Some(x) = v.get("translation") {
        t.translation = Vec3::from_array(numbers::<3>(x, &format!("{at}.translation"))?);
    }
    if let Some(x) = v.get("rotation") {
        t.rotation = Quat::from_array(numbers::<4>(x, &format!("{at}.rotation"))?)
            .normalize()
            .map_err(|e| SkinError::Invalid(format!("{at}.rotation: {e}")))?;
    }
    if let Some(x) = v.get("scale") {
        t.scale = Vec3::from_array(numbers::<3>(x, &format!("{at}.scale"))?);
    }
    Ok(t)
}

/// Parses a JSON rig.
pub fn parse_rig(text: &str, name: &str) -> Result<Rig> {
    let v: Value = serde_json::from_str(text)
        .map_err(|e| SkinError::Invalid(format!("{name}: not valid JSON: {e}")))?;
    let ctx = |e: SkinError| SkinError::Invalid(format!("{name}: {e}"));
    let positions = array(&v, "positions")
        .map_err(ctx)?
        .iter()
        .enumerate()
        .map(|(i, p)| numbers::<3>(p, &format!("positions[{i}]")).map(Vec3::from_array))
        .collect::<Result<Vec<_>>>()
        .map_err(ctx)?;
    let triangles = array(&v, "triangles")
        .map_err(ctx)?
        .iter()
        .enumerate()
        .map(|(i, t)| {
            let t = numbers::<3>(t, &format!("triangles[{i}]"))?;
            if t.iter().any(|x| *x < 0.0 || x.fract() != 0.0) {
                return invalid(format!(
                    "triangles[{i}]: vertex indices must be whole and non-negative"
                ));
            }
            Ok(t.map(|x| x as u32))
        })
        .collect::<Result<Vec<_>>>()
        .map_err(ctx)?;
    if let Some((i, t)) = triangles
        .iter()
        .enumerate()
        .find(|(_, t)| t.iter().any(|x| *x as usize >= positions.len()))
    {
        return invalid(format!(
            "{name}: triangle {i} {t:?} names a vertex out of range (there are {})",
            positions.len()
        ));
    }
    let joints_v = array(&v, "joints").map_err(ctx)?;
    let mut nodes = Vec::with_capacity(joints_v.len());
    for (i, j) in joints_v.iter().enumerate() {
        let at = format!("joints[{i}]");
        let parent = match j.get("parent") {
            None | Some(Value::Null) => None,
            Some(p) => {
                let p = p.as_u64().ok_or_else(|| {
                    SkinError::Invalid(format!(
                        "{name}: {at}.parent: expected a joint index or null"
                    ))
                })? as usize;
                if p >= i {
                    return invalid(format!(
                        "{name}: {at}.parent is {p}: parents must come before their children"
                    ));
                }
                Some(p)
            }
        };
        nodes.push(Node {
            name: j
                .get("name")
                .and_then(Value::as_str)
                .unwrap_or("")
                .to_string(),
            parent,
            rest: trs(j, &at, Trs::default()).map_err(ctx)?,
        });
    }
    let nj = nodes.len();
    let lists = array(&v, "influences")
        .map_err(ctx)?
        .iter()
        .enumerate()
        .map(|(i, l)| {
            let at = format!("influences[{i}]");
            l.as_array()
                .ok_or_else(|| {
                    SkinError::Invalid(format!("{at}: expected a list of [joint, weight] pairs"))
                })?
                .iter()
                .map(|pair| {
                    let [j, w] = numbers::<2>(pair, &at)?;
                    if j < 0.0 || j.fract() != 0.0 {
                        return invalid(format!(
                            "{at}: joint index {j} is not a whole non-negative number"
                        ));
                    }
                    Ok((j as usize, w))
                })
                .collect::<Result<Vec<_>>>()
        })
        .collect::<Result<Vec<_>>>()
        .map_err(ctx)?;
    if lists.len() != positions.len() {
        return invalid(format!(
            "{name}: {} vertices but {} influence lists",
            positions.len(),
            lists.len()
        ));
    }
    let influences = Influences::from_lists(&lists, nj).map_err(ctx)?;
    let normals = match v.get("normals") {
        Some(n) => n
            .as_array()
            .ok_or_else(|| {
                SkinError::Invalid(format!("{name}: field 'normals': expected an array"))
            })?
            .iter()
            .enumerate()
            .map(|(i, p)| {
                numbers::<3>(p, &format!("normals[{i}]")).map(|a| {
                    Vec3::from_array(a)
                        .normalize()
                        .unwrap_or(Vec3::new(0.0, 0.0, 1.0))
                })
            })
            .collect::<Result<Vec<_>>>()
            .map_err(ctx)?,
        None => compute_normals(&positions, &triangles),
    };
    let mut rig = Rig {
        name: name.to_string(),
        mesh: Mesh {
            positions,
            normals,
            triangles,
        },
        nodes,
        joints: (0..nj).collect(),
        inverse_bind: Vec::new(),
        influences,
        animations: Vec::new(),
    };
    rig.inverse_bind = match v.get("inverse_bind") {
        Some(ib) => ib
            .as_array()
            .ok_or_else(|| {
                SkinError::Invalid(format!(
                    "{name}: field 'inverse_bind': expected an array of 4x4 matrices"
                ))
            })?
            .iter()
            .enumerate()
            .map(|(i, m)| {
                let rows = m.as_array().filter(|r| r.len() == 4).ok_or_else(|| {
                    SkinError::Invalid(format!("{name}: inverse_bind[{i}]: expected 4 rows"))
                })?;
                let r = rows
                    .iter()
                    .enumerate()
                    .map(|(k, row)| numbers::<4>(row, &format!("inverse_bind[{i}][{k}]")))
                    .collect::<Result<Vec<_>>>()?;
                Ok(Mat4::from_rows([r[0], r[1], r[2], r[3]]))
            })
            .collect::<Result<Vec<_>>>()
            .map_err(ctx)?,
        None => {
            let rest = world(&rig, &Pose::rest(&rig))?;
            rest.iter()
                .enumerate()
                .map(|(i, m)| {
                    let a = m.linear_part().inverse().ok_or_else(|| {
                        SkinError::Invalid(format!(
                            "{name}: joints[{i}] has a singular rest transform"
                        ))
                    })?;
                    Ok(Mat4::from_rotation_translation(
                        &a,
                        -a.mul_vec(m.translation()),
                    ))
                })
                .collect::<Result<Vec<_>>>()?
        }
    };
    rig.validate()?;
    Ok(rig)
}

/// Parses a JSON pose for `rig`: joints by name or index, the rest at rest.
pub fn parse_pose(text: &str, rig: &Rig, name: &str) -> Result<Pose> {
    let v: Value = serde_json::from_str(text)
        .map_err(|e| SkinError::Invalid(format!("{name}: not valid JSON: {e}")))?;
    let joints = v.get("joints").and_then(Value::as_object).ok_or_else(|| {
        SkinError::Invalid(format!(
            "{name}: expected {{\"joints\": {{name or index: {{rotation, translation, scale}}}}}}"
        ))
    })?;
    let mut pose = Pose::rest(rig);
    for (key, t) in joints {
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
            .ok_or_else(|| {
                SkinError::Invalid(format!("{name}: no joint named or numbered '{key}'"))
            })?;
        pose.local[node] = trs(t, &format!("{name}: joints.{key}"), pose.local[node])?;
    }
    Ok(pose)
}
