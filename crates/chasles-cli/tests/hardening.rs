//! The attacks of issue 17 that crashed, hung or printed NaN, each now a bounded run or a
//! one-line typed error (exit 2, never 101 or an abort): absurd sizes, device files posing
//! as inputs, endless lines, values past f64's range, iteration caps, malformed glTF.

mod common;
use common::*;
use std::path::Path;
use std::process::{Command, Output, Stdio};

/// Exit 2 with one line of error saying `words`.
fn refused(o: &Output, words: &str) {
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(err.contains(words), "{err}");
    assert_eq!(err.trim().lines().count(), 1, "{err}");
}

#[test]
fn absurd_sizes_are_refused_before_any_allocation() {
    refused(
        &chasles(&[
            "convert",
            "--precision",
            "65536",
            "--from",
            "quat",
            "--to",
            "matrix",
            "--",
            "1",
            "0",
            "0",
            "0",
        ]),
        "65536 is not in 0..=17",
    );
    let interp = |extra: &[&str]| {
        let mut a = vec!["interp", "--method", "slerp", "--keys", "builtin:table5.1"];
        a.extend_from_slice(extra);
        chasles(&a)
    };
    refused(
        &interp(&["--frames", "18446744073709551615"]),
        "more than --max-frames 1000000",
    );
    refused(
        &interp(&["--frames", "1000000000"]),
        "more than --max-frames",
    );
    // Raised past what memory can hold: the library refuses the allocation itself.
    refused(
        &interp(&[
            "--frames",
            "18446744073709551615",
            "--max-frames",
            "18446744073709551615",
        ]),
        "cannot hold 18446744073709551615 frames in memory",
    );
    refused(
        &chasles(&[
            "interp",
            "--method",
            "justdoit",
            "--keys",
            "builtin:table5.1",
            "--levels",
            "22,110,550",
            "--iterations",
            "200,150,99999999999",
        ]),
        "at most 10000000",
    );
    refused(
        &chasles(&["tour", "--samples", "99999999999"]),
        "not in 1..=10000000",
    );
    refused(
        &chasles(&["properties", "--samples", "0"]),
        "not in 1..=10000000",
    );
}

#[test]
fn device_files_and_endless_input_are_refused() {
    if Path::new("/dev/zero").exists() {
        refused(
            &chasles(&["interp", "--method", "slerp", "--keys", "/dev/zero"]),
            "not a regular file",
        );
        refused(
            &chasles(&["blend", "--method", "dlb", "--input", "/dev/zero"]),
            "not a regular file",
        );
        // A model named like one but a device: refused before reading.
        let dir = tempfile::tempdir().unwrap();
        let link = dir.path().join("zero.glb");
        std::os::unix::fs::symlink("/dev/zero", &link).unwrap();
        refused(
            &chasles(&[
                "skin",
                "--rig",
                link.to_str().unwrap(),
                "--out",
                dir.path().join("o.obj").to_str().unwrap(),
            ]),
            "not a regular file",
        );
    }
    // One endless line on stdin: an error at the cap, not a read without end.
    let zeros = vec![b'0'; (1 << 20) + 10];
    refused(
        &with_stdin(&["convert", "--jsonl", "--to", "quat"], &zeros),
        "line 1 is longer than 1048576 bytes",
    );
    // Past the blend input's cap on stdin.
    let big = vec![b' '; (64 << 20) + 1];
    refused(
        &with_stdin(&["blend", "--method", "dlb", "--input", "-"], &big),
        "past the limit of 67108864 bytes",
    );
}

#[test]
fn values_past_the_range_of_f64_never_print_nan_or_inf() {
    // A rotation vector of 1e155: a unit quaternion (its norm no longer overflows).
    let out = stdout(&chasles(&[
        "convert", "--from", "rotvec", "--to", "quat", "--", "1e155", "0", "0",
    ]));
    let q: Vec<f64> = out
        .trim()
        .trim_matches(|c| c == '[' || c == ']')
        .split(',')
        .map(|x| x.trim().parse().unwrap())
        .collect();
    let n: f64 = q.iter().map(|x| x * x).sum::<f64>().sqrt();
    assert!((n - 1.0).abs() < 1e-12, "{out}");
    // A dual part of 1e200 is a translation of 2e200; of 1e308, past f64: an error.
    let out = stdout(&chasles(&[
        "convert", "--from", "dq", "--to", "screw", "--", "1", "0", "0", "0", "0", "1e200", "0",
        "0",
    ]));
    assert!(out.contains("translation 2000000000"), "{out}");
    refused(
        &chasles(&[
            "convert", "--from", "dq", "--to", "rt", "--", "1", "0", "0", "0", "0", "1e308", "0",
            "0",
        ]),
        "the result's translation[0] is not a finite number",
    );
    // Translations of 1e308: log-matrix blending overflows on them (the others stay in
    // range): an error naming the field, not `null` in the output.
    let case = r#"{"transforms": [{"rotation": [1,0,0,0], "translation": [1e308,1e308,1e308]}, {"rotation": [0,0,0.6,0.8], "translation": [1e308,-1e308,1e308]}], "weights": [0.5, 0.5]}"#;
    let o = with_stdin(
        &["blend", "--method", "log", "--input", "-"],
        case.as_bytes(),
    );
    refused(
        &o,
        "case 0: the blend's translation[0] is not a finite number",
    );
    // Translations of 1e155: every method gives a finite blend or says which part
    // overflowed — the iterative ones once printed their start (the identity for log-iter)
    // as if converged.
    let case = r#"{"transforms": [{"rotation": [1,0,0,0], "translation": [1e155,0,0]}, {"rotation": [0.6,0.8,0,0], "translation": [0,1e155,0]}], "weights": [0.5, 0.5]}"#;
    for m in ["lin", "dec", "log", "log-iter", "qlb", "dlb", "dib"] {
        let o = with_stdin(&["blend", "--method", m, "--input", "-"], case.as_bytes());
        if o.status.success() {
            let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
            let t = v[0]["translation"][0].as_f64().unwrap();
            assert!(t > 1e154, "{m}: translation {t} from translations of 1e155");
        } else {
            refused(&o, "(the inputs overflow its squares) is not finite");
        }
    }
}

#[test]
fn iterations_are_capped_and_stop_where_rounding_does() {
    let case = |extra: &str| {
        format!(
            r#"{{"transforms": [{{"rotation": [1,0,0,0]}}, {{"rotation": [0.6,0.8,0,0], "translation": [1,2,3]}}, {{"rotation": [0,0,1,0]}}], "weights": [0.3, 0.3, 0.4]{extra}}}"#
        )
    };
    refused(
        &with_stdin(
            &["blend", "--method", "dib", "--input", "-"],
            case(r#", "max_iterations": 1000000"#).as_bytes(),
        ),
        "max_iterations: must be a whole number up to 10000",
    );
    // A precision below what f64 resolves stops where the updates stop shrinking.
    let out = stdout(&with_stdin(
        &["blend", "--method", "dib", "--input", "-"],
        case(r#", "precision": 5e-324, "max_iterations": 10000"#).as_bytes(),
    ));
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    let it = v[0]["iterations"].as_u64().unwrap();
    assert!(it < 100, "{it} iterations");
    assert!(v[0].get("capped").is_none());
    // Stopped by its cap, each iterative method says so, in the output and on stderr.
    for m in ["dib", "dec", "log-iter"] {
        let o = with_stdin(
            &["blend", "--method", m, "--input", "-"],
            case(r#", "precision": 1e-300, "max_iterations": 1"#).as_bytes(),
        );
        let v: serde_json::Value = serde_json::from_str(&stdout(&o)).unwrap();
        assert_eq!(v[0]["iterations"], 1, "{m}");
        assert_eq!(v[0]["capped"], true, "{m}");
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(
            err.contains(&format!("note: case 0: {m} ran all max_iterations = 1 updates; its stopping rule (precision 1e-300) had not stopped it")),
            "{err}"
        );
    }
}

#[test]
fn a_malformed_gltf_is_one_line_and_exit_2() {
    let mut doc: serde_json::Value =
        serde_json::from_slice(chasles_models::SIMPLE_SKIN.bytes).unwrap();
    doc["accessors"][2]["componentType"] = serde_json::json!(5126);
    let dir = tempfile::tempdir().unwrap();
    let f = dir.path().join("joints-float.gltf");
    std::fs::write(&f, serde_json::to_vec(&doc).unwrap()).unwrap();
    let out = dir.path().join("o.obj");
    refused(
        &chasles(&[
            "skin",
            "--rig",
            f.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
        ]),
        "JOINTS_0: accessor 2 holds VEC4 FLOAT",
    );
    assert!(!out.exists());
    // An external buffer that is a device.
    if Path::new("/dev/zero").exists() {
        let mut doc: serde_json::Value =
            serde_json::from_slice(chasles_models::SIMPLE_SKIN.bytes).unwrap();
        doc["buffers"][0]["uri"] = serde_json::json!("/dev/zero");
        std::fs::write(&f, serde_json::to_vec(&doc).unwrap()).unwrap();
        refused(
            &chasles(&[
                "skin",
                "--rig",
                f.to_str().unwrap(),
                "--out",
                out.to_str().unwrap(),
            ]),
            "buffer 0: refers to /dev/zero, which cannot be read: /dev/zero: not a regular file",
        );
    }
    // A buffer file that does not exist: named, its cause said once.
    let mut doc: serde_json::Value =
        serde_json::from_slice(chasles_models::SIMPLE_SKIN.bytes).unwrap();
    doc["buffers"][0]["uri"] = serde_json::json!("no-such.bin");
    std::fs::write(&f, serde_json::to_vec(&doc).unwrap()).unwrap();
    let o = chasles(&[
        "skin",
        "--rig",
        f.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]);
    refused(&o, "buffer 0: refers to no-such.bin, which cannot be read");
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(err.matches("No such file").count(), 1, "{err}");
}

/// SimpleSkin with its clip's last key moved to `t` seconds (the sampler input, accessor 5,
/// edited in its embedded buffer).
fn simple_skin_lasting(t: f32) -> Vec<u8> {
    use base64::Engine;
    let mut d: serde_json::Value =
        serde_json::from_slice(chasles_models::SIMPLE_SKIN.bytes).unwrap();
    let acc = d["accessors"][5].clone();
    let view = d["bufferViews"][acc["bufferView"].as_u64().unwrap() as usize].clone();
    let b = view["buffer"].as_u64().unwrap() as usize;
    let uri = d["buffers"][b]["uri"].as_str().unwrap().to_string();
    let (head, payload) = uri.split_once(";base64,").unwrap();
    let mut bytes = base64::engine::general_purpose::STANDARD
        .decode(payload)
        .unwrap();
    let count = acc["count"].as_u64().unwrap() as usize;
    let at = (view["byteOffset"].as_u64().unwrap_or(0) + acc["byteOffset"].as_u64().unwrap_or(0))
        as usize
        + 4 * (count - 1);
    bytes[at..at + 4].copy_from_slice(&t.to_le_bytes());
    d["accessors"][5]["max"] = serde_json::json!([t]);
    d["buffers"][b]["uri"] = serde_json::json!(format!(
        "{head};base64,{}",
        base64::engine::general_purpose::STANDARD.encode(&bytes)
    ));
    serde_json::to_vec(&d).unwrap()
}

#[test]
fn a_clip_of_a_week_is_refused_before_any_frame_is_written() {
    let dir = tempfile::tempdir().unwrap();
    let rig = dir.path().join("long.gltf");
    std::fs::write(&rig, simple_skin_lasting(1e7)).unwrap();
    let frames = dir.path().join("frames");
    refused(
        &chasles(&[
            "skin",
            "--rig",
            rig.to_str().unwrap(),
            "--all-frames",
            "--fps",
            "24",
            "--out",
            frames.to_str().unwrap(),
        ]),
        "more than --max-frames 10000",
    );
    assert!(!frames.exists());
    refused(
        &chasles(&[
            "skin",
            "--rig",
            rig.to_str().unwrap(),
            "--gif",
            dir.path().join("a.gif").to_str().unwrap(),
        ]),
        "more than --max-frames 2000",
    );
    assert!(!dir.path().join("a.gif").exists());
    // A short clip with the ceiling raised runs.
    std::fs::write(&rig, simple_skin_lasting(100.0)).unwrap();
    let o = chasles(&[
        "skin",
        "--rig",
        rig.to_str().unwrap(),
        "--all-frames",
        "--fps",
        "0.2",
        "--max-frames",
        "21",
        "--out",
        frames.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert_eq!(std::fs::read_dir(&frames).unwrap().count(), 21);
}

/// A tour stopped by SIGINT half-way leaves no half report and no temporary file.
/// `chasles ARGS`, stopped by `signal` (`-INT`, `-TERM`) once something appears in `dir`:
/// it must exit 130 saying so and leave `dir` empty — or, had it finished first (allowed
/// only when `may_finish`: a run that lasts long enough must be stopped), hold only `done`.
fn interrupted_leaves_nothing(
    args: &[&str],
    signal: &str,
    dir: &Path,
    done: &str,
    may_finish: bool,
) {
    let child = Command::new(env!("CARGO_BIN_EXE_chasles"))
        .args(args)
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    // Once the run has started writing (its hidden folder exists), stop it.
    let start = std::time::Instant::now();
    while std::fs::read_dir(dir).unwrap().count() == 0 {
        assert!(
            start.elapsed().as_secs() < 60,
            "{args:?} never started writing"
        );
        std::thread::sleep(std::time::Duration::from_millis(20));
    }
    std::thread::sleep(std::time::Duration::from_millis(300));
    let killed = Command::new("kill")
        .args([signal, &child.id().to_string()])
        .status()
        .unwrap();
    assert!(killed.success());
    let o = child.wait_with_output().unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    let left: Vec<_> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name())
        .collect();
    if o.status.success() {
        assert!(may_finish, "{args:?} finished before {signal} reached it");
        assert_eq!(left, [done], "{args:?} finished first, leaving {left:?}");
        return;
    }
    assert_eq!(o.status.code(), Some(130), "{err}");
    assert!(err.contains("interrupted"), "{err}");
    assert!(
        left.is_empty(),
        "{args:?} stopped by {signal} left {left:?}"
    );
}

/// A tour stopped by SIGINT half-way leaves no half report and no temporary file; a
/// `skin --all-frames` stopped by SIGTERM leaves no frames and no hidden folder.
#[test]
fn interrupted_runs_leave_nothing_behind() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("report");
    interrupted_leaves_nothing(
        &["tour", "--out", out.to_str().unwrap()],
        "-INT",
        dir.path(),
        "report",
        true,
    );

    let rigs = tempfile::tempdir().unwrap();
    let rig = rigs.path().join("CesiumMan.glb");
    std::fs::write(&rig, chasles_models::CESIUM_MAN.bytes).unwrap();
    let dir = tempfile::tempdir().unwrap();
    let frames = dir.path().join("frames");
    let args = [
        "skin",
        "--rig",
        rig.to_str().unwrap(),
        "--all-frames",
        "--fps",
        "400",
        "--out",
        frames.to_str().unwrap(),
    ];
    interrupted_leaves_nothing(&args, "-TERM", dir.path(), "frames", false);
}

/// `interp --gif` draws every frame: a ceiling, checked before any picture is made or any
/// file written (the plot asked for beside it is not written either).
#[test]
fn interp_pictures_are_all_made_before_any_is_written() {
    let dir = tempfile::tempdir().unwrap();
    let (gif, plot, csv) = (
        dir.path().join("a.gif"),
        dir.path().join("v.svg"),
        dir.path().join("f.csv"),
    );
    refused(
        &chasles(&[
            "interp",
            "--method",
            "slerp",
            "--keys",
            "builtin:table5.1",
            "--frames",
            "5000",
            "--gif",
            gif.to_str().unwrap(),
            "--plot",
            plot.to_str().unwrap(),
            "--out",
            csv.to_str().unwrap(),
        ]),
        "--gif draws every frame: at most 2000",
    );
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 0);
    let o = chasles(&[
        "interp",
        "--method",
        "slerp",
        "--keys",
        "builtin:table5.1",
        "--frames",
        "40",
        "--plot",
        plot.to_str().unwrap(),
        "--out",
        csv.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(plot.is_file() && csv.is_file());
}

/// `skin` and `blend` make every output before writing any, and write all or none: a late
/// failure (an --out of a kind skin cannot write, a folder that does not exist) leaves
/// nothing behind, not the GIF or plot made before it.
#[test]
fn skin_and_blend_write_all_their_outputs_or_none() {
    let dir = tempfile::tempdir().unwrap();
    let rig = dir.path().join("simple.gltf");
    std::fs::write(&rig, chasles_models::SIMPLE_SKIN.bytes).unwrap();
    let at = |name: &str| dir.path().join(name).to_str().unwrap().to_string();
    let rig = rig.to_str().unwrap();
    let before = || std::fs::read_dir(dir.path()).unwrap().count();
    let n = before();
    refused(
        &chasles(&[
            "skin",
            "--rig",
            rig,
            "--gif",
            &at("walk.gif"),
            "--out",
            &at("mesh.xyz"),
        ]),
        "--out must end in .obj, .ply, .glb or .json",
    );
    assert_eq!(before(), n, "the GIF was written before --out failed");
    refused(
        &chasles(&[
            "skin",
            "--rig",
            rig,
            "--all-frames",
            "--render",
            &at("r.png"),
            "--out",
            &at("frames"),
        ]),
        "--render draws one pose",
    );
    assert_eq!(before(), n);
    let missing = dir.path().join("no-such-folder").join("mesh.obj");
    let o = chasles(&[
        "skin",
        "--rig",
        rig,
        "--plot",
        &at("volume.svg"),
        "--render",
        &at("methods.png"),
        "--out",
        missing.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(2));
    assert_eq!(
        before(),
        n,
        "pictures were written though --out could not be"
    );
    let o = chasles(&[
        "skin",
        "--rig",
        rig,
        "--plot",
        &at("volume.svg"),
        "--render",
        &at("methods.png"),
        "--out",
        &at("mesh.obj"),
    ]);
    stdout(&o);
    assert_eq!(before(), n + 3);

    let case = r#"{"transforms": [{"rotation": [1,0,0,0]}, {"rotation": [0.6,0.8,0,0], "translation": [1,2,3]}], "weights": [0.5, 0.5]}"#;
    let input = dir.path().join("case.json");
    std::fs::write(&input, case).unwrap();
    let n = before();
    let o = chasles(&[
        "blend",
        "--method",
        "dlb",
        "--input",
        input.to_str().unwrap(),
        "--plot",
        &at("blend.svg"),
        "--render",
        missing.with_extension("png").to_str().unwrap(),
    ]);
    assert_eq!(
        o.status.code(),
        Some(2),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    assert_eq!(
        before(),
        n,
        "the plot was written though the render could not be"
    );
}

/// A bind position or a joint past the range every skinning path keeps finite (±2⁶⁰ for
/// positions and translations, ±2³⁰ for the 3×3 block) is refused naming it, on the CPU
/// (and on the GPU alike: `crates/chasles-skin/tests/gpu.rs`).
#[test]
fn positions_and_joints_past_the_reach_of_f32_are_named() {
    let dir = tempfile::tempdir().unwrap();
    let rig = dir.path().join("far.json");
    std::fs::write(
        &rig,
        r#"{"positions": [[0,0,0],[1,0,0],[0,1e20,0]], "triangles": [[0,1,2]],
            "joints": [{"name": "root"}], "influences": [[[0,1]],[[0,1]],[[0,1]]]}"#,
    )
    .unwrap();
    let out = dir.path().join("o.obj");
    refused(
        &chasles(&[
            "skin",
            "--rig",
            rig.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
        ]),
        "the position of vertex 2 (coordinate 1) is 1e20, past ±1.1529215e18",
    );
    std::fs::write(
        &rig,
        r#"{"positions": [[0,0,0],[1,0,0],[0,1,0]], "triangles": [[0,1,2]],
            "joints": [{"name": "root"}], "influences": [[[0,1]],[[0,1]],[[0,1]]]}"#,
    )
    .unwrap();
    let pose = dir.path().join("pose.json");
    std::fs::write(&pose, r#"{"joints": {"0": {"scale": [1e10, 1, 1]}}}"#).unwrap();
    refused(
        &chasles(&[
            "skin",
            "--rig",
            rig.to_str().unwrap(),
            "--pose",
            pose.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
        ]),
        "joint 0's matrix entry (0, 0) is 1e10, past ±1.0737418e9",
    );
    assert!(!out.exists());
}

/// A tour given a folder of models (`$CHASLES_DATA`) with a broken one leaves that model
/// out, says why, and still writes its whole report.
#[test]
fn a_tour_with_a_broken_model_leaves_it_out() {
    let data = tempfile::tempdir().unwrap();
    std::fs::write(data.path().join("junk.glb"), b"glTF\x02\x00\x00\x00junk").unwrap();
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("report");
    let o = Command::new(env!("CARGO_BIN_EXE_chasles"))
        .args(["tour", "--samples", "10", "--out", out.to_str().unwrap()])
        .env("CHASLES_DATA", data.path())
        .output()
        .unwrap();
    let text = stdout(&o);
    assert!(text.contains("junk.glb does not load, left out"), "{text}");
    assert!(out.join("index.html").is_file());
    let left: Vec<_> = std::fs::read_dir(dir.path())
        .unwrap()
        .map(|e| e.unwrap().file_name())
        .collect();
    assert_eq!(left, ["report"]);
}
