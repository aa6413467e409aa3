//! The representations `chasles convert` reads and writes, and how each looks as plain
//! numbers, as text and as JSON.
//!
//! Every value is read into a unit dual quaternion (a rotation is one with no translation),
//! then written out in the target representation. Quaternions are `[w, x, y, z]`, matrices
//! row-major, angles in radians, dual quaternions `[w, x, y, z, wε, xε, yε, zε]`.
//!
//! In JSON a value is a serde-derived type ([`MotionJson`], [`MotionFields`]) read through
//! `serde_path_to_error` ([`crate::json`]): every error names the path of the bad field
//! (`rotation[3]`, `screw.axis`), unknown fields are refused, and so is text after the value.
//!
//! Past 500 lines because it is one table read both ways — every representation parsed
//! from numbers and from JSON and printed back — and each form's parse and print sit
//! together so that a change to a form touches one place.

use crate::json::{from_json_line, FieldError, Numbers, Order};
use anyhow::{anyhow, bail, Context, Result};
use chasles::{DualQuat, EulerOrder, Mat3, Mat4, Quat, Screw, Vec3};
use serde::de::value::{MapAccessDeserializer, SeqAccessDeserializer};
use serde::de::{Deserializer, MapAccess, SeqAccess, Visitor};
use serde::Deserialize;
use serde_json::{json, Value};
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

/// The forms a JSON object may take, for messages.
const FORMS: &str =
    "quat, rotation (+ translation), matrix, dq, euler (+ order), axis (+ angle), rotvec, screw";

/// A rigid motion as a JSON object names it: exactly one of `{"quat": [w,x,y,z]}`,
/// `{"rotation": [w,x,y,z], "translation"?: [x,y,z]}`, `{"matrix": …}` (3×3 or 4×4, rows or
/// flat), `{"dq": [8 numbers]}`, `{"euler": [a,b,c], "order": "xyz"}`, `{"axis": [x,y,z],
/// "angle": a}`, `{"rotvec": [x,y,z]}` or `{"screw": {"axis", "point", "angle",
/// "translation"}}`. Unknown fields are refused; so are two forms at once and a companion
/// (`translation`, `order`, `angle`) without its form. Numbers may be nested
/// ([`Numbers`]). The fields `convert --jsonl` writes besides (`gimbal_lock`, a screw's
/// `moment` and `pitch`) are read and ignored, so its output reads back.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MotionFields {
    /// `[w, x, y, z]`.
    quat: Option<Numbers>,
    /// `[w, x, y, z]`, optionally with `translation`.
    rotation: Option<Numbers>,
    /// `[x, y, z]`, applied after `rotation`.
    translation: Option<Numbers>,
    /// 9 or 16 numbers row-major, as rows or flat.
    matrix: Option<Numbers>,
    /// `[w, x, y, z, wε, xε, yε, zε]`.
    dq: Option<Numbers>,
    /// Three angles in radians, in `order`.
    euler: Option<Numbers>,
    /// The Euler order of `euler`.
    order: Option<Order>,
    /// As `convert --to euler:…` writes it, beside `euler`; ignored.
    gimbal_lock: Option<bool>,
    /// The rotation axis of `angle`.
    axis: Option<Numbers>,
    /// The angle about `axis`, radians.
    angle: Option<Numbers>,
    /// Axis times angle.
    rotvec: Option<Numbers>,
    /// A screw motion.
    screw: Option<ScrewFields>,
}

/// A screw motion in JSON: the axis direction, a point on it, the angle about it and the
/// slide along it. `moment` and `pitch`, which `convert --to screw` writes and which follow
/// from the others, are read and ignored.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct ScrewFields {
    /// The axis direction.
    axis: Numbers,
    /// A point on the axis.
    point: Numbers,
    /// The rotation angle about the axis, radians.
    angle: Numbers,
    /// The slide along the axis.
    translation: Numbers,
    /// The axis's moment, point × axis; ignored.
    #[serde(rename = "moment")]
    _moment: Option<Numbers>,
    /// translation / angle (null for a pure translation); ignored.
    #[serde(rename = "pitch")]
    _pitch: Option<f64>,
}

/// `e` (from [`motion_from_numbers`]) as the error of the field at `path`.
fn at(path: &str) -> impl Fn(anyhow::Error) -> FieldError + '_ {
    move |e| FieldError::new(path, format!("{e:#}"))
}

impl MotionFields {
    /// The motion this object gives; errors name the field (`rotation`, `screw.axis`).
    pub fn motion(self) -> Result<Motion, FieldError> {
        let (rotation, euler, axis) = (
            self.rotation.is_some(),
            self.euler.is_some(),
            self.axis.is_some(),
        );
        for (field, given, form, form_given) in [
            (
                "translation",
                self.translation.is_some(),
                "rotation",
                rotation,
            ),
            ("order", self.order.is_some(), "euler", euler),
            ("gimbal_lock", self.gimbal_lock.is_some(), "euler", euler),
            ("angle", self.angle.is_some(), "axis", axis),
        ] {
            if given && !form_given {
                return Err(FieldError::new(
                    field,
                    format!("given without `{form}`, which it goes with"),
                ));
            }
        }
        let forms = [
            ("quat", self.quat.is_some()),
            ("rotation", self.rotation.is_some()),
            ("matrix", self.matrix.is_some()),
            ("dq", self.dq.is_some()),
            ("euler", self.euler.is_some()),
            ("axis", self.axis.is_some()),
            ("rotvec", self.rotvec.is_some()),
            ("screw", self.screw.is_some()),
        ];
        let given: Vec<&str> = forms.iter().filter(|f| f.1).map(|f| f.0).collect();
        if let [a, b, ..] = given[..] {
            return Err(FieldError::new(
                "",
                format!("conflicting fields `{a}` and `{b}`: give exactly one of {FORMS}"),
            ));
        }
        if let Some(q) = self.quat {
            motion_from_numbers(Repr::Quat, &q.0).map_err(at("quat"))
        } else if let Some(r) = self.rotation {
            let r = r.exactly(4, "rotation", "[w, x, y, z]")?;
            match self.translation {
                Some(t) => {
                    let t = t.exactly(3, "translation", "[x, y, z]")?;
                    let v: Vec<f64> = r.iter().chain(t).copied().collect();
                    motion_from_numbers(Repr::Rt, &v).map_err(at("rotation"))
                }
                None => motion_from_numbers(Repr::Quat, r).map_err(at("rotation")),
            }
        } else if let Some(m) = self.matrix {
            motion_from_numbers(Repr::Matrix, &m.0).map_err(at("matrix"))
        } else if let Some(d) = self.dq {
            motion_from_numbers(Repr::Dq, &d.0).map_err(at("dq"))
        } else if let Some(e) = self.euler {
            let Order(order) = self.order.ok_or_else(|| {
                FieldError::new(
                    "",
                    "missing field `order` (e.g. \"xyz\" extrinsic, \"XYZ\" intrinsic)",
                )
            })?;
            motion_from_numbers(Repr::Euler(order), &e.0).map_err(at("euler"))
        } else if let Some(a) = self.axis {
            let a = a.exactly(3, "axis", "[x, y, z]")?;
            let angle = self
                .angle
                .ok_or_else(|| FieldError::new("", "missing field `angle` (radians)"))?;
            let angle = angle.exactly(1, "angle", "")?;
            let v: Vec<f64> = a.iter().chain(angle).copied().collect();
            motion_from_numbers(Repr::AxisAngle, &v).map_err(at("axis"))
        } else if let Some(r) = self.rotvec {
            motion_from_numbers(Repr::RotVec, &r.0).map_err(at("rotvec"))
        } else if let Some(s) = self.screw {
            let mut v = Vec::with_capacity(8);
            for (name, x, n) in [
                ("screw.axis", &s.axis, 3),
                ("screw.point", &s.point, 3),
                ("screw.angle", &s.angle, 1),
                ("screw.translation", &s.translation, 1),
            ] {
                v.extend(x.exactly(n, name, "")?);
            }
            motion_from_numbers(Repr::Screw, &v).map_err(at("screw"))
        } else {
            Err(FieldError::new(
                "",
                format!("expected one of the fields {FORMS}"),
            ))
        }
    }
}

/// A rigid motion that must be a JSON object ([`MotionFields`]), as blend's transforms are.
#[derive(Debug)]
pub struct MotionObject(pub MotionFields);

impl<'de> Deserialize<'de> for MotionObject {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        /// Accepts an object only, saying what one looks like otherwise.
        struct V;
        impl<'de> Visitor<'de> for V {
            type Value = MotionObject;
            fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                f.write_str("an object such as {\"rotation\": [w,x,y,z], \"translation\": [x,y,z]}")
            }
            fn visit_map<A: MapAccess<'de>>(self, map: A) -> Result<MotionObject, A::Error> {
                MotionFields::deserialize(MapAccessDeserializer::new(map)).map(MotionObject)
            }
        }
        d.deserialize_map(V)
    }
}

/// A rigid motion as one JSON value: a bare array of numbers in the `--from`
/// representation (nested arrays read flat), or an object that names its form
/// ([`MotionFields`]).
#[derive(Debug)]
pub enum MotionJson {
    /// A bare array.
    Numbers(Numbers),
    /// An object (boxed: it is large beside a bare array).
    Object(Box<MotionFields>),
}

impl<'de> Deserialize<'de> for MotionJson {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        /// An array or an object; the path into either is kept.
        struct V;
        impl<'de> Visitor<'de> for V {
            type Value = MotionJson;
            fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                f.write_str("an array of numbers or an object such as {\"quat\": [1, 0, 0, 0]}")
            }
            fn visit_seq<A: SeqAccess<'de>>(self, seq: A) -> Result<MotionJson, A::Error> {
                Numbers::deserialize(SeqAccessDeserializer::new(seq)).map(MotionJson::Numbers)
            }
            fn visit_map<A: MapAccess<'de>>(self, map: A) -> Result<MotionJson, A::Error> {
                MotionFields::deserialize(MapAccessDeserializer::new(map))
                    .map(|o| MotionJson::Object(Box::new(o)))
            }
        }
        d.deserialize_any(V)
    }
}

impl MotionJson {
    /// The motion this value gives; `from` says what a bare array is.
    pub fn motion(self, from: Option<Repr>) -> Result<Motion, FieldError> {
        match self {
            MotionJson::Object(o) => o.motion(),
            MotionJson::Numbers(v) => {
                let repr = from.ok_or_else(|| {
                    FieldError::new(
                        "",
                        "a bare array needs --from to say what it is; or give an object such as {\"quat\": [1, 0, 0, 0]}",
                    )
                })?;
                motion_from_numbers(repr, &v.0).map_err(at(""))
            }
        }
    }
}

/// Reads a motion from one line of JSON lines ([`MotionJson`]): `from` says what a bare
/// array is. Errors name the path of the bad field and the column; text after the value is
/// refused.
pub fn motion_from_json_line(text: &str, from: Option<Repr>) -> Result<Motion, FieldError> {
    from_json_line::<MotionJson>(text)?.motion(from)
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
    if let Some(at) = first_non_finite(&json, "") {
        bail!("the result's {at} is not a finite number: the input is beyond the range of f64");
    }
    Ok(Output { text, json, notes })
}

/// The path of the first number of `v` that is not finite — which `serde_json` holds as
/// `null` — leaving out `pitch`, whose `null` means a pure translation.
pub fn first_non_finite(v: &serde_json::Value, at: &str) -> Option<String> {
    use serde_json::Value;
    match v {
        Value::Null => Some(at.to_string()),
        Value::Number(n) => n
            .as_f64()
            .filter(|x| !x.is_finite())
            .map(|_| at.to_string()),
        Value::Array(a) => a
            .iter()
            .enumerate()
            .find_map(|(i, x)| first_non_finite(x, &format!("{at}[{i}]"))),
        Value::Object(o) => o
            .iter()
            .filter(|(k, _)| k.as_str() != "pitch")
            .find_map(|(k, x)| {
                let p = if at.is_empty() {
                    k.clone()
                } else {
                    format!("{at}.{k}")
                };
                first_non_finite(x, &p)
            }),
        _ => None,
    }
}
