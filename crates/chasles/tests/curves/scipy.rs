//! The C² spline against SciPy's `RotationSpline` itself: rotations, angular rates and
//! accelerations at many times, when a Python 3 with SciPy is there (`$CHASLES_PYTHON`,
//! else `python3`); otherwise the test says so and passes. (CI's Python package tests run
//! the same comparison through the CLI, `crates/chasles-py/tests/test_curves.py`.)

use super::*;
use std::process::Command;

fn python() -> String {
    std::env::var("CHASLES_PYTHON").unwrap_or_else(|_| "python3".into())
}

fn has_scipy(py: &str) -> bool {
    Command::new(py)
        .args(["-c", "import scipy.spatial.transform"])
        .output()
        .is_ok_and(|o| o.status.success())
}

/// SciPy's rotations (`[w, x, y, z]`), rates and accelerations at `at` for these keys.
fn scipy(py: &str, q: &[Quat<f64>], times: &[f64], at: &[f64]) -> Vec<[f64; 10]> {
    let list = |v: Vec<String>| format!("[{}]", v.join(","));
    let quats = list(
        q.iter()
            .map(|q| format!("[{:?},{:?},{:?},{:?}]", q.x, q.y, q.z, q.w))
            .collect(),
    );
    let num = |v: &[f64]| list(v.iter().map(|x| format!("{x:?}")).collect());
    let script = format!(
        "from scipy.spatial.transform import Rotation, RotationSpline\n\
         s = RotationSpline({}, Rotation.from_quat({quats}))\n\
         t = {}\n\
         r, w, a = s(t).as_quat(), s(t, 1), s(t, 2)\n\
         for i in range(len(t)):\n    \
             print(' '.join(repr(float(v)) for v in [r[i][3], r[i][0], r[i][1], r[i][2], *w[i], *a[i]]))\n",
        num(times),
        num(at)
    );
    let out = Command::new(py).args(["-c", &script]).output().unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8(out.stdout)
        .unwrap()
        .lines()
        .map(|l| {
            let v: Vec<f64> = l.split(' ').map(|x| x.parse().unwrap()).collect();
            core::array::from_fn(|k| v[k])
        })
        .collect()
}

#[test]
fn c2_spline_agrees_with_scipy() {
    let py = python();
    if !has_scipy(&py) {
        println!("skipped: no Python 3 with SciPy ({py}); set CHASLES_PYTHON to one");
        return;
    }
    let mut worst = [0.0f64; 3];
    for (q, times) in [
        (wild::<f64>(), uneven(7)),
        (table::<f64>(), (0..6).map(|i| i as f64).collect()),
        (wild::<f64>()[..3].to_vec(), vec![0.0, 0.4, 2.0]),
    ] {
        let kf = keys(&q, Some(&times));
        let c2 = C2Spline::new(&kf).unwrap();
        let mut at = Vec::new();
        let mut ours = Vec::new();
        for i in 0..times.len() - 1 {
            for j in 0..10 {
                let h = j as f64 / 10.0;
                at.push(kf.parameter(i, h));
                ours.push((
                    c2.eval(i, h),
                    c2.angular_velocity(i, h),
                    c2.angular_acceleration(i, h),
                ));
            }
        }
        let theirs = scipy(&py, kf.quats(), &times, &at);
        for ((r, w, a), s) in ours.iter().zip(&theirs) {
            let sq = Quat::new(s[0], s[1], s[2], s[3]);
            worst[0] = worst[0].max(diff(*r, sq));
            worst[1] = worst[1].max((*w - Vec3::new(s[4], s[5], s[6])).norm());
            worst[2] = worst[2].max((*a - Vec3::new(s[7], s[8], s[9])).norm());
        }
    }
    println!(
        "C2 spline against SciPy's RotationSpline: rotations {:.1e}, rates {:.1e}, accelerations {:.1e}",
        worst[0], worst[1], worst[2]
    );
    assert!(worst.iter().all(|w| *w < 1e-9), "{worst:?}");
}
