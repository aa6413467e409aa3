//! The tour's blending pictures (Kavan et al. 2006, §4): two transforms 170° apart and
//! what every method makes of them along the path of weights.

use chasles::blend::Options;
use chasles::{DualQuat, Quat, Vec3};
use chasles_paper::Section;

/// Every method's rotation along the path (1 − t, t), and each one's 50/50 blend drawn.
pub fn two_transforms() -> Section {
    let mut s = Section::new("Kavan et al. §4: two transforms 170° apart, blended by every method");
    let x = match Quat::from_axis_angle(Vec3::new(0.0, 0.0, 1.0), 170f64.to_radians()) {
        Ok(q) => [
            DualQuat::identity(),
            DualQuat::from_rotation_translation(q, Vec3::new(3.0, 1.0, 0.0)),
        ],
        Err(e) => {
            s.text(format!("the transforms could not be built: failed: {e}"));
            return s;
        }
    };
    let opt = Options::default();
    let case = crate::blend_pictures::Case {
        x: &x,
        w: &[0.5, 0.5],
        opt: &opt,
    };
    s.try_figure(
        "blend-path.svg",
        crate::blend_pictures::plot(&case).map(String::into_bytes),
        "Two transforms 170° apart, weights (1 − t, t): the rotation every method produces. ScLERP (dashed) is a straight line, constant speed; DLB stays within 8.15° of it; Lin's rotation part races through the middle",
    );
    s.try_figure(
        "blend-render.png",
        crate::blend_pictures::render(&case).map(|i| i.png()),
        "The same two transforms (grey) and each method's 50/50 blend (red): Lin's matrix shrinks the letter to a sliver, the rigid methods keep it whole",
    );
    s
}
