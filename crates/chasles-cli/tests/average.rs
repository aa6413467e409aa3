//! `chasles average` end to end: the mean of poses in every form, weights, the robust means
//! marking outliers, and bad input (one line, exit 2, nothing written).

mod common;
use common::*;
use serde_json::Value;

fn json_of(o: &std::process::Output) -> Value {
    serde_json::from_str(&stdout(o)).unwrap()
}

fn nums(v: &Value) -> Vec<f64> {
    v.as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect()
}

#[test]
fn the_mean_of_two_poses_in_three_forms() {
    // The identity and 90° about z then (2, 0, 0) as a matrix: the mean of two poses is
    // ScLERP's half-way pose (Lemma 3), a closed form.
    let input = r#"{"poses": [
        {"rotation": [1, 0, 0, 0], "translation": [0, 0, 0]},
        {"matrix": [[0, -1, 0, 2], [1, 0, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]}
    ]}"#;
    let o = json_of(&with_stdin(&["average", "--input", "-"], input));
    // Half the screw: 22.5° half-angle about z.
    let r = nums(&o["rotation"]);
    let c = (std::f64::consts::PI / 8.0).cos();
    let s = (std::f64::consts::PI / 8.0).sin();
    assert!(
        (r[0] - c).abs() < 1e-12 && (r[3] - s).abs() < 1e-12,
        "{r:?}"
    );
    // The axis passes through (1, 1, 0) (the fixed point of the 90° motion): the half turn
    // about it moves the origin to (1, 1, 0) + Rz(45°)(−1, −1, 0) = (1, 1 − √2, 0).
    let t = nums(&o["translation"]);
    assert!(
        (t[0] - 1.0).abs() < 1e-12 && (t[1] - (1.0 - 2f64.sqrt())).abs() < 1e-12,
        "{t:?}"
    );
    assert_eq!(o["method"], "dib");
    // Equal weights: DIB's start, DLB, is already the half-way screw (the midpoint of the
    // normalized sum is symmetric in the two poses, as ScLERP's is), so no update is made.
    assert_eq!(o["iterations"], 0);
    // A dq form, weights, and a bare array.
    let input = r#"{"poses": [{"dq": [1, 0, 0, 0, 0, 0.5, 0, 0]}, {"rotation": [1, 0, 0, 0], "translation": [3, 0, 0]}], "weights": [3, 1]}"#;
    let o = json_of(&with_stdin(&["average", "--input", "-"], input));
    assert!((nums(&o["translation"])[0] - 1.5).abs() < 1e-12);
    let bare = r#"[{"rotation": [1, 0, 0, 0], "translation": [1, 2, 3]}]"#;
    let o = json_of(&with_stdin(&["average", "--input", "-"], bare));
    assert_eq!(nums(&o["translation"]), vec![1.0, 2.0, 3.0]);
}

#[test]
fn the_robust_mean_marks_the_outliers() {
    // Eight poses near the identity, two far off.
    let mut poses = Vec::new();
    for i in 0..8 {
        let e = 0.01 * (i as f64 - 3.5);
        poses.push(format!(
            r#"{{"rotation": [1, {e}, 0, 0], "translation": [{e}, 0, {}]}}"#,
            -e
        ));
    }
    poses.push(r#"{"rotation": [0, 0, 1, 0], "translation": [5, 5, 5]}"#.into());
    poses.push(r#"{"rotation": [0, 1, 0, 0], "translation": [-4, 6, 2]}"#.into());
    let input = format!("[{}]", poses.join(","));
    let plain = json_of(&with_stdin(&["average", "--input", "-"], &input));
    let o = json_of(&with_stdin(
        &["average", "--input", "-", "--robust", "tukey"],
        &input,
    ));
    assert_eq!(o["method"], "tukey");
    assert_eq!(o["outliers"], serde_json::json!([8, 9]));
    let t = nums(&o["translation"]);
    assert!(t.iter().all(|x| x.abs() < 1e-3), "{t:?}");
    let tp = nums(&plain["translation"]);
    assert!(tp.iter().any(|x| x.abs() > 0.5), "{tp:?}");
    let w = nums(&o["weights"]);
    assert!((w.iter().sum::<f64>() - 1.0).abs() < 1e-12);
    // Huber keeps every pose, down-weighted; to a file, whole.
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("mean.json");
    let o = with_stdin(
        &[
            "average",
            "--input",
            "-",
            "--robust",
            "huber",
            "--out",
            out.to_str().unwrap(),
        ],
        &input,
    );
    stdout(&o);
    let v: Value = serde_json::from_str(&std::fs::read_to_string(&out).unwrap()).unwrap();
    assert_eq!(v["method"], "huber");
    assert!(nums(&v["weights"]).iter().all(|w| *w > 0.0));
}

#[test]
fn bad_input_is_one_line_exit_2_and_nothing_written() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("mean.json");
    let o = out.to_str().unwrap();
    let one = r#"{"rotation": [1, 0, 0, 0], "translation": [0, 0, 0]}"#;
    for (input, args, says) in [
        ("[]", vec![], "no poses"),
        ("{\"poses\": []}", vec![], "no poses"),
        (
            "[{\"rotation\": [0, 0, 0, 0]}]",
            vec![],
            "poses[0].rotation",
        ),
        ("[{\"rotation\": [1, 0, 0]}]", vec![], "poses[0].rotation"),
        ("[{\"dq\": [1, 0, 0, 0, 0, 0, 0]}]", vec![], "poses[0].dq"),
        (
            "[{\"matrix\": [[2, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]}]",
            vec![],
            "poses[0].matrix",
        ),
        (
            "[{\"rotation\": [1, 0, 0, 0], \"translation\": [1e400, 0, 0]}]",
            vec![],
            "poses",
        ),
        ("[{\"rotaton\": [1, 0, 0, 0]}]", vec![], "poses[0]"),
        (
            "{\"poses\": [{\"quat\": [1, 0, 0, 0]}], \"weights\": [-1]}",
            vec![],
            "weight 0",
        ),
        (
            "{\"poses\": [{\"quat\": [1, 0, 0, 0]}], \"weights\": [0]}",
            vec![],
            "sum",
        ),
        (
            "{\"poses\": [{\"quat\": [1, 0, 0, 0]}], \"weights\": [1, 2]}",
            vec![],
            "weights",
        ),
        ("{\"poses\": [", vec![], "not valid JSON"),
        (
            "[{\"quat\": [1, 0, 0, 0]}]",
            vec!["--robust", "tukey", "--tuning", "0"],
            "tuning",
        ),
        (
            "[{\"quat\": [1, 0, 0, 0]}]",
            vec!["--robust", "huber", "--scale", "-1"],
            "scale",
        ),
        (
            "[{\"quat\": [1, 0, 0, 0]}]",
            vec!["--scale", "1"],
            "--robust",
        ),
        (
            "[{\"quat\": [1, 0, 0, 0]}]",
            vec!["--precision", "0"],
            "--precision",
        ),
        (
            "[{\"quat\": [1, 0, 0, 0]}]",
            vec!["--max-iterations", "99999"],
            "--max-iterations",
        ),
        (
            "[{\"quat\": [1, 0, 0, 0]}]",
            vec!["--robust", "cauchy"],
            "possible values",
        ),
    ] {
        let mut a = vec!["average", "--input", "-", "--out", o];
        a.extend(args);
        let r = with_stdin(&a, input);
        let err = String::from_utf8_lossy(&r.stderr);
        assert_eq!(r.status.code(), Some(2), "{input}: {err}");
        assert_eq!(err.trim().lines().count(), 1, "{input}: {err}");
        assert!(err.contains(says), "{input}: {err}");
        assert!(!out.exists(), "{input}: wrote {}", out.display());
    }
    // A good input to a bad --out.
    let r = with_stdin(&["average", "--input", "-", "--out", "x.csv"], one);
    assert_eq!(r.status.code(), Some(2));
}
