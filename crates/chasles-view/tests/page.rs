//! The viewer's page without a browser: its shaders are naga's translation of the shared
//! skinning WGSL, it refers to nothing outside itself, and the palettes it embeds are the
//! library's own for the poses it names (Kavan et al. 2006, §6). The browser tests are in
//! `chasles-cli/tests/view.rs`.

use base64::Engine;
use chasles_skin::fast::{FastRig, Joints, Palette};
use chasles_skin::pose::skinning_matrices;
use chasles_skin::{gltf_load, Method, Pose, Rig};
use chasles_view::page::external_reference;
use chasles_view::{scene, shader, ViewError};

/// The JSON the page embeds.
fn data(html: &str) -> serde_json::Value {
    let start = html.find("id=\"chasles-data\">").expect("data element") + 18;
    let end = start + html[start..].find("</script>").expect("data end");
    serde_json::from_str(&html[start..end]).expect("data is JSON")
}

fn floats(b64: &serde_json::Value) -> Vec<f32> {
    let bytes = base64::engine::general_purpose::STANDARD
        .decode(b64.as_str().expect("base64 string"))
        .expect("base64");
    bytes
        .chunks(4)
        .map(|c| f32::from_le_bytes(c.try_into().unwrap()))
        .collect()
}

/// The palette floats (LBS rows then dual quaternion, joint by joint) the library makes for
/// `pose`.
fn library_palette(rig: &Rig, pose: &Pose) -> Vec<f32> {
    let fast = FastRig::<4>::new(rig).unwrap();
    let m = skinning_matrices(rig, pose).unwrap();
    let lbs = Palette::from_matrices(Method::Lbs, &fast, &m, false).unwrap();
    let dqs = Palette::from_matrices(Method::Dqs, &fast, &m, false).unwrap();
    let (Joints::Lbs(a), Joints::Dqs(d)) = (lbs.data(), dqs.data()) else {
        panic!("palette kinds")
    };
    a.iter()
        .zip(d)
        .flat_map(|(a, d)| {
            let mut v: Vec<f32> = a.rows.iter().flatten().copied().collect();
            v.extend(d.real);
            v.extend(d.dual);
            v
        })
        .collect()
}

fn model(m: chasles_models::Model) -> Rig {
    gltf_load::load_slice(m.bytes, m.file).unwrap()
}

#[test]
fn the_glsl_is_nagas_translation_of_the_shared_wgsl() {
    let wgsl = shader::wgsl();
    assert!(wgsl.starts_with(chasles_skin::shader::SKINNING_WGSL));
    let g = shader::glsl().unwrap();
    for (name, src) in [("lbs", &g.lbs), ("dqs", &g.dqs), ("surface", &g.surface)] {
        assert!(src.starts_with("#version 300 es\n"), "{name}");
        assert!(src.contains("void main()"), "{name}");
    }
    // The vertex shaders call the compute shaders' functions, by name.
    assert!(g.lbs.contains("lbs_blend(") && g.lbs.contains("lbs_move("));
    assert!(g.dqs.contains("dqs_blend(") && g.dqs.contains("rigid_move("));
    assert!(g.dqs.contains("dqs_add(") && g.dqs.contains("dot("));
    assert!(g.lbs.contains("texelFetch(") && g.lbs.contains(&g.palette));
    // The View uniform, read by both stages: a block in each, every one bound by name.
    assert_eq!(g.blocks.len(), 2, "{:?}", g.blocks);
    assert!(g.blocks.iter().any(|b| g.lbs.contains(b.as_str())));
    assert!(g.blocks.iter().any(|b| g.surface.contains(b.as_str())));
    assert_eq!(
        (g.skinned.as_str(), g.det.as_str()),
        ("_vs2fs_location2", "_vs2fs_location3")
    );
    // No GLSL is written by hand in this crate: nothing in src/ declares a version.
    let src = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut stack = vec![src];
    while let Some(dir) = stack.pop() {
        for e in std::fs::read_dir(dir).unwrap() {
            let p = e.unwrap().path();
            if p.is_dir() {
                stack.push(p);
            } else {
                let text = std::fs::read_to_string(&p).unwrap_or_default();
                assert!(
                    !text.contains("#version 3"),
                    "hand-written GLSL in {}",
                    p.display()
                );
            }
        }
    }
}

#[test]
fn every_built_in_page_refers_to_nothing_outside_itself() {
    for m in chasles_models::ALL {
        let rig = model(m);
        let page = chasles_view::character(&rig, None, 30.0, m.credit).unwrap();
        assert_eq!(external_reference(&page.html), None, "{}", m.file);
        assert_eq!(page.vertices, m.vertices, "{}", m.file);
        assert_eq!(page.joints, m.joints, "{}", m.file);
        let d = data(&page.html);
        assert_eq!(d["credit"], m.credit);
        assert!(page
            .html
            .contains(&format!("<title>chasles view: {}", m.file)));
        assert!(
            page.html.ends_with("</html>\n"),
            "{}: written whole",
            m.file
        );
    }
    let c = chasles_view::cylinder().unwrap();
    assert_eq!(external_reference(&c.html), None);
    assert_eq!(c.frames, 73 * 37);
}

#[test]
fn a_name_is_text_wherever_it_goes() {
    let mut rig = model(chasles_models::SIMPLE_SKIN);
    rig.name = "{{DATA}} <i>x</i> & {{SCRIPT}}".into();
    let page = chasles_view::character(&rig, None, 30.0, "{{STYLE}}").unwrap();
    assert!(page
        .html
        .contains("<title>chasles view: {{DATA}} &lt;i&gt;x&lt;/i&gt; &amp; {{SCRIPT}}, LBS"));
    let d = data(&page.html);
    assert_eq!(d["title"], "{{DATA}} <i>x</i> & {{SCRIPT}}");
    assert_eq!(d["credit"], "{{STYLE}}");
    assert_eq!(page.html.matches("id=\"chasles-data\"").count(), 1);
}

#[test]
fn external_references_are_found() {
    for bad in [
        "<img src=\"a.png\">",
        "<a href=\"x\">",
        "see https://example.invalid",
        "HTTP://EXAMPLE",
        "fetch('x')",
        "background: url(x.png)",
        "@import 'x.css'",
        "new WebSocket(u)",
        "<link rel=stylesheet>",
        "navigator.sendBeacon(u)",
        "import('./m.js')",
        "data:image/png;base64,AAAA",
    ] {
        assert!(external_reference(bad).is_some(), "{bad}");
    }
    for fine in [
        "texelFetch(tex, p, 0)",
        "the joint's rows, then",
        "reimport(x)",
    ] {
        assert_eq!(external_reference(fine), None, "{fine}");
    }
}

#[test]
fn the_page_holds_the_librarys_palettes_at_the_times_it_names() {
    let rig = model(chasles_models::CESIUM_MAN);
    let page = chasles_view::character(&rig, None, 30.0, "").unwrap();
    let d = data(&page.html);
    let clip = &d["clips"][0];
    let times: Vec<f32> = serde_json::from_value(clip["times"].clone()).unwrap();
    assert_eq!(times.len(), 61, "2 s at 30 fps, both ends");
    assert_eq!(times[60], rig.animations[0].duration());
    let palettes = floats(&d["palettes"][0]);
    let per = rig.joints.len() * scene::FLOATS_PER_JOINT;
    assert_eq!(palettes.len(), times.len() * per);
    let worst = clip["worst"].as_u64().unwrap() as usize;
    for k in [0, worst, 60] {
        let pose = Pose::animated(&rig, 0, times[k]).unwrap();
        assert_eq!(
            palettes[k * per..(k + 1) * per],
            library_palette(&rig, &pose)[..],
            "frame {k}"
        );
    }
    // The worst frame is where LBS's det is smallest, as the library measures it.
    let min_det: Vec<f32> = serde_json::from_value(clip["min_det"].clone()).unwrap();
    let pose = Pose::animated(&rig, 0, times[worst]).unwrap();
    assert_eq!(
        min_det[worst],
        chasles_skin::volume::lbs_min_determinant(&rig, &pose).unwrap()
    );
    assert!(min_det.iter().all(|d| *d >= min_det[worst]));
    assert!(
        min_det[worst] < 0.5,
        "CesiumMan's walk: LBS keeps {}",
        min_det[worst]
    );
    // The mesh as laid out for the vertex shaders: four influences, heaviest first.
    let weights = floats(&d["mesh"]["weights"]);
    assert_eq!(weights.len(), 4 * rig.mesh.positions.len());
    for w in weights.chunks(4) {
        assert!((w.iter().sum::<f32>() - 1.0).abs() < 1e-5 && w[0] >= w[1]);
    }
}

#[test]
fn the_cylinder_grid_holds_the_librarys_twist_and_bend() {
    let rig = chasles_skin::cylinder::twisted_cylinder();
    let page = chasles_view::cylinder().unwrap();
    let d = data(&page.html);
    let twist: Vec<f32> = serde_json::from_value(d["grid"]["twist"].clone()).unwrap();
    let bend: Vec<f32> = serde_json::from_value(d["grid"]["bend"].clone()).unwrap();
    let palettes = floats(&d["palettes"][0]);
    let per = 2 * scene::FLOATS_PER_JOINT;
    let at = |t: f32, b: f32| {
        let k = bend.iter().position(|x| *x == b).unwrap() * twist.len()
            + twist.iter().position(|x| *x == t).unwrap();
        palettes[k * per..(k + 1) * per].to_vec()
    };
    use chasles_skin::cylinder::{pose, Motion};
    let close = |a: &[f32], b: &[f32]| a.iter().zip(b).all(|(x, y)| (x - y).abs() < 1e-6);
    let twisted = library_palette(&rig, &pose(&rig, Motion::Twist, 180f32.to_radians()));
    assert!(close(&at(180.0, 0.0), &twisted));
    let bent = library_palette(&rig, &pose(&rig, Motion::Bend, 90f32.to_radians()));
    assert!(close(&at(0.0, 90.0), &bent));
    // LBS keeps cos²(θ/2) of the volume halfway across the twisted joint: 0 at 180°.
    let min_det: Vec<f32> = serde_json::from_value(d["grid"]["min_det"].clone()).unwrap();
    let k180 = twist.iter().position(|x| *x == 180.0).unwrap();
    assert!(min_det[k180].abs() < 1e-5, "{}", min_det[k180]);
    assert!((min_det[0] - 1.0).abs() < 1e-5);
}

#[test]
fn bad_requests_are_typed_errors() {
    let fox = model(chasles_models::FOX);
    let e = chasles_view::character(&fox, Some("Dance"), 30.0, "").unwrap_err();
    assert!(matches!(e, ViewError::UnknownClip { .. }));
    assert_eq!(
        e.to_string(),
        "Fox.glb: no clip 'Dance'; there are: Survey, Walk, Run"
    );
    assert!(chasles_view::character(&fox, Some("Run"), 30.0, "").is_ok());
    assert!(chasles_view::character(&fox, Some("2"), 30.0, "").is_ok());
    for fps in [0.0, -1.0, f32::NAN, 1000.0] {
        assert!(matches!(
            chasles_view::character(&fox, None, fps, ""),
            Err(ViewError::Fps(_))
        ));
    }
    // Five influences a vertex: the four-influence shaders cannot skin it.
    let mut rig = chasles_skin::cylinder::twisted_cylinder();
    let n = rig.mesh.positions.len();
    let five: Vec<Vec<(usize, f32)>> =
        vec![vec![(0, 0.2), (1, 0.2), (0, 0.2), (1, 0.2), (0, 0.2)]; n];
    rig.influences = chasles_skin::Influences::from_lists(&five, 2).unwrap();
    assert_eq!(rig.influences.max_per_vertex(), 5);
    let e = chasles_view::character(&rig, None, 30.0, "").unwrap_err();
    assert!(
        matches!(e, ViewError::Skin(_)) && e.to_string().contains("influences"),
        "{e}"
    );
}

#[test]
fn a_rig_without_clips_shows_its_rest_pose_and_the_snake_is_large() {
    let rig = chasles_skin::cylinder::twisted_cylinder();
    let page = chasles_view::character(&rig, None, 30.0, "").unwrap();
    let d = data(&page.html);
    assert_eq!(d["clips"][0]["name"], "rest pose");
    assert_eq!(page.frames, 1);
    let snake = chasles_view::synthetic::snake(100_000).unwrap();
    assert_eq!(snake.mesh.positions.len(), 100_000);
    assert_eq!(snake.animations[0].duration(), 2.0);
    let small = chasles_view::synthetic::snake(2_000).unwrap();
    let page = chasles_view::character(&small, Some("wave"), 30.0, "").unwrap();
    assert_eq!((page.vertices, page.joints, page.frames), (2_000, 8, 61));
    let worst: f32 =
        serde_json::from_value(data(&page.html)["clips"][0]["min_det"][0].clone()).unwrap();
    assert!(worst < 0.9, "the wave twists the joints: LBS keeps {worst}");
}
