//! Key-frame files (TOML or JSON) and the built-in sets.
//!
//! ```toml
//! order = "xyz"            # optional: Euler order for keys given as `euler` (default xyz)
//! [[keys]]
//! angle = 1.0              # radians, about `axis` (Dam et al. Table 5.1)
//! axis = [1, 3, 0]
//! time = 0.0               # optional, on every key or on none
//! velocity = [0, 0.5, 0]   # optional: angular velocity at this key (rad per unit time,
//!                          # world axes); squad and spring (converged) honour it
//! [[keys]]
//! quat = [1, 0, 0, 0]      # [w, x, y, z]
//! [[keys]]
//! euler = [0.1, 0.2, 0.3]  # radians
//! order = "ZYX"            # optional per key
//! tension = 0.3            # optional on any key, for --method tcb: its own tension,
//! continuity = -0.2        #   continuity and bias, each in [-1, 1] (Kochanek–Bartels);
//! bias = 0.5               #   those left out are --tension/--continuity/--bias (or 0)
//! [[keys]]
//! rotation = [1, 0, 0, 0]  # a rigid key (chasles interp --rigid): [w, x, y, z] and
//! translation = [1, 2, 3]  #   [x, y, z] (any rotation form may take a translation)
//! [[keys]]
//! matrix = [[1, 0, 0, 1], [0, 1, 0, 2], [0, 0, 1, 3], [0, 0, 0, 1]]  # 4x4, row-major
//! [[keys]]
//! dq = [1, 0, 0, 0, 0, 0.5, 1, 1.5]  # a unit dual quaternion [w,x,y,z, wε,xε,yε,zε]
//! [[keys]]
//! yaw = 0.5                # a camera (radians): yaw about the up axis, pitch, and an
//! pitch = -0.1             #   optional roll (default 0), looking along its x axis, with
//!                          #   the file's `horizon` axis up (z when it names none)
//! [spring]                 # optional: Spring's controls, as `chasles interp`'s options
//! levels = [22, 110, 550]  # frames per step; the last is the total
//! iterations = [200, 150, 100]
//! step = "fixed:0.02"      # or normalized:E, adaptive:E, accelerated:E
//! penalty = 1.0            # c of eq. 6.28
//! width = "one"            # one (eq. 6.43), chord (eq. 6.24) or angle
//! key_weight = 1.3         # c_k
//! velocity_weight = 0.0    # c_w (eq. 6.41)
//! start = "slerp"          # or squad
//! ```
//!
//! A top-level `horizon = "Z"` (or `"Y"`) names the up axis of the camera keys and asks for
//! a path with a stable horizon, as `chasles interp --horizon` does.
//!
//! JSON takes the same shape, `{"order": "xyz", "keys": [{"angle": 1, "axis": [1, 3, 0]}, …]}`,
//! or just the array of keys. Both are serde-derived types read through
//! `serde_path_to_error`: syntax errors name the line and column, every other error the
//! path of the key and field, e.g. `keys[2].axis` (a field of the wrong type, a misspelt
//! field, an unknown Euler order, a zero axis alike).

use crate::json::{from_json, Order};
use crate::repr::{motion_from_numbers, Repr};
use crate::spring_args::SpringArgs;
use anyhow::{anyhow, bail, Context, Result};
use chasles::interp::tcb::check_parameter;
use chasles::interp::{examples, TcbKey, Up};
use chasles::{DualQuat, EulerOrder, Quat, Vec3};
use serde::de::value::{MapAccessDeserializer, SeqAccessDeserializer};
use serde::de::{Deserializer, MapAccess, SeqAccess, Visitor};
use serde::Deserialize;
use std::fmt;
use std::path::Path;

/// A key file: the default Euler order and the keys.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct Doc {
    /// The Euler order of keys given as `euler` without their own.
    #[serde(default)]
    order: Option<Order>,
    /// The keys, in order.
    keys: Vec<Spec>,
    /// Spring's controls ([`SpringArgs`]).
    #[serde(default)]
    spring: Option<SpringArgs>,
    /// The up axis of camera keys, and a stable horizon.
    #[serde(default)]
    horizon: Option<HorizonName>,
}

/// An up axis as written: `"Z"` or `"Y"` (either case).
#[derive(Deserialize, Clone, Copy)]
enum HorizonName {
    #[serde(alias = "z")]
    Z,
    #[serde(alias = "y")]
    Y,
}

impl HorizonName {
    fn up(self) -> Up {
        match self {
            HorizonName::Z => Up::Z,
            HorizonName::Y => Up::Y,
        }
    }
}

/// A JSON key file: a [`Doc`], or just its array of keys. (Not an untagged enum, which
/// would hide the path of the bad field.)
struct JsonDoc(Doc);

impl<'de> Deserialize<'de> for JsonDoc {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        /// An object or an array of keys; the path into either is kept.
        struct V;
        impl<'de> Visitor<'de> for V {
            type Value = JsonDoc;
            fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                f.write_str("an object {\"keys\": [...]} or an array of keys")
            }
            fn visit_seq<A: SeqAccess<'de>>(self, seq: A) -> Result<JsonDoc, A::Error> {
                let keys = Vec::deserialize(SeqAccessDeserializer::new(seq))?;
                Ok(JsonDoc(Doc {
                    order: None,
                    keys,
                    spring: None,
                    horizon: None,
                }))
            }
            fn visit_map<A: MapAccess<'de>>(self, map: A) -> Result<JsonDoc, A::Error> {
                Doc::deserialize(MapAccessDeserializer::new(map)).map(JsonDoc)
            }
        }
        d.deserialize_any(V)
    }
}

/// One key: `angle` and `axis`, `quat`, `euler` (with an optional `order`) or a camera's
/// `yaw` and `pitch` (and optional `roll`); an optional `time`; optional Kochanek–Bartels
/// `tension`, `continuity` and `bias`.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct Spec {
    /// Radians about `axis`.
    angle: Option<f64>,
    /// The axis of `angle`.
    axis: Option<[f64; 3]>,
    /// `[w, x, y, z]`.
    quat: Option<[f64; 4]>,
    /// `[w, x, y, z]` (as `quat`; the rigid forms' name).
    rotation: Option<[f64; 4]>,
    /// `[x, y, z]`, applied after the rotation (a rigid key).
    translation: Option<[f64; 3]>,
    /// A 4×4 rigid matrix, row-major, as four rows.
    matrix: Option<[[f64; 4]; 4]>,
    /// A unit dual quaternion `[w, x, y, z, wε, xε, yε, zε]`.
    dq: Option<[f64; 8]>,
    /// Three angles in radians.
    euler: Option<[f64; 3]>,
    /// The Euler order of this key's `euler`.
    order: Option<Order>,
    /// The key's time.
    time: Option<f64>,
    /// The angular velocity at this key (rad per unit of time, world axes).
    velocity: Option<[f64; 3]>,
    /// A camera's yaw about the up axis (radians).
    yaw: Option<f64>,
    /// A camera's pitch (radians).
    pitch: Option<f64>,
    /// A camera's roll (radians; 0 when left out).
    roll: Option<f64>,
    /// Kochanek–Bartels tension at this key.
    tension: Option<f64>,
    /// Kochanek–Bartels continuity at this key.
    continuity: Option<f64>,
    /// Kochanek–Bartels bias at this key.
    bias: Option<f64>,
}

/// Key frames as read: rotations, optional times, and where they came from.
pub struct Keys {
    /// The key rotations.
    pub quats: Vec<Quat<f64>>,
    /// Times, when every key has one.
    pub times: Option<Vec<f64>>,
    /// The Euler triples and their order, when every key is given as `euler` in one order
    /// (LinEuler then interpolates the triples as given, eq. 6.1).
    pub euler: Option<(EulerOrder, Vec<[f64; 3]>)>,
    /// The file's `[spring]` table, if any.
    pub spring: Option<SpringArgs>,
    /// The angular velocity at each key that gives one.
    pub velocities: Option<Vec<Option<Vec3<f64>>>>,
    /// Each key's own tension, continuity and bias, when some key has one.
    pub tcb: Option<Vec<TcbKey>>,
    /// The file's `horizon`: the up axis of its camera keys and a stable horizon.
    pub horizon: Option<Up>,
    /// Whether some key is a camera given by yaw and pitch.
    pub cameras: bool,
    /// The keys as rigid motions, when some key carries a translation (`translation`,
    /// `matrix` or `dq`); the others have none.
    pub poses: Option<Vec<DualQuat<f64>>>,
    /// A name for messages: the file or `builtin:NAME`.
    pub source: String,
}

/// Reads `builtin:NAME` or a `.toml` / `.json` file.
pub fn load(spec: &str) -> Result<Keys> {
    if let Some(name) = spec.strip_prefix("builtin:") {
        let set = examples::by_name(name).ok_or_else(|| {
            let names: Vec<&str> = examples::all().iter().map(|s| s.name).collect();
            anyhow!(
                "no built-in key set '{name}'; there are: {}",
                names.join(", ")
            )
        })?;
        return Ok(Keys {
            quats: set.keys,
            times: None,
            euler: None,
            spring: None,
            velocities: None,
            tcb: None,
            horizon: None,
            cameras: false,
            poses: None,
            source: spec.to_string(),
        });
    }
    let path = Path::new(spec);
    let text = chasles_skin::bounded::read_text(path, chasles_skin::bounded::MAX_TEXT_BYTES)
        .with_context(|| format!("cannot read key file {spec}"))?;
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .unwrap_or("")
        .to_ascii_lowercase();
    from_text(&text, &ext, spec)
}

/// Reads key-file `text` in the format of the extension `ext` (`toml` or `json`, lower
/// case); `spec` names the file in messages.
pub fn from_text(text: &str, ext: &str, spec: &str) -> Result<Keys> {
    let doc = match ext {
        "toml" => {
            let de = toml::Deserializer::parse(text)
                .map_err(|e| anyhow!("{spec}: {}", one_line(&e.to_string())))?;
            serde_path_to_error::deserialize::<_, Doc>(de).map_err(|e| {
                let path = match e.path().to_string() {
                    root if root == "." => String::new(),
                    path => format!("{path}: "),
                };
                anyhow!("{spec}: {path}{}", one_line(&e.into_inner().to_string()))
            })?
        }
        "json" => {
            let doc = from_json::<JsonDoc>(text).map_err(|e| {
                // A bare array of keys: its `[i]` is `keys[i]`, as in the object form.
                let e = if e.path.starts_with('[') {
                    e.within("keys")
                } else {
                    e
                };
                anyhow!("{spec}: {e}")
            })?;
            doc.0
        }
        other => bail!("{spec}: key files must end in .toml or .json (got '.{other}')"),
    };
    parse(doc, spec)
}

/// `s` (a TOML error, drawn over several lines) on one line.
fn one_line(s: &str) -> String {
    s.lines()
        .map(str::trim)
        .filter(|l| !l.is_empty())
        .collect::<Vec<_>>()
        .join(" ")
}

/// The keys of `doc` (read from `source`) as rotations, checked: at least two, times on
/// all or none, each key exactly one form.
fn parse(doc: Doc, source: &str) -> Result<Keys> {
    let default_order = doc.order.map_or(EulerOrder::DAM, |Order(o)| o);
    if doc.keys.len() < 2 {
        bail!("{source}: need at least 2 keys, found {}", doc.keys.len());
    }
    let with_time = doc.keys.iter().filter(|k| k.time.is_some()).count();
    if with_time != 0 && with_time != doc.keys.len() {
        let i = doc.keys.iter().position(|k| k.time.is_none()).unwrap_or(0);
        bail!("{source}: keys[{i}].time is missing: give a time on every key or on none");
    }
    let up = doc.horizon.map_or(Up::Z, HorizonName::up);
    let mut quats = Vec::with_capacity(doc.keys.len());
    let mut triples: Vec<(EulerOrder, [f64; 3])> = Vec::new();
    let mut tcb = Vec::with_capacity(doc.keys.len());
    let mut cameras = false;
    let mut posed: Vec<(usize, DualQuat<f64>)> = Vec::new();
    for (i, k) in doc.keys.iter().enumerate() {
        let at = |field: &str| format!("{source}: keys[{i}].{field}");
        for (field, v) in [
            ("angle", k.angle),
            ("time", k.time),
            ("yaw", k.yaw),
            ("pitch", k.pitch),
            ("roll", k.roll),
        ] {
            if v.is_some_and(|v| !v.is_finite()) {
                bail!("{} is not a finite number", at(field));
            }
        }
        if k.velocity.is_some_and(|v| v.iter().any(|x| !x.is_finite())) {
            bail!("{} is not finite", at("velocity"));
        }
        for (field, v) in [
            ("tension", k.tension),
            ("continuity", k.continuity),
            ("bias", k.bias),
        ] {
            if let Some(v) = v.filter(|v| check_parameter("", *v).is_err()) {
                bail!("{} must be a finite number in [-1, 1], got {v}", at(field));
            }
        }
        tcb.push(TcbKey {
            tension: k.tension,
            continuity: k.continuity,
            bias: k.bias,
        });
        let camera = match (k.yaw, k.pitch, k.roll) {
            (None, None, None) => None,
            (Some(yaw), Some(pitch), roll) => Some([yaw, pitch, roll.unwrap_or(0.0)]),
            (None, _, _) => bail!(
                "{} is missing (a camera key needs yaw and pitch)",
                at("yaw")
            ),
            (_, None, _) => bail!(
                "{} is missing (a camera key needs yaw and pitch)",
                at("pitch")
            ),
        };
        // A rigid key given whole: a matrix or a dual quaternion, alone.
        let whole = match (k.matrix, k.dq) {
            (Some(_), Some(_)) => {
                bail!("{source}: keys[{i}] must have one of {{matrix}} or {{dq}}, not both")
            }
            (Some(m), None) => Some(("matrix", Repr::Matrix4, m.concat())),
            (None, Some(d)) => Some(("dq", Repr::Dq, d.to_vec())),
            (None, None) => None,
        };
        if let Some((field, repr, numbers)) = whole {
            if camera.is_some()
                || k.angle.is_some()
                || k.axis.is_some()
                || k.quat.is_some()
                || k.euler.is_some()
                || k.rotation.is_some()
                || k.translation.is_some()
            {
                bail!("{}: a whole rigid motion, given with another rotation or a translation (give it alone)", at(field));
            }
            if numbers.iter().any(|v| !v.is_finite()) {
                bail!("{} is not finite", at(field));
            }
            let m = motion_from_numbers(repr, &numbers).with_context(|| at(field))?;
            posed.push((i, m.dq));
            quats.push(m.dq.real);
            continue;
        }
        if let Some(t) = k.translation {
            if t.iter().any(|v| !v.is_finite()) {
                bail!("{} is not finite", at("translation"));
            }
        }
        if let Some(ypr) = camera {
            if k.angle.is_some()
                || k.axis.is_some()
                || k.quat.is_some()
                || k.euler.is_some()
                || k.rotation.is_some()
            {
                bail!("{source}: keys[{i}] must have exactly one of {{angle, axis}}, {{quat}}, {{euler}} or {{yaw, pitch}}");
            }
            cameras = true;
            let q = Quat::from_euler(up.order(), ypr);
            if let Some(t) = k.translation {
                posed.push((
                    i,
                    DualQuat::from_rotation_translation(q, Vec3::from_array(t)),
                ));
            }
            quats.push(q);
            continue;
        }
        let quat = match (k.quat, k.rotation) {
            (Some(_), Some(_)) => bail!("{source}: keys[{i}] must have exactly one of {{angle, axis}}, {{quat}}, {{rotation}}, {{euler}} or {{yaw, pitch}}"),
            (q, r) => q.or(r),
        };
        let quat_field = if k.rotation.is_some() {
            "rotation"
        } else {
            "quat"
        };
        let q = match (k.angle, k.axis, quat, k.euler) {
            (Some(angle), Some(axis), None, None) => {
                Quat::from_axis_angle(Vec3::from_array(axis), angle).with_context(|| at("axis"))?
            }
            (None, None, Some(q), None) => Quat::from_array(q).normalize().with_context(|| at(quat_field))?,
            (None, None, None, Some(e)) => {
                let order = k.order.map_or(default_order, |Order(o)| o);
                if e.iter().any(|v| !v.is_finite()) {
                    bail!("{} is not finite", at("euler"));
                }
                triples.push((order, e));
                Quat::from_euler(order, e)
            }
            (Some(_), None, None, None) => bail!("{} is missing (angle needs an axis)", at("axis")),
            (None, Some(_), None, None) => bail!("{} is missing (axis needs an angle)", at("angle")),
            _ => bail!("{source}: keys[{i}] must have exactly one of {{angle, axis}}, {{quat}}, {{euler}} or {{yaw, pitch}}"),
        };
        if let Some(t) = k.translation {
            posed.push((
                i,
                DualQuat::from_rotation_translation(q, Vec3::from_array(t)),
            ));
        }
        quats.push(q);
    }
    let poses = (!posed.is_empty()).then(|| {
        let mut p: Vec<DualQuat<f64>> = quats.iter().map(|q| DualQuat::from_rotation(*q)).collect();
        for (i, d) in &posed {
            p[*i] = *d;
        }
        p
    });
    let times = (with_time > 0).then(|| doc.keys.iter().map(|k| k.time.unwrap_or(0.0)).collect());
    let euler = match triples.first() {
        Some(&(order, _))
            if triples.len() == quats.len() && triples.iter().all(|(o, _)| *o == order) =>
        {
            Some((order, triples.iter().map(|(_, e)| *e).collect()))
        }
        _ => None,
    };
    let velocities = doc.keys.iter().any(|k| k.velocity.is_some()).then(|| {
        doc.keys
            .iter()
            .map(|k| k.velocity.map(Vec3::from_array))
            .collect()
    });
    let any_tcb = tcb
        .iter()
        .any(|k| k.tension.is_some() || k.continuity.is_some() || k.bias.is_some());
    Ok(Keys {
        quats,
        times,
        euler,
        spring: doc.spring,
        velocities,
        tcb: any_tcb.then_some(tcb),
        horizon: doc.horizon.map(HorizonName::up),
        cameras,
        poses,
        source: source.to_string(),
    })
}
