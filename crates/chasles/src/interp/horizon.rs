//! Camera paths with a stable horizon (Dam et al. 1998, §8.2's cameras; K. Shoemake,
//! "Fiber bundle twist reduction", Graphics Gems IV, 1994).
//!
//! A camera looks along its local x axis; with the world axis `up` (z or y) it has a yaw
//! about `up`, a pitch about its horizontal side axis and a roll about the viewing axis —
//! Euler angles in the intrinsic order ZYX for z up (`R = Rz(yaw) Ry(pitch) Rx(roll)`) and
//! YZX for y up (`R = Ry(yaw) Rz(pitch) Rx(roll)`). A camera "keeps the horizon" when its
//! roll is 0: its side axis (local y for z up, local z for y up) is horizontal.
//!
//! Rotations fibre over the sphere of viewing directions: the fibre over a direction `d`
//! holds the cameras looking along `d`, one per twist about `d` (Shoemake's bundle). A
//! quaternion curve through rollless keys generally leaves the horizontal section of that
//! bundle between the keys — Slerp from yawing left to pitching down rolls on the way. The
//! construction here keeps each frame's viewing direction and replaces its twist by the
//! horizontal one: the frame is turned about its own viewing axis by minus its roll,
//!
//! ```text
//! roll(q) = atan2(ŷ·up, ẑ·up)        (z up: ŷ, ẑ the frame's local y and z axes)
//! roll(q) = atan2(−ẑ·up, ŷ·up)       (y up)
//! level(q) = q · [cos(roll/2), −sin(roll/2) x̂]   (R Rx(−roll): the first column, d, kept)
//! ```
//!
//! — the section of the bundle "direction and up", as building the orientation from the
//! viewing direction `d` and `up` (`x = d`, side `= normalize(up × d)`) would give, without
//! a division. It applies to every method (any curve of directions), keeps the keys when
//! they have no roll, and is as smooth as the method's curve of viewing directions; where
//! that curve passes straight through `±up` the roll is undefined (App. B.2's rule sets it
//! to 0, and so does [`roll`] within √ε of it: the frame is kept).

use super::{interpolate, Frame, KeyFrames, Method, Timing};
use crate::{Error, EulerOrder, Quat, Real, Result, Vec3};

/// The world's up axis of a camera.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Up {
    /// y up: yaw about y, then pitch about z, then roll about x (intrinsic YZX).
    Y,
    /// z up: yaw about z, then pitch about y, then roll about x (intrinsic ZYX).
    #[default]
    Z,
}

impl Up {
    /// The yaw–pitch–roll Euler order: intrinsic ZYX (z up) or YZX (y up).
    pub fn order(self) -> EulerOrder {
        match self {
            Up::Z => EulerOrder {
                axes: [2, 1, 0],
                intrinsic: true,
            },
            Up::Y => EulerOrder {
                axes: [1, 2, 0],
                intrinsic: true,
            },
        }
    }
    /// The up axis as a unit vector.
    pub fn axis<T: Real>(self) -> Vec3<T> {
        match self {
            Up::Z => Vec3::unit(2),
            Up::Y => Vec3::unit(1),
        }
    }
    /// Its name, `"Y"` or `"Z"`.
    pub fn name(self) -> &'static str {
        match self {
            Up::Y => "Y",
            Up::Z => "Z",
        }
    }
}

/// The camera with this yaw and pitch (radians) and no roll.
pub fn camera<T: Real>(up: Up, yaw: T, pitch: T) -> Quat<T> {
    Quat::from_euler(up.order(), [yaw, pitch, T::ZERO])
}

/// The roll of the camera `q` (radians, in ]−π, π]); 0 when it looks along ±up to within
/// √ε (the cosine of its pitch below 1.5e-8 in f64), where the roll is undefined (App.
/// B.2's gimbal-lock rule).
pub fn roll<T: Real>(q: Quat<T>, up: Up) -> T {
    let u = up.axis::<T>();
    let side_y = q.rotate(Vec3::unit(1)).dot(u);
    let side_z = q.rotate(Vec3::unit(2)).dot(u);
    if (side_y * side_y + side_z * side_z).sqrt() <= T::EPSILON.sqrt() {
        return T::ZERO;
    }
    match up {
        Up::Z => side_y.atan2(side_z),
        Up::Y => (-side_z).atan2(side_y),
    }
}

/// `q` turned about its own viewing axis (local x) by minus its roll: the same viewing
/// direction, no roll.
pub fn level<T: Real>(q: Quat<T>, up: Up) -> Quat<T> {
    let half = -roll(q, up) * T::HALF;
    let (s, c) = half.sin_cos();
    q * Quat::new(c, s, T::ZERO, T::ZERO)
}

/// Checks that no key rolls: `|roll| ≤ √ε` (1.5e-8 rad in f64, 3.5e-4 in f32). Errors:
/// [`Error::BadKey`] naming the first key that rolls, with [`Error::BadParameter`]
/// (`"roll"`) giving its roll.
pub fn check_keys<T: Real>(keys: &KeyFrames<T>, up: Up) -> Result<()> {
    let tol = T::EPSILON.sqrt();
    for (index, k) in keys.quats().iter().enumerate() {
        let r = roll(*k, up);
        if r.abs() > tol {
            return Err(Error::BadKey {
                index,
                source: Box::new(Error::BadParameter {
                    what: "roll",
                    rule: "0 for a camera path with a stable horizon (the keys must not roll)",
                    value: r.to_f64(),
                }),
            });
        }
    }
    Ok(())
}

/// Levels every frame ([`level`]), in place; the largest roll removed, in radians.
pub fn level_frames<T: Real>(frames: &mut [Frame<T>], up: Up) -> T {
    let mut most = T::ZERO;
    for f in frames {
        most = most.max(roll(f.q, up).abs());
        f.q = level(f.q, up);
    }
    most
}

/// [`interpolate`] for a camera: the keys checked ([`check_keys`]), the curve made by
/// `method`, and every frame levelled. Errors: those of both.
pub fn interpolate_camera<T: Real>(
    method: Method,
    keys: &KeyFrames<T>,
    frames: usize,
    timing: Timing,
    up: Up,
) -> Result<Vec<Frame<T>>> {
    check_keys(keys, up)?;
    let mut out = interpolate(method, keys, frames, timing)?;
    level_frames(&mut out, up);
    Ok(out)
}
