//! `chasles skin`: skin a rigged glTF mesh with any method (Kavan et al. 2006, §6), one pose
//! or a whole clip, and the candy-wrapper table (`--artifacts`).

use crate::choice::SkinMethod;
use crate::output::{check_frames_dir, extension, write_frames_dir, Pending};
use crate::picture_args::Pictures;
use crate::picture_args::MAX_GIF_FRAMES;
use crate::pictures;
use anyhow::{anyhow, bail, Context, Result};
use chasles_skin::cylinder::{self, Motion};
use chasles_skin::{json_rig, peers, writers, Method, Pose, Rig, Skinned};
use std::path::{Path, PathBuf};

/// Options of `chasles skin`.
#[derive(Debug, clap::Args)]
pub struct SkinArgs {
    /// The rig: .gltf, .glb, or .json (the plain format of chasles_skin::json_rig).
    #[arg(long)]
    pub rig: Option<PathBuf>,
    /// The clip, by name or index (default: the first, when --time or --all-frames is given).
    #[arg(long)]
    pub anim: Option<String>,
    /// Time in the clip, seconds (default 0; without --anim and --time: the rest pose).
    #[arg(long, allow_negative_numbers = true)]
    pub time: Option<f32>,
    /// A JSON pose, {"joints": {name or index: {rotation, translation, scale}}}, instead of a clip.
    #[arg(long)]
    pub pose: Option<PathBuf>,
    /// The skinning method.
    #[arg(long, value_enum, default_value = "dqs")]
    pub method: SkinMethod,
    /// Output .obj, .ply, .glb or .json; with --all-frames, a folder for frame_NNNNN.obj files.
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// Skin every frame of the clip.
    #[arg(long)]
    pub all_frames: bool,
    /// Frames per second for --all-frames.
    #[arg(long, default_value_t = 30.0)]
    pub fps: f32,
    /// The most frames --all-frames writes or --gif draws (a ceiling against a clip that
    /// lasts a week; raise it for long clips).
    #[arg(long, default_value_t = 10_000)]
    pub max_frames: usize,
    /// Print the candy-wrapper table (twist and bend of a two-bone cylinder, every method).
    #[arg(long)]
    pub artifacts: bool,
    /// Measure every method on synthetic meshes of 10^5 and 10^6 vertices beside the glam
    /// and nalgebra baselines, a copy of the bytes moved and the fast paths' loads and
    /// stores alone (the two bounds; interleaved rounds); with
    /// --rig, on that rig in the pose asked for (--pose, --anim/--time; by default the
    /// first clip half-way through, or the rest pose where there is none).
    #[arg(long)]
    pub bench: bool,
    /// --bench: the synthetic mesh sizes, e.g. 100000,4000000 (each at most 10^8; default
    /// 100000,1000000; not with --rig).
    #[arg(long, value_delimiter = ',', value_name = "N,N,…")]
    pub bench_vertices: Option<Vec<usize>>,
    /// --bench: how the synthetic meshes' joints turn: near (within 60° of the identity, as
    /// in skinning; the default) or uniform (over all rotations: far-apart joints, random
    /// antipodality signs, DIB's longest iteration); not with --rig.
    #[arg(long, value_enum, value_name = "KIND")]
    pub bench_rotations: Option<BenchRotations>,
    /// --bench: timed rounds per table (default 21, or 7 for meshes over 2·10^5 vertices;
    /// at most 10000).
    #[arg(long, value_name = "N")]
    pub bench_rounds: Option<usize>,
    /// --bench: the thread counts, e.g. 1,2,4,all (the scaling curve; each at most 1024;
    /// default 1,all).
    #[arg(long, value_delimiter = ',', value_name = "N,N,…", value_parser = threads)]
    pub bench_threads: Option<Vec<usize>>,
    #[command(flatten)]
    pub pictures: Pictures,
    /// Where to skin: cpu, gpu (any adapter, lavapipe included) or auto (a hardware GPU for lbs/dqs/dib when there is one).
    #[arg(long, value_enum, default_value_t = crate::device::Device::Auto)]
    pub device: crate::device::Device,
}

fn clip(rig: &Rig, anim: &Option<String>) -> Result<usize> {
    let Some(a) = anim else {
        if rig.animations.is_empty() {
            bail!("{}: has no animations", rig.name);
        }
        return Ok(0);
    };
    if let Some(i) = rig.animations.iter().position(|x| &x.name == a) {
        return Ok(i);
    }
    match a.parse::<usize>() {
        Ok(i) if i < rig.animations.len() => Ok(i),
        _ => {
            let names: Vec<String> = rig
                .animations
                .iter()
                .enumerate()
                .map(|(i, x)| {
                    if x.name.is_empty() {
                        i.to_string()
                    } else {
                        format!("{} ({i})", x.name)
                    }
                })
                .collect();
            bail!(
                "{}: no animation '{a}'; there are: {}",
                rig.name,
                names.join(", ")
            )
        }
    }
}

fn encode(rig: &Rig, s: &Skinned, path: &Path, comment: &str) -> Result<Vec<u8>> {
    Ok(match extension(path).as_str() {
        "obj" => writers::obj(&rig.mesh, s, comment).into_bytes(),
        "ply" => writers::ply(&rig.mesh, s, comment).into_bytes(),
        "glb" => writers::glb(&rig.mesh, s, comment),
        "json" => serde_json::json!({
            "comment": comment,
            "positions": s.positions.iter().map(|p| p.to_array()).collect::<Vec<_>>(),
            "normals": s.normals.iter().map(|p| p.to_array()).collect::<Vec<_>>(),
            "triangles": rig.mesh.triangles,
        })
        .to_string()
        .into_bytes(),
        other => bail!("--out must end in .obj, .ply, .glb or .json (got '.{other}')"),
    })
}

/// The candy-wrapper table as Markdown.
pub fn artifacts_table() -> Result<String> {
    let rig = cylinder::twisted_cylinder();
    let mut out = String::from(
        "Twisted cylinder (two bones, smooth weights across the joint), relative to rest:\n\
         r = mean radius of the middle cross-section, V = volume, b = largest distance from the bones (bulge)\n\n",
    );
    for (motion, angles, what) in [
        (Motion::Twist, [0, 45, 90, 135, 180], "twist"),
        (Motion::Bend, [0, 30, 60, 90, 120], "bend"),
    ] {
        let mut angles = angles.to_vec();
        if motion == Motion::Bend {
            angles.push(150);
        }
        out.push_str(&format!("| {what} |"));
        for m in Method::ALL {
            out.push_str(&format!(" {} r | V | b |", m.name()));
        }
        out.push_str("\n|---|");
        out.push_str(&"---|---|---|".repeat(Method::ALL.len()));
        out.push('\n');
        for a in angles {
            out.push_str(&format!("| {a}° |"));
            for m in Method::ALL {
                let r = cylinder::measure(&rig, m, motion, (a as f32).to_radians())?;
                out.push_str(&format!(
                    " {:.3} | {:.3} | {:.3} |",
                    r.radius, r.volume, r.bulge
                ));
            }
            out.push('\n');
        }
        out.push('\n');
    }
    Ok(out)
}

/// Median seconds of `f` over `runs` runs after one warm-up.
pub(crate) fn median_secs(runs: usize, mut f: impl FnMut() -> Result<()>) -> Result<f64> {
    f()?;
    let mut t = Vec::with_capacity(runs);
    for _ in 0..runs {
        let start = std::time::Instant::now();
        f()?;
        t.push(start.elapsed().as_secs_f64());
    }
    t.sort_by(f64::total_cmp);
    Ok(t[runs / 2])
}

/// A thread count of `--bench-threads`: a number from 1 to 1024, or `all` (rayon's count:
/// the machine's, or `RAYON_NUM_THREADS`).
fn threads(s: &str) -> std::result::Result<usize, String> {
    if s == "all" {
        return Ok(rayon::current_num_threads());
    }
    match s.parse::<usize>() {
        Ok(n) if (1..=1024).contains(&n) => Ok(n),
        _ => Err(format!("{s} is not a thread count from 1 to 1024 or all")),
    }
}

/// `--bench-rotations`: how the synthetic meshes' joints turn ([`peers::Rotations`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum BenchRotations {
    /// Within 60° of the identity.
    Near,
    /// Uniform over all rotations.
    Uniform,
}

/// What `chasles skin --bench` measures: synthetic meshes of some sizes, or a rig of one's
/// own in one pose (described in words).
pub enum BenchMesh<'a> {
    /// [`chasles_skin::peers::measure_posed`]'s meshes of these vertex counts, their joints
    /// turned so.
    Synthetic(&'a [usize], peers::Rotations),
    /// A rig, its joint transforms and words for the pose.
    Rig(&'a Rig, chasles_skin::JointTransforms, String),
}

/// Each timed sample of a rig skins it this many vertices' worth or more (repeating it).
const RIG_SAMPLE_VERTICES: usize = 100_000;

/// `chasles skin --bench`: on `mesh` (synthetic meshes, 54 joints, 4 influences; or a rig),
/// on each of `threads`, every method's fast path (the pose's joint data made in each run)
/// beside the careful glam and nalgebra baselines of [`chasles_skin::peers`] and a memory
/// copy of the bytes each vertex moves (the bandwidth bound: 72 with four influences, 96
/// with eight) and the fast paths' loads and stores alone ([`chasles_skin::fast::traffic`]:
/// the bound of their own traffic, 48 bytes read a vertex, 72 with eight influences, and 24
/// written), timed in `rounds` interleaved rounds ([`chasles_skin::peers::measure_posed`],
/// [`chasles_skin::peers::measure_rig`]; by default 21, 7 above 2·10⁵ vertices; the caller
/// checks the range): the median rate of each with its spread, our
/// speed over each baseline's (LBS over the LBS baselines, DQS over the DQS ones) and each
/// kernel's share of each bound, all taken round by round. A run during which other
/// processes (or the host of a virtual machine) kept more than a quarter of the CPUs busy is
/// flagged.
pub fn bench(mesh: &BenchMesh, threads: &[usize], rounds: Option<usize>) -> Result<()> {
    let rounds_for = |n: usize| rounds.unwrap_or(if n <= 200_000 { 21 } else { 7 });
    let load = peers::Load::start();
    let mut tables = Vec::new();
    if let BenchMesh::Synthetic(sizes, _) = mesh {
        if let Some(n) = sizes.iter().find(|n| **n == 0 || **n > 100_000_000) {
            bail!("--bench-vertices: {n} is not between 1 and 10^8");
        }
    }
    // On a terminal, which table is being timed (hidden when stderr is not one; cleared
    // when done or on an error).
    let count = match mesh {
        BenchMesh::Synthetic(sizes, _) => sizes.len(),
        BenchMesh::Rig(..) => 1,
    } * threads.len();
    let bar =
        indicatif::ProgressBar::new(count as u64).with_finish(indicatif::ProgressFinish::AndClear);
    bar.set_style(
        indicatif::ProgressStyle::with_template("timing {msg} [{bar:20}] {pos}/{len} tables")
            .unwrap_or_else(|_| indicatif::ProgressStyle::default_bar()),
    );
    let progress = |n: usize, t: usize| bar.set_message(format!("{n} vertices on {t} thread(s)"));
    match mesh {
        BenchMesh::Synthetic(sizes, rotations) => {
            for &n in *sizes {
                for &t in threads {
                    progress(n, t);
                    tables.push(peers::measure_posed(n, t, rounds_for(n), *rotations)?);
                    bar.inc(1);
                }
            }
        }
        BenchMesh::Rig(rig, jt, _) => {
            let n = rig.mesh.positions.len();
            for &t in threads {
                progress(n, t);
                tables.push(peers::measure_rig(
                    rig,
                    jt,
                    t,
                    rounds_for(n),
                    RIG_SAMPLE_VERTICES,
                )?);
                bar.inc(1);
            }
        }
    }
    bar.finish_and_clear();
    // After the timing, so that an error (an empty rig) comes alone.
    if let BenchMesh::Rig(rig, _, when) = mesh {
        println!(
            "{}: {} vertices, {} joints, at most {} influences a vertex, in {when}; each sample skins it {} times",
            rig.name,
            rig.mesh.positions.len(),
            rig.joints.len(),
            rig.influences.max_per_vertex(),
            tables.first().map_or(0, |t| t.repeats),
        );
    }
    println!("{}", peers::markdown(&tables));
    println!("{}", kernels_used());
    for t in &tables {
        let r = |name: &str| t.rate(name).unwrap_or(f64::NAN);
        let dqs = r("dqs");
        let centres = if t.synthetic {
            format!(
                "SBS solved {} rotation centres a pose here, real rigs far fewer",
                t.centres
            )
        } else {
            format!("SBS solved {} rotation centres a pose", t.centres)
        };
        println!(
            "{} vertices, {} thread(s): DQS costs {:.2}× LBS; DQS is {:.1}× Log, {:.1}× SBS and {:.1}× DIB (Figure 1: 2.3× and 2.2× for Log and SBS; {centres})",
            t.vertices,
            t.threads,
            r("lbs") / dqs,
            dqs / r("log"),
            dqs / r("sbs"),
            dqs / r("dib"),
        );
    }
    for t in tables
        .iter()
        .filter(|t| t.rate(peers::UNGROUPED_DIB).is_some())
    {
        let r = |name: &str| t.rate(name).unwrap_or(f64::NAN);
        let (v, threads) = (t.vertices, t.threads);
        if t.dib_grouped {
            println!(
                "{v} vertices, {threads} thread(s): DIB ran on the vertices grouped by influence count (the fast path's own choice on this rig), {:.2}× as fast as in the rig's order; in that order DQS is {:.1}× DIB",
                r("dib") / r(peers::UNGROUPED_DIB),
                r("dqs") / r(peers::UNGROUPED_DIB),
            );
        } else {
            println!(
                "{v} vertices, {threads} thread(s): DIB ran in the rig's order (grouping its vertices by influence count would gain little here, or the SIMD kernels do not run)"
            );
        }
    }
    for note in peers::cache_notes(&tables, peers::last_level_cache()) {
        println!("{note}");
    }
    if let Some(others) = load.others() {
        println!(
            "other processes kept {:.0}% of the CPUs busy during the run",
            others * 100.0
        );
        if others > 0.25 {
            println!("warning: that is more than a quarter: these figures are not to be trusted; run again on a quieter machine");
        }
    }
    Ok(())
}

/// Which kernels the fast paths ran here, for the bench's reader: the eight-vertex AVX2+FMA
/// ones (built with AVX-512's 32 registers where it runs) and DIB's sixteen-vertex AVX-512F
/// one where it runs, or the portable scalar ones.
fn kernels_used() -> &'static str {
    use chasles_skin::fast::{uses_avx512, uses_simd};
    match (uses_simd(4), uses_avx512(4)) {
        (true, true) => "the fast paths ran their AVX2+FMA kernels, eight vertices at a time, built with AVX-512F and VL's 32 registers, and DIB its AVX-512F kernel, sixteen at a time",
        (true, false) => "the fast paths ran their AVX2+FMA kernels, eight vertices at a time (no AVX-512F and VL here for the 32-register builds and DIB's sixteen-vertex kernel)",
        _ => "the fast paths ran their portable scalar kernels (no AVX2+FMA here)",
    }
}

/// `chasles skin --bench`'s mesh and pose from the arguments, then [`bench`].
fn bench_args(a: &SkinArgs) -> Result<()> {
    if let Some(r) = a.bench_rounds.filter(|r| !(1..=10_000).contains(r)) {
        bail!("--bench-rounds: {r} is not between 1 and 10000");
    }
    let all = [1, rayon::current_num_threads()];
    let threads = a.bench_threads.as_deref().unwrap_or(&all);
    let Some(path) = &a.rig else {
        let sizes = a.bench_vertices.as_deref().unwrap_or(&[100_000, 1_000_000]);
        let rotations = match a.bench_rotations {
            Some(BenchRotations::Uniform) => peers::Rotations::Uniform,
            Some(BenchRotations::Near) | None => peers::Rotations::Near,
        };
        return bench(
            &BenchMesh::Synthetic(sizes, rotations),
            threads,
            a.bench_rounds,
        );
    };
    if a.bench_vertices.is_some() {
        bail!("--bench-vertices sizes the synthetic meshes: not with --rig");
    }
    if a.bench_rotations.is_some() {
        bail!("--bench-rotations turns the synthetic meshes' joints: not with --rig");
    }
    let rig = chasles_skin::load(path)?;
    let (pose, when) = if a.pose.is_none() && a.anim.is_none() && a.time.is_none() {
        match rig.animations.first() {
            Some(clip) => {
                let t = clip.duration() / 2.0;
                (
                    Pose::animated(&rig, 0, t)?,
                    format!("animation 0 at t = {t} s"),
                )
            }
            None => (Pose::rest(&rig), "the rest pose".to_string()),
        }
    } else {
        chosen_pose(&rig, a)?
    };
    let jt = chasles_skin::joint_transforms(&rig, &pose)?;
    bench(&BenchMesh::Rig(&rig, jt, when), threads, a.bench_rounds)
}

/// `chasles skin --bench --device gpu`: the GPU's own table (synthetic meshes of 10^5 to
/// 10^7 vertices, the shader's clock), which takes none of the CPU table's options.
fn bench_gpu_args(a: &SkinArgs) -> Result<()> {
    let given = [
        ("--rig", a.rig.is_some()),
        ("--bench-vertices", a.bench_vertices.is_some()),
        ("--bench-rounds", a.bench_rounds.is_some()),
        ("--bench-threads", a.bench_threads.is_some()),
        ("--bench-rotations", a.bench_rotations.is_some()),
    ];
    if let Some((flag, _)) = given.iter().find(|(_, g)| *g) {
        bail!("{flag} is for the CPU's table: --bench --device gpu times synthetic meshes of 10^5 to 10^7 vertices only");
    }
    crate::device::bench_gpu()
}

/// Writes `pending` all or none and says so on stdout.
fn write_pending(pending: &Pending) -> Result<()> {
    for line in pending.write()? {
        println!("{line}");
    }
    Ok(())
}

/// Runs `chasles skin`: every picture and output is made and checked before any file is
/// written; `--all-frames` removes the frames it wrote when a later one fails.
pub fn run(a: SkinArgs) -> Result<()> {
    if a.bench {
        return match a.device {
            crate::device::Device::Gpu => bench_gpu_args(&a),
            _ => bench_args(&a),
        };
    }
    a.pictures.check(&["svg"])?;
    let mut pending = Pending::default();
    if a.artifacts {
        let table = artifacts_table()?;
        let rig = cylinder::twisted_cylinder();
        if let Some(p) = &a.pictures.render {
            let pose = cylinder::pose(&rig, Motion::Twist, std::f32::consts::PI);
            let img = pictures::methods_side_by_side(&rig, &pose, &Method::ALL)?;
            pending.add(
                p,
                img.png(),
                Some("the cylinder twisted 180°, every method".into()),
            );
        }
        if let Some(p) = &a.pictures.gif {
            let frames = pictures::twist_sweep(25)?;
            let gif = chasles_viz::gif(&frames, 6)?;
            pending.add(p, gif, Some("twist 0°→180°→0°, LBS beside DQS".into()));
        }
        if let Some(p) = &a.pictures.plot {
            let svg = pictures::twist_plot()?.into_bytes();
            pending.add(
                p,
                svg,
                Some("middle radius against twist, every method".into()),
            );
        }
        write_pending(&pending)?;
        print!("{table}");
        return Ok(());
    }
    let m = a.method.0;
    let rig_path = a
        .rig
        .as_ref()
        .ok_or_else(|| anyhow!("--rig FILE is required (or --artifacts)"))?;
    let rig = chasles_skin::load(rig_path)?;
    if let Some(p) = &a.pictures.plot {
        let c = clip(&rig, &a.anim)?;
        let svg = pictures::volume_plot(&rig, c)?.into_bytes();
        pending.add(
            p,
            svg,
            Some("LBS's smallest local volume over the clip".into()),
        );
    }
    if let Some(p) = &a.pictures.sphere {
        let c = clip(&rig, &a.anim)?;
        let (img, joint) = pictures::rotation_sphere(&rig, c)?;
        pending.add(
            p,
            img.png(),
            Some(format!("the rotation of {joint} over the clip")),
        );
    }
    if let Some(p) = &a.pictures.gif {
        if a.all_frames || a.pose.is_some() || a.time.is_some() {
            bail!("--gif plays a whole clip: give --anim (or none for the first), not --pose, --time or --all-frames");
        }
        if !(a.fps > 0.0 && a.fps <= 50.0) {
            bail!("--gif needs --fps in (0, 50], got {}", a.fps);
        }
        let c = clip(&rig, &a.anim)?;
        let n = frame_count(&rig, c, a.fps, a.max_frames.min(MAX_GIF_FRAMES), "--gif")?;
        let frames = pictures::clip_frames(&rig, c, a.fps, n)?;
        let gif = chasles_viz::gif(&frames, (100.0 / a.fps).round() as u16)?;
        pending.add(
            p,
            gif,
            Some(format!("{} frames, LBS beside DQS", frames.len())),
        );
    }
    let pictures_only =
        a.pictures.plot.is_some() || a.pictures.sphere.is_some() || a.pictures.gif.is_some();
    if a.out.is_none() && !a.all_frames {
        if let Some(p) = &a.pictures.render {
            let pose = chosen_pose(&rig, &a)?.0;
            let img = pictures::methods_side_by_side(&rig, &pose, &Method::ALL)?;
            pending.add(p, img.png(), Some("every method side by side".into()));
            return write_pending(&pending);
        }
        if pictures_only {
            return write_pending(&pending);
        }
    }
    let out = a
        .out
        .as_ref()
        .ok_or_else(|| anyhow!("--out is required (or --render/--gif)"))?;
    if a.all_frames && a.pictures.render.is_some() {
        bail!("--render draws one pose (--pose, --anim/--time or the rest pose), not --all-frames");
    }
    if a.all_frames {
        if !(a.fps > 0.0 && a.fps.is_finite() && a.fps <= 1000.0) {
            bail!("--fps must be in (0, 1000], got {}", a.fps);
        }
        let c = clip(&rig, &a.anim)?;
        let duration = rig.animations[c].duration();
        let frames = frame_count(&rig, c, a.fps, a.max_frames, "--all-frames")?;
        check_frames_dir("--all-frames --out", out)?;
        all_frames(&rig, &a, c, frames, out, || write_pending(&pending))?;
        println!(
            "wrote {frames} frames of {:.3} s at {} fps to {}",
            duration,
            a.fps,
            out.display()
        );
        return Ok(());
    }
    let (pose, when) = chosen_pose(&rig, &a)?;
    if let Some(p) = &a.pictures.render {
        let img = pictures::methods_side_by_side(&rig, &pose, &Method::ALL)?;
        pending.add(p, img.png(), Some("every method side by side".into()));
    }
    let engine = crate::device::Engine::new(a.device, &rig, m)?;
    let s = engine.skin(&rig, &pose, m)?;
    let comment = format!("{} skinned with {} in {when}", rig.name, m.name());
    pending.add(out, encode(&rig, &s, out, &comment)?, None);
    write_pending(&pending)?;
    println!(
        "{}: {} vertices, {} joints, skinned with {} in {when} on {}; wrote {}",
        rig.name,
        rig.mesh.positions.len(),
        rig.joints.len(),
        m.name(),
        engine.describe(),
        out.display()
    );
    Ok(())
}

/// Skins `frames` frames of clip `c` into the folder `out`, one OBJ each, all or nothing
/// ([`write_frames_dir`]: a hidden folder renamed onto `out` at the end, removed on a
/// failure or Ctrl-C), `then` (the other outputs) written before the rename.
fn all_frames(
    rig: &Rig,
    a: &SkinArgs,
    c: usize,
    frames: usize,
    out: &Path,
    then: impl FnOnce() -> Result<()>,
) -> Result<()> {
    let m = a.method.0;
    let engine = crate::device::Engine::new(a.device, rig, m)?;
    let frame = |f: usize| {
        let t = f as f32 / a.fps;
        let s = engine
            .skin(rig, &Pose::animated(rig, c, t)?, m)
            .with_context(|| format!("frame {f} of {frames}"))?;
        let name = format!("frame_{f:05}.obj");
        let comment = format!("{} skinned with {} at t = {t} s", rig.name, m.name());
        Ok((name.clone(), encode(rig, &s, Path::new(&name), &comment)?))
    };
    write_frames_dir(out, frames, "skinning", frame, then)
}

/// The frames of clip `c` at `fps` (`duration · fps` + 1), checked against `max` (the
/// ceiling of `flag`) before anything is made: a clip whose last key is at 1e7 s is an
/// error, not a week of writing.
fn frame_count(rig: &Rig, c: usize, fps: f32, max: usize, flag: &str) -> Result<usize> {
    let duration = rig.animations[c].duration();
    let n = (f64::from(duration) * f64::from(fps)).floor() + 1.0;
    if !n.is_finite() || n > max as f64 {
        bail!(
            "{flag}: clip {c} lasts {duration} s, {n} frames at {fps} fps: more than --max-frames {max}"
        );
    }
    Ok(n as usize)
}

/// The pose asked for: `--pose FILE`, `--anim/--time`, or the rest pose; and words for it.
fn chosen_pose(rig: &Rig, a: &SkinArgs) -> Result<(Pose, String)> {
    if a.pose.is_some() && (a.anim.is_some() || a.time.is_some()) {
        bail!("give either --pose or --anim/--time, not both");
    }
    Ok(match (&a.anim, a.time) {
        _ if a.pose.is_some() => {
            let p = a.pose.as_ref().unwrap_or_else(|| unreachable!());
            let text = chasles_skin::bounded::read_text(p, chasles_skin::bounded::MAX_TEXT_BYTES)
                .with_context(|| format!("cannot read {}", p.display()))?;
            (
                json_rig::parse_pose(&text, rig, &p.display().to_string())?,
                format!("the pose of {}", p.display()),
            )
        }
        (None, None) => (Pose::rest(rig), "the rest pose".to_string()),
        (anim, t) => {
            let c = clip(rig, anim)?;
            let t = t.unwrap_or(0.0);
            (
                Pose::animated(rig, c, t)?,
                format!("animation {c} at t = {t} s"),
            )
        }
    })
}
