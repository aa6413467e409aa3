//! The representations `chasles convert` reads and writes, and how each looks as plain
//! numbers, as text and as JSON.
//!
//! Every value is read into a unit dual quaternion (a rotation is one with no translation),
//! then written out in the target representation. Quaternions are `[w, x, y, z]`, matrices
//! row-major, angles in radians, dual quaternions `[w, x, y, z, wε, xε, yε, zε]`.

use anyhow::{anyhow, bail, Context, Result};
use chasles::{DualQuat, EulerOrder, Mat3, Mat4, Quat, Screw, Vec3};
use serde_json::{json, Map, Value};
use std::fmt;
use std::str::FromStr;

/// A representation name as given to `--from` / `--to`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Repr {
    /// `quat`: w x y z.
    Quat,
    /// `matrix`: 9 (3×3) or 16 (4×4) numbers row-major; as output, 4×4 when the value has
    /// a translation, else 3×3.
    Matrix,
    /// `matrix3`: 9 numbers row-major.
    Matrix3,
    /// `matrix4`: 16 numbers row-major.
    Matrix4,
    /// `euler:ORDER`: three angles; lower-case order extrinsic, upper-case intrinsic.
    Euler(EulerOrder),
    /// `axis-angle`: ax ay az angle.
    AxisAngle,
    /// `rotvec`: the rotation vector axis·angle.
    RotVec,
    /// `rt`: rotation then translation, w x y z tx ty tz.
    Rt,
    /// `dq`: unit dual quaternion, 8 numbers.
    Dq,
    /// `screw`: ax ay az px py pz angle translation (axis direction, a point on the axis,
    /// the rotation angle about it and the slide along it).
    Screw,
}

/// The names accepted, for error messages and `--help`.
pub const NAMES: &str =
    "quat, matrix, matrix3, matrix4, euler:ORDER (e.g. euler:xyz, euler:ZYX), axis-angle, rotvec, rt, dq, screw";

impl FromStr for Repr {
    type Err = anyhow::Error;
    fn from_str(s: &str) -> Result<Self> {
        Ok(match s {
            "quat" | "quaternion" => Repr::Quat,
            "matrix" => Repr::Matrix,
            "matrix3" => Repr::Matrix3,
            "matrix4" => Repr::Matrix4,
            "axis-angle" | "axisangle" => Repr::AxisAngle,
            "rotvec" => Repr::RotVec,
            "rt" => Repr::Rt,
            "dq" => Repr::Dq,
            "screw" => Repr::Screw,
            other => match other.strip_prefix("euler:") {
                Some(order) => Repr::Euler(order.parse()?),
                None if other == "euler" => {
                    bail!("'euler' needs an order, e.g. euler:xyz (extrinsic) or euler:XYZ (intrinsic)")
                }
                None => bail!("unknown representation '{other}'; use one of: {NAMES}"),
            },
        })
    }
}

impl fmt::Display for Repr {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Repr::Quat => write!(f, "quat"),
            Repr::Matrix => write!(f, "matrix"),
            Repr::Matrix3 => write!(f, "matrix3"),
            Repr::Matrix4 => write!(f, "matrix4"),
            Repr::Euler(o) => write!(f, "euler:{o}"),
            Repr::AxisAngle => write!(f, "axis-angle"),
            Repr::RotVec => write!(f, "rotvec"),
            Repr::Rt => write!(f, "rt"),
            Repr::Dq => write!(f, "dq"),
            Repr::Screw => write!(f, "screw"),
        }
    }
}

/// A value read from the user: a rigid motion, whether it was given with a translation,
/// and notes worth telling (normalization, gimbal lock).
#[derive(Debug, Clone)]
pub struct Motion {
    /// The motion as a unit dual quaternion.
    pub dq: DualQuat<f64>,
    /// The input representation could carry a translation (rt, dq, matrix4, screw).
    pub rigid: bool,
    /// Remarks for stderr.
    pub notes: Vec<String>,
}

impl Motion {
    fn rotation(q: Quat<f64>, notes: Vec<String>) -> Self {
        Motion {
            dq: DualQuat::from_rotation(q),
            rigid: false,
            notes,
        }
    }
    fn rigid(dq: DualQuat<f64>, notes: Vec<String>) -> Self {
        Motion {
            dq,
            rigid: true,
            notes,
        }
    }
}

/// Splits arguments like `0.1 -0.2`, `[0.1, 0.2]` or `0.1,0.2` into finite numbers.
pub fn parse_numbers(args: &[String]) -> Result<Vec<f64>> {
    let mut out = Vec::new();
    for arg in args {
        for tok in arg
            .split(|c: char| c.is_whitespace() || c == ',' || c == '[' || c == ']')
            .filter(|t| !t.is_empty())
        {
            let v: f64 = tok
                .parse()
                .map_err(|_| anyhow!("value {} ('{tok}') is not a number", out.len() + 1))?;
            if !v.is_finite() {
                bail!("value {} ('{tok}') is not a finite number", out.len() + 1);
            }
            out.push(v);
        }
    }
    Ok(out)
}

fn expect_len(repr: Repr, v: &[f64], n: usize, layout: &str) -> Result<()> {
    if v.len() != n {
        bail!("{repr} needs {n} numbers ({layout}), got {}", v.len());
    }
    Ok(())
}

fn unit_quat(q: Quat<f64>, what: &str, notes: &mut Vec<String>) -> Result<Quat<f64>> {
    let u = q.normalize().with_context(|| what.to_string())?;
    let n = q.norm();
    if (n - 1.0).abs() > 1e-6 {
        notes.push(format!("{what} had norm {n}; normalized"));
    }
    Ok(u)
}

/// Reads a motion from plain numbers in the given representation.
pub fn motion_from_numbers(repr: Repr, v: &[f64]) -> Result<Motion> {
    let mut notes = Vec::new();
    let v3 = |i: usize| Vec3::new(v[i], v[i + 1], v[i + 2]);
    Ok(match repr {
        Repr::Quat => {
            expect_len(repr, v, 4, "w x y z")?;
            let q = unit_quat(Quat::new(v[0], v[1], v[2], v[3]), "quaternion", &mut notes)?;
            Motion::rotation(q, notes)
        }
        Repr::Matrix => match v.len() {
            9 => motion_from_numbers(Repr::Matrix3, v)?,
            16 => motion_from_numbers(Repr::Matrix4, v)?,
            n => bail!("matrix needs 9 (3x3) or 16 (4x4) numbers, row-major, got {n}"),
        },
        Repr::Matrix3 => {
            expect_len(repr, v, 9, "3x3 row-major")?;
            let m = Mat3::from_row_major(core::array::from_fn(|i| v[i]));
            Motion::rotation(Quat::from_rotation_matrix(&m)?, notes)
        }
        Repr::Matrix4 => {
            expect_len(repr, v, 16, "4x4 row-major")?;
            let m = Mat4::from_row_major(core::array::from_fn(|i| v[i]));
            Motion::rigid(DualQuat::from_matrix4(&m)?, notes)
        }
        Repr::Euler(order) => {
            expect_len(repr, v, 3, "three angles in radians")?;
            Motion::rotation(Quat::from_euler(order, [v[0], v[1], v[2]]), notes)
        }
        Repr::AxisAngle => {
            expect_len(repr, v, 4, "ax ay az angle")?;
            Motion::rotation(Quat::from_axis_angle(v3(0), v[3])?, notes)
        }
        Repr::RotVec => {
            expect_len(repr, v, 3, "x y z: axis times angle")?;
            Motion::rotation(Quat::from_rotation_vector(v3(0))?, notes)
        }
        Repr::Rt => {
            expect_len(repr, v, 7, "w x y z tx ty tz")?;
            let q = unit_quat(
                Quat::new(v[0], v[1], v[2], v[3]),
                "rotation quaternion",
                &mut notes,
            )?;
            Motion::rigid(DualQuat::from_rotation_translation(q, v3(4)), notes)
        }
        Repr::Dq => {
            expect_len(repr, v, 8, "w x y z we xe ye ze")?;
            let raw = DualQuat::from_array(core::array::from_fn(|i| v[i]));
            let dq = raw.normalize()?;
            if !raw.is_unit(1e-6) {
                notes.push("dual quaternion was not unit; normalized (real part to length 1, dual part made orthogonal to it)".into());
            }
            Motion::rigid(dq, notes)
        }
        Repr::Screw => {
            expect_len(repr, v, 8, "ax ay az px py pz angle translation")?;
            let s = Screw::from_point(v3(0), v3(3), v[6], v[7])?;
            Motion::rigid(DualQuat::from_screw(&s)?, notes)
        }
    })
}

fn json_numbers(v: &Value, field: &str) -> Result<Vec<f64>> {
    let mut out = Vec::new();
    fn walk(v: &Value, field: &str, out: &mut Vec<f64>) -> Result<()> {
        match v {
            Value::Number(n) => {
                out.push(
                    n.as_f64()
                        .ok_or_else(|| anyhow!("field '{field}': {n} is not a finite number"))?,
                );
                Ok(())
            }
            Value::Array(a) => a.iter().try_for_each(|x| walk(x, field, out)),
            other => bail!("field '{field}': expected numbers, found {other}"),
        }
    }
    walk(v, field, &mut out)?;
    Ok(out)
}

fn field<'a>(o: &'a Map<String, Value>, name: &str) -> Result<&'a Value> {
    o.get(name).ok_or_else(|| anyhow!("missing field '{name}'"))
}

/// Reads a motion from a JSON value: an array of numbers in the `--from` representation,
/// or an object that names its own: `{"quat": [w,x,y,z]}`, `{"rotation": [w,x,y,z],
/// "translation": [x,y,z]}`, `{"matrix": [[...]]}` (3×3 or 4×4, nested or flat),
/// `{"dq": [8 numbers]}`, `{"euler": [a,b,c], "order": "xyz"}`, `{"axis": [x,y,z],
/// "angle": a}`, `{"rotvec": [x,y,z]}`, `{"screw": {"axis", "point", "angle",
/// "translation"}}`.
pub fn motion_from_json(v: &Value, from: Option<Repr>) -> Result<Motion> {
    let o = match v {
        Value::Array(_) => {
            let repr = from.ok_or_else(|| anyhow!("a bare array needs --from to say what it is; or give an object such as {{\"quat\": [1, 0, 0, 0]}}"))?;
            return motion_from_numbers(repr, &json_numbers(v, "value")?);
        }
        Value::Object(o) => o,
        other => bail!("expected a JSON array or object, found {other}"),
    };
    let nums = |name: &str| -> Result<Vec<f64>> { json_numbers(field(o, name)?, name) };
    let with_field = |name: &'static str, repr: Repr| -> Result<Motion> {
        motion_from_numbers(repr, &nums(name)?).with_context(|| format!("field '{name}'"))
    };
    if o.contains_key("quat") {
        with_field("quat", Repr::Quat)
    } else if o.contains_key("rotation") {
        let mut v = nums("rotation")?;
        if v.len() != 4 {
            bail!(
                "field 'rotation': expected 4 numbers [w, x, y, z], got {}",
                v.len()
            );
        }
        match o.get("translation") {
            Some(t) => {
                let t = json_numbers(t, "translation")?;
                if t.len() != 3 {
                    bail!("field 'translation': expected 3 numbers, got {}", t.len());
                }
                v.extend(t);
                motion_from_numbers(Repr::Rt, &v)
            }
            None => motion_from_numbers(Repr::Quat, &v).context("field 'rotation'"),
        }
    } else if o.contains_key("matrix") {
        with_field("matrix", Repr::Matrix)
    } else if o.contains_key("dq") {
        with_field("dq", Repr::Dq)
    } else if o.contains_key("euler") {
        let order: EulerOrder = match o.get("order") {
            Some(Value::String(s)) => s.parse().context("field 'order'")?,
            Some(other) => bail!("field 'order': expected a string such as \"xyz\", found {other}"),
            None => bail!("missing field 'order' (e.g. \"xyz\" extrinsic, \"XYZ\" intrinsic)"),
        };
        with_field("euler", Repr::Euler(order))
    } else if o.contains_key("axis") {
        let mut v = nums("axis")?;
        if v.len() != 3 {
            bail!("field 'axis': expected 3 numbers, got {}", v.len());
        }
        v.extend(nums("angle")?);
        motion_from_numbers(Repr::AxisAngle, &v)
    } else if o.contains_key("rotvec") {
        with_field("rotvec", Repr::RotVec)
    } else if let Some(s) = o.get("screw") {
        let s = s
            .as_object()
            .ok_or_else(|| anyhow!("field 'screw': expected an object"))?;
        let mut v = Vec::new();
        for (name, n) in [("axis", 3), ("point", 3), ("angle", 1), ("translation", 1)] {
            let x = json_numbers(field(s, name).context("field 'screw'")?, name)?;
            if x.len() != n {
                bail!(
                    "field 'screw.{name}': expected {n} number(s), got {}",
                    x.len()
                );
            }
            v.extend(x);
        }
        motion_from_numbers(Repr::Screw, &v)
    } else {
        bail!("unrecognized object: expected one of the keys quat, rotation (+ translation), matrix, dq, euler (+ order), axis (+ angle), rotvec, screw")
    }
}

/// A converted value, ready to print as text or JSON.
pub struct Output {
    /// Human-readable text (one or more lines).
    pub text: String,
    /// The same as a JSON object.
    pub json: Value,
    /// Remarks for stderr.
    pub notes: Vec<String>,
}

/// Number formatting: shortest round-trip by default, or fixed decimals.
#[derive(Debug, Clone, Copy)]
pub struct Fmt(pub Option<usize>);

impl Fmt {
    fn num(&self, x: f64) -> String {
        let x = if x == 0.0 { 0.0 } else { x }; // no "-0"
        match self.0 {
            Some(p) => format!("{x:.p$}"),
            None => format!("{x}"),
        }
    }
    fn arr(&self, xs: &[f64]) -> String {
        let parts: Vec<String> = xs.iter().map(|x| self.num(*x)).collect();
        format!("[{}]", parts.join(", "))
    }
    fn rows(&self, rows: &[&[f64]]) -> String {
        rows.iter()
            .map(|r| self.arr(r))
            .collect::<Vec<_>>()
            .join("\n")
    }
}

fn rotation_only(m: &Motion, to: Repr) -> Result<Quat<f64>> {
    let t = m.dq.translation();
    if t.norm() > 1e-12 {
        bail!(
            "the value has a translation {:?}; --to {to} would drop it (use --to rt, dq, matrix4 or screw)",
            t.to_array()
        );
    }
    Ok(m.dq.real)
}

/// Writes a motion in the target representation.
pub fn render(m: &Motion, to: Repr, f: Fmt) -> Result<Output> {
    let mut notes = Vec::new();
    let (text, json) = match to {
        Repr::Quat => {
            let q = rotation_only(m, to)?.to_array();
            (f.arr(&q), json!({ "quat": q }))
        }
        Repr::Matrix if m.rigid => return render(m, Repr::Matrix4, f),
        Repr::Matrix | Repr::Matrix3 => {
            let r = rotation_only(m, to)?.to_rotation_matrix();
            let rows: Vec<&[f64]> = r.m.iter().map(|r| &r[..]).collect();
            (f.rows(&rows), json!({ "matrix": r.m }))
        }
        Repr::Matrix4 => {
            let r = m.dq.to_matrix4();
            let rows: Vec<&[f64]> = r.m.iter().map(|r| &r[..]).collect();
            (f.rows(&rows), json!({ "matrix": r.m }))
        }
        Repr::Euler(order) => {
            let e = rotation_only(m, to)?.to_euler(order)?;
            if e.gimbal_lock {
                notes.push(
                    "gimbal lock: the third angle is set to 0 (Dam et al. 1998, App. B.2)".into(),
                );
            }
            (
                f.arr(&e.angles),
                json!({ "euler": e.angles, "order": order.to_string(), "gimbal_lock": e.gimbal_lock }),
            )
        }
        Repr::AxisAngle => {
            let (axis, angle) = rotation_only(m, to)?
                .to_positive_hemisphere()
                .to_axis_angle()?;
            let mut v = axis.to_array().to_vec();
            v.push(angle);
            (
                f.arr(&v),
                json!({ "axis": axis.to_array(), "angle": angle }),
            )
        }
        Repr::RotVec => {
            let r = rotation_only(m, to)?.to_rotation_vector()?.to_array();
            (f.arr(&r), json!({ "rotvec": r }))
        }
        Repr::Rt => {
            let (q, t) = (m.dq.real.to_array(), m.dq.translation().to_array());
            (
                format!("rotation {}\ntranslation {}", f.arr(&q), f.arr(&t)),
                json!({ "rotation": q, "translation": t }),
            )
        }
        Repr::Dq => {
            let d = m.dq.to_array();
            (f.arr(&d), json!({ "dq": d }))
        }
        Repr::Screw => {
            let s = m.dq.to_positive_hemisphere().to_screw()?;
            let pitch = s.pitch();
            let text = format!(
                "axis {}\nmoment {}\npoint {}\nangle {}\ntranslation {}\npitch {}",
                f.arr(&s.axis.to_array()),
                f.arr(&s.moment.to_array()),
                f.arr(&s.point().to_array()),
                f.num(s.angle),
                f.num(s.translation),
                pitch.map_or("inf (pure translation)".to_string(), |p| f.num(p)),
            );
            let json = json!({ "screw": {
                "axis": s.axis.to_array(), "moment": s.moment.to_array(), "point": s.point().to_array(),
                "angle": s.angle, "translation": s.translation, "pitch": pitch,
            }});
            (text, json)
        }
    };
    Ok(Output { text, json, notes })
}
