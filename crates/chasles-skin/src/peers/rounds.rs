//! Every fast path beside the baselines of [`super::BASELINES`] and two bounds, timed in
//! interleaved rounds: each round runs every kernel once, so a slow spell of a shared
//! machine hits all of them alike, and every ratio is taken within a round (a baseline's
//! time over our kernel's of the same method, a bound's time over a kernel's) before the
//! median is taken over the rounds, on a synthetic mesh or a rig of one's own. The two
//! bounds: the copy of the bytes a vertex moves, half read and half written
//! ([`copy_bound`]), and the fast paths' own loads and stores without their arithmetic
//! ([`crate::fast::traffic`]: each vertex read whole, its six floats written by the
//! kernels' stores), which read 48 bytes a vertex (72 with eight influences) and write 24.
//! The one measurement behind `chasles skin --bench` (with `--rig`: [`measure_rig`]) and
//! the criterion bench's closing table (Kavan et al. 2006, §6: what skinning costs).
//!
//! Each round runs the kernels in an order of its own ([`order`]). Every kernel but the copy
//! reads the same mesh, so on a machine whose last-level cache holds much of it, the kernel
//! that follows the copy starts colder than the rest. In a fixed order that was always the
//! traffic bound: on a 2-core Intel Xeon reporting 480 MiB of L3 (2026-12-04) it ran at
//! 233 M vertices/s at 10⁶ vertices on one thread, below the DQS (255) whose loads and
//! stores it is, where a loop that ran it after LBS gave 380–395. Shuffled, a kernel
//! follows the copy in about one round in as many as there are other kernels (12 in the
//! synthetic table, 13 on a rig of up to four influences, 8 on one of more: a rig's table
//! also times DIB with its grouping turned off), which the medians leave out.

use super::{copy_bound, run, Joints, BASELINES};
use crate::error::Result;
use crate::fast::{skin_pose, traffic, FastRig, Out, Vertex};
use crate::{synthetic, JointTransforms, Method, Rig};
use std::time::Instant;

/// The traffic bound's row name ([`crate::fast::traffic`]).
pub const TRAFFIC: &str = "traffic: loads and stores alone";

/// [`Table::mesh`] of [`measure`]'s synthetic meshes.
pub const SYNTHETIC: &str = "synthetic";

/// [`Table::mesh`] of the synthetic meshes posed with uniform rotations
/// ([`measure_posed`], [`Rotations::Uniform`]).
pub const SYNTHETIC_UNIFORM: &str = "synthetic, uniform rotations";

/// How a synthetic mesh's joints are turned.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Rotations {
    /// Within 60° of the identity, as in skinning ([`synthetic::joints`]): every joint's
    /// quaternion in one hemisphere, so no antipodality sign ever flips, and most of DIB's
    /// blocks converge in one update (two passes; a few take a second).
    #[default]
    Near,
    /// Uniform over all rotations ([`synthetic::uniform_joints`]): the signs flip at random
    /// (a baseline's branch on them mispredicts) and DIB's iteration takes its most
    /// updates.
    Uniform,
}

/// A median over rounds with the lowest and highest value.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Spread {
    /// The median.
    pub median: f64,
    /// The lowest value.
    pub lo: f64,
    /// The highest value.
    pub hi: f64,
}

impl Spread {
    /// The median, lowest and highest of `x` (not empty; NaN sorts last).
    pub fn of(mut x: Vec<f64>) -> Spread {
        x.sort_by(f64::total_cmp);
        Spread {
            median: x[x.len() / 2],
            lo: x[0],
            hi: x[x.len() - 1],
        }
    }
}

/// What a timed kernel is.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Role {
    /// One of our fast paths.
    Ours(Method),
    /// A baseline of [`BASELINES`], compared with our kernel of this method.
    Baseline(Method),
    /// The copy of the bytes a vertex moves ([`copy_bound`]: 72 with four influences, 96
    /// with eight).
    Bound,
    /// The fast paths' loads and stores alone ([`crate::fast::traffic`]).
    Traffic,
    /// One of our fast paths with DIB's grouping of the vertices by influence count turned
    /// off ([`FastRig::without_dib_grouping`]; [`measure_rig`] times DIB so:
    /// [`UNGROUPED_DIB`]).
    Ungrouped(Method),
}

/// The row name of DIB in the rig's vertex order, its grouping turned off ([`measure_rig`]).
pub const UNGROUPED_DIB: &str = "dib, in the rig's order (not grouped)";

/// One kernel's figures over the rounds.
#[derive(Debug, Clone)]
pub struct Row {
    /// Its name (a method's, a baseline's, the copy's, the traffic's, or [`UNGROUPED_DIB`]).
    pub name: String,
    /// What it is.
    pub role: Role,
    /// Vertices per second.
    pub rate: Spread,
    /// For a baseline: our kernel's speed over its, round by round.
    pub ours_over: Option<Spread>,
    /// Its speed over the copy's (the share of the bandwidth bound), round by round.
    pub share: Spread,
    /// Its speed over the traffic kernel's (the share of what the memory gives the fast
    /// paths' loads and stores), round by round.
    pub traffic_share: Spread,
}

/// The figures of one mesh on one or on all threads.
#[derive(Debug, Clone)]
pub struct Table {
    /// The mesh: [`SYNTHETIC`] ([`measure`]), [`SYNTHETIC_UNIFORM`] ([`measure_posed`]) or
    /// the rig's name ([`measure_rig`]).
    pub mesh: String,
    /// Whether the mesh is a synthetic one ([`measure`], [`measure_posed`]), not a rig.
    pub synthetic: bool,
    /// Vertices in the mesh.
    pub vertices: usize,
    /// Threads (1, or rayon's count).
    pub threads: usize,
    /// Rotation centres SBS solved a pose (one per vertex cluster).
    pub centres: usize,
    /// Timed rounds.
    pub rounds: usize,
    /// How many times each timed sample skins the mesh.
    pub repeats: usize,
    /// The bytes a skinned vertex moves (its vertex read, its position and normal written:
    /// 72 with four influences, 96 with eight), the copy's.
    pub moved: usize,
    /// Whether DIB's fast path ran on the vertices grouped by influence count
    /// ([`FastRig::groups_dib`]: the SIMD kernels run and grouping gains on this mesh).
    pub dib_grouped: bool,
    /// Every kernel: our methods (on a rig, DIB also ungrouped), the baselines, the copy, the
    /// traffic.
    pub rows: Vec<Row>,
}

impl Table {
    /// Whether the mesh's bytes (its vertices read, its output written: [`Table::moved`] a
    /// vertex) fit in a cache of `cache` bytes: then its rows time that cache, not memory.
    pub fn fits_in(&self, cache: u64) -> bool {
        self.vertices as u64 * self.moved as u64 <= cache
    }

    /// The median rate of the kernel named `name`.
    pub fn rate(&self, name: &str) -> Option<f64> {
        self.rows
            .iter()
            .find(|r| r.name == name)
            .map(|r| r.rate.median)
    }
}

/// Times every method's fast path (the pose's joint data made in each run, as
/// [`skin_pose`] does), every baseline and both bounds on a synthetic mesh of `n` vertices
/// (54 joints, 4 random influences, [`synthetic::rig`]) in `rounds` interleaved rounds after
/// one untimed one, on `threads` threads (1: the caller's; more: a rayon pool of that many,
/// the fast paths' chunks spread over it). The random joints make nearly every vertex its
/// own SBS cluster: SBS's worst case.
pub fn measure(n: usize, threads: usize, rounds: usize) -> Result<Table> {
    measure_posed(n, threads, rounds, Rotations::Near)
}

/// [`measure`] with the joints turned as `rotations` says; the table's mesh is
/// [`SYNTHETIC`] or [`SYNTHETIC_UNIFORM`].
pub fn measure_posed(
    n: usize,
    threads: usize,
    rounds: usize,
    rotations: Rotations,
) -> Result<Table> {
    let rig = synthetic::rig(n, 54, 7);
    let (jt, name) = match rotations {
        Rotations::Near => (synthetic::joints(54, 7), SYNTHETIC),
        Rotations::Uniform => (synthetic::uniform_joints(54, 7), SYNTHETIC_UNIFORM),
    };
    on_threads(threads, |parallel| {
        let mesh = Mesh {
            synthetic: true,
            ..Mesh::four(name, &rig, &jt, 1)
        };
        measure_on(mesh, parallel, rounds, threads.max(1))
    })
}

/// [`measure`] on a rig of one's own in the pose `jt` (a character mid-clip, say): every
/// method's fast path, and, where no vertex has more than four influences, the baselines
/// (which are written for four); and DIB again with its grouping of the vertices by
/// influence count turned off ([`UNGROUPED_DIB`]: the same results, in the rig's order
/// alone; [`FastRig`]). Each timed sample skins the mesh as many times as make
/// `min_vertices` vertices or more (a character of a few thousand vertices takes
/// microseconds, too short to time alone), and every rate counts them all; the copy bound
/// copies the same bytes as often. An error where the mesh has no vertex (nothing to
/// time) or some vertex has more than 8 influences (the fast path's widest layout).
pub fn measure_rig(
    rig: &Rig,
    jt: &JointTransforms,
    threads: usize,
    rounds: usize,
    min_vertices: usize,
) -> Result<Table> {
    let n = rig.mesh.positions.len();
    if n == 0 {
        return Err(crate::SkinError::Parameter {
            what: "the rig",
            value: rig.name.clone(),
            reason: "has no vertices to time",
        });
    }
    let reps = repeats(n, min_vertices);
    if rig.influences.max_per_vertex() <= 4 {
        let fast = FastRig::<4>::new(rig)?;
        let ungrouped = fast.clone().without_dib_grouping();
        on_threads(threads, |parallel| {
            let mesh = Mesh {
                ungrouped: Some(&ungrouped),
                ..Mesh::four(&rig.name, &fast, jt, reps)
            };
            measure_on(mesh, parallel, rounds, threads.max(1))
        })
    } else {
        let fast = FastRig::<8>::new(rig)?;
        let ungrouped = fast.clone().without_dib_grouping();
        on_threads(threads, |parallel| {
            let mesh = Mesh {
                name: &rig.name,
                rig: &fast,
                jt,
                baselines: None,
                ungrouped: Some(&ungrouped),
                reps,
                synthetic: false,
            };
            measure_on(mesh, parallel, rounds, threads.max(1))
        })
    }
}

/// How many times a sample skins a mesh of `n` vertices to skin `min_vertices` or more
/// (at least once).
pub fn repeats(n: usize, min_vertices: usize) -> usize {
    min_vertices.div_ceil(n.max(1)).max(1)
}

/// `f(parallel)` on `threads` threads: the caller's alone (`parallel` false), or a rayon
/// pool of that many.
fn on_threads<R: Send>(threads: usize, f: impl FnOnce(bool) -> Result<R> + Send) -> Result<R> {
    if threads <= 1 {
        return f(false);
    }
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .map_err(|e| crate::SkinError::Threads(e.to_string()))?;
    pool.install(|| f(true))
}

/// What one table times: a laid-out mesh, its pose, the vertices the baselines read (four
/// influences; `None` where the layout has more), the layout with DIB's grouping turned
/// off (a rig's) and how often a sample skins the mesh.
struct Mesh<'a, const K: usize> {
    name: &'a str,
    rig: &'a FastRig<K>,
    jt: &'a JointTransforms,
    baselines: Option<&'a [Vertex<4>]>,
    ungrouped: Option<&'a FastRig<K>>,
    reps: usize,
    /// A synthetic mesh ([`Table::synthetic`]).
    synthetic: bool,
}

impl<'a> Mesh<'a, 4> {
    /// A four-influence mesh, baselines included.
    fn four(name: &'a str, rig: &'a FastRig<4>, jt: &'a JointTransforms, reps: usize) -> Self {
        Mesh {
            name,
            rig,
            jt,
            baselines: Some(rig.vertices()),
            ungrouped: None,
            reps,
            synthetic: false,
        }
    }
}

/// The order of `count` kernels in round `round`: a Fisher–Yates shuffle driven by
/// SplitMix64 from the round's number, the same in every run (no random source needed).
pub fn order(count: usize, round: usize) -> Vec<usize> {
    // The round's number, mixed, starts the sequence: with a plain multiple of the
    // increment, round r + 1's draws would be round r's shifted by one.
    let mut state = mix((round as u64) << 32 | 0x5EED);
    let mut next = || {
        state = state.wrapping_add(0x9E37_79B9_7F4A_7C15);
        mix(state)
    };
    let mut o: Vec<usize> = (0..count).collect();
    for i in (1..count).rev() {
        o.swap(i, (next() % (i as u64 + 1)) as usize);
    }
    o
}

/// SplitMix64's finalizer: a bijection of 64-bit words that scatters neighbouring inputs.
fn mix(mut z: u64) -> u64 {
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

/// [`measure`] and [`measure_rig`] on the current rayon pool (`parallel`) or the caller's
/// thread.
fn measure_on<const K: usize>(
    mesh: Mesh<K>,
    parallel: bool,
    rounds: usize,
    threads: usize,
) -> Result<Table> {
    let Mesh {
        rig,
        jt,
        reps,
        baselines,
        ungrouped,
        ..
    } = mesh;
    let n = rig.vertices().len();
    let pj = Joints::of(jt);
    let mut out = vec![[0f32; 6]; n];
    // The copy reads and writes half the bytes a vertex moves each: its K-influence
    // vertex in, its output out (72 B for four influences, 96 for eight).
    let moved = std::mem::size_of::<Vertex<K>>() + std::mem::size_of::<Out>();
    let half = moved / 2;
    let src = vec![1u8; n * half];
    let mut dst = vec![0u8; n * half];
    type Run<'a> = Box<dyn FnMut(&mut [Out]) -> Result<()> + 'a>;
    let mut kernels: Vec<(String, Role, Run)> = Vec::new();
    for m in Method::ALL {
        let f: Run = Box::new(move |o| skin_pose(rig, jt, m, o, parallel));
        kernels.push((m.name().into(), Role::Ours(m), f));
    }
    if let Some(u) = ungrouped {
        let f: Run = Box::new(move |o| skin_pose(u, jt, Method::Dib, o, parallel));
        kernels.push((UNGROUPED_DIB.into(), Role::Ungrouped(Method::Dib), f));
    }
    for (name, f) in baselines.map_or(&[][..], |_| &BASELINES[..]) {
        let (pj, v) = (&pj, baselines.unwrap_or_default());
        let method = if name.contains("lbs") {
            Method::Lbs
        } else {
            Method::Dqs
        };
        let f: Run = Box::new(move |o| {
            run(v, o, parallel, &|v, o| f(v, pj, o));
            Ok(())
        });
        kernels.push(((*name).into(), Role::Baseline(method), f));
    }
    let (src, dst) = (&src, &mut dst);
    let copy: Run = Box::new(move |_| {
        copy_bound(src, dst, half, parallel);
        Ok(())
    });
    let bound = kernels.len();
    kernels.push((format!("memcpy, {moved} B a vertex"), Role::Bound, copy));
    let alone: Run = Box::new(move |o| traffic(rig, o, parallel));
    let traffic_at = kernels.len();
    kernels.push((TRAFFIC.into(), Role::Traffic, alone));
    let mut secs = vec![Vec::with_capacity(rounds); kernels.len()];
    for round in 0..=rounds.max(1) {
        // A new order each round (see the module docs: which kernel follows the copy, the
        // one that touches other memory, changes from round to round).
        for k in order(kernels.len(), round) {
            let f = &mut kernels[k].2;
            let start = Instant::now();
            for _ in 0..reps {
                f(&mut out)?;
            }
            if round > 0 {
                secs[k].push(start.elapsed().as_secs_f64());
            }
        }
    }
    let ours = |m: Method| kernels.iter().position(|k| k.1 == Role::Ours(m));
    // `a`'s time over `b`'s, round by round: `b`'s speed over `a`'s.
    let over =
        |a: usize, b: usize| Spread::of(secs[a].iter().zip(&secs[b]).map(|(a, b)| a / b).collect());
    let skinned = (n * reps) as f64;
    let rows = kernels
        .iter()
        .enumerate()
        .map(|(k, (name, role, _))| Row {
            name: name.clone(),
            role: *role,
            rate: Spread::of(secs[k].iter().map(|t| skinned / t).collect()),
            ours_over: match role {
                Role::Baseline(m) => ours(*m).map(|o| over(k, o)),
                _ => None,
            },
            share: over(bound, k),
            traffic_share: over(traffic_at, k),
        })
        .collect();
    Ok(Table {
        mesh: mesh.name.to_string(),
        synthetic: mesh.synthetic,
        vertices: n,
        threads,
        centres: rig.clusters().len(),
        rounds: rounds.max(1),
        repeats: reps,
        moved,
        dib_grouped: rig.groups_dib(),
        rows,
    })
}

/// The Markdown table of `tables`: per kernel the median rate with its spread, our speed
/// over each baseline and every kernel's share of the copy bound and of the traffic bound
/// (medians of the rounds' ratios, with their spreads). A rig's rows name it beside its
/// vertex count.
pub fn markdown(tables: &[Table]) -> String {
    let mut s = String::from(
        "| vertices | threads | kernel | M vertices/s (median) | spread | ours / it (median, spread) | share of the copy (median, spread) | share of the traffic (median, spread) |\n|---|---|---|---|---|---|---|---|\n",
    );
    let m = |x: f64| x / 1e6;
    for t in tables {
        for r in &t.rows {
            let ours = r.ours_over.map_or(String::new(), |o| {
                format!("{:.2}× ({:.2}–{:.2})", o.median, o.lo, o.hi)
            });
            s += &format!(
                "| {} | {} | {} | {:.1} | {:.1}–{:.1} | {ours} | {:.2} ({:.2}–{:.2}) | {:.2} ({:.2}–{:.2}) |\n",
                if t.synthetic && t.mesh == SYNTHETIC {
                    t.vertices.to_string()
                } else {
                    format!("{} ({})", t.vertices, t.mesh)
                },
                t.threads,
                r.name,
                m(r.rate.median),
                m(r.rate.lo),
                m(r.rate.hi),
                r.share.median,
                r.share.lo,
                r.share.hi,
                r.traffic_share.median,
                r.traffic_share.lo,
                r.traffic_share.hi
            );
        }
    }
    s
}

/// The busy time of the machine and of this process, to tell how much of the CPUs other
/// processes (and, on a virtual machine, the host: steal time counts as busy) kept during a
/// measurement. Linux only (`/proc`); elsewhere [`Load::others`] is `None`.
#[derive(Debug, Clone, Copy)]
pub struct Load {
    start: Instant,
    jiffies: Option<(u64, u64, usize)>,
}

impl Load {
    /// Starts counting.
    pub fn start() -> Load {
        Load {
            start: Instant::now(),
            jiffies: cpu_jiffies(),
        }
    }

    /// The share of all CPUs' time since [`Load::start`] that went to other processes.
    pub fn others(&self) -> Option<f64> {
        let ((busy0, mine0, cpus), (busy1, mine1, _)) = (self.jiffies?, cpu_jiffies()?);
        // Jiffies are 1/100 s on Linux.
        let wall = self.start.elapsed().as_secs_f64() * 100.0 * cpus as f64;
        Some((busy1 - busy0).saturating_sub(mine1 - mine0) as f64 / wall.max(1.0))
    }
}

/// The size of this machine's last-level cache in bytes (the largest of cpu0's caches in
/// `/sys`), where Linux tells it. A mesh whose bytes it holds is timed in the cache, not in
/// memory, whatever its size.
pub fn last_level_cache() -> Option<u64> {
    let dir = std::fs::read_dir("/sys/devices/system/cpu/cpu0/cache").ok()?;
    dir.filter_map(|e| std::fs::read_to_string(e.ok()?.path().join("size")).ok())
        .filter_map(|s| cache_size(&s))
        .max()
}

/// A note for each mesh size among `tables` of at least 2·10⁵ vertices (the sizes the
/// benches take to time memory rather than the cache, as 10⁶ and 4·10⁶ do on most machines)
/// whose bytes fit in a last-level cache of `cache` bytes ([`Table::fits_in`]; none where
/// the size is not known), each size once, smallest first.
pub fn cache_notes(tables: &[Table], cache: Option<u64>) -> Vec<String> {
    let Some(cache) = cache else {
        return Vec::new();
    };
    let mut sizes: Vec<(usize, usize)> = tables
        .iter()
        .filter(|t| t.vertices >= 200_000 && t.fits_in(cache))
        .map(|t| (t.vertices, t.moved))
        .collect();
    sizes.sort_unstable();
    sizes.dedup();
    sizes
        .iter()
        .map(|&(n, moved)| {
            format!(
                "note: at {n} vertices the mesh and its output ({:.0} MB) fit in this machine's last-level cache ({:.0} MiB): those rows time the cache, not the memory",
                n as f64 * moved as f64 / 1e6,
                cache as f64 / (1u64 << 20) as f64
            )
        })
        .collect()
}

/// A cache size as `/sys` writes it (`48K`, `2048K`, `480M`, a count of bytes).
fn cache_size(s: &str) -> Option<u64> {
    let s = s.trim();
    let (digits, unit) = match s.char_indices().find(|(_, c)| !c.is_ascii_digit()) {
        Some((at, _)) => s.split_at(at),
        None => (s, ""),
    };
    let scale: u64 = match unit {
        "" => 1,
        "K" => 1 << 10,
        "M" => 1 << 20,
        "G" => 1 << 30,
        _ => return None,
    };
    digits.parse::<u64>().ok()?.checked_mul(scale)
}

/// CPU time since boot: (all CPUs' busy jiffies, this process's jiffies, the CPUs), from
/// `/proc/stat` and `/proc/self/stat`.
fn cpu_jiffies() -> Option<(u64, u64, usize)> {
    let stat = std::fs::read_to_string("/proc/stat").ok()?;
    let cpu: Vec<u64> = stat
        .lines()
        .next()?
        .split_whitespace()
        .skip(1)
        .filter_map(|x| x.parse().ok())
        .collect();
    // user nice system idle iowait irq softirq steal (guest guest_nice, already in user and
    // nice): busy is the first eight but idle and iowait.
    let cpus = stat
        .lines()
        .filter(|l| l.starts_with("cpu") && l.as_bytes().get(3).is_some_and(u8::is_ascii_digit))
        .count();
    let busy = cpu.iter().take(8).sum::<u64>() - cpu.get(3)? - cpu.get(4).copied().unwrap_or(0);
    let own = std::fs::read_to_string("/proc/self/stat").ok()?;
    // After the command name's closing parenthesis: utime and stime are fields 14 and 15.
    let rest: Vec<&str> = own.rsplit_once(')')?.1.split_whitespace().collect();
    let mine = rest.get(11)?.parse::<u64>().ok()? + rest.get(12)?.parse::<u64>().ok()?;
    Some((busy, mine, cpus.max(1)))
}

#[cfg(test)]
mod tests {
    use super::{cache_notes, cache_size, order, Table};

    /// A mesh fits in a cache that holds its vertices and output, and not in one a byte
    /// smaller.
    #[test]
    fn a_mesh_fits_in_a_cache_that_holds_its_bytes() {
        let t = Table {
            mesh: "m".into(),
            synthetic: true,
            vertices: 1_000_000,
            threads: 1,
            centres: 0,
            rounds: 1,
            repeats: 1,
            moved: 72,
            dib_grouped: false,
            rows: vec![],
        };
        assert!(t.fits_in(72_000_000) && t.fits_in(480 << 20));
        assert!(!t.fits_in(71_999_999) && !t.fits_in(32 << 20));
        let small = Table {
            vertices: 100_000,
            ..t.clone()
        };
        let tables = [t.clone(), small, t.clone()];
        let notes = cache_notes(&tables, Some(480 << 20));
        assert_eq!(notes.len(), 1, "{notes:?}");
        assert!(notes[0].starts_with("note: at 1000000 vertices") && notes[0].contains("(72 MB)"));
        assert!(notes[0].contains("(480 MiB)"), "{}", notes[0]);
        assert!(cache_notes(&tables, Some(32 << 20)).is_empty());
        assert!(cache_notes(&tables, None).is_empty());
    }

    /// Cache sizes as Linux writes them; anything else is no size.
    #[test]
    fn cache_sizes_read_as_sys_writes_them() {
        assert_eq!(cache_size("48K\n"), Some(48 << 10));
        assert_eq!(cache_size("491520K"), Some(480 << 20));
        assert_eq!(cache_size("32M"), Some(32 << 20));
        assert_eq!(cache_size("1G"), Some(1 << 30));
        assert_eq!(cache_size("4096"), Some(4096));
        for bad in ["", "K", "12Q", "-3K", "99999999999999999999G", "1.5M"] {
            assert_eq!(cache_size(bad), None, "{bad:?}");
        }
    }

    /// Every round's order holds each kernel once, and the kernel after any one of them
    /// (the copy's follower, in the bench) changes from round to round.
    #[test]
    fn each_round_runs_every_kernel_once_in_an_order_of_its_own() {
        for count in [1, 2, 14, 15] {
            for round in 0..22 {
                let mut o = order(count, round);
                o.sort_unstable();
                assert_eq!(o, (0..count).collect::<Vec<_>>(), "{count} kernels");
            }
        }
        let orders: Vec<Vec<usize>> = (0..8).map(|r| order(14, r)).collect();
        for k in 0..14 {
            // What runs after kernel k: the next in its round, or the next round's first.
            let followers: std::collections::BTreeSet<usize> = (0..8)
                .map(|r| {
                    let at = orders[r].iter().position(|&x| x == k).unwrap();
                    orders[r]
                        .get(at + 1)
                        .copied()
                        .unwrap_or_else(|| order(14, r + 1)[0])
                })
                .collect();
            assert!(
                followers.len() >= 4,
                "kernel {k} is followed by {followers:?}"
            );
        }
    }
}
