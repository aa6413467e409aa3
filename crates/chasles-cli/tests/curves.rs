//! `chasles interp` with the curves past the report (issue 21, items 4–5): `--method
//! tcb|catmull-rom|bezier|c2`, Kochanek–Bartels' `--tension/--continuity/--bias` and per-key
//! values in key files, camera keys (`yaw`, `pitch`) and `--horizon Z|Y` on any method, and
//! the one-line errors for values out of range.

mod common;
use chasles::interp::horizon::roll;
use chasles::interp::Up;
use chasles::Quat;
use common::*;
use std::path::Path;
use std::process::Output;

fn failed(o: &Output) -> String {
    assert!(!o.status.success(), "succeeded: {o:?}");
    assert_eq!(o.status.code(), Some(2));
    let err = String::from_utf8_lossy(&o.stderr).to_string();
    assert_eq!(err.trim().lines().count(), 1, "{err}");
    err
}

/// `(quaternion, key)` of every CSV row.
fn rows(csv: &str) -> Vec<(Quat<f64>, Option<usize>)> {
    csv.lines()
        .skip(1)
        .map(|l| {
            let c: Vec<&str> = l.split(',').collect();
            let v: Vec<f64> = c[2..6].iter().map(|x| x.parse().unwrap()).collect();
            (Quat::new(v[0], v[1], v[2], v[3]), c[7].parse().ok())
        })
        .collect()
}

fn write(dir: &Path, name: &str, text: &str) -> String {
    let p = dir.join(name);
    std::fs::write(&p, text).unwrap();
    p.to_str().unwrap().to_string()
}

fn interp(args: &[&str]) -> Vec<(Quat<f64>, Option<usize>)> {
    let mut all = vec!["interp", "--frames", "120"];
    all.extend_from_slice(args);
    rows(&stdout(&chasles(&all)))
}

fn same(a: &[(Quat<f64>, Option<usize>)], b: &[(Quat<f64>, Option<usize>)]) -> f64 {
    assert_eq!(a.len(), b.len());
    a.iter()
        .zip(b)
        .map(|(x, y)| (x.0 - y.0).norm())
        .fold(0.0, f64::max)
}

#[test]
fn every_new_method_passes_through_the_keys() {
    let keys = chasles::interp::examples::table_5_1().keys;
    for m in ["tcb", "catmull-rom", "bezier", "c2"] {
        let r = interp(&["--method", m, "--keys", "builtin:table5.1"]);
        assert_eq!(r.len(), 120);
        for (q, k) in &r {
            assert!((q.norm() - 1.0).abs() < 1e-12, "{m}");
            if let Some(k) = k {
                assert!(
                    (*q - keys[*k]).norm().min((*q + keys[*k]).norm()) < 1e-12,
                    "{m}"
                );
            }
        }
    }
    // Zero parameters are Catmull–Rom.
    let tcb = interp(&[
        "--method",
        "tcb",
        "--keys",
        "builtin:table5.1",
        "--tension",
        "0",
    ]);
    let cr = interp(&["--method", "catmull-rom", "--keys", "builtin:table5.1"]);
    assert!(same(&tcb, &cr) < 1e-12);
}

#[test]
fn parameters_from_flags_and_from_keys() {
    let dir = tempfile::tempdir().unwrap();
    let plain = "[[keys]]\nangle = 1.0\naxis = [1, 3, 0]\n[[keys]]\nangle = 1.9\naxis = [-1, 0, 0]\n[[keys]]\nangle = 0.5\naxis = [-2, 1, 0]\n[[keys]]\nangle = -2.0\naxis = [3, 4, 0]\n";
    let keys = write(dir.path(), "k.toml", plain);
    // A key's own tension equals the flag when every key has it.
    let own = plain.replace("[[keys]]\n", "[[keys]]\ntension = -0.4\n");
    let own = write(dir.path(), "own.toml", &own);
    let a = interp(&["--method", "tcb", "--keys", &keys, "--tension", "-0.4"]);
    let b = interp(&["--method", "tcb", "--keys", &own]);
    assert!(same(&a, &b) < 1e-15);
    // Negative values also as --bias=-0.5; the key's own wins over the flag.
    let c = interp(&[
        "--method",
        "tcb",
        "--keys",
        &own,
        "--tension=0.9",
        "--bias=-0.5",
    ]);
    let d = interp(&[
        "--method",
        "tcb",
        "--keys",
        &keys,
        "--tension",
        "-0.4",
        "--bias",
        "-0.5",
    ]);
    assert!(same(&c, &d) < 1e-15);
    assert!(same(&a, &d) > 1e-3);
    // JSON too.
    let json = write(
        dir.path(),
        "k.json",
        r#"[{"quat": [1, 0, 0, 0], "continuity": -1}, {"quat": [0.8, 0.6, 0, 0], "continuity": -1}, {"quat": [0.8, 0, 0.6, 0], "continuity": -1}]"#,
    );
    let e = interp(&["--method", "tcb", "--keys", &json]);
    let s = interp(&["--method", "slerp", "--keys", &json]);
    assert!(same(&e, &s) < 1e-12, "continuity -1 everywhere is Slerp");
}

#[test]
fn values_out_of_range_are_one_line_errors() {
    let dir = tempfile::tempdir().unwrap();
    let e = failed(&chasles(&[
        "interp",
        "--method",
        "tcb",
        "--keys",
        "builtin:table5.1",
        "--tension",
        "1.5",
    ]));
    assert!(
        e.contains("--tension must be a finite number in [-1, 1], got 1.5"),
        "{e}"
    );
    let e = failed(&chasles(&[
        "interp",
        "--method",
        "tcb",
        "--keys",
        "builtin:table5.1",
        "--bias",
        "NaN",
    ]));
    assert!(e.contains("--bias"), "{e}");
    let e = failed(&chasles(&[
        "interp",
        "--method",
        "squad",
        "--keys",
        "builtin:table5.1",
        "--continuity",
        "0.2",
    ]));
    assert!(
        e.contains("--continuity is a Kochanek-Bartels control") && e.contains("squad"),
        "{e}"
    );
    let k = write(
        dir.path(),
        "bad.toml",
        "[[keys]]\nquat = [1, 0, 0, 0]\n[[keys]]\nquat = [0, 1, 0, 0]\ncontinuity = -1.2\n",
    );
    let e = failed(&chasles(&["interp", "--method", "tcb", "--keys", &k]));
    assert!(
        e.contains("keys[1].continuity must be a finite number in [-1, 1], got -1.2"),
        "{e}"
    );
    let k = write(
        dir.path(),
        "bad.json",
        r#"[{"quat": [1, 0, 0, 0], "bias": "x"}, {"quat": [1, 0, 0, 0]}]"#,
    );
    let e = failed(&chasles(&["interp", "--method", "tcb", "--keys", &k]));
    assert!(e.contains("keys[0].bias"), "{e}");
}

const CAMERA: &str = "[[keys]]\nyaw = 0.0\npitch = 0.0\n[[keys]]\nyaw = 0.9\npitch = -0.4\n[[keys]]\nyaw = 1.8\npitch = 0.3\n[[keys]]\nyaw = 2.2\npitch = 0.9\n[[keys]]\nyaw = 3.4\npitch = -0.2\n";

#[test]
fn horizon_on_every_method_rolls_no_frame() {
    let dir = tempfile::tempdir().unwrap();
    for (up, head) in [(Up::Z, ""), (Up::Y, "horizon = \"Y\"\n")] {
        let keys = write(dir.path(), "cam.toml", &format!("{head}{CAMERA}"));
        for m in [
            "lineuler",
            "linmat",
            "lerp",
            "slerp",
            "squad",
            "spring",
            "tcb",
            "catmull-rom",
            "bezier",
            "c2",
        ] {
            let flag = ["--horizon", up.name()];
            let out = chasles(
                &[
                    &["interp", "--method", m, "--keys", &keys, "--frames", "90"][..],
                    &flag,
                ]
                .concat(),
            );
            let r = rows(&stdout(&out));
            let summary = String::from_utf8_lossy(&out.stderr);
            assert!(
                summary.contains(&format!("horizon           {} up", up.name())),
                "{summary}"
            );
            let worst = r
                .iter()
                .map(|(q, _)| roll(*q, up).abs())
                .fold(0.0, f64::max);
            assert!(worst < 1e-12, "{m} {up:?}: {worst}");
            // The keys as cameras: yaw, pitch, no roll.
            let cams: Vec<(f64, f64)> =
                vec![(0.0, 0.0), (0.9, -0.4), (1.8, 0.3), (2.2, 0.9), (3.4, -0.2)];
            for (q, k) in r.iter().filter_map(|(q, k)| k.map(|k| (q, k))) {
                let want = chasles::interp::horizon::camera(up, cams[k].0, cams[k].1);
                assert!(
                    (*q - want).norm().min((*q + want).norm()) < 1e-12,
                    "{m} key {k}"
                );
            }
        }
    }
}

#[test]
fn horizon_errors_name_the_problem() {
    let dir = tempfile::tempdir().unwrap();
    let keys = write(dir.path(), "cam.toml", CAMERA);
    // Cameras made with z up cannot be levelled about y unless the file says so.
    let e = failed(&chasles(&[
        "interp",
        "--method",
        "slerp",
        "--keys",
        &keys,
        "--horizon",
        "Y",
    ]));
    assert!(e.contains("horizon = \"Y\""), "{e}");
    let y = write(dir.path(), "y.toml", &format!("horizon = \"Y\"\n{CAMERA}"));
    let e = failed(&chasles(&[
        "interp",
        "--method",
        "slerp",
        "--keys",
        &y,
        "--horizon",
        "z",
    ]));
    assert!(e.contains("differ"), "{e}");
    // A key that rolls, named.
    let rolled = CAMERA.replace(
        "yaw = 2.2\npitch = 0.9\n",
        "yaw = 2.2\npitch = 0.9\nroll = 0.1\n",
    );
    let r = write(dir.path(), "r.toml", &rolled);
    let e = failed(&chasles(&[
        "interp",
        "--method",
        "c2",
        "--keys",
        &r,
        "--horizon",
        "Z",
    ]));
    assert!(e.contains("key frame 3: roll must be 0"), "{e}");
    // Without --horizon a rolling camera key is just a key.
    stdout(&chasles(&["interp", "--method", "c2", "--keys", &r]));
    // A camera key needs both angles, and only one form.
    let half = write(
        dir.path(),
        "h.toml",
        "[[keys]]\nyaw = 0.1\n[[keys]]\nyaw = 0.2\npitch = 0.0\n",
    );
    let e = failed(&chasles(&["interp", "--method", "slerp", "--keys", &half]));
    assert!(e.contains("keys[0].pitch is missing"), "{e}");
    let two = write(
        dir.path(),
        "t.toml",
        "[[keys]]\nyaw = 0.1\npitch = 0.0\nquat = [1, 0, 0, 0]\n[[keys]]\nyaw = 0.2\npitch = 0.0\n",
    );
    let e = failed(&chasles(&["interp", "--method", "slerp", "--keys", &two]));
    assert!(e.contains("keys[0] must have exactly one of"), "{e}");
    // The horizon of the file alone levels the path.
    let out = chasles(&[
        "interp", "--method", "squad", "--keys", &y, "--frames", "50",
    ]);
    let worst = rows(&stdout(&out))
        .iter()
        .map(|(q, _)| roll(*q, Up::Y).abs())
        .fold(0.0, f64::max);
    assert!(worst < 1e-12);
}

#[test]
fn c2_through_timed_keys() {
    let dir = tempfile::tempdir().unwrap();
    let keys = write(
        dir.path(),
        "t.toml",
        "[[keys]]\nquat = [1, 0, 0, 0]\ntime = 0\n[[keys]]\nangle = 1.0\naxis = [0, 0, 1]\ntime = 0.5\n[[keys]]\nangle = 1.5\naxis = [1, 1, 0]\ntime = 2.0\n[[keys]]\nangle = 0.3\naxis = [0, 1, 0]\ntime = 2.4\n",
    );
    let csv = stdout(&chasles(&[
        "interp", "--method", "c2", "--keys", &keys, "--frames", "60", "--timing", "uniform",
    ]));
    let t: Vec<f64> = csv
        .lines()
        .skip(1)
        .map(|l| l.split(',').nth(1).unwrap().parse().unwrap())
        .collect();
    assert_eq!(t.first(), Some(&0.0));
    assert!((t.last().unwrap() - 2.4).abs() < 1e-15);
    assert!(t.windows(2).all(|w| w[1] > w[0]));
}
