//! The report's example key sets (Dam et al. 1998, Table 5.1 and chapter 7).
//!
//! Only Table 5.1 is printed in the report; chapter 7 shows its sets as pictures. The sets
//! here are built to show what each section describes, and all of them keep the
//! quaternion's z component at 0 (like Table 5.1, whose axes lie in the xy plane), so
//! their curves can be drawn on the ordinary sphere of (w, x, y) (§5.3).
//!
//! Apart from Table 5.1 the keys are placed in the tangent plane at the identity and
//! mapped to the sphere by the exponential: the point (a, b) is the rotation
//! `exp([0, (a, b, 0)])`, by the angle `2√(a² + b²)` about the axis (a, b, 0). Straight
//! lines through the origin of that plane are great arcs on the sphere; other shapes come
//! out slightly bent, like a map projection.

use crate::{Quat, Real, Vec3};

/// A named key set and what it is for.
#[derive(Debug, Clone, PartialEq)]
pub struct KeySet {
    /// Short name, e.g. `table5.1`.
    pub name: &'static str,
    /// The report's section.
    pub section: &'static str,
    /// What the set shows and how its keys were chosen.
    pub description: &'static str,
    /// The key rotations, `[w, x, y, z]`, z = 0.
    pub keys: Vec<Quat<f64>>,
}

impl KeySet {
    /// The keys in precision T.
    pub fn keys<T: Real>(&self) -> Vec<Quat<T>> {
        self.keys.iter().map(|q| q.cast()).collect()
    }
}

fn tangent(points: &[(f64, f64)]) -> Vec<Quat<f64>> {
    points
        .iter()
        .map(|&(a, b)| Quat::pure(Vec3::new(a, b, 0.0)).exp())
        .collect()
}

/// Table 5.1: six keys given as rotation angle and axis (the axes have z = 0).
pub fn table_5_1() -> KeySet {
    let rows = [
        (1.0, (1.0, 3.0)),
        (1.9, (-1.0, 0.0)),
        (0.0, (-2.0, 1.0)),
        (-2.0, (3.0, 4.0)),
        (-1.0, (-1.0, 4.0)),
        (1.0, (1.0, 3.0)),
    ];
    let keys = rows
        .iter()
        .map(|&(angle, (x, y))| {
            let n = Vec3::new(x, y, 0.0) / (x * x + y * y).sqrt();
            Quat::from_scalar_vector((angle * 0.5).cos(), n * (angle * 0.5).sin())
        })
        .collect();
    KeySet {
        name: "table5.1",
        section: "§5.4, Table 5.1",
        description: "The report's key frames for Figures 5.1-5.3 and 6.7-6.20: six rotations (angle, axis) with axes in the xy plane.",
        keys,
    }
}

/// All built-in sets.
pub fn all() -> Vec<KeySet> {
    vec![
        table_5_1(),
        KeySet {
            name: "semicircle",
            section: "§7.1",
            description: "Corners of a spherical square, visited along three sides: (-0.5,-0.5), (0.5,-0.5), (0.5,0.5), (-0.5,0.5) in the tangent plane. Around the two middle keys the curve should be close to a semicircle.",
            keys: tangent(&[(-0.5, -0.5), (0.5, -0.5), (0.5, 0.5), (-0.5, 0.5)]),
        },
        KeySet {
            name: "soft",
            section: "§7.2",
            description: "A soft loop that crosses itself: keys on the nodal cubic x = 0.35(t^2-1), y = 0.25 t(t^2-1) at t = -1.5, -0.8, 0, 0.8, 1.5; the curve passes the crossing point (t = -1 and t = 1) twice.",
            keys: tangent(&[
                (0.4375, -0.46875),
                (-0.126, 0.072),
                (-0.35, 0.0),
                (-0.126, -0.072),
                (0.4375, 0.46875),
            ]),
        },
        KeySet {
            name: "cusp",
            section: "§7.3",
            description: "An arrowhead: the middle key (0.5, 0) is the tip of a sharp turn whose neighbours (0, +-0.03) lie close together, so Squad's velocity there (half the difference of the neighbours' logarithms) nearly vanishes and its curve comes to a point; the outer keys (-0.2, +-0.7) are far apart across the turn, and Spring, which sees all keys, carries their sideways motion through the tip and rounds it with a clearly nonzero speed. (With the outer keys close too, as in a plain hairpin, the minimum of eq. 6.23 itself slows down at the tip and both curves are pointed.)",
            keys: tangent(&[(-0.2, 0.7), (0.0, 0.03), (0.5, 0.0), (0.0, -0.03), (-0.2, -0.7)]),
        },
        KeySet {
            name: "pendulum",
            section: "§7.4",
            description: "Three keys on one great arc, first = last: a rotation by -1.2, +1.2, -1.2 rad about the x axis. Every method should stay on the arc.",
            keys: tangent(&[(-0.6, 0.0), (0.6, 0.0), (-0.6, 0.0)]),
        },
        KeySet {
            name: "perturbed",
            section: "§7.5",
            description: "The pendulum with its first and last key moved slightly off the arc, to opposite sides (y = +0.03 and -0.03): no longer a fixed point of the descent, so Spring can round the turn.",
            keys: tangent(&[(-0.6, 0.03), (0.6, 0.0), (-0.6, -0.03)]),
        },
        KeySet {
            name: "global",
            section: "§7.6",
            description: "Five keys: the first three and the last three on two nearly straight arcs meeting at the middle key at an angle. Squad, being local, draws two arcs and a sharp corner; Spring spreads the turn over all intervals.",
            keys: tangent(&[(-0.8, -0.3), (-0.4, -0.15), (0.0, 0.0), (0.4, -0.15), (0.8, -0.3)]),
        },
    ]
}

/// The set of that name, if it exists.
pub fn by_name(name: &str) -> Option<KeySet> {
    all().into_iter().find(|s| s.name == name)
}
