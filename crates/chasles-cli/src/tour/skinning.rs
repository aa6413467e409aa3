//! The tour's skinning (Kavan et al. 2006, §6, Figure 6(a)–(b)): the candy wrapper on a
//! two-bone cylinder, and linear blending's volume loss on the real characters
//! (CesiumMan's walk and Fox's run, built in; more from `$CHASLES_DATA`), each with a
//! viewer page beside the report (`chasles-view`: LBS and DQS live in the browser).

use crate::pictures;
use chasles_paper::Paper::Kavan2006;
use chasles_paper::{PaperFigure, Section};

/// Figure 6's caption.
const FIGURE_6: &str = "(a) Typical \u{201c}candy wrapper\u{201d} of linear blending, (b) solved by dual quaternion blending. (c) Non-shortest path of log-matrix blending implies non-natural deformations, (d) shortest-path dual quaternion blending.";
use chasles_skin::cylinder::{self, Motion};
use chasles_skin::{gltf_load, Method, Pose, Rig};

/// The twist and the bend of the two-bone cylinder, every method.
pub fn candy_wrapper() -> Section {
    let mut s =
        Section::new("Kavan et al. §6, Figure 6(a)–(b): the candy wrapper on a two-bone cylinder");
    let rig = cylinder::twisted_cylinder();
    s.attempt(
        Kavan2006,
        "§6, Figure 6(a)–(b)",
        "linear blend skinning collapses a joint twisted by 180° to a point (the candy wrapper); dual-quaternion skinning keeps its shape",
        |s| -> anyhow::Result<_> {
            let mut t = chasles_paper::Table::new(
                "the middle ring's radius, relative to rest",
                &["twist", "LBS middle radius", "DQS middle radius"],
            );
            let mut at180 = (f32::NAN, f32::NAN);
            for deg in [0.0f32, 90.0, 135.0, 180.0] {
                let l = cylinder::measure(&rig, Method::Lbs, Motion::Twist, deg.to_radians())?;
                let d = cylinder::measure(&rig, Method::Dqs, Motion::Twist, deg.to_radians())?;
                t.row(vec![
                    chasles_paper::Cell::text(format!("{deg}°")),
                    chasles_paper::Cell::Number(chasles_paper::Number::fixed(l.radius.into(), 3)),
                    chasles_paper::Cell::Number(chasles_paper::Number::fixed(d.radius.into(), 3)),
                ]);
                at180 = (l.radius, d.radius);
            }
            s.table(t);
            Ok((
                format!(
                    "middle radius at 180° twist, relative to rest: LBS {:.3}, DQS {:.3}",
                    at180.0, at180.1
                ),
                at180.0 < 0.05 && (at180.1 - 1.0).abs() < 0.02,
            ))
        },
    );
    s.try_figure(
        "twist-radius.svg",
        pictures::twist_plot().map(String::into_bytes),
        "The middle radius against the twist angle for every method: LBS follows cos(θ/2) (dashed; the blended matrix there is (I + Rx(θ))/2) down to 0 at 180°, every rigid method keeps 1",
    );
    let pose = cylinder::pose(&rig, Motion::Twist, std::f32::consts::PI);
    s.paper_figure(
        PaperFigure::new(Kavan2006, "6(a)–(b)", FIGURE_6),
        "cylinder-twist.png",
        pictures::methods_side_by_side(&rig, &pose, &Method::ALL).map(|i| i.png()),
        "The cylinder's second bone twisted 180° about its axis, every method: LBS collapses to a point, the others keep the radius",
    );
    s.try_figure(
        "cylinder-viewer.html",
        chasles_view::cylinder().map(|p| p.html.into_bytes()),
        "The candy wrapper live in the browser (one self-contained page, WebGL2): LBS and DQS side by side under one camera, twist and bend sliders, a sweep of the twist, the heat map of LBS's lost volume",
    );
    let pose = cylinder::pose(&rig, Motion::Bend, 120f32.to_radians());
    s.try_figure(
        "cylinder-bend.png",
        pictures::methods_side_by_side(&rig, &pose, &Method::ALL).map(|i| i.png()),
        "The same cylinder bent 120°: LBS thins at the elbow, DQS keeps the volume and bulges slightly outward",
    );
    s.try_figure(
        "twist-sweep.gif",
        pictures::twist_sweep(25).and_then(|f| Ok(chasles_viz::gif(&f, 6)?)),
        "The twist swept 0° → 180° → 0°: LBS (left) against DQS (right)",
    );
    s.attempt(
        Kavan2006,
        "§6",
        "on bending, LBS loses volume at the joint while DQS keeps it, at the price of a slight bulge",
        |s| -> anyhow::Result<_> {
            let l = cylinder::measure(&rig, Method::Lbs, Motion::Bend, 150f32.to_radians())?;
            let d = cylinder::measure(&rig, Method::Dqs, Motion::Bend, 150f32.to_radians())?;
            s.text(format!(
                "bend 150°: LBS thins to {:.3} and loses {:.1} % volume; DQS keeps the radius and bulges {:.1} % out",
                l.radius,
                (1.0 - l.volume) * 100.0,
                (d.bulge - 1.0) * 100.0
            ));
            Ok((
                format!(
                    "bend 150°: LBS radius {:.3}, volume {:.3}; DQS radius {:.3}, volume {:.3}, bulge {:.3}",
                    l.radius, l.volume, d.radius, d.volume, d.bulge
                ),
                l.volume < 0.97 && d.radius > 0.95 && d.bulge > 1.0,
            ))
        },
    );
    s
}

/// Figure 6(c)–(d): the cylinder's first bone turned 170° about its axis and the second a
/// further 20° (190° in all): the two joints are 20° apart, but their matrix logarithms
/// (+170° and −170°) average to no turn at all, so log-matrix skinning twists the joint
/// region back the long way (340° across it), while DQS, with the antipodality fix, turns
/// it the short way (180° at the middle, 20° across).
pub fn long_way() -> Section {
    let mut s = Section::new(
        "Kavan et al. §6, Figure 6(c)–(d): log-matrix skinning takes the long way past 180°, DQS the short one",
    );
    let rig = cylinder::twisted_cylinder();
    s.attempt(
        Kavan2006,
        "§6, Figure 6(c)–(d)",
        "(c) Non-shortest path of log-matrix blending implies non-natural deformations, (d) shortest-path dual quaternion blending",
        |s| -> anyhow::Result<_> {
            let about_x = |deg: f32| {
                chasles::Quat::from_axis_angle(chasles::Vec3::new(1.0, 0.0, 0.0), deg.to_radians())
            };
            let mut pose = Pose::rest(&rig);
            pose.local[0].rotation = about_x(170.0)?;
            pose.local[1].rotation = about_x(20.0)?;
            // The middle ring's turn about x: its first vertex (rest (1, r, 0)) as placed.
            let middle = |m: Method| -> anyhow::Result<f32> {
                let out = chasles_skin::skin(&rig, &pose, m)?;
                let p = out.positions[(cylinder::RINGS / 2) * cylinder::SEGMENTS];
                Ok(p.z.atan2(p.y).to_degrees().rem_euclid(360.0))
            };
            let (log, dqs) = (middle(Method::Log)?, middle(Method::Dqs)?);
            s.paper_figure(
                PaperFigure::new(Kavan2006, "6(c)–(d)", FIGURE_6),
                "kavan-figure-6cd.png",
                pictures::methods_side_by_side(&rig, &pose, &[Method::Log, Method::Dqs]).map(|i| i.png()),
                "The cylinder with its bones turned 170° and 190° about its axis (stripes show the twist): log-matrix skinning (left, Figure 6(c)) winds the joint region back through the rest orientation; DQS (right, Figure 6(d)) turns it the short way",
            );
            Ok((
                format!("the middle ring turned {log:.1}° by Log and {dqs:.1}° by DQS (the joints: 170° and 190°)"),
                (dqs - 180.0).abs() < 5.0 && (log.min(360.0 - log)) < 20.0,
            ))
        },
    );
    s
}

/// Figure 1(c): SBS's seams on the paper's piece of cloth (6000 vertices, 49 joints, built
/// in code: `chasles_skin::cloth`), crumpled by turning neighbouring joints ±0.6 rad about
/// the normal: the largest kink along the grid lines across an SBS cluster border, against
/// DQS's.
pub fn figure_1c() -> Section {
    let mut s = Section::new(
        "Kavan et al. §6, Figure 1(c): spherical blend skinning's seams between vertex clusters",
    );
    s.attempt(
        Kavan2006,
        "§6, Figure 1(c)",
        "To make real-time execution possible, SVD is computed only for clusters of vertices. However, this introduces discontinuities in the deformed skin between individual clusters",
        |s| -> anyhow::Result<_> {
            let rig = chasles_skin::cloth::cloth()?;
            let pose = chasles_skin::cloth::pose(&rig, 0.6);
            let mut t = chasles_paper::Table::new(
                "the largest kink ‖p(v−1) − 2p(v) + p(v+1)‖ along the cloth's grid lines (spacing 0.03)",
                &["method", "across a cluster border", "inside a cluster", "ratio"],
            );
            let mut kinks = Vec::new();
            for m in [Method::Lbs, Method::Dqs, Method::Sbs] {
                let out = chasles_skin::skin(&rig, &pose, m)?;
                let (seam, inside) = chasles_skin::cloth::seams(&rig, &out.positions);
                t.row(vec![
                    chasles_paper::Cell::text(m.name()),
                    chasles_paper::Cell::Number(chasles_paper::Number::fixed(seam, 4)),
                    chasles_paper::Cell::Number(chasles_paper::Number::fixed(inside, 4)),
                    chasles_paper::Cell::Number(chasles_paper::Number::fixed(seam / inside, 2)),
                ]);
                kinks.push((m, seam, inside));
            }
            s.table(t);
            s.paper_figure(
                PaperFigure::new(Kavan2006, "1(c)", "A comparison of different rigid transformation blending algorithms applied in skinning shows that blending based on dual quaternions not only eliminates artifacts, but is also much easier to implement and more than twice as fast as previous methods."),
                "kavan-figure-1c.png",
                {
                    // The middle of the cloth: rest x in [1.1, 1.9], y in [0.5, 1.3].
                    let focus: Vec<usize> = (0..rig.mesh.positions.len())
                        .filter(|v| {
                            let p = rig.mesh.positions[*v];
                            (1.1..=1.9).contains(&p.x) && (0.5..=1.3).contains(&p.y)
                        })
                        .collect();
                    pictures::methods_facing(&rig, &pose, &[Method::Sbs, Method::Dqs], &focus, (420, 420)).map(|i| i.png())
                },
                "The middle of the cloth (6000 vertices, 49 joints) crumpled in its plane, a checkerboard of 3 × 3 grid cells drawn on it: SBS (left) breaks the lines along the borders of its vertex clusters, where the rotation centre jumps; DQS (right) bends them smoothly",
            );
            let get = |m: Method| kinks.iter().find(|k| k.0 == m).map_or((f64::NAN, f64::NAN), |k| (k.1, k.2));
            let ((sbs, sbs_in), (dqs, dqs_in)) = (get(Method::Sbs), get(Method::Dqs));
            Ok((
                format!("largest kink across a cluster border: SBS {sbs:.4} ({:.2}× its inside), DQS {dqs:.4} ({:.2}× its inside)", sbs / sbs_in, dqs / dqs_in),
                sbs > 1.5 * dqs && sbs > 1.5 * sbs_in && dqs < 1.1 * dqs_in,
            ))
        },
    );
    s
}

/// A character the tour skins: its file name (never a path), the clip to play, its credit.
struct Character {
    file: String,
    clip: String,
    credit: String,
    rig: Rig,
}

/// The characters: CesiumMan's walk and Fox's run, built in (`chasles-models`), then every
/// other `.glb`/`.gltf` in `$CHASLES_DATA` if that is set (first clip). A file there that
/// does not load is reported in the section and left out.
fn characters_of(s: &mut Section) -> anyhow::Result<Vec<Character>> {
    let mut out = Vec::new();
    for (m, clip) in [
        (chasles_models::CESIUM_MAN, ""),
        (chasles_models::FOX, "Run"),
    ] {
        out.push(Character {
            file: m.file.into(),
            clip: clip.into(),
            credit: m.credit.into(),
            rig: gltf_load::load_slice(m.bytes, m.file)?,
        });
    }
    let Some(dir) = std::env::var_os("CHASLES_DATA") else {
        return Ok(out);
    };
    let entries = match std::fs::read_dir(&dir) {
        Ok(e) => e,
        Err(e) => {
            // The built-in characters stay; the extra folder is reported.
            s.text(format!(
                "($CHASLES_DATA={} cannot be read, no extra characters: {e})",
                dir.to_string_lossy()
            ));
            return Ok(out);
        }
    };
    let mut files: Vec<std::path::PathBuf> = entries
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| {
            matches!(
                p.extension().and_then(|e| e.to_str()),
                Some("glb") | Some("gltf")
            )
        })
        .collect();
    files.sort();
    for path in files {
        let file = path
            .file_name()
            .map(|f| f.to_string_lossy().into_owned())
            .unwrap_or_default();
        if out.iter().any(|c| c.file == file) {
            continue;
        }
        match gltf_load::load(&path) {
            Ok(rig) if !rig.animations.is_empty() => out.push(Character {
                credit: format!("{file} from $CHASLES_DATA (its own licence applies)"),
                file,
                clip: String::new(),
                rig,
            }),
            Ok(_) => s.text(format!("($CHASLES_DATA/{file} has no animation: left out)")),
            Err(e) => s.text(format!(
                "($CHASLES_DATA/{file} does not load, left out: {e})"
            )),
        }
    }
    Ok(out)
}

/// Where linear blending loses volume on each character, and its pictures.
pub fn characters() -> Section {
    let mut s = Section::new("Kavan et al. §6 on real characters: where linear blending loses volume (smallest det of the blended 3×3 over the clip)");
    let words = "linear blending of joint matrices shrinks the mesh where joints turn apart; DQS blends only rigid motions";
    let list = match characters_of(&mut s) {
        Ok(l) => l,
        Err(e) => {
            s.claim(chasles_paper::Claim::check(Kavan2006, "§6", words, Err(e)));
            return s;
        }
    };
    for ch in list {
        let (file, credit, rig) = (&ch.file, &ch.credit, &ch.rig);
        let c = rig
            .animations
            .iter()
            .position(|a| a.name == ch.clip)
            .unwrap_or(0);
        let mut worst_t = None;
        s.attempt(Kavan2006, "§6", words, |s| -> anyhow::Result<_> {
            let over = chasles_skin::volume::lbs_volume_over_clip(rig, c, 40)?;
            let (t, worst) = over
                .iter()
                .copied()
                .fold((0.0, f32::INFINITY), |a, b| if b.1 < a.1 { b } else { a });
            s.text(format!(
                "{file} ({} vertices, {} joints): LBS down to {worst:.2} of the local volume; DQS keeps 1 (rigid blends). Credit: {credit}",
                rig.mesh.positions.len(),
                rig.joints.len()
            ));
            worst_t = Some((t, worst));
            Ok((
                format!("{file}: smallest det of LBS's blended 3×3 over the clip {worst:.2} (DQS: 1)"),
                worst < 0.95,
            ))
        });
        let name = file
            .rsplit_once('.')
            .map_or(file.as_str(), |(s, _)| s)
            .to_lowercase();
        s.try_figure(
            &format!("{name}-volume.svg"),
            pictures::volume_plot(rig, c).map(String::into_bytes),
            &format!("{file}: LBS's smallest local volume at 41 times of its clip; rigid blends keep 1. Credit: {credit}"),
        );
        match pictures::rotation_sphere(rig, c) {
            Ok((sphere, joint)) => s.figure(
                &format!("{name}-sphere.png"),
                sphere.png(),
                &format!("{file}: the rotation of {joint}, the joint that turns most in the clip, on the unit sphere (§5.3's plot on real data): its keys and the sampled curve. Credit: {credit}"),
            ),
            Err(e) => s.text(format!("picture {name}-sphere.png failed: {e}")),
        }
        s.try_figure(
            &format!("{name}-viewer.html"),
            chasles_view::character(rig, Some(&c.to_string()), chasles_view::DEFAULT_FPS, credit)
                .map(|p| p.html.into_bytes()),
            &format!("{file} in the browser (one self-contained page, WebGL2): LBS and DQS side by side under one camera, the clip to play or scrub (its button jumps to where LBS loses the most volume), the heat map of LBS's lost volume, orbit, pan and zoom. Credit: {credit}"),
        );
        let Some((t, worst)) = worst_t else { continue };
        let pose = match Pose::animated(rig, c, t) {
            Ok(p) => p,
            Err(e) => {
                s.text(format!(
                    "pictures {name}.png and {name}-closeup.png failed: {e}"
                ));
                continue;
            }
        };
        s.try_figure(
            &format!("{name}.png"),
            pictures::methods_side_by_side(rig, &pose, &Method::ALL).map(|i| i.png()),
            &format!("{file} at t = {t:.2} s of its clip, where LBS loses the most volume, skinned by every method. Credit: {credit}"),
        );
        s.try_figure(
            &format!("{name}-closeup.png"),
            pictures::methods_closeup(rig, &pose, &Method::ALL).map(|i| i.png()),
            &format!("{file}, the same pose, close up around the vertex where LBS keeps the least volume ({worst:.2}): LBS pinches, the rigid blends keep the limb's thickness"),
        );
    }
    s
}
