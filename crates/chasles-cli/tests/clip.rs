//! `chasles clip blend` and `chasles clip compress` (Kavan et al. 2006, §7): the files they
//! write load back and play in `chasles skin`, the compressed file meets its tolerance, and
//! bad input is an error naming it, with nothing written.

mod common;

use chasles_skin::clip_compress::ClipSkins;
use chasles_skin::{gltf_load, Method};
use common::{chasles, model, stdout};
use std::path::Path;

fn s(p: &Path) -> String {
    p.display().to_string()
}

#[test]
fn blend_writes_a_rig_whose_blended_clip_skins_like_any_clip() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("trot.glb");
    let fox = model("Fox.glb");
    let text = stdout(&chasles(&[
        "clip",
        "blend",
        "--rig",
        &fox,
        "--clips",
        "Walk,Run",
        "--weight",
        "0.5",
        "--sync",
        "--out",
        &s(&out),
    ]));
    assert!(
        text.contains("'Walk+Run 0.5'") && text.contains("rigid per joint"),
        "{text}"
    );
    // 0.5 · (0.7083 + 1.1583) s at 24 fps: 22 intervals.
    assert!(text.contains("23 frames"), "{text}");
    let rig = gltf_load::load(&out).unwrap();
    assert_eq!(rig.animations.len(), 1);
    assert_eq!(rig.animations[0].name, "Walk+Run 0.5");
    assert_eq!(rig.mesh.positions.len(), chasles_models::FOX.vertices);
    let obj = dir.path().join("frame.obj");
    let text = stdout(&chasles(&[
        "skin",
        "--rig",
        &s(&out),
        "--anim",
        "Walk+Run 0.5",
        "--time",
        "0.3",
        "--out",
        &s(&obj),
    ]));
    assert!(text.contains("1728 vertices"), "{text}");
    // And the viewer shows it.
    let page = dir.path().join("trot.html");
    stdout(&chasles(&[
        "view",
        &s(&out),
        "--clip",
        "Walk+Run 0.5",
        "--out",
        &s(&page),
    ]));
    assert!(std::fs::read_to_string(&page)
        .unwrap()
        .contains("Walk+Run 0.5"));
    assert!(
        std::fs::read_to_string(&obj)
            .unwrap()
            .lines()
            .filter(|l| l.starts_with("v "))
            .count()
            == 1728
    );
    // --keep-clips: the blend first, then the rig's own three.
    let both = dir.path().join("all.glb");
    stdout(&chasles(&[
        "clip",
        "blend",
        "--rig",
        &fox,
        "--clips",
        "1,2",
        "--weight",
        "0.25",
        "--name",
        "mix",
        "--keep-clips",
        "--out",
        &s(&both),
    ]));
    let names: Vec<String> = gltf_load::load(&both)
        .unwrap()
        .animations
        .into_iter()
        .map(|a| a.name)
        .collect();
    assert_eq!(names, ["mix", "Survey", "Walk", "Run"]);
}

#[test]
fn compress_writes_a_file_within_the_tolerance() {
    let dir = tempfile::tempdir().unwrap();
    let man = model("CesiumMan.glb");
    for (rotation, tolerance) in [("slerp", 0.005), ("squad", 0.005), ("squad", 0.001)] {
        let out = dir.path().join(format!("{rotation}-{tolerance}.glb"));
        let text = stdout(&chasles(&[
            "clip",
            "compress",
            "--rig",
            &man,
            "--clip",
            "0",
            "--tolerance",
            &tolerance.to_string(),
            "--rotation",
            rotation,
            "--out",
            &s(&out),
        ]));
        assert!(
            text.contains("kept ") && text.contains("of 2736 keys"),
            "{text}"
        );
        let original = gltf_load::load(Path::new(&man)).unwrap();
        let back = gltf_load::load(&out).unwrap();
        let frames = original.animations[0].key_times();
        let reference =
            ClipSkins::new(&original, &original.animations[0], &frames, Method::Dqs).unwrap();
        let file = ClipSkins::new(&back, &back.animations[0], &frames, Method::Dqs).unwrap();
        let worst = reference.worst_distance(&file).unwrap().distance;
        assert!(worst <= tolerance, "{rotation} {tolerance}: {worst}");
        let kept: usize = back.animations[0]
            .channels
            .iter()
            .map(|c| c.times.len())
            .sum();
        assert!(
            kept < 2736 && text.contains(&format!("kept {kept} of 2736")),
            "{text}"
        );
        let obj = dir.path().join("f.obj");
        stdout(&chasles(&[
            "skin",
            "--rig",
            &s(&out),
            "--anim",
            "0",
            "--time",
            "1.1",
            "--out",
            &s(&obj),
        ]));
    }
    // Without --out: the report alone.
    let text = stdout(&chasles(&[
        "clip",
        "compress",
        "--rig",
        &man,
        "--clip",
        "0",
        "--tolerance",
        "0.01",
    ]));
    assert!(
        text.contains("in the written file") && !text.contains("wrote"),
        "{text}"
    );
}

#[test]
fn bad_input_is_an_error_naming_it_and_writes_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out.glb");
    let (fox, man) = (model("Fox.glb"), model("CesiumMan.glb"));
    let bad = dir.path().join("bad.glb");
    std::fs::write(&bad, b"glTF\x02\x00\x00\x00\x10\x00\x00\x00garbage").unwrap();
    let blend = |rig: &str, clips: &str, w: &str| {
        chasles(&[
            "clip",
            "blend",
            "--rig",
            rig,
            "--clips",
            clips,
            "--weight",
            w,
            "--out",
            &s(&out),
        ])
    };
    let compress = |rig: &str, clip: &str, d: &str| {
        chasles(&[
            "clip",
            "compress",
            "--rig",
            rig,
            "--clip",
            clip,
            "--tolerance",
            d,
            "--out",
            &s(&out),
        ])
    };
    for (o, says) in [
        (
            blend(&fox, "Walk,Gallop", "0.5"),
            "no animation 'Gallop'; there are: Survey (0), Walk (1), Run (2)",
        ),
        (
            blend(&fox, "Walk,Run", "NaN"),
            "the weight NaN is not a number in [0, 1]",
        ),
        (
            blend(&fox, "Walk,Run", "-0.5"),
            "the weight -0.5 is not a number in [0, 1]",
        ),
        (
            blend(&fox, "Walk,Run", "1.01"),
            "the weight 1.01 is not a number in [0, 1]",
        ),
        (blend(&fox, "Walk", "0.5"), "--clips takes two clips"),
        (blend(&s(&bad), "Walk,Run", "0.5"), "bad.glb"),
        (compress(&fox, "Trot", "1"), "no animation 'Trot'"),
        (
            compress(&man, "0", "0"),
            "the tolerance 0 is not a positive number",
        ),
        (
            compress(&man, "0", "-2"),
            "the tolerance -2 is not a positive number",
        ),
        (
            compress(&man, "0", "NaN"),
            "the tolerance NaN is not a positive number",
        ),
        (
            compress(&man, "0", "1e-9"),
            "below the rounding of the written file",
        ),
        (compress(&s(&bad), "0", "1"), "bad.glb"),
        (
            chasles(&[
                "clip",
                "blend",
                "--rig",
                &fox,
                "--clips",
                "Walk,Run",
                "--weight",
                "0.5",
                "--out",
                &s(&dir.path().join("x.obj")),
            ]),
            "must end in .glb",
        ),
    ] {
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{says}: {err}");
        assert!(err.contains(says), "wanted '{says}' in: {err}");
        assert!(
            !err.contains("internal error") && !err.contains("panicked"),
            "{err}"
        );
    }
    let left: Vec<_> = std::fs::read_dir(dir.path())
        .unwrap()
        .map(|e| e.unwrap().file_name())
        .collect();
    assert_eq!(left, [std::ffi::OsString::from("bad.glb")]);
}
