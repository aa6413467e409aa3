//! `chasles interp --rigid` end to end: keys given as rotation and translation, matrix and
//! dq met exactly in the rows (`tx,ty,tz` added), ScLERP through pure translations the
//! polygon, the pictures, and bad input (one line, exit 2, nothing written).

mod common;
use common::*;
use std::path::Path;

const KEYS: &str = r#"
[[keys]]
rotation = [1, 0, 0, 0]
translation = [0, 0, 0]
[[keys]]
angle = 1.2
axis = [0, 0, 1]
translation = [2, 1, 0]
[[keys]]
matrix = [[0, -1, 0, 3], [1, 0, 0, -1], [0, 0, 1, 1], [0, 0, 0, 1]]
[[keys]]
dq = [1, 0, 0, 0, 0, 3, 1, 1]
"#;

fn write(dir: &Path, name: &str, text: &str) -> String {
    let p = dir.join(name);
    std::fs::write(&p, text).unwrap();
    p.to_str().unwrap().to_string()
}

/// The CSV rows as numbers (the key column: -1 where empty).
fn rows(csv: &str) -> Vec<Vec<f64>> {
    let mut lines = csv.lines();
    assert_eq!(lines.next(), Some("index,t,w,x,y,z,tx,ty,tz,velocity,key"));
    lines
        .map(|l| {
            l.split(',')
                .map(|x| {
                    if x.is_empty() {
                        -1.0
                    } else {
                        x.parse().unwrap()
                    }
                })
                .collect()
        })
        .collect()
}

#[test]
fn keys_in_three_forms_are_met_exactly() {
    let dir = tempfile::tempdir().unwrap();
    let keys = write(dir.path(), "keys.toml", KEYS);
    // Key poses: rotation, translation.
    let (c, s) = (0.6f64.cos(), 0.6f64.sin());
    let h = std::f64::consts::FRAC_1_SQRT_2;
    let want = [
        ([1.0, 0.0, 0.0, 0.0], [0.0, 0.0, 0.0]),
        ([c, 0.0, 0.0, s], [2.0, 1.0, 0.0]),
        ([h, 0.0, 0.0, h], [3.0, -1.0, 1.0]),
        ([1.0, 0.0, 0.0, 0.0], [6.0, 2.0, 2.0]),
    ];
    for method in ["sclerp", "slerp", "squad", "spring"] {
        let o = chasles(&[
            "interp", "--rigid", "--method", method, "--keys", &keys, "--frames", "31",
        ]);
        let r = rows(&stdout(&o));
        assert_eq!(r.len(), 31);
        let at: Vec<&Vec<f64>> = r.iter().filter(|x| x[10] >= 0.0).collect();
        assert_eq!(at.len(), 4, "{method}");
        for (row, (q, t)) in at.iter().zip(&want) {
            for k in 0..4 {
                assert!((row[2 + k] - q[k]).abs() < 1e-15, "{method}: {row:?}");
            }
            for k in 0..3 {
                assert!((row[6 + k] - t[k]).abs() < 1e-14, "{method}: {row:?}");
            }
        }
        let summary = String::from_utf8_lossy(&o.stderr);
        assert!(summary.contains("(rigid) through"), "{summary}");
    }
}

#[test]
fn sclerp_through_translations_is_the_polygon_and_json_has_tx_ty_tz() {
    let dir = tempfile::tempdir().unwrap();
    let keys = write(
        dir.path(),
        "t.json",
        r#"[{"quat": [1, 0, 0, 0], "translation": [0, 0, 0], "time": 0},
            {"quat": [1, 0, 0, 0], "translation": [2, 0, 0], "time": 1},
            {"quat": [1, 0, 0, 0], "translation": [2, 4, 0], "time": 3}]"#,
    );
    let out = dir.path().join("c.json");
    let o = chasles(&[
        "interp",
        "--rigid",
        "--method",
        "sclerp",
        "--keys",
        &keys,
        "--frames",
        "7",
        "--out",
        out.to_str().unwrap(),
    ]);
    stdout(&o);
    let v: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&out).unwrap()).unwrap();
    let rows = v.as_array().unwrap();
    assert_eq!(rows.len(), 7);
    // Frames by key times: 1 in-between in [0, 1], 3 in [1, 3] (t = 1.5, 2, 2.5).
    for r in rows {
        let (t, tx, ty) = (
            r["t"].as_f64().unwrap(),
            r["tx"].as_f64().unwrap(),
            r["ty"].as_f64().unwrap(),
        );
        let want = if t <= 1.0 {
            (2.0 * t, 0.0)
        } else {
            (2.0, 2.0 * (t - 1.0))
        };
        assert!(
            (tx - want.0).abs() < 1e-14 && (ty - want.1).abs() < 1e-14,
            "{r}"
        );
        assert_eq!(r["w"].as_f64(), Some(1.0));
        assert_eq!(r["tz"].as_f64(), Some(0.0));
    }
}

#[test]
fn any_rotation_form_takes_a_translation() {
    // A camera key (yaw, pitch) and Euler angles with translations: the rows at the keys
    // carry them; keys without one stay at the origin.
    let dir = tempfile::tempdir().unwrap();
    let keys = write(
        dir.path(),
        "c.toml",
        "[[keys]]\nyaw = 0.5\npitch = 0.1\ntranslation = [1, 2, 3]\n[[keys]]\neuler = [0.1, 0.2, 0.3]\ntranslation = [-1, 0, 4]\n[[keys]]\nquat = [1, 0, 0, 0]\n",
    );
    let o = chasles(&[
        "interp", "--rigid", "--method", "squad", "--keys", &keys, "--frames", "3",
    ]);
    let r = rows(&stdout(&o));
    let t: Vec<[f64; 3]> = r.iter().map(|x| [x[6], x[7], x[8]]).collect();
    for (got, want) in t
        .iter()
        .zip([[1.0, 2.0, 3.0], [-1.0, 0.0, 4.0], [0.0, 0.0, 0.0]])
    {
        for k in 0..3 {
            assert!((got[k] - want[k]).abs() < 1e-14, "{t:?}");
        }
    }
}

#[test]
fn pictures_are_written() {
    let dir = tempfile::tempdir().unwrap();
    let keys = write(dir.path(), "keys.toml", KEYS);
    let gif = dir.path().join("r.gif");
    let png = dir.path().join("r.png");
    let o = chasles(&[
        "interp",
        "--rigid",
        "--method",
        "spring",
        "--energy",
        "screw",
        "--keys",
        &keys,
        "--frames",
        "24",
        "--gif",
        gif.to_str().unwrap(),
        "--render",
        png.to_str().unwrap(),
        "--out",
        dir.path().join("r.csv").to_str().unwrap(),
    ]);
    let s = stdout(&o);
    assert!(s.contains("screw energy, length scale 1"), "{s}");
    assert!(std::fs::read(&gif).unwrap().starts_with(b"GIF89a"));
    assert!(std::fs::read(&png).unwrap().starts_with(b"\x89PNG"));
}

#[test]
fn bad_input_is_one_line_exit_2_and_nothing_written() {
    let dir = tempfile::tempdir().unwrap();
    let keys = write(dir.path(), "keys.toml", KEYS);
    let out = dir.path().join("o.csv");
    let o = out.to_str().unwrap();
    let file = |name: &str, text: &str| write(dir.path(), name, text);
    let cases: Vec<(Vec<String>, &str)> = vec![
        (vec!["--method".into(), "squad".into(), "--keys".into(), keys.clone()], "--rigid"),
        (vec!["--rigid".into(), "--method".into(), "lerp".into(), "--keys".into(), keys.clone()], "sclerp (slerp), squad or spring"),
        (vec!["--method".into(), "slerp".into(), "--keys".into(), "builtin:table5.1".into(), "--energy".into(), "screw".into()], "--energy applies to --rigid"),
        (vec!["--rigid".into(), "--method".into(), "squad".into(), "--keys".into(), keys.clone(), "--energy".into(), "screw".into()], "--rigid --method spring"),
        (vec!["--rigid".into(), "--method".into(), "spring".into(), "--keys".into(), keys.clone(), "--length-scale".into(), "0".into()], "--length-scale"),
        (vec!["--rigid".into(), "--method".into(), "squad".into(), "--keys".into(), keys.clone(), "--horizon".into(), "Z".into()], "--horizon"),
        (vec!["--rigid".into(), "--method".into(), "spring".into(), "--keys".into(), keys.clone(), "--levels".into(), "10".into()], "--levels"),
        (vec!["--rigid".into(), "--method".into(), "squad".into(), "--keys".into(), keys.clone(), "--frames".into(), "3".into()], "frames"),
        (vec!["--rigid".into(), "--method".into(), "squad".into(), "--keys".into(), file("m.toml", "[[keys]]\nmatrix = [[2, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]\n[[keys]]\nquat = [1, 0, 0, 0]\n")], "keys[0].matrix"),
        (vec!["--rigid".into(), "--method".into(), "squad".into(), "--keys".into(), file("d.toml", "[[keys]]\ndq = [1, 0, 0, 0, 0, 0, 0]\n[[keys]]\nquat = [1, 0, 0, 0]\n")], "keys[0].dq"),
        (vec!["--rigid".into(), "--method".into(), "squad".into(), "--keys".into(), file("n.toml", "[[keys]]\nquat = [1, 0, 0, 0]\ntranslation = [nan, 0, 0]\n[[keys]]\nquat = [1, 0, 0, 0]\n")], "keys[0].translation"),
        (vec!["--rigid".into(), "--method".into(), "squad".into(), "--keys".into(), file("b.toml", "[[keys]]\ndq = [1, 0, 0, 0, 0, 0, 0, 0]\nquat = [1, 0, 0, 0]\n[[keys]]\nquat = [1, 0, 0, 0]\n")], "keys[0].dq"),
        (vec!["--rigid".into(), "--method".into(), "squad".into(), "--keys".into(), file("z.toml", "[[keys]]\ndq = [0, 0, 0, 0, 0, 0, 0, 0]\n[[keys]]\nquat = [1, 0, 0, 0]\n")], "keys[0].dq"),
    ];
    for (args, says) in cases {
        let mut a: Vec<&str> = vec!["interp", "--out", o];
        a.extend(args.iter().map(|s| s.as_str()));
        let r = chasles(&a);
        let err = String::from_utf8_lossy(&r.stderr);
        assert_eq!(r.status.code(), Some(2), "{args:?}: {err}");
        assert_eq!(err.trim().lines().count(), 1, "{args:?}: {err}");
        assert!(err.contains(says), "{args:?}: {err}");
        assert!(!out.exists(), "{args:?}");
    }
}
