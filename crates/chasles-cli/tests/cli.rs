//! The `chasles` binary end to end: conversions checked against closed forms, JSON lines,
//! errors on bad input (one line, non-zero exit), and the tour.

mod common;
use common::*;
use std::process::{Command, Stdio};

fn numbers(s: &str) -> Vec<f64> {
    s.split(|c: char| c.is_whitespace() || c == ',' || c == '[' || c == ']')
        .filter_map(|t| t.parse().ok())
        .collect()
}

fn assert_close(got: &[f64], want: &[f64], tol: f64) {
    assert_eq!(got.len(), want.len(), "{got:?} vs {want:?}");
    for (g, w) in got.iter().zip(want) {
        assert!((g - w).abs() <= tol, "{got:?} vs {want:?}");
    }
}

#[test]
fn euler_to_quaternion_matches_closed_form() {
    // Extrinsic xyz: q = qz(γ) qy(β) qx(α), product of half-angle quaternions.
    let (a, b, g) = (0.1f64 / 2.0, 0.2f64 / 2.0, 0.3f64 / 2.0);
    let w = g.cos() * b.cos() * a.cos() + g.sin() * b.sin() * a.sin();
    let x = g.cos() * b.cos() * a.sin() - g.sin() * b.sin() * a.cos();
    let y = g.cos() * b.sin() * a.cos() + g.sin() * b.cos() * a.sin();
    let z = g.sin() * b.cos() * a.cos() - g.cos() * b.sin() * a.sin();
    let out = stdout(&chasles(&[
        "convert",
        "--from",
        "euler:xyz",
        "--to",
        "quat",
        "0.1",
        "0.2",
        "0.3",
    ]));
    assert!(
        out.trim_start().starts_with('['),
        "quaternions print as [w, x, y, z]: {out}"
    );
    assert_close(&numbers(&out), &[w, x, y, z], 1e-15);
}

#[test]
fn negative_numbers_and_rigid_motions() {
    // 180° about x (w = 0), then translate (−1, 2, 3): dual part ½ t q0.
    let out = stdout(&chasles(&[
        "convert", "--from", "rt", "--to", "dq", "--", "0", "1", "0", "0", "-1", "2", "3",
    ]));
    // ½ [0, (−1, 2, 3)] [0, (1, 0, 0)] = ½ [1, (0, 3, −2)]
    assert_close(
        &numbers(&out),
        &[0.0, 1.0, 0.0, 0.0, 0.5, 0.0, 1.5, -1.0],
        1e-15,
    );
    let out = stdout(&chasles(&[
        "convert", "--from", "rt", "--to", "matrix", "0", "1", "0", "0", "-1", "2", "3",
    ]));
    assert_close(
        &numbers(&out),
        &[
            1.0, 0.0, 0.0, -1.0, 0.0, -1.0, 0.0, 2.0, 0.0, 0.0, -1.0, 3.0, 0.0, 0.0, 0.0, 1.0,
        ],
        1e-15,
    );
    // Round trip through the printed 4×4 matrix, pasted back as one argument.
    let back = stdout(&chasles(&[
        "convert", "--from", "matrix", "--to", "rt", &out,
    ]));
    assert_close(
        &numbers(&back),
        &[0.0, 1.0, 0.0, 0.0, -1.0, 2.0, 3.0],
        1e-15,
    );
}

#[test]
fn screw_of_a_known_motion() {
    // 90° about z then (1, 2, 3): axis z through (−0.5, 1.5, 0), slide 3.
    let h = std::f64::consts::FRAC_PI_4;
    let q = [h.cos(), 0.0, 0.0, h.sin()];
    let args: Vec<String> = q
        .iter()
        .chain(&[1.0, 2.0, 3.0])
        .map(|v| v.to_string())
        .collect();
    let mut a = vec![
        "convert",
        "--from",
        "rt",
        "--to",
        "screw",
        "--precision",
        "9",
    ];
    a.extend(args.iter().map(|s| s.as_str()));
    let out = stdout(&chasles(&a));
    let line = |k: &str| numbers(out.lines().find(|l| l.starts_with(k)).unwrap());
    assert_close(&line("axis"), &[0.0, 0.0, 1.0], 1e-9);
    assert_close(&line("point"), &[-0.5, 1.5, 0.0], 1e-9);
    assert_close(&line("angle"), &[std::f64::consts::FRAC_PI_2], 1e-9);
    assert_close(&line("translation"), &[3.0], 1e-9);
    // And back from the screw.
    let back = stdout(&chasles(&[
        "convert",
        "--from",
        "screw",
        "--to",
        "rt",
        "0",
        "0",
        "1",
        "-0.5",
        "1.5",
        "0",
        "1.5707963267948966",
        "3",
    ]));
    assert_close(
        &numbers(&back),
        &[q[0], 0.0, 0.0, q[3], 1.0, 2.0, 3.0],
        1e-12,
    );
}

#[test]
fn half_turn_matrix_and_gimbal_note() {
    let out = stdout(&chasles(&[
        "convert", "--from", "matrix", "--to", "quat", "1", "0", "0", "0", "-1", "0", "0", "0",
        "-1",
    ]));
    let q = numbers(&out);
    assert!((q[1].abs() - 1.0).abs() < 1e-15, "{out}");
    let o = chasles(&[
        "convert",
        "--from",
        "euler:xyz",
        "--to",
        "euler:xyz",
        "0.4",
        "1.5707963267948966",
        "-1.1",
    ]);
    let angles = numbers(&stdout(&o));
    assert_close(&angles, &[1.5, std::f64::consts::FRAC_PI_2, 0.0], 1e-12);
    assert!(String::from_utf8_lossy(&o.stderr).contains("gimbal lock"));
}

#[test]
fn json_lines_keep_order_and_flag_bad_lines() {
    let input = r#"{"quat": [0, 1, 0, 0]}
[0.1, 0.2, 0.3]

{"rotation": [1, 0, 0, 0], "translation": [1, 2]}
not json
{"euler": [0, 0, 1.5707963267948966], "order": "xyz"}
"#;
    let o = with_stdin(
        &["convert", "--jsonl", "--from", "rotvec", "--to", "quat"],
        input,
    );
    assert_eq!(o.status.code(), Some(1), "a bad line makes the exit code 1");
    let lines: Vec<serde_json::Value> = String::from_utf8(o.stdout)
        .unwrap()
        .lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect();
    assert_eq!(lines.len(), 5);
    assert_eq!(lines[0]["quat"], serde_json::json!([0.0, 1.0, 0.0, 0.0]));
    let rv = lines[1]["quat"].as_array().unwrap();
    let n = (0.01f64 + 0.04 + 0.09).sqrt();
    assert!((rv[0].as_f64().unwrap() - (n / 2.0).cos()).abs() < 1e-15);
    assert_eq!(lines[2]["line"], 4);
    assert!(lines[2]["error"].as_str().unwrap().contains("translation"));
    assert_eq!(lines[3]["line"], 5);
    assert!(lines[3]["error"]
        .as_str()
        .unwrap()
        .contains("not valid JSON"));
    let q = lines[4]["quat"].as_array().unwrap();
    assert!((q[3].as_f64().unwrap() - std::f64::consts::FRAC_1_SQRT_2).abs() < 1e-15);
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert!(
        stderr.contains("line 4") && stderr.contains("line 5"),
        "{stderr}"
    );
}

#[test]
fn bad_input_gets_one_line_error_and_non_zero_exit() {
    let cases: &[(&[&str], &str)] = &[
        (
            &[
                "convert", "--from", "quat", "--to", "matrix", "0", "0", "0", "0",
            ],
            "zero length",
        ),
        (
            &["convert", "--from", "quat", "--to", "matrix", "1", "0", "0"],
            "needs 4 numbers",
        ),
        (
            &[
                "convert", "--from", "quat", "--to", "matrix", "1", "nan", "0", "0",
            ],
            "not a finite number",
        ),
        (
            &[
                "convert", "--from", "quat", "--to", "matrix", "1", "x", "0", "0",
            ],
            "not a number",
        ),
        (
            &[
                "convert",
                "--from",
                "euler:xxy",
                "--to",
                "quat",
                "0",
                "0",
                "0",
            ],
            "unknown Euler order",
        ),
        (
            &["convert", "--from", "spin", "--to", "quat", "0"],
            "unknown representation",
        ),
        (
            &[
                "convert", "--from", "matrix", "--to", "quat", "-1", "0", "0", "0", "1", "0", "0",
                "0", "1",
            ],
            "reflection",
        ),
        (
            &[
                "convert", "--from", "rt", "--to", "quat", "1", "0", "0", "0", "1", "0", "0",
            ],
            "translation",
        ),
        (
            &[
                "convert",
                "--from",
                "axis-angle",
                "--to",
                "quat",
                "0",
                "0",
                "0",
                "1",
            ],
            "rotation axis",
        ),
        (
            &["convert", "--to", "quat", "1", "0", "0", "0"],
            "--from is required",
        ),
    ];
    for (args, needle) in cases {
        let o = chasles(args);
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(!o.status.success(), "{args:?} succeeded");
        assert!(err.contains(needle), "{args:?}: {err}");
        assert_eq!(
            err.trim().lines().count(),
            1,
            "{args:?}: not one line: {err}"
        );
        assert!(o.stdout.is_empty(), "{args:?} printed a result");
    }
}

#[test]
fn non_unit_quaternion_is_normalized_with_a_note() {
    let o = chasles(&[
        "convert",
        "--from",
        "quat",
        "--to",
        "axis-angle",
        "2",
        "0",
        "0",
        "2",
    ]);
    let v = numbers(&stdout(&o));
    assert_close(&v, &[0.0, 0.0, 1.0, std::f64::consts::FRAC_PI_2], 1e-15);
    assert!(String::from_utf8_lossy(&o.stderr).contains("normalized"));
}

/// A PNG's width, height and RGB bytes.
fn decode_png(bytes: &[u8]) -> (usize, usize, Vec<u8>) {
    let mut r = png::Decoder::new(std::io::Cursor::new(bytes))
        .read_info()
        .expect("png");
    let mut buf = vec![0; r.output_buffer_size().expect("size")];
    let info = r.next_frame(&mut buf).expect("png frame");
    buf.truncate(info.buffer_size());
    (info.width as usize, info.height as usize, buf)
}

/// Every picture `index.html` refers to, with the check that it is a valid file of its
/// kind (PNG and GIF decoded in full; SVG a complete document with drawn content).
fn check_pictures(dir: &std::path::Path) -> usize {
    let html = std::fs::read_to_string(dir.join("index.html")).expect("index.html");
    let mut images = 0;
    for part in html.split("<img src=\"").skip(1) {
        let name = &part[..part.find('"').expect("closing quote")];
        let bytes = std::fs::read(dir.join(name)).unwrap_or_else(|_| panic!("{name} missing"));
        match name.rsplit('.').next() {
            Some("png") => {
                let mut r = png::Decoder::new(std::io::Cursor::new(&bytes))
                    .read_info()
                    .unwrap_or_else(|e| panic!("{name}: {e}"));
                let mut buf = vec![0; r.output_buffer_size().expect("size")];
                let info = r
                    .next_frame(&mut buf)
                    .unwrap_or_else(|e| panic!("{name}: {e}"));
                assert!(info.width >= 100 && info.height >= 100, "{name} too small");
                // Not blank: over 1 % of the pixels differ from the corner (background).
                let px: Vec<&[u8]> = buf[..info.buffer_size()].chunks(3).collect();
                let drawn = px.iter().filter(|c| **c != px[0]).count();
                assert!(drawn * 100 > px.len(), "{name} looks blank");
            }
            Some("gif") => {
                let mut opts = gif::DecodeOptions::new();
                opts.set_color_output(gif::ColorOutput::RGBA);
                let mut d = opts
                    .read_info(std::io::Cursor::new(&bytes))
                    .unwrap_or_else(|e| panic!("{name}: {e}"));
                let mut frames = 0;
                while d
                    .read_next_frame()
                    .unwrap_or_else(|e| panic!("{name}: {e}"))
                    .is_some()
                {
                    frames += 1;
                }
                assert!(frames >= 10, "{name}: {frames} frames");
            }
            Some("svg") => {
                let t = String::from_utf8(bytes).expect("utf-8");
                assert!(
                    t.starts_with("<svg xmlns=\"http://www.w3.org/2000/svg\""),
                    "{name}"
                );
                assert!(t.trim_end().ends_with("</svg>"), "{name} incomplete");
                assert!(
                    ["<polyline", "class=\"bar\"", "class=\"cell\""]
                        .iter()
                        .any(|k| t.contains(k)),
                    "{name} draws nothing"
                );
            }
            other => panic!("{name}: unexpected kind {other:?}"),
        }
        images += 1;
    }
    images
}

/// The tour's report: valid pictures, and every claim row with a number and a verdict.
fn check_report(dir: &std::path::Path) -> usize {
    let images = check_pictures(dir);
    let html = std::fs::read_to_string(dir.join("index.html")).expect("index.html");
    let rows: Vec<&str> = html.split("<tr class=\"claim\">").skip(1).collect();
    assert!(rows.len() >= 15, "only {} claims", rows.len());
    for r in &rows {
        let measured = r
            .split("<td class=\"measured\">")
            .nth(1)
            .expect("measured cell");
        let measured = &measured[..measured.find("</td>").expect("cell end")];
        assert!(
            measured.chars().any(|c| c.is_ascii_digit()),
            "no number in: {measured}"
        );
        assert!(
            r.contains("class=\"yes\"") || r.contains("class=\"no\""),
            "no verdict"
        );
    }
    images
}

#[test]
fn tour_prints_computed_numbers_and_writes_the_report() {
    let dir = tempfile::tempdir().expect("tempdir");
    let report = dir.path().join("report");
    let o = chasles(&[
        "tour",
        "--samples",
        "200",
        "--out",
        report.to_str().expect("utf-8 path"),
    ]);
    let out = stdout(&o);
    assert!(out.contains("report: "), "no report line");
    // The report was built aside and put in place whole: nothing else is left beside it.
    let beside: Vec<_> = std::fs::read_dir(dir.path())
        .unwrap()
        .map(|e| e.unwrap().file_name())
        .collect();
    assert_eq!(beside, ["report"], "{beside:?}");
    assert!(check_report(&report) >= 15, "too few pictures");
    // The characters are built in: a fresh clone shows them with nothing beside it.
    for (file, picture) in [("CesiumMan.glb", "cesiumman.png"), ("Fox.glb", "fox.png")] {
        assert!(out.contains(file), "{file} not in the tour");
        assert!(report.join(picture).is_file(), "{picture} not written");
    }
    assert!(!out.contains("not found"), "the tour missed its data");
    // The page names files, never the folders they came from.
    let html = std::fs::read_to_string(report.join("index.html")).unwrap();
    // A viewer beside the report for each character and the cylinder, linked from it.
    for page in [
        "cesiumman-viewer.html",
        "fox-viewer.html",
        "cylinder-viewer.html",
    ] {
        let text = std::fs::read_to_string(report.join(page)).expect(page);
        assert_eq!(
            chasles_view::page::external_reference(&text),
            None,
            "{page}"
        );
        assert!(
            html.contains(&format!("href=\"{page}\"")),
            "{page} not linked"
        );
    }
    let here = env!("CARGO_MANIFEST_DIR");
    let tmp = dir.path().to_str().unwrap();
    assert!(
        !html.contains(here) && !html.contains(tmp),
        "an absolute path in the page"
    );
    for section in [
        "App. B.4",
        "gimbal lock",
        "eq. (1)",
        "Lemma 1",
        "Identities over 200",
    ] {
        assert!(out.contains(section), "missing {section}");
    }
    // Chapter 7's figures with their captions' frames and iterations, and its outcomes.
    let (header, rows) = terminal_table(&out, "Figures 7.1–7.12", "frames", 12);
    let at = |h: &str| header.iter().position(|x| x == h).unwrap();
    let cell = |n: &str, h: &str| rows.iter().find(|r| r[0] == n).unwrap()[at(h)].clone();
    assert_eq!(cell("7.2", "frames"), "430");
    assert_eq!(cell("7.12", "frames"), "430");
    assert!(cell("7.12", "method").contains("c_k 4"));
    assert_eq!(cell("7.5", "frames"), "200");
    for s in [
        "§4.1, Figure 4.1",
        "§4.1, Figure 4.3",
        "§7.1",
        "§7.2",
        "§7.3",
        "§7.4",
        "§7.5",
        "§7.6",
    ] {
        assert!(
            out.lines().any(|l| l.contains("[yes]") && l.contains(s)),
            "{s} does not come out"
        );
    }
    // Every figure of Dam et al. ch. 5–7, its paper's caption beside ours, in the contents.
    for n in [
        "4-1", "4-3", "5-1", "6-1", "6-15", "6-17", "6-20", "7-6", "7-12",
    ] {
        assert!(report.join(format!("dam-figure-{n}.png")).is_file(), "{n}");
    }
    assert!(html.contains(
        "Dam et al. 1998, Figure 6.16.</b> The paper: <i>The multi-step algorithm, first step."
    ));
    assert!(html.contains("<a href=\"#f-dam-figure-7-12-png\">7.12</a>"));
    assert!(!out.contains("Figure 5.5") && !out.contains("Figure 1, §6"));
    // Every figure the issue lists, paper by paper in the papers' order.
    let listed = |paper: &str| -> Vec<String> {
        let line = html
            .lines()
            .find(|l| l.contains(&format!("{paper}, figures:</b>")))
            .unwrap_or_else(|| panic!("no figure list for {paper}"));
        line.split("\">")
            .skip(1)
            .map(|p| p.split('<').next().unwrap().to_string())
            .collect()
    };
    let dam: Vec<String> = "4.1 4.3 5.1 5.2 5.3 6.1 6.2 6.3 6.6 6.7 6.8 6.11 6.15 6.16 6.17 6.18 6.19 6.20 7.1 7.2 7.3 7.4 7.5 7.6 7.7 7.8 7.9 7.10 7.11 7.12"
        .split(' ')
        .map(String::from)
        .collect();
    assert_eq!(listed("Dam et al. 1998"), dam);
    assert_eq!(
        listed("Kavan et al. 2006"),
        ["1(c)", "2", "3", "4", "5", "6(a)–(b)", "6(c)–(d)", "7"]
    );
    // Every identity row carries two measured errors, within the test-suite tolerances.
    let (header, rows) = terminal_table(&out, "Identities over", "identity", 8);
    assert_eq!(header[..2], ["f64", "f32"]);
    for r in rows {
        let v: Vec<f64> = r[..2].iter().flat_map(|c| numbers(c)).collect();
        assert!(v.len() == 2 && v[0] < 1e-12 && v[1] < 1e-5, "{r:?}");
    }
}

/// The table of the tour's section titled with `section`: the header (the first line
/// after the title with a column named `column`) and the `n` rows after it, each split into
/// columns at runs of two or more spaces.
fn terminal_table(
    out: &str,
    section: &str,
    column: &str,
    n: usize,
) -> (Vec<String>, Vec<Vec<String>>) {
    let split = |l: &str| -> Vec<String> {
        l.trim()
            .split("  ")
            .map(str::trim)
            .filter(|c| !c.is_empty())
            .map(String::from)
            .collect()
    };
    let mut lines = out
        .lines()
        .skip_while(|l| !(l.starts_with("== ") && l.contains(section)))
        .skip_while(|l| !split(l).iter().any(|c| c == column));
    let header = split(
        lines
            .next()
            .unwrap_or_else(|| panic!("no table in {section}")),
    );
    let rows: Vec<Vec<String>> = lines.take(n).map(split).collect();
    assert_eq!(rows.len(), n, "{section}");
    for r in &rows {
        assert_eq!(r.len(), header.len(), "{section}: {r:?}");
    }
    (header, rows)
}

fn csv_rows(text: &str) -> Vec<Vec<String>> {
    text.lines()
        .skip(1)
        .map(|l| l.split(',').map(str::to_string).collect())
        .collect()
}

#[test]
fn interp_every_method_on_builtin_sets() {
    let dir = tempfile::tempdir().unwrap();
    for method in [
        "lineuler",
        "linmat",
        "lerp",
        "slerp",
        "squad",
        "spring",
        "slerpsvupti",
        "squadsvupti",
        "justdoit",
    ] {
        for set in ["table5.1", "cusp"] {
            let out = dir.path().join(format!("{method}-{set}.csv"));
            let o = chasles(&[
                "interp",
                "--method",
                method,
                "--keys",
                &format!("builtin:{set}"),
                "--frames",
                "60",
                "--out",
                out.to_str().unwrap(),
            ]);
            let summary = stdout(&o);
            assert!(
                summary.contains("curvature energy")
                    && summary.contains("velocity")
                    && summary.contains("time"),
                "{summary}"
            );
            let text = std::fs::read_to_string(&out).unwrap();
            assert!(text.starts_with("index,t,w,x,y,z,velocity,key\n"));
            let rows = csv_rows(&text);
            assert_eq!(rows.len(), 60, "{method} {set}");
            let keys: Vec<usize> = rows
                .iter()
                .filter(|r| !r[7].is_empty())
                .map(|r| r[7].parse().unwrap())
                .collect();
            let n_keys = if set == "cusp" { 5 } else { 6 };
            assert_eq!(
                keys,
                (0..n_keys).collect::<Vec<_>>(),
                "{method} {set}: keys appear once each, in order"
            );
            for r in &rows {
                let q: Vec<f64> = r[2..6].iter().map(|v| v.parse().unwrap()).collect();
                let n = q.iter().map(|v| v * v).sum::<f64>().sqrt();
                assert!((n - 1.0).abs() < 1e-9, "{method}: frame not unit ({n})");
                assert!(r[6].parse::<f64>().unwrap() >= 0.0);
            }
            assert!(
                !String::from_utf8_lossy(&o.stderr).contains("iterations"),
                "no progress bar when not on a terminal"
            );
        }
    }
}

#[test]
fn interp_key_files_json_output_and_errors() {
    let dir = tempfile::tempdir().unwrap();
    let toml = dir.path().join("keys.toml");
    std::fs::write(&toml, "order = \"ZYX\"\n[[keys]]\nangle = 1.0\naxis = [1, 3, 0]\ntime = 0\n[[keys]]\nquat = [1, 0, 0, 0]\ntime = 1\n[[keys]]\neuler = [0.3, 0, 0]\ntime = 3\n").unwrap();
    let out = dir.path().join("o.json");
    stdout(&chasles(&[
        "interp",
        "--method",
        "squad",
        "--keys",
        toml.to_str().unwrap(),
        "--frames",
        "9",
        "--timing",
        "uniform",
        "--out",
        out.to_str().unwrap(),
    ]));
    let rows: Vec<serde_json::Value> =
        serde_json::from_str(&std::fs::read_to_string(&out).unwrap()).unwrap();
    assert_eq!(rows.len(), 9);
    let names: Vec<&str> = rows[0]
        .as_object()
        .unwrap()
        .keys()
        .map(|k| k.as_str())
        .collect();
    assert_eq!(names, ["index", "t", "w", "x", "y", "z", "velocity", "key"]);
    // Times 0, 1, 3: uniform timing shares the 6 in-betweens 1 : 2 → key 1 is row 3.
    assert_eq!(rows[3]["key"], 1);
    assert_eq!(rows[3]["t"], 1.0);
    assert_eq!(rows[8]["t"], 3.0);
    // Intrinsic ZYX with (0.3, 0, 0): 0.3 about z.
    let z = rows[8]["z"].as_f64().unwrap();
    assert!((z - 0.15f64.sin()).abs() < 1e-15);
    // Stdout CSV when there is no --out; the summary goes to stderr.
    let o = chasles(&[
        "interp",
        "--method",
        "slerp",
        "--keys",
        "builtin:pendulum",
        "--frames",
        "5",
    ]);
    assert!(stdout(&o).starts_with("index,t,w,x,y,z,velocity,key"));
    assert!(String::from_utf8_lossy(&o.stderr).contains("curvature energy"));

    let cases: &[(&str, &str, &str)] = &[
        ("bad.toml", "[[keys]]\nangle = 1.0\naxis = [1, 3, 0]\n[[keys]]\neuler = [0.1, 0.2\n", "line 5"),
        ("zero.toml", "[[keys]]\nangle = 1.0\naxis = [0, 0, 0]\n[[keys]]\nquat = [1, 0, 0, 0]\n", "keys[0].axis"),
        ("both.toml", "[[keys]]\nangle = 1.0\naxis = [1, 0, 0]\nquat = [1, 0, 0, 0]\n[[keys]]\nquat = [1, 0, 0, 0]\n", "keys[0] must have exactly one"),
        ("time.toml", "[[keys]]\nquat = [1, 0, 0, 0]\ntime = 0\n[[keys]]\nquat = [1, 0, 0, 0]\n", "keys[1].time"),
        ("back.toml", "[[keys]]\nquat = [1, 0, 0, 0]\ntime = 1\n[[keys]]\nquat = [1, 0, 0, 0]\ntime = 0\n", "key time 1"),
        ("typo.json", "{\"keys\": [{\"angle\": 1, \"axis\": [1, 0, 0]}, {\"quat\": [1, 0, 0, 0], \"tim\": 2}]}", "unknown field `tim`"),
        ("zeroq.json", "[{\"quat\": [0, 0, 0, 0]}, {\"quat\": [1, 0, 0, 0]}]", "keys[0].quat"),
        ("one.json", "[{\"quat\": [1, 0, 0, 0]}]", "at least 2 keys"),
        ("keys.txt", "", "must end in .toml or .json"),
        // Serde types read through serde_path_to_error: the path of a bad or misspelt field.
        ("typo.toml", "[[keys]]\nangle = 1.0\naxis = [1, 3, 0]\n[[keys]]\nquat = [1, 0, 0, 0]\ntine = 2\n", "keys[1].tine: TOML parse error at line 6"),
        ("type.toml", "[[keys]]\nangle = 1.0\naxis = [1, 3, 0]\n[[keys]]\nquat = [1, 0, \"a\", 0]\n", "keys[1].quat[2]"),
        ("order.toml", "order = \"xxy\"\n[[keys]]\nquat = [1, 0, 0, 0]\n[[keys]]\nquat = [1, 0, 0, 0]\n", "order: TOML parse error"),
        ("typo2.json", "[{\"quat\": [1, 0, 0, 0]}, {\"quat\": [1, 0, 0, 0], \"tim\": 2}]", "keys[1].tim: unknown field `tim`"),
        ("type.json", "{\"keys\": [{\"quat\": [1, 0, 0, 0]}, {\"euler\": [1, true, 0]}]}", "keys[1].euler[1]: invalid type: boolean `true`"),
        ("order.json", "{\"keys\": [{\"quat\": [1, 0, 0, 0]}, {\"euler\": [1, 0, 0], \"order\": \"xxy\"}]}", "keys[1].order: unknown Euler order"),
        ("trail.json", "[{\"quat\": [1, 0, 0, 0]}, {\"quat\": [1, 0, 0, 0]}] []", "not valid JSON: trailing characters"),
    ];
    for (name, text, needle) in cases {
        let path = dir.path().join(name);
        std::fs::write(&path, text).unwrap();
        let target = dir.path().join("never.csv");
        let o = chasles(&[
            "interp",
            "--method",
            "spring",
            "--keys",
            path.to_str().unwrap(),
            "--out",
            target.to_str().unwrap(),
        ]);
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(!o.status.success() && err.contains(needle), "{name}: {err}");
        assert_eq!(err.trim().lines().count(), 1, "{name}: {err}");
        assert!(!target.exists(), "{name}: no output file on error");
    }
    for (args, needle) in [
        (
            vec!["--method", "nurbs", "--keys", "builtin:cusp"],
            "invalid value 'nurbs' for '--method <METHOD>' [possible values: lineuler, linmat, lerp, slerp, squad, spring, slerpsvupti, squadsvupti, justdoit, tcb, catmull-rom, bezier, c2]",
        ),
        (
            vec!["--method", "slerp", "--keys", "builtin:nothing"],
            "no built-in key set",
        ),
        (
            vec![
                "--method",
                "slerp",
                "--keys",
                "builtin:cusp",
                "--frames",
                "3",
            ],
            "at least 5",
        ),
        (
            vec![
                "--method",
                "slerp",
                "--keys",
                "builtin:cusp",
                "--out",
                "x.txt",
            ],
            ".csv or .json",
        ),
        (
            vec![
                "--method",
                "spring",
                "--keys",
                "builtin:cusp",
                "--key-weight",
                "-1",
            ],
            "key weight",
        ),
    ] {
        let mut a = vec!["interp"];
        a.extend(args);
        let o = chasles(&a);
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(!o.status.success() && err.contains(needle), "{a:?}: {err}");
    }
}

#[test]
fn blend_cases_from_stdin_and_file() {
    // Two pure rotations about z (0° and 90°) with a translation: DLB/DIB/ScLERP agree at ½.
    let input = r#"[
      {"transforms": [{"rotation": [1, 0, 0, 0], "translation": [0, 0, 0]},
                      {"matrix": [[0, -1, 0, 2], [1, 0, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]}],
       "weights": [1, 1]},
      {"transforms": [{"dq": [1, 0, 0, 0, 0, 0, 0, 0]}, {"rotation": [0.7071067811865476, 0, 0, 0.7071067811865476], "translation": [2, 0, 0]}],
       "weights": [0.5, 0.5], "precision": 1e-12}
    ]"#;
    let mut results = Vec::new();
    for method in ["sclerp", "dlb", "dib"] {
        let o = with_stdin(&["blend", "--method", method, "--input", "-"], input);
        let v: serde_json::Value = serde_json::from_str(&stdout(&o)).unwrap();
        let arr = v.as_array().unwrap();
        assert_eq!(arr.len(), 2);
        for r in arr {
            assert_eq!(r["rigid"], true);
            for k in ["rotation", "translation", "matrix", "dq"] {
                assert!(r.get(k).is_some(), "{method}: missing {k}");
            }
            assert_eq!(r.get("iterations").is_some(), method == "dib");
        }
        results.push(arr[0].clone());
    }
    // ScLERP at ½ of a 90° screw about the vertical line through (1, 1): 45° about z.
    let q: Vec<f64> = results[0]["rotation"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_f64().unwrap())
        .collect();
    let h = std::f64::consts::FRAC_PI_8;
    assert_close(&q, &[h.cos(), 0.0, 0.0, h.sin()], 1e-12);
    // DIB of two = ScLERP (Lemma 3); DLB shares the axis here by symmetry too.
    for r in &results[1..] {
        let m0: Vec<f64> = results[0]["matrix"]
            .as_array()
            .unwrap()
            .iter()
            .flat_map(|row| {
                row.as_array()
                    .unwrap()
                    .iter()
                    .map(|v| v.as_f64().unwrap())
                    .collect::<Vec<_>>()
            })
            .collect();
        let m1: Vec<f64> = r["matrix"]
            .as_array()
            .unwrap()
            .iter()
            .flat_map(|row| {
                row.as_array()
                    .unwrap()
                    .iter()
                    .map(|v| v.as_f64().unwrap())
                    .collect::<Vec<_>>()
            })
            .collect();
        assert_close(&m1, &m0, 1e-9);
    }
    // The sclerp form, and lin reporting non-rigid results, from a file.
    let dir = tempfile::tempdir().unwrap();
    let f = dir.path().join("case.json");
    std::fs::write(&f, r#"{"from": {"rotation": [1, 0, 0, 0]}, "to": {"rotation": [0, 0, 0, 1], "translation": [1, 0, 0]}, "t": 0.25}"#).unwrap();
    let v: serde_json::Value = serde_json::from_str(&stdout(&chasles(&[
        "blend",
        "--method",
        "sclerp",
        "--input",
        f.to_str().unwrap(),
    ])))
    .unwrap();
    assert_eq!(v.as_array().unwrap().len(), 1);
    let lin = with_stdin(
        &["blend", "--method", "lin", "--input", "-"],
        r#"{"transforms": [{"rotation": [1,0,0,0]}, {"rotation": [0,0,0,1]}], "weights": [1, 1]}"#,
    );
    let v: serde_json::Value = serde_json::from_str(&stdout(&lin)).unwrap();
    assert_eq!(v[0]["rigid"], false, "Lin of a half turn is not rigid");
}

#[test]
fn blend_errors_name_the_case_and_field() {
    let cases: &[(&str, &str, &str)] = &[
        (
            "dlb",
            r#"[{"transforms": [{"rotation": [1,0,0,0]}], "weights": [1]}, {"transforms": [{"rotation": [1,0,0]}], "weights": [1]}]"#,
            "case 1",
        ),
        (
            "dlb",
            r#"[{"transforms": [{"rotation": [1,0,0,0]}], "weights": [1]}, {"transforms": [{"rotation": [1,0,0]}], "weights": [1]}]"#,
            "transforms[0]",
        ),
        (
            "dlb",
            r#"{"transforms": [{"rotation": [1,0,0,0]}, {"rotation": [1,0,0,0]}], "weights": [-1, 2]}"#,
            "weight 0 is -1",
        ),
        (
            "dlb",
            r#"{"transforms": [{"rotation": [1,0,0,0]}, {"rotation": [1,0,0,0]}], "weights": [0, 0]}"#,
            "sum to 0",
        ),
        (
            "dlb",
            r#"{"transforms": [{"rotation": [1,0,0,0]}], "weights": [1, 1]}"#,
            "1 transforms but 2 weights",
        ),
        (
            "dib",
            r#"{"transforms": [{"rotation": [1,0,0,0]}], "weights": ["a"]}"#,
            "weights[0]",
        ),
        (
            "dlb",
            r#"{"transforms": [{"matrix": [[2,0,0,0],[0,1,0,0],[0,0,1,0],[0,0,0,1]]}], "weights": [1]}"#,
            "not a rigid transformation",
        ),
        ("dlb", r#"{"weights": [1]}"#, "missing field `transforms`"),
        (
            "sclerp",
            r#"{"from": {"rotation": [1,0,0,0]}, "to": {"rotation": [1,0,0,0]}, "t": 2}"#,
            "case 0: t: must be in [0, 1], got 2",
        ),
        (
            "sclerp",
            r#"{"transforms": [{"rotation": [1,0,0,0]}], "weights": [1]}"#,
            "exactly two",
        ),
        ("dlb", "{not json", "not valid JSON"),
        // Serde types read through serde_path_to_error: the case and the field's path.
        (
            "dlb",
            r#"[{"transforms": [{"rotation": [1,0,0,0]}], "weights": [1]}, {"transforms": [{"quat": [1,0,0,0]}, {"quat": [1,0,0,0]}, {"rotation": [1,0,0,"x"]}], "weights": [1,1,1]}]"#,
            "case 1: transforms[2].rotation[3]: invalid type: string \"x\"",
        ),
        (
            "dlb",
            r#"{"transforms": [{"rotation": [1,0,0,0]}], "weight": [1]}"#,
            "case 0: weight: unknown field `weight`",
        ),
        (
            "dlb",
            r#"{"transforms": [{"rotation": [1,0,0,0], "translaton": [1,0,0]}], "weights": [1]}"#,
            "case 0: transforms[0].translaton: unknown field `translaton`",
        ),
        (
            "dlb",
            r#"{"transforms": [{"quat": [1,0,0,0], "rotation": [1,0,0,0]}], "weights": [1]}"#,
            "case 0: transforms[0]: conflicting fields `quat` and `rotation`",
        ),
        (
            "dlb",
            r#"{"transforms": [{"quat": [1,0,0,0], "translation": [1,0,0]}], "weights": [1]}"#,
            "case 0: transforms[0].translation: given without `rotation`",
        ),
        (
            "dlb",
            r#"{"transforms": [[1,0,0,0]], "weights": [1]}"#,
            "case 0: transforms[0]: invalid type: sequence, expected an object",
        ),
        (
            "sclerp",
            r#"{"from": {"rotation": [1,0,0,0]}, "to": {"screw": {"axis": [0,0,1], "point": [0,0], "angle": 1, "translation": 0}}, "t": 0.5}"#,
            "case 0: to.screw.point: expected 3 numbers, got 2",
        ),
        (
            "sclerp",
            r#"{"from": {"rotation": [1,0,0,0]}, "to": {"rotation": [1,0,0,0]}}"#,
            "case 0: missing field `t`",
        ),
        (
            "sclerp",
            r#"{"from": {"rotation": [1,0,0,0]}, "to": {"rotation": [1,0,0,0]}, "t": 0.5, "weights": [1, 1]}"#,
            "case 0: conflicting fields `weights` and `from`",
        ),
        (
            "dlb",
            r#"{"transforms": [{"rotation": [1,0,0,0]}], "weights": [1], "center": [0, 0]}"#,
            "case 0: center: invalid length 2",
        ),
        (
            "dlb",
            r#"{"transforms": [{"rotation": [1,0,0,0]}], "weights": [1]} {"transforms": []}"#,
            "not valid JSON: trailing characters",
        ),
        (
            "slerpy",
            "{}",
            "invalid value 'slerpy' for '--method <METHOD>' [possible values: lin, dec, log, log-iter, qlb, sclerp, dlb, dib]",
        ),
    ];
    for (method, input, needle) in cases {
        let o = with_stdin(&["blend", "--method", method, "--input", "-"], input);
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(!o.status.success(), "{input}");
        assert!(err.contains(needle), "{input}: {err}");
        assert_eq!(
            err.trim().lines().count(),
            1,
            "{input}: not one line: {err}"
        );
        assert!(o.stdout.is_empty(), "no partial output");
    }
}

#[test]
fn json_lines_name_the_line_and_the_field() {
    let input = [
        r#"{"quatt": [1, 0, 0, 0]}"#,
        r#"{"rotation": [1, 0, 0, "a"], "translation": [1, 2, 3]}"#,
        r#"{"quat": [1, 0, 0, 0]} {"quat": [1, 0, 0, 0]}"#,
        r#"{"matrix": [[1, 0, 0], [0, 1, 0], [0, 0, null]]}"#,
        r#"{"euler": [0, 0, 0], "order": "xxy"}"#,
        r#"{"rotvec": [0, 0, 1], "angle": 1}"#,
        r#"{"screw": {"axis": [0, 0, 1], "point": [0, 0, 0], "angle": 1}}"#,
        r#"{"axis": [0, 0, 1], "angle": 1}"#,
    ]
    .join("\n");
    let o = with_stdin(&["convert", "--jsonl", "--to", "quat"], &input);
    assert_eq!(o.status.code(), Some(1));
    let lines: Vec<serde_json::Value> = String::from_utf8(o.stdout)
        .unwrap()
        .lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect();
    assert_eq!(lines.len(), 8, "one output line per input line");
    let want = [
        "quatt: unknown field `quatt`",
        "rotation[3]: invalid type: string \"a\", expected a number",
        "not valid JSON: trailing characters at column 24",
        "matrix[2][2]: invalid type: null",
        "order: unknown Euler order",
        "angle: given without `axis`",
        "screw: missing field `translation`",
    ];
    for (k, w) in want.iter().enumerate() {
        assert_eq!(lines[k]["line"], k + 1, "{:?}", lines[k]);
        let e = lines[k]["error"].as_str().unwrap();
        assert!(e.starts_with(w), "line {}: {e}", k + 1);
    }
    assert!(lines[7]["quat"].is_array(), "a good line after bad ones");
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert_eq!(stderr.lines().count(), 7, "{stderr}");
    assert!(
        stderr.contains("error: line 2: rotation[3]: invalid type"),
        "{stderr}"
    );
}

#[test]
fn json_output_of_convert_reads_back_as_input() {
    // convert --jsonl writes the fields it reads, plus gimbal_lock and a screw's moment and
    // pitch: each is accepted back (and ignored), giving the same motion.
    let value =
        r#"{"rotation": [0.7071067811865476, 0, 0, 0.7071067811865476], "translation": [1, 2, 3]}"#;
    let dq = stdout(&with_stdin(&["convert", "--jsonl", "--to", "dq"], value));
    for to in ["screw", "rt", "dq", "matrix"] {
        let written = stdout(&with_stdin(&["convert", "--jsonl", "--to", to], value));
        let back = stdout(&with_stdin(&["convert", "--jsonl", "--to", "dq"], &written));
        let (a, b): (serde_json::Value, serde_json::Value) = (
            serde_json::from_str(&dq).unwrap(),
            serde_json::from_str(&back).unwrap(),
        );
        let num = |v: &serde_json::Value| -> Vec<f64> {
            v["dq"]
                .as_array()
                .unwrap()
                .iter()
                .map(|x| x.as_f64().unwrap())
                .collect()
        };
        assert_close(&num(&b), &num(&a), 1e-12);
    }
    let euler = stdout(&with_stdin(
        &["convert", "--jsonl", "--to", "euler:ZYX"],
        r#"{"quat": [0.9, 0.1, 0.2, 0.3]}"#,
    ));
    assert!(euler.contains("gimbal_lock"), "{euler}");
    let back = stdout(&with_stdin(&["convert", "--jsonl", "--to", "quat"], &euler));
    let q = numbers(&back);
    let n = (0.81f64 + 0.01 + 0.04 + 0.09).sqrt();
    assert_close(&q, &[0.9 / n, 0.1 / n, 0.2 / n, 0.3 / n], 1e-12);
}

#[test]
fn properties_table_and_claims() {
    let out = stdout(&chasles(&["properties", "--samples", "40", "--claims"]));
    assert!(
        out.contains("All 36 property cells the paper lists agree with it."),
        "{out}"
    );
    for needle in [
        "| FLOPS |",
        "2 of 6 FLOPS cells agree",
        "Lemma 3",
        "Lemma 2",
        "Figure 7",
        "8.149",
    ] {
        assert!(out.contains(needle), "missing {needle}");
    }
    // The slide bound as measured (the claim's text also names the supremum 15.014 %).
    let worst = out
        .split("worst: ")
        .nth(1)
        .and_then(|r| r.split(" %").next())
        .and_then(|x| x.parse::<f64>().ok())
        .expect("the measured slide");
    assert!((worst - 15.014).abs() < 0.01, "DLB slides {worst} %");
    let j: serde_json::Value = serde_json::from_str(&stdout(&chasles(&[
        "properties",
        "--samples",
        "30",
        "--format",
        "json",
    ])))
    .unwrap();
    let items = j["sections"][0]["items"].as_array().unwrap();
    let claim = items
        .iter()
        .find(|i| i["kind"] == "claim" && i["section"] == "Table 1")
        .expect("the Table 1 claim");
    assert_eq!(claim["verdict"], "agrees", "{claim}");
    let table = items
        .iter()
        .find(|i| i["kind"] == "table" && i["caption"].as_str().unwrap().starts_with("Table 1"))
        .expect("Table 1");
    assert_eq!(
        table["header"].as_array().unwrap().len(),
        9,
        "a column per method"
    );
    let mut measured = 0;
    for r in table["rows"].as_array().unwrap() {
        let r = r.as_array().unwrap();
        let p = r[0]["text"].as_str().unwrap();
        if !matches!(
            p,
            "rigidity"
                | "bi-invariance"
                | "coordinate invariance"
                | "constant speed"
                | "shortest path"
        ) {
            continue;
        }
        measured += 1;
        assert_eq!(r.len(), 9);
        for c in &r[1..] {
            assert_eq!(c["kind"], "check", "{p}: {c}");
            assert!(
                c["worst"]["value"].is_number(),
                "{p}: every cell carries its measured deviation: {c}"
            );
            // No disagreement with the paper.
            assert!(c["paper"].is_null() || c["paper"] == c["holds"], "{p}: {c}");
        }
    }
    assert_eq!(measured, 5);
    let o = chasles(&["properties", "--samples", "0"]);
    assert!(!o.status.success());
}

#[test]
fn skin_writes_obj_ply_json_and_whole_clips() {
    let dir = tempfile::tempdir().unwrap();
    for (ext, first) in [("obj", "# "), ("ply", "ply"), ("json", "{")] {
        let out = dir.path().join(format!("fox.{ext}"));
        let o = chasles(&[
            "skin",
            "--rig",
            &model("Fox.glb"),
            "--anim",
            "Run",
            "--time",
            "0.4",
            "--method",
            "dqs",
            "--out",
            out.to_str().unwrap(),
        ]);
        assert!(stdout(&o).contains("1728 vertices"));
        let text = std::fs::read_to_string(&out).unwrap();
        assert!(text.starts_with(first), "{ext}");
        if ext == "obj" {
            assert_eq!(text.lines().filter(|l| l.starts_with("v ")).count(), 1728);
            assert_eq!(text.lines().filter(|l| l.starts_with("f ")).count(), 576);
        }
    }
    let frames = dir.path().join("frames");
    let o = chasles(&[
        "skin",
        "--rig",
        &model("SimpleSkin.gltf"),
        "--all-frames",
        "--fps",
        "2",
        "--method",
        "lbs",
        "--out",
        frames.to_str().unwrap(),
    ]);
    assert!(
        stdout(&o).contains("wrote 12 frames"),
        "5.5 s at 2 fps: frames 0 … 11"
    );
    assert_eq!(std::fs::read_dir(&frames).unwrap().count(), 12);
    assert!(
        !String::from_utf8_lossy(&o.stderr).contains("frames"),
        "no progress bar when not on a terminal"
    );
    let table = stdout(&chasles(&["skin", "--artifacts"]));
    assert!(
        table.contains("| 180° | 0.000 |"),
        "LBS collapses at 180°:\n{table}"
    );
}

#[test]
fn skin_errors_are_one_line_and_leave_no_file() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("x.obj");
    let o = out.to_str().unwrap();
    let junk = dir.path().join("junk.glb");
    std::fs::write(&junk, b"not a gltf").unwrap();
    let cases: Vec<(Vec<String>, &str)> = vec![
        (
            vec![
                "--rig".into(),
                model("Fox.glb"),
                "--method".into(),
                "blend".into(),
                "--out".into(),
                o.into(),
            ],
            "invalid value 'blend' for '--method <METHOD>' [possible values: lbs, dqs, dib, log, qlb, sbs]",
        ),
        (
            vec![
                "--rig".into(),
                model("Fox.glb"),
                "--anim".into(),
                "Swim".into(),
                "--out".into(),
                o.into(),
            ],
            "no animation 'Swim'",
        ),
        (
            vec![
                "--rig".into(),
                model("Fox.glb"),
                "--out".into(),
                dir.path().join("x.txt").to_str().unwrap().into(),
            ],
            ".obj, .ply, .glb or .json",
        ),
        (
            vec![
                "--rig".into(),
                junk.to_str().unwrap().into(),
                "--out".into(),
                o.into(),
            ],
            "not a valid glTF",
        ),
        (
            vec![
                "--rig".into(),
                dir.path().join("none.glb").to_str().unwrap().into(),
                "--out".into(),
                o.into(),
            ],
            "none.glb",
        ),
        (
            vec![
                "--rig".into(),
                model("Fox.glb"),
                "--all-frames".into(),
                "--fps".into(),
                "0".into(),
                "--out".into(),
                o.into(),
            ],
            "--fps",
        ),
        (vec!["--out".into(), o.into()], "--rig FILE is required"),
    ];
    for (args, needle) in cases {
        let mut a = vec!["skin".to_string()];
        a.extend(args);
        let a: Vec<&str> = a.iter().map(|s| s.as_str()).collect();
        let r = chasles(&a);
        let err = String::from_utf8_lossy(&r.stderr);
        assert!(!r.status.success() && err.contains(needle), "{a:?}: {err}");
        assert_eq!(err.trim().lines().count(), 1, "{err}");
        assert!(!out.exists(), "{a:?} left a file");
    }
}

/// A two-joint strip of four triangles in the plain JSON rig format.
const STRIP_JSON: &str = r#"{"positions": [[0,0,0],[1,0,0],[2,0,0],[0,1,0],[1,1,0],[2,1,0]],
      "triangles": [[0,1,4],[0,4,3],[1,2,5],[1,5,4]],
      "joints": [{"name": "a"}, {"name": "b", "parent": 0, "translation": [1,0,0]}],
      "influences": [[[0,1]],[[0,0.5],[1,0.5]],[[1,1]],[[0,1]],[[0,0.5],[1,0.5]],[[1,1]]]}"#;

#[test]
fn skin_json_rig_with_a_pose_file() {
    let dir = tempfile::tempdir().unwrap();
    let rig = dir.path().join("strip.json");
    std::fs::write(&rig, STRIP_JSON).unwrap();
    let pose = dir.path().join("pose.json");
    std::fs::write(
        &pose,
        r#"{"joints": {"b": {"rotation": [0.7071067811865476, 0, 0, 0.7071067811865476]}}}"#,
    )
    .unwrap();
    let out = dir.path().join("out.json");
    stdout(&chasles(&[
        "skin",
        "--rig",
        rig.to_str().unwrap(),
        "--pose",
        pose.to_str().unwrap(),
        "--method",
        "dib",
        "--out",
        out.to_str().unwrap(),
    ]));
    let v: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&out).unwrap()).unwrap();
    let p2: Vec<f64> = v["positions"][2]
        .as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect();
    assert_close(&p2, &[1.0, 1.0, 0.0], 1e-6);
    let o = chasles(&[
        "skin",
        "--rig",
        rig.to_str().unwrap(),
        "--pose",
        pose.to_str().unwrap(),
        "--time",
        "1",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(String::from_utf8_lossy(&o.stderr).contains("not both"));
}

#[test]
fn interp_writes_the_velocity_graph_and_the_sphere_plot() {
    let dir = tempfile::tempdir().unwrap();
    let p = |n: &str| dir.path().join(n).to_str().unwrap().to_string();
    let o = chasles(&[
        "interp",
        "--method",
        "squad",
        "--keys",
        "builtin:cusp",
        "--frames",
        "80",
        "--out",
        &p("c.csv"),
        "--plot",
        &p("v.svg"),
        "--sphere",
        &p("s.png"),
    ]);
    stdout(&o);
    let o = chasles(&[
        "interp",
        "--method",
        "slerp",
        "--keys",
        "builtin:cusp",
        "--frames",
        "30",
        "--out",
        &p("d.csv"),
        "--plot",
        &p("v.png"),
        "--gif",
        &p("r.gif"),
        "--render",
        &p("strip.png"),
    ]);
    stdout(&o);
    std::fs::create_dir(dir.path().join("report")).unwrap();
    let html = "<img src=\"../v.svg\"><img src=\"../s.png\"><img src=\"../v.png\"><img src=\"../r.gif\"><img src=\"../strip.png\">";
    std::fs::write(dir.path().join("report/index.html"), html).unwrap();
    assert_eq!(check_pictures(&dir.path().join("report")), 5);
    // Eight frames of 180 pixels in the strip.
    let strip = decode_png(&std::fs::read(p("strip.png")).unwrap());
    assert_eq!((strip.0, strip.1), (8 * 180, 180));
    for (flag, name, msg) in [
        ("--plot", "v.txt", "must end in .svg or .png"),
        ("--sphere", "s.svg", "must end in .png"),
        ("--gif", "r.png", "must end in .gif"),
    ] {
        let bad = chasles(&[
            "interp",
            "--method",
            "slerp",
            "--keys",
            "builtin:cusp",
            flag,
            &p(name),
        ]);
        assert!(String::from_utf8_lossy(&bad.stderr).contains(msg), "{flag}");
        assert!(!dir.path().join(name).exists(), "{name} written");
    }
}

#[test]
fn skin_renders_every_method_and_the_twist_sweep() {
    let dir = tempfile::tempdir().unwrap();
    let p = |n: &str| dir.path().join(n).to_str().unwrap().to_string();
    let o = chasles(&[
        "skin",
        "--artifacts",
        "--render",
        &p("twist.png"),
        "--gif",
        &p("twist.gif"),
        "--plot",
        &p("radius.svg"),
    ]);
    let out = stdout(&o);
    let svg = std::fs::read_to_string(p("radius.svg")).unwrap();
    assert_eq!(
        svg.matches("class=\"series\"").count(),
        7,
        "six methods and cos(θ/2)"
    );
    assert!(out.contains("wrote") && out.contains("twist.gif"));
    std::fs::create_dir(dir.path().join("r")).unwrap();
    std::fs::write(
        dir.path().join("r/index.html"),
        "<img src=\"../twist.png\"><img src=\"../twist.gif\">",
    )
    .unwrap();
    assert_eq!(check_pictures(&dir.path().join("r")), 2);
    // Six panels side by side, each 300 wide; in the LBS panel the middle of the cylinder
    // has collapsed, in the DQS panel the middle column crosses the cylinder's full width.
    let img = decode_png(&std::fs::read(p("twist.png")).unwrap());
    assert_eq!((img.0, img.1), (6 * 300, 170));
    let drawn = |x0: usize| {
        (0..img.1)
            .filter(|y| {
                let k = (y * img.0 + x0) * 3;
                let c = &img.2[k..k + 3];
                c.iter().any(|v| *v < 200) || (c[0] > 225 && c[2] < 240)
            })
            .count()
    };
    let (lbs, dqs) = (drawn(150), drawn(300 + 150));
    assert!(lbs * 4 < dqs, "LBS middle {lbs} px, DQS middle {dqs} px");
    // A rigged file: every method side by side, without --out.
    let rig = dir.path().join("rig.json");
    std::fs::write(&rig, STRIP_JSON).unwrap();
    let r = rig.to_str().unwrap();
    stdout(&chasles(&["skin", "--rig", r, "--render", &p("strip.png")]));
    let img = decode_png(&std::fs::read(p("strip.png")).unwrap());
    assert_eq!((img.0, img.1), (6 * 260, 320));
    let bad = chasles(&["skin", "--rig", r, "--render", &p("x.jpg")]);
    assert!(String::from_utf8_lossy(&bad.stderr).contains("must end in .png"));
    let bad = chasles(&["skin", "--rig", r, "--gif", &p("x.gif")]);
    assert!(String::from_utf8_lossy(&bad.stderr).contains("has no animations"));
    assert!(!dir.path().join("x.gif").exists());
}

#[test]
fn blend_draws_the_path_of_weights_and_every_method() {
    let dir = tempfile::tempdir().unwrap();
    let p = |n: &str| dir.path().join(n).to_str().unwrap().to_string();
    let two = r#"{"transforms": [{"rotation": [1,0,0,0]},
        {"rotation": [0,0,0,1], "translation": [3,0,0]}], "weights": [0.5, 0.5]}"#;
    let o = with_stdin(
        &[
            "blend",
            "--method",
            "dlb",
            "--input",
            "-",
            "--plot",
            &p("two.svg"),
            "--render",
            &p("two.png"),
            "--gif",
            &p("two.gif"),
            "--sphere",
            &p("sphere.png"),
        ],
        two,
    );
    stdout(&o);
    std::fs::create_dir(dir.path().join("r")).unwrap();
    std::fs::write(
        dir.path().join("r/index.html"),
        r#"<img src="../two.svg"><img src="../two.png"><img src="../two.gif"><img src="../sphere.png">"#,
    )
    .unwrap();
    assert_eq!(check_pictures(&dir.path().join("r")), 4);
    let svg = std::fs::read_to_string(p("two.svg")).unwrap();
    assert_eq!(svg.matches("class=\"series\"").count(), 8, "every method");
    assert_eq!(decode_png(&std::fs::read(p("two.png")).unwrap()).0, 8 * 260);
    // Three transforms: ScLERP does not apply and is left out.
    let three = r#"{"transforms": [{"rotation": [1,0,0,0]}, {"rotation": [0,1,0,0]},
        {"rotation": [0,0,1,0], "translation": [0,2,0]}], "weights": [0.3, 0.3, 0.4]}"#;
    stdout(&with_stdin(
        &[
            "blend",
            "--method",
            "dib",
            "--input",
            "-",
            "--plot",
            &p("three.svg"),
        ],
        three,
    ));
    let svg = std::fs::read_to_string(p("three.svg")).unwrap();
    assert_eq!(svg.matches("class=\"series\"").count(), 7);
    assert!(!svg.contains(">sclerp<"));
    let bad = with_stdin(
        &[
            "blend",
            "--method",
            "dib",
            "--input",
            "-",
            "--render",
            &p("x.svg"),
        ],
        three,
    );
    assert!(String::from_utf8_lossy(&bad.stderr).contains("must end in .png"));
    assert!(!dir.path().join("x.svg").exists());
}

#[test]
fn skin_pictures_of_a_real_clip() {
    let dir = tempfile::tempdir().unwrap();
    let p = |n: &str| dir.path().join(n).to_str().unwrap().to_string();
    let o = chasles(&[
        "skin",
        "--rig",
        &model("CesiumMan.glb"),
        "--plot",
        &p("volume.svg"),
        "--sphere",
        &p("knee.png"),
        "--render",
        &p("all.png"),
        "--time",
        "0.5",
    ]);
    let out = stdout(&o);
    assert!(out.contains("the rotation of leg_joint_"), "{out}");
    // LBS's smallest volume over the walk reaches 0.47 (the plot's lowest point): 41
    // samples, read back through the plot's axis (chasles_viz::plot::lines_svg: plot area
    // from y = 40 to y = 290 pixels; the data start near 0, so the axis runs from 0 to 1.05,
    // the rigid blends' 1 plus 5 %).
    let svg = std::fs::read_to_string(p("volume.svg")).unwrap();
    assert_eq!(svg.matches("class=\"series\"").count(), 2);
    let lbs = svg
        .split("<polyline class=\"series\" points=\"")
        .nth(1)
        .unwrap();
    let ys: Vec<f64> = lbs[..lbs.find('"').unwrap()]
        .split_whitespace()
        .map(|xy| xy.split(',').nth(1).unwrap().parse().unwrap())
        .collect();
    assert_eq!(ys.len(), 41);
    let lowest = ys.iter().fold(0.0f64, |m, y| m.max(*y));
    let det = 1.05 * (1.0 - (lowest - 40.0) / 250.0);
    assert!((det - 0.47).abs() < 0.03, "lowest LBS volume {det}");
    std::fs::create_dir(dir.path().join("r")).unwrap();
    std::fs::write(
        dir.path().join("r/index.html"),
        r#"<img src="../volume.svg"><img src="../knee.png"><img src="../all.png">"#,
    )
    .unwrap();
    assert_eq!(check_pictures(&dir.path().join("r")), 3);
    assert_eq!(decode_png(&std::fs::read(p("all.png")).unwrap()).0, 6 * 260);
    // A clip is needed for the sphere.
    let rig = dir.path().join("strip.json");
    std::fs::write(&rig, STRIP_JSON).unwrap();
    let bad = chasles(&[
        "skin",
        "--rig",
        rig.to_str().unwrap(),
        "--sphere",
        &p("s.png"),
    ]);
    assert!(String::from_utf8_lossy(&bad.stderr).contains("has no animations"));
    assert!(!dir.path().join("s.png").exists());
}

#[test]
fn skin_on_the_gpu_matches_the_cpu() {
    let dir = tempfile::tempdir().unwrap();
    let run = |device: &str| {
        let out = dir.path().join(format!("{device}.json"));
        let o = chasles(&[
            "skin",
            "--rig",
            &model("CesiumMan.glb"),
            "--time",
            "0.7",
            "--method",
            "dqs",
            "--device",
            device,
            "--out",
            out.to_str().unwrap(),
        ]);
        (o, out)
    };
    let (cpu, cpu_out) = run("cpu");
    assert!(stdout(&cpu).contains("on the CPU"));
    let (gpu, gpu_out) = run("gpu");
    let err = String::from_utf8_lossy(&gpu.stderr);
    if err.contains("no GPU adapter") {
        eprintln!("skipping: {err}");
        return;
    }
    assert!(stdout(&gpu).contains("on the GPU ("));
    let read = |p: &std::path::Path| -> Vec<f64> {
        let v: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(p).unwrap()).unwrap();
        v["positions"]
            .as_array()
            .unwrap()
            .iter()
            .flat_map(|p| p.as_array().unwrap().iter().map(|x| x.as_f64().unwrap()))
            .collect()
    };
    let (a, b) = (read(&cpu_out), read(&gpu_out));
    assert_eq!(a.len(), 3273 * 3);
    let worst = a
        .iter()
        .zip(&b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max);
    assert!(worst < 1e-4, "GPU vs CPU {worst:e}");
    // DIB runs on the GPU too; methods without a shader are refused with the reason.
    let (log, _) = {
        let out = dir.path().join("log.json");
        let o = chasles(&[
            "skin",
            "--rig",
            &model("CesiumMan.glb"),
            "--method",
            "log",
            "--device",
            "gpu",
            "--out",
            out.to_str().unwrap(),
        ]);
        (o, out)
    };
    assert!(String::from_utf8_lossy(&log.stderr).contains("log has no GPU path"));
    assert!(!dir.path().join("log.json").exists());
}

#[cfg(unix)]
#[test]
fn a_closed_pipe_ends_quietly() {
    use std::io::{BufRead, BufReader};
    use std::os::unix::process::ExitStatusExt;
    // 10^5 CSV rows (several MB) into a pipe whose reader leaves after the first line.
    let mut child = Command::new(env!("CARGO_BIN_EXE_chasles"))
        .args([
            "interp",
            "--method",
            "slerp",
            "--keys",
            "builtin:table5.1",
            "--frames",
            "100000",
        ])
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let mut first = String::new();
    BufReader::new(child.stdout.take().unwrap())
        .read_line(&mut first)
        .unwrap();
    assert!(first.starts_with("index,t,w,x,y,z"), "{first}");
    // The reader is gone now.
    let o = child.wait_with_output().unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(!err.contains("panicked"), "{err}");
    assert!(
        o.status.success() || o.status.signal() == Some(13),
        "ended with {:?}: {err}",
        o.status
    );
    assert_ne!(o.status.code(), Some(101), "{err}");
}

#[test]
fn skin_bench_measures_a_rig_of_ones_own_in_its_clip() {
    let rig = model("RiggedFigure.glb");
    let out = stdout(&chasles(&[
        "skin",
        "--rig",
        &rig,
        "--bench",
        "--bench-threads",
        "1",
        "--bench-rounds",
        "1",
    ]));
    // The mesh, its pose (the first clip half-way through) and the repeats.
    assert!(
        out.contains("RiggedFigure.glb: 370 vertices, 19 joints, at most 4 influences a vertex, in animation 0 at t = ")
            && out.contains("each sample skins it 271 times"),
        "{out}"
    );
    let rows: Vec<Vec<&str>> = out
        .lines()
        .filter(|l| l.starts_with("| 370 (RiggedFigure.glb) | 1 |"))
        .map(|l| l.split('|').map(str::trim).collect())
        .collect();
    // Six methods, DIB again with its grouping turned off, five baselines (four influences
    // at most), the copy and the traffic.
    assert_eq!(rows.len(), 14, "{out}");
    let rate = |name: &str| -> f64 {
        let r = rows
            .iter()
            .find(|r| r[3] == name)
            .unwrap_or_else(|| panic!("{name}: {out}"));
        r[4].parse().unwrap()
    };
    assert!(
        rate("dib") > 0.0
            && rate("dib, in the rig's order (not grouped)") > 0.0
            && rate("glam dqs (Vec4, careful)") > 0.0,
        "{out}"
    );
    assert!(out.contains("× DIB") && out.contains("SBS solved"), "{out}");
    assert!(
        out.contains("370 vertices, 1 thread(s): DIB ran ")
            && (out.contains("as fast as in the rig's order; in that order DQS is ")
                || !chasles_skin::fast::uses_simd(4)),
        "{out}"
    );
    // Sizes are the synthetic meshes'; rounds are counted.
    for (args, says) in [
        (
            vec!["--bench-vertices", "100"],
            "--bench-vertices sizes the synthetic meshes: not with --rig",
        ),
        (
            vec!["--bench-rounds", "0"],
            "--bench-rounds: 0 is not between 1 and 10000",
        ),
        (
            vec!["--bench-rotations", "uniform"],
            "--bench-rotations turns the synthetic meshes' joints: not with --rig",
        ),
        // The GPU's table is its own: it takes none of the CPU table's options.
        (
            vec!["--device", "gpu"],
            "--rig is for the CPU's table: --bench --device gpu times synthetic meshes",
        ),
    ] {
        let mut all = vec!["skin", "--rig", &rig, "--bench"];
        all.extend(args);
        let bad = chasles(&all);
        assert_eq!(bad.status.code(), Some(2));
        assert!(
            String::from_utf8_lossy(&bad.stderr).contains(says),
            "{says}"
        );
    }
    // A rig of no vertex has nothing to time: an error naming it, before any table.
    let dir = tempfile::tempdir().unwrap();
    let empty = dir.path().join("empty.json");
    std::fs::write(
        &empty,
        r#"{"positions": [], "triangles": [], "joints": [{"name": "a", "parent": null}], "influences": []}"#,
    )
    .unwrap();
    let bad = chasles(&["skin", "--rig", empty.to_str().unwrap(), "--bench"]);
    assert_eq!(bad.status.code(), Some(2));
    assert!(
        bad.stdout.is_empty(),
        "{}",
        String::from_utf8_lossy(&bad.stdout)
    );
    assert!(
        String::from_utf8_lossy(&bad.stderr).contains("the rig empty.json has no vertices to time"),
        "{}",
        String::from_utf8_lossy(&bad.stderr)
    );
}

#[test]
fn skin_bench_prints_every_kernel_on_every_thread_count_with_round_by_round_ratios() {
    // The bench on synthetic meshes of 64 vertices, on these threads, with `more`.
    let bench64 = |threads: &str, more: &[&str]| {
        let mut args = vec!["skin", "--bench", "--bench-vertices", "64"];
        args.extend(["--bench-threads", threads]);
        args.extend(more);
        stdout(&chasles(&args))
    };
    let out = bench64("1,2", &[]);
    let rows: Vec<Vec<&str>> = out
        .lines()
        .filter(|l| l.starts_with("| 64 |"))
        .map(|l| l.split('|').map(str::trim).collect())
        .collect();
    // Six methods, five baselines, the copy and the traffic, on 1 and on 2 threads; every
    // row as many cells as the header.
    assert_eq!(rows.len(), 2 * 13, "{out}");
    let header = out.lines().find(|l| l.starts_with("| vertices |")).unwrap();
    assert!(
        rows.iter().all(|r| r.len() == header.split('|').count()),
        "{out}"
    );
    for threads in ["1", "2"] {
        let of = |name: &str| {
            rows.iter()
                .find(|r| r[2] == threads && r[3] == name)
                .unwrap_or_else(|| panic!("no {name} on {threads}: {out}"))
        };
        // A baseline's ratio: median and spread, "1.23× (1.01–1.50)".
        let ratio = of("glam dqs (Vec4, careful)")[6];
        assert!(ratio.ends_with(')') && ratio.contains("× ("), "{ratio}");
        assert_eq!(of("memcpy, 72 B a vertex")[7], "1.00 (1.00–1.00)");
        assert_eq!(of("traffic: loads and stores alone")[8], "1.00 (1.00–1.00)");
        assert_eq!(of("dqs")[6], "", "our kernels have no ratio to themselves");
    }
    assert!(out.contains("of the CPUs busy during the run"), "{out}");
    // The kernels that ran, as this processor has them.
    let kernels = match (
        chasles_skin::fast::uses_simd(4),
        chasles_skin::fast::uses_avx512(4),
    ) {
        (true, true) => "VL's 32 registers, and DIB its AVX-512F kernel, sixteen at a time",
        (true, false) => "eight vertices at a time (no AVX-512F and VL here",
        _ => "their portable scalar kernels",
    };
    assert!(out.contains(kernels), "{kernels}: {out}");
    let bad = chasles(&["skin", "--bench", "--bench-threads", "0"]);
    assert_eq!(bad.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&bad.stderr)
        .contains("0 is not a thread count from 1 to 1024 or all"));
    // Joints turned uniformly: the same rows, the mesh named; an unknown kind is refused.
    let out = bench64("1", &["--bench-rotations", "uniform"]);
    let uniform = out
        .lines()
        .filter(|l| l.starts_with("| 64 (synthetic, uniform rotations) | 1 |"))
        .count();
    assert_eq!(uniform, 13, "{out}");
    assert!(
        out.contains("rotation centres a pose here, real rigs far fewer"),
        "{out}"
    );
    let bad = chasles(&["skin", "--bench", "--bench-rotations", "sideways"]);
    assert_eq!(bad.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&bad.stderr).contains("sideways"));
}
