//! `chasles interp` with the report's program's controls (Dam et al. 1998, App. C and
//! §6.3.7): Spring's steps, iterations, step rule, penalty, width, weights and start on the
//! command line and in a key file's `[spring]` table, the presets written back as those
//! options, frames as a numbered PNG sequence, and LinEuler on keys given as Euler triples
//! (eq. 6.1 on the triples themselves).

mod common;
use common::*;
use std::path::Path;
use std::process::Output;

fn ok(o: &Output) -> (String, String) {
    let err = String::from_utf8_lossy(&o.stderr).to_string();
    assert!(o.status.success(), "failed: {err}");
    (String::from_utf8(o.stdout.clone()).unwrap(), err)
}

fn failed(o: &Output) -> String {
    assert!(!o.status.success(), "succeeded: {:?}", o);
    String::from_utf8_lossy(&o.stderr).to_string()
}

/// The `w,x,y,z` of every CSV row.
fn quats(csv: &str) -> Vec<[f64; 4]> {
    csv.lines()
        .skip(1)
        .map(|l| {
            let c: Vec<f64> = l
                .split(',')
                .skip(2)
                .take(4)
                .map(|x| x.parse().unwrap())
                .collect();
            [c[0], c[1], c[2], c[3]]
        })
        .collect()
}

/// The number after `what` in the summary (e.g. the final energy).
fn summary_number(text: &str, what: &str) -> f64 {
    let line = text
        .lines()
        .find(|l| l.starts_with(what))
        .unwrap_or_else(|| panic!("{what} in {text}"));
    line[what.len()..]
        .split_whitespace()
        .next()
        .unwrap()
        .parse()
        .unwrap()
}

fn write(dir: &Path, name: &str, text: &str) -> String {
    let p = dir.join(name);
    std::fs::write(&p, text).unwrap();
    p.to_str().unwrap().to_string()
}

#[test]
fn lineuler_interpolates_the_euler_triples_of_the_key_file() {
    let dir = tempfile::tempdir().unwrap();
    let keys = write(
        dir.path(),
        "keys.toml",
        "order = \"xyz\"\n[[keys]]\neuler = [0, 0, 0]\n[[keys]]\neuler = [0, 0, 4]\n",
    );
    let (csv, _) = ok(&chasles(&[
        "interp", "--method", "lineuler", "--keys", &keys, "--frames", "3", "--timing", "uniform",
    ]));
    // Halfway: 2 rad about z, (cos 1, 0, 0, sin 1) — not the principal angles' −1.14 rad.
    // The last row continues the path (the key as the triples give it, no sign jump).
    let rows = quats(&csv);
    let want = [1f64.cos(), 0.0, 0.0, 1f64.sin()];
    let dot: f64 = (0..4).map(|k| rows[1][k] * want[k]).sum();
    assert!(dot > 1.0 - 1e-12, "{rows:?}");
    let end = [2f64.cos(), 0.0, 0.0, 2f64.sin()];
    let dot: f64 = (0..4).map(|k| rows[2][k] * end[k]).sum();
    assert!(dot > 1.0 - 1e-12, "{rows:?}");
    // The same rotations as quaternions: the principal angles, as before.
    let (c, s) = (2f64.cos(), 2f64.sin());
    let keys = write(
        dir.path(),
        "quats.toml",
        &format!("[[keys]]\nquat = [1, 0, 0, 0]\n[[keys]]\nquat = [{c}, 0, 0, {s}]\n"),
    );
    let (csv, _) = ok(&chasles(&[
        "interp", "--method", "lineuler", "--keys", &keys, "--frames", "3", "--timing", "uniform",
    ]));
    let q = quats(&csv)[1];
    let half = (4.0 - std::f64::consts::TAU) / 4.0;
    assert!((q[0].abs() - half.cos()).abs() < 1e-12, "{q:?}");
}

#[test]
fn spring_controls_on_the_command_line_and_in_the_key_file() {
    // The report's justdoit written out as options equals the preset: the same frames.
    let justdoit = ok(&chasles(&[
        "interp",
        "--method",
        "justdoit",
        "--keys",
        "builtin:table5.1",
        "--frames",
        "550",
    ]));
    assert!(justdoit.1.contains(
        "spring options    --solver report --start slerp --levels 22,110,550 --iterations 200,150,100 --step adaptive:0.02 --penalty 1 --width one --key-weight 1 --velocity-weight 0"
    ), "{}", justdoit.1);
    let spelled = ok(&chasles(&[
        "interp",
        "--method",
        "squadsvupti",
        "--keys",
        "builtin:table5.1",
        "--start",
        "slerp",
        "--levels",
        "22,110,550",
        "--iterations",
        "200,150,100",
        "--step",
        "adaptive:0.02",
        "--penalty",
        "1",
        "--width",
        "one",
        "--key-weight",
        "1",
        "--velocity-weight",
        "0",
    ]));
    assert_eq!(justdoit.0, spelled.0);
    // One step of 350 frames and 500 iterations (Figure 6.15's), here with the report's
    // fixed step.
    let one = ok(&chasles(&[
        "interp",
        "--method",
        "slerpsvupti",
        "--keys",
        "builtin:table5.1",
        "--levels",
        "350",
        "--iterations",
        "500",
        "--step",
        "fixed:0.02",
    ]));
    assert_eq!(quats(&one.0).len(), 350);
    assert!(one.1.contains("500 iterations over 1 levels"), "{}", one.1);
    // A heavier key weight changes the curve. The other widths run and minimize another
    // energy: measured with l = 1 they end above the run that minimizes that one.
    let heavy = ok(&chasles(&[
        "interp",
        "--method",
        "justdoit",
        "--keys",
        "builtin:cusp",
        "--key-weight",
        "4",
    ]));
    let plain = ok(&chasles(&[
        "interp",
        "--method",
        "justdoit",
        "--keys",
        "builtin:cusp",
    ]));
    assert_ne!(heavy.0, plain.0);
    for width in ["chord", "angle"] {
        let w = ok(&chasles(&[
            "interp",
            "--method",
            "justdoit",
            "--keys",
            "builtin:cusp",
            "--width",
            width,
        ]));
        assert!(w.1.contains(&format!("--width {width}")), "{}", w.1);
        let (e, e1) = (
            summary_number(&w.1, "curvature energy"),
            summary_number(&plain.1, "curvature energy"),
        );
        assert!(e.is_finite() && e > e1, "{width}: {e} vs l = 1: {e1}");
    }
    // The key file's [spring] table, overridden by the command line.
    let dir = tempfile::tempdir().unwrap();
    let keys = write(
        dir.path(),
        "keys.toml",
        "[[keys]]\nangle = 0.0\naxis = [1, 0, 0]\n[[keys]]\nangle = 1.5\naxis = [1, 2, 0]\n[[keys]]\nangle = 2.5\naxis = [0, 1, 0]\n\
         [spring]\nsolver = \"report\"\nlevels = [9, 40]\niterations = [30, 20]\nstep = \"normalized:0.001\"\nkey_weight = 1.2\nstart = \"squad\"\n",
    );
    let (csv, err) = ok(&chasles(&[
        "interp",
        "--method",
        "spring",
        "--keys",
        &keys,
        "--key-weight",
        "2",
    ]));
    assert_eq!(quats(&csv).len(), 40);
    assert!(
        err.contains("--solver report --start squad --levels 9,40 --iterations 30,20 --step normalized:0.001"),
        "{err}"
    );
    assert!(err.contains("--key-weight 2 "), "{err}");
    // Spring's default is the converged solver: Table 5.1 at 550 frames by angle comes to
    // the minimum of eq. 6.23 (1.8465e-5), below the report's justdoit (1.9921e-5 above).
    let (csv, err) = ok(&chasles(&[
        "interp",
        "--method",
        "spring",
        "--keys",
        "builtin:table5.1",
        "--frames",
        "550",
    ]));
    assert_eq!(quats(&csv).len(), 550);
    assert!(err.contains("--solver converged --start slerp --width one --key-weight 1 --velocity-weight 0 --tolerance 1e-10"), "{err}");
    assert!(
        err.contains("converged solver: ") && err.contains("(converged)"),
        "{err}"
    );
    let e = summary_number(&err, "curvature energy");
    assert!((e / 1.8465e-5 - 1.0).abs() < 1e-4, "{e}");
    assert!(e < summary_number(&justdoit.1, "curvature energy"));
}

#[test]
fn bad_spring_controls_are_one_line_errors() {
    let run = |extra: &[&str]| {
        let mut a = vec![
            "interp",
            "--method",
            "spring",
            "--keys",
            "builtin:table5.1",
            "--solver",
            "report",
        ];
        a.extend_from_slice(extra);
        failed(&chasles(&a))
    };
    // The report's controls are refused by the converged solver, its tolerance by the report's.
    let converged = |extra: &[&str]| {
        let mut a = vec!["interp", "--method", "spring", "--keys", "builtin:table5.1"];
        a.extend_from_slice(extra);
        failed(&chasles(&a))
    };
    let e = converged(&["--levels", "22,550"]);
    assert!(e.contains("--levels (or its key-file field) is a control of the report's gradient descent: add --solver report"), "{e}");
    assert!(converged(&["--tolerance", "2"]).contains("tolerance"));
    assert!(run(&["--tolerance", "1e-8"]).contains("control of the converged solver"));
    assert!(run(&["--levels", "22,110", "--frames", "100"]).contains("--frames is 100"));
    assert!(run(&["--iterations", "5"]).contains("1 counts but there are 3"));
    assert!(run(&["--step", "fixed"]).contains("RULE:LENGTH"));
    assert!(run(&["--width", "wide"]).contains("one, chord, angle"));
    assert!(run(&["--penalty", "-1"]).contains("unit penalty"));
    assert!(run(&["--key-weight", "nan"]).contains("key weight"));
    let e = failed(&chasles(&[
        "interp",
        "--method",
        "squad",
        "--keys",
        "builtin:table5.1",
        "--levels",
        "22,550",
    ]));
    assert!(e.contains("--levels is a Spring control"), "{e}");
    let dir = tempfile::tempdir().unwrap();
    let keys = write(
        dir.path(),
        "keys.toml",
        "[[keys]]\nquat = [1, 0, 0, 0]\n[[keys]]\nquat = [0, 1, 0, 0]\n[spring]\nwidth = \"wide\"\n",
    );
    let e = failed(&chasles(&["interp", "--method", "spring", "--keys", &keys]));
    assert!(e.contains("spring.width"), "{e}");
    assert_eq!(e.trim().lines().count(), 1, "{e}");
}

#[test]
fn frames_dir_holds_every_frame_as_a_numbered_png_or_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let frames = dir.path().join("frames");
    let f = frames.to_str().unwrap();
    ok(&chasles(&[
        "interp",
        "--method",
        "squad",
        "--keys",
        "builtin:table5.1",
        "--frames",
        "30",
        "--frames-dir",
        f,
        "--out",
        dir.path().join("s.csv").to_str().unwrap(),
    ]));
    let mut names: Vec<String> = std::fs::read_dir(&frames)
        .unwrap()
        .map(|e| e.unwrap().file_name().into_string().unwrap())
        .collect();
    names.sort();
    assert_eq!(names.len(), 30);
    assert_eq!(
        (names[0].as_str(), names[29].as_str()),
        ("frame-0000.png", "frame-0029.png")
    );
    let png = std::fs::read(frames.join("frame-0007.png")).unwrap();
    assert_eq!(&png[1..4], b"PNG");
    // Two frames differ: the R turns.
    assert_ne!(png, std::fs::read(frames.join("frame-0020.png")).unwrap());
    // Not written over; refused before any work when the folder is not empty or its parent
    // is missing; a run that fails leaves no folder and no hidden temporary one.
    let run = |dir: &str, frames: &str| {
        chasles(&[
            "interp",
            "--method",
            "squad",
            "--keys",
            "builtin:table5.1",
            "--frames",
            frames,
            "--frames-dir",
            dir,
        ])
    };
    assert!(failed(&run(f, "30")).contains("is not empty"));
    let orphan = dir.path().join("no/such/frames");
    assert!(failed(&run(orphan.to_str().unwrap(), "30")).contains("is not a folder"));
    let other = dir.path().join("none");
    failed(&run(other.to_str().unwrap(), "3"));
    let left: Vec<_> = std::fs::read_dir(dir.path())
        .unwrap()
        .map(|e| e.unwrap().file_name())
        .collect();
    assert_eq!(left.len(), 2, "{left:?}");
    // An empty folder given is filled.
    let empty = dir.path().join("empty");
    std::fs::create_dir(&empty).unwrap();
    ok(&run(empty.to_str().unwrap(), "12"));
    assert_eq!(std::fs::read_dir(&empty).unwrap().count(), 12);
}

#[test]
fn key_velocities_in_the_key_file() {
    // A key that asks to be passed at rest: Squad and Spring slow to a stop there (the
    // frames beside it a second-order distance away), the other methods refuse the field.
    let dir = tempfile::tempdir().unwrap();
    let body = |velocity: &str| {
        format!(
            "[[keys]]\nangle = 0.0\naxis = [1, 0, 0]\n[[keys]]\nangle = 1.0\naxis = [0, 1, 0]\n{velocity}[[keys]]\nangle = 2.0\naxis = [0, 0, 1]\n"
        )
    };
    let still = write(dir.path(), "still.toml", &body("velocity = [0, 0, 0]\n"));
    let free = write(dir.path(), "free.toml", &body(""));
    let step_beside_key = |keys: &str, method: &str| {
        let (csv, _) = ok(&chasles(&[
            "interp", "--method", method, "--keys", keys, "--frames", "201", "--timing", "uniform",
        ]));
        let q = quats(&csv);
        let d: f64 = (0..4).map(|k| (q[101][k] - q[100][k]).powi(2)).sum();
        d.sqrt()
    };
    for method in ["squad", "spring"] {
        let (s, f) = (
            step_beside_key(&still, method),
            step_beside_key(&free, method),
        );
        assert!(s < 1e-3 && f > 4e-3, "{method}: {s} at rest, {f} free");
    }
    let e = failed(&chasles(&["interp", "--method", "slerp", "--keys", &still]));
    assert!(
        e.contains("key velocities are honoured by squad and by spring"),
        "{e}"
    );
    let e = failed(&chasles(&[
        "interp", "--method", "spring", "--solver", "report", "--keys", &still,
    ]));
    assert!(
        e.contains("key frame 1's angular velocity: only the converged Spring solver"),
        "{e}"
    );
    let bad = write(dir.path(), "bad.toml", &body("velocity = [0, nan, 0]\n"));
    let e = failed(&chasles(&["interp", "--method", "squad", "--keys", &bad]));
    assert!(e.contains("keys[1].velocity is not finite"), "{e}");
}
