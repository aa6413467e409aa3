//! The fast path for every method: a compact vertex layout, fixed influence counts (4 or
//! 8), eight-vertex AVX2+FMA kernels chosen at run time (every method, for 4 and 8 influences;
//! where the processor has AVX-512F and VL, built a second time with its 32 registers,
//! module `avx2::registers`, and DIB sixteen vertices at a time, module `avx512`, both to
//! the same bits; elsewhere, and for meshes of under eight vertices, the scalar kernels), joint
//! transforms as flat arrays made once per pose (12 floats per matrix, 8 per dual
//! quaternion — the register saving Kavan et al. 2006 note in §6; a 24-float row for QLB and
//! SBS, module `qlb`; twists for Log, module `log`), one pass per vertex with no allocation
//! (DIB, module `dib`: in lanes, or the library's allocation-free blend on the stack), and rayon
//! over chunks of vertices. It agrees with [`crate::skinning`]'s reference path to 1e-5
//! (tests check it on the real models). [`Skinner`] puts every method behind one call.
//!
//! Per vertex it reads 48 bytes (position, normal, four u16 joints, four f32 weights) and
//! writes 24 (position, normal): 72 bytes, the figure the bandwidth bound is computed
//! from. Meshes of `STREAM_VERTICES` (2¹⁸) or more write their packed output by non-temporal
//! stores (an ordinary store that misses the cache first reads the line it writes: 96
//! bytes a vertex). Every vertex of a mesh of eight or more goes through the SIMD kernel
//! (every chunk has eight or more, `job`'s grid; blocks at a chunk's ends overlap their
//! neighbours), so a vertex's numbers do not depend on the output's layout, alignment or
//! chunking. Influences are sorted by weight, heaviest first, so the DQS pivot (the heaviest
//! influence, as in the reference path) is simply the first.
//!
//! DQS normalizes the blended dual quaternion by ‖q0‖ only: removing qε's component along
//! q0 would change nothing, because the point transform uses only the vector part of
//! `qε q0*`, which that component does not touch. And since every term of the transform is
//! quadratic in the blend, that normalization is one factor 2/‖q0‖² (no square root). The
//! antipodality signs depend only on the pair (pivot joint, joint), so the SIMD kernels of
//! DQS, QLB and SBS look them up in a table made once per pose (`antipodes`), as which of
//! each joint's two signed copies to blend.
//!
//! The quaternion and dual-quaternion algebra the kernels share — cross products, rotation
//! by an unnormalized quaternion, DQS's transformation, products, Horner's rule, Log's
//! exponential, and DIB whole (`lane::dib`: normalization, the branch-free logarithm and
//! exponential by series, the stopping rule, the iteration) — is written once in `lane`,
//! generic over the lane type (`f32`, `__m256`, and `__m512` for DIB). What stays
//! kernel-specific is the data movement (loads, blends, transposes, stores); Log's AVX2
//! kernel writes the exponential's steps out in its own order with the algebra's parts
//! (the generic one inlined there measured 6 % slower). The scalar DIB kernel runs the
//! library's `dib_convex` instead of `lane::dib` on `f32`, so that it equals the reference
//! path bit for bit.
//!
//! This file runs past 500 lines because it holds what every kernel module relies on
//! together: the layout ([`FastRig`], [`Vertex`], checked once), the switches that choose
//! the SIMD code, the `Kernel` trait with its chunk cover, and each method's entry point;
//! the kernels' safety contract (joint indices checked at layout, sizes checked per job) is
//! stated and kept in one place.

use crate::error::{same_count, Result, SkinError, FAST_RIG};
use crate::pose::JointTransforms;
use crate::rig::Rig;
use crate::rotation_centre::{joint_centres, Clusters};
use chasles::{DualQuat, Vec3};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::OnceLock;

/// One vertex with K influences (unused slots have weight 0).
#[derive(Debug, Clone, Copy, PartialEq)]
#[repr(C)]
pub struct Vertex<const K: usize> {
    /// Bind position.
    pub p: [f32; 3],
    /// Bind normal.
    pub n: [f32; 3],
    /// Joint indices. DQS, QLB and SBS take slot 0 as the antipodality pivot:
    /// [`FastRig::new`] puts the heaviest influence there, as the reference path pivots on
    /// it; a layout built by hand pivots on whatever it puts there (which changes a blend
    /// only where the joints' quaternions, each taken into the pivot's hemisphere, are not
    /// all in one hemisphere with one another: joints turned far apart, near 180°), and
    /// DIB finds the heaviest itself. Every slot's joint must exist, weight 0 or not (the
    /// kernels read them all).
    pub j: [u16; K],
    /// Weights: finite, not negative, summing to 1 within [`WEIGHT_SUM_TOLERANCE`]
    /// ([`FastRig::from_vertices`] checks them; [`FastRig::new`] takes a checked rig's as
    /// they are, as the reference path does; LBS blends by them as they are).
    pub w: [f32; K],
}

mod antipodes;
#[cfg(target_arch = "x86_64")]
mod avx2;
#[cfg(target_arch = "x86_64")]
mod avx512;
mod dest;
mod dib;
mod grouped;
mod job;
mod lane;
mod log;
pub(crate) mod palette;
mod qlb;
mod skinner;
mod traffic;

use antipodes::Antipodes;
use dest::Dest;
pub use dib::dib;
use job::for_chunks;
pub use job::{Output, SkinningJob};
pub use log::{log, twists};
pub use palette::{Affine3x4, Joints, Palette, QlbJoint, RotationCentre, Twist, UnitDualQuat};
pub use qlb::{clusters, qlb, sbs, Row};
pub use skinner::{skin_pose, Skinner};
pub use traffic::traffic;

/// A rig laid out for the fast path. Its joint indices are checked on construction (the
/// SIMD kernels rely on it), so the fields are private. Its vertices are the rig's, in the
/// rig's order. Where DIB's SIMD kernels would cost a tenth less or more with the vertices
/// grouped by influence count (fewer blocks that iterate or take a ScLERP), the first DIB
/// job makes a grouped copy of them and every DIB job runs on it, giving every vertex the
/// same bits in the rig's order (module `grouped`: the built-in characters 1.39–1.56× as
/// fast);
/// [`FastRig::without_dib_grouping`] forgoes the copy, and a rig reordered once by
/// [`crate::vertex_order`] needs none.
#[derive(Debug, Clone)]
pub struct FastRig<const K: usize> {
    vertices: Vec<Vertex<K>>,
    /// Each joint's bind-pose origin (decomposed QLB and SBS rotate about these).
    centres: Vec<Vec3<f32>>,
    /// SBS's vertex clusters, made on first use.
    clusters: OnceLock<Clusters>,
    /// DIB's vertices grouped by influence count, where that gains (`grouped`), made by the
    /// first DIB job that runs the SIMD kernels.
    dib_groups: OnceLock<Option<grouped::Groups<K>>>,
}

/// Two layouts are equal when their vertices and joint origins are: the clusters and DIB's
/// groups are caches (and whether DIB groups at all, [`FastRig::without_dib_grouping`], a
/// choice of speed: the results are the same).
impl<const K: usize> PartialEq for FastRig<K> {
    fn eq(&self, other: &Self) -> bool {
        self.vertices == other.vertices && self.centres == other.centres
    }
}

/// Output: position and normal per vertex.
pub type Out = [f32; 6];

impl<const K: usize> FastRig<K> {
    /// Lays out a rig; an error if a vertex has more than K influences.
    pub fn new(rig: &Rig) -> Result<Self> {
        let most = rig.influences.max_per_vertex();
        if most > K {
            return Err(SkinError::TooManyInfluences {
                rig: rig.name.clone(),
                most,
                layout: K,
            });
        }
        let vertices = (0..rig.mesh.positions.len())
            .map(|v| {
                // Influences are stored heaviest first (`Influences::from_lists`).
                let mut j = [0u16; K];
                let mut w = [0f32; K];
                for (k, (jj, ww)) in rig.influences.of(v).enumerate() {
                    j[k] = jj as u16;
                    w[k] = ww;
                }
                Vertex {
                    p: rig.mesh.positions[v].to_array(),
                    n: rig.mesh.normals[v].to_array(),
                    j,
                    w,
                }
            })
            .collect();
        // The rig's weights were checked by `Rig::new` (`Influences::check`) and are taken
        // as they are, as the reference path takes them.
        Self::laid_out(vertices, joint_centres(&rig.inverse_bind))
    }

    /// A rig from laid-out vertices and the bind-pose origin of each joint (see
    /// [`joint_centres`]; their number is the joint count). Errors name the vertex: a
    /// joint index out of range ([`SkinError::JointOutOfRange`]), a weight negative or not
    /// finite, or weights whose sum is not 1 within [`WEIGHT_SUM_TOLERANCE`]
    /// ([`SkinError::BadWeights`]: scale them first, as [`crate::Influences`] does); a
    /// position too far out ([`crate::reach`]).
    pub fn from_vertices(vertices: Vec<Vertex<K>>, centres: Vec<Vec3<f32>>) -> Result<Self> {
        for (vertex, v) in vertices.iter().enumerate() {
            check_weights(vertex, v)?;
        }
        Self::laid_out(vertices, centres)
    }

    /// [`FastRig::from_vertices`] without the weights' check: joint indices and positions.
    fn laid_out(vertices: Vec<Vertex<K>>, centres: Vec<Vec3<f32>>) -> Result<Self> {
        let joints = centres.len();
        if let Some((i, v)) = vertices
            .iter()
            .enumerate()
            .find(|(_, v)| v.j.iter().any(|j| usize::from(*j) >= joints))
        {
            let joint = v.j.iter().map(|j| usize::from(*j)).max().unwrap_or(0);
            return Err(SkinError::JointOutOfRange {
                vertex: i,
                joint,
                joints,
            });
        }
        let positions: Vec<Vec3<f32>> = vertices.iter().map(|v| Vec3::from_array(v.p)).collect();
        crate::reach::check_positions(crate::error::FAST_RIG, &positions)?;
        Ok(FastRig {
            vertices,
            centres,
            clusters: OnceLock::new(),
            dib_groups: OnceLock::new(),
        })
    }

    /// The vertices.
    pub fn vertices(&self) -> &[Vertex<K>] {
        &self.vertices
    }

    /// The number of joints.
    pub fn joints(&self) -> usize {
        self.centres.len()
    }

    /// Each joint's bind-pose origin.
    pub fn centres(&self) -> &[Vec3<f32>] {
        &self.centres
    }

    /// SBS's clusters of vertices moved by the same joints ([`clusters`]), made on the
    /// first call.
    pub fn clusters(&self) -> &Clusters {
        self.clusters.get_or_init(|| clusters(self))
    }

    /// This layout with DIB's grouping by influence count turned off: DIB's kernels run on
    /// the vertices in the rig's order, with no grouped copy of them (the same results,
    /// slower where the grouping would have been made: see [`FastRig`]).
    pub fn without_dib_grouping(self) -> Self {
        FastRig {
            dib_groups: OnceLock::from(None),
            ..self
        }
    }

    /// Whether DIB's jobs run on a grouped copy of the vertices here: the SIMD kernels run
    /// ([`uses_simd`]) and grouping gains on this rig (the copy is made by the first DIB
    /// job, or by this call; see [`FastRig`]).
    pub fn groups_dib(&self) -> bool {
        simd(K) && self.dib_groups().is_some()
    }

    /// DIB's grouped vertices, made on the first call (`None` where grouping gains little).
    fn dib_groups(&self) -> Option<&grouped::Groups<K>> {
        self.dib_groups
            .get_or_init(|| grouped::Groups::of(&self.vertices))
            .as_ref()
    }
}

/// How far from 1 a laid-out vertex's weights may sum ([`FastRig::from_vertices`]): f32
/// rounding of a handful of weights is a few 1e-7; weights stored in 8 or 16 bits (glTF's
/// normalized integers) can be off by more and are to be scaled first.
pub const WEIGHT_SUM_TOLERANCE: f32 = 1e-3;

/// A laid-out vertex's weights: finite, not negative, summing to 1 within
/// [`WEIGHT_SUM_TOLERANCE`].
fn check_weights<const K: usize>(vertex: usize, v: &Vertex<K>) -> Result<()> {
    for (&j, &w) in v.j.iter().zip(&v.w) {
        crate::rig::check_weight(vertex, usize::from(j), w)?;
    }
    let sum: f32 = v.w.iter().sum();
    if (sum - 1.0).abs() > WEIGHT_SUM_TOLERANCE {
        return Err(SkinError::BadWeights {
            vertex,
            reason: format!("the weights sum to {sum}, not 1 (scale them first)"),
        });
    }
    Ok(())
}

/// Joint matrices as 12 floats, row-major 3×4.
pub fn matrices12(jt: &JointTransforms) -> Vec<[f32; 12]> {
    jt.matrices
        .iter()
        .map(|m| bytemuck::cast(palette::affine(m)))
        .collect()
}

/// Joint dual quaternions as 8 floats `[w, x, y, z, wε, xε, yε, zε]`.
pub fn dual_quats8(jt: &JointTransforms) -> Vec<[f32; 8]> {
    arrays8(&jt.dual_quats, palette::unit)
}

/// Dual quaternions as 8 floats each, as the kernels read them, each made a joint by
/// `joint` (`palette::unit`, or `palette::dib_unit` for DIB).
fn arrays8(
    d: &[DualQuat<f32>],
    joint: fn(&DualQuat<f32>) -> palette::UnitDualQuat,
) -> Vec<[f32; 8]> {
    d.iter().map(|d| bytemuck::cast(joint(d))).collect()
}

#[inline(always)]
fn lbs_vertex<const K: usize>(v: &Vertex<K>, m: &[[f32; 12]]) -> Out {
    let mut a = [0f32; 12];
    for k in 0..K {
        let w = v.w[k];
        let mj = &m[usize::from(v.j[k])];
        for i in 0..12 {
            a[i] += w * mj[i];
        }
    }
    let [x, y, z] = v.p;
    let px = a[0] * x + a[1] * y + a[2] * z + a[3];
    let py = a[4] * x + a[5] * y + a[6] * z + a[7];
    let pz = a[8] * x + a[9] * y + a[10] * z + a[11];
    // Normal by the cofactor matrix (det · inverse transpose), renormalized.
    let [nx, ny, nz] = v.n;
    let c00 = a[5] * a[10] - a[6] * a[9];
    let c01 = a[6] * a[8] - a[4] * a[10];
    let c02 = a[4] * a[9] - a[5] * a[8];
    let c10 = a[2] * a[9] - a[1] * a[10];
    let c11 = a[0] * a[10] - a[2] * a[8];
    let c12 = a[1] * a[8] - a[0] * a[9];
    let c20 = a[1] * a[6] - a[2] * a[5];
    let c21 = a[2] * a[4] - a[0] * a[6];
    let c22 = a[0] * a[5] - a[1] * a[4];
    let mx = c00 * nx + c01 * ny + c02 * nz;
    let my = c10 * nx + c11 * ny + c12 * nz;
    let mz = c20 * nx + c21 * ny + c22 * nz;
    let l = (mx * mx + my * my + mz * mz).sqrt();
    let (mx, my, mz) = if l > 0.0 {
        (mx / l, my / l, mz / l)
    } else {
        (nx, ny, nz)
    };
    [px, py, pz, mx, my, mz]
}

/// `⟨q̂, p̂⟩` of two joints' rotation quaternions (the first 4 of their N floats: the real
/// part of a dual quaternion, or a QLB row's rotation), summed in one fixed order: the
/// antipodality test of the scalar kernels and of the table of signed copies alike.
#[inline(always)]
fn real_dot<const N: usize>(q: &[f32; N], p: &[f32; N]) -> f32 {
    q[0] * p[0] + q[1] * p[1] + q[2] * p[2] + q[3] * p[3]
}

#[inline(always)]
fn dqs_vertex<const K: usize>(v: &Vertex<K>, d: &[[f32; 8]]) -> Out {
    let pivot = &d[usize::from(v.j[0])];
    let mut b = [0f32; 8];
    for k in 0..K {
        let dj = &d[usize::from(v.j[k])];
        let w = if real_dot(dj, pivot) < 0.0 {
            -v.w[k]
        } else {
            v.w[k]
        };
        for i in 0..8 {
            b[i] += w * dj[i];
        }
    }
    // The unit dual quaternion is b / ‖b0‖; every term is quadratic in b, so the
    // normalization is one factor 2 / ‖b0‖² (no square root, no eight divisions).
    lane::transform(b, v.p, v.n)
}

/// `x + s v × (v × x + w x)` for a quaternion `(w, v)` and `s = 2 / ‖(w, v)‖²`: x rotated by
/// the unit quaternion `(w, v) / ‖(w, v)‖` with no square root (QLB's rotation about a
/// centre); the lane algebra's [`lane::rotate`] on one vertex.
#[inline(always)]
fn rotate_scaled(q: [f32; 4], s: f32, x: [f32; 3]) -> [f32; 3] {
    let [w0, x0, y0, z0] = q;
    lane::rotate(w0, [x0, y0, z0], s, x)
}

/// A vertex's output from its position and normal.
#[inline(always)]
fn out_of(p: Vec3<f32>, n: Vec3<f32>) -> Out {
    let ([px, py, pz], [nx, ny, nz]) = (p.to_array(), n.to_array());
    [px, py, pz, nx, ny, nz]
}

/// Asks the cache for the line holding `p` (x86-64's prefetch into every level; nothing on
/// other targets): a hint, harmless for any address, as the pointer is never read. The
/// kernels' input ahead, SBS's centres and its solve's tables ahead take it.
#[inline(always)]
pub(crate) fn ask_cache<T>(p: *const T) {
    #[cfg(target_arch = "x86_64")]
    // SAFETY: a prefetch of any address is harmless; the pointer is never read.
    unsafe {
        std::arch::x86_64::_mm_prefetch::<{ std::arch::x86_64::_MM_HINT_T0 }>(p.cast())
    };
    #[cfg(not(target_arch = "x86_64"))]
    let _ = p;
}

/// A loop of `count` turns, `end(k, take(k))` for k = 0 … count − 1. With `ahead`, each
/// turn takes item k + 1 before it ends item k, carrying what `take` made (a few registers
/// of lanes) into the next turn, so that the next item's loads are under way while this
/// one's last steps run; without, each item is taken and ended in its own turn. The
/// kernels' blocks of eight (`avx2::blocks_ahead`, whose module docs have the figures, "The
/// next block ahead") and the centre solve's groups of eight clusters
/// (`rotation_centre::wide::eights`) run on it. `ahead` is a constant in every caller, so
/// each compiles one loop; both closures are meant to be `#[inline(always)]`: the loop is a
/// kernel's body, compiled in its caller's build.
#[inline(always)]
pub(crate) fn take_ahead<T: Copy>(
    count: usize,
    ahead: bool,
    take: impl Fn(usize) -> T,
    mut end: impl FnMut(usize, T),
) {
    if count == 0 {
        return;
    }
    let mut cur = take(0);
    for k in 0..count {
        if !ahead && k > 0 {
            cur = take(k);
        }
        let next = if ahead && k + 1 < count {
            take(k + 1)
        } else {
            cur
        };
        end(k, cur);
        cur = next;
    }
}

/// Vertices per chunk, the job's unit of work (`job`'s grid: the first chunk may be up to 7
/// longer, so that the others' streamed output starts a 64-byte line, and the last up to 7
/// longer).
const CHUNK: usize = 4096;

/// Meshes of at least this many vertices (18.9 MB moved a pose, more than a core's share of
/// most last-level caches) have their packed output written by non-temporal stores, which
/// skip reading each output line before writing it; smaller ones, whose output may stay
/// in the cache for whoever reads it next, by ordinary stores.
const STREAM_VERTICES: usize = 1 << 18;

/// The 8-vertex SIMD kernel of a method, if this processor has one: it skins a prefix of
/// whole blocks into the output (any layout, [`Dest`]) and returns how many vertices it
/// did; with the flag (only where the output is packed and 32-byte aligned, see
/// [`simd_start`]) it writes by non-temporal stores.
type SimdKernel<const K: usize, J, T> = unsafe fn(&[Vertex<K>], &[J], &T, Dest<'_>, bool) -> usize;

/// Where a SIMD kernel starts in a chunk's output `o`, and whether it streams: with
/// `stream` and a packed `o`, at the first vertex whose output is 32-byte aligned (24-byte
/// vertices come back to an alignment every 4; an output that is not 8-byte aligned never
/// reaches 32), the vertices before it skinned by the overlapping block 0..8 ([`cover`]);
/// else at 0, not streaming
/// (interleaved and split outputs are never streamed: their vertices do not fill whole
/// lines of one array).
fn simd_start(o: &Dest<'_>, stream: bool) -> (usize, bool) {
    let stream = stream && o.layout() == dest::Layout::Packed;
    match aligned_from(o.addr(), 32) {
        Some(lead) if stream && lead + 8 <= o.len() => (lead, true),
        _ => (0, false),
    }
}

/// The first vertex of a packed output at `addr` whose six floats start on a `bytes`-byte
/// boundary (32 or 64: 24-byte vertices come back to such a boundary every `bytes / 8`), if
/// any (none where `addr` is not 8-byte aligned).
fn aligned_from(addr: usize, bytes: usize) -> Option<usize> {
    (0..bytes / 8).find(|l| (addr + 24 * l).is_multiple_of(bytes))
}

/// Orders a SIMD kernel's non-temporal stores before whatever follows (the job's end, which
/// hands the output to other threads).
#[cfg(target_arch = "x86_64")]
fn fence_streams() {
    // SAFETY: SSE is part of every x86-64 processor.
    unsafe { std::arch::x86_64::_mm_sfence() }
}

/// Every vertex of a chunk of `n ≥ 8` through a SIMD kernel, so that each vertex's numbers
/// are the same whatever the output's layout, alignment or chunking: `kernel(from, to,
/// stream)` skins the whole blocks of `from..to` and returns how many vertices it did.
/// The whole blocks from `lead` (streamed with `streams`, see [`simd_start`]); before them
/// the block `0..8`, after them the block `n − 8..n` where vertices are left over — both
/// overlap their neighbours, whose vertices they skin again to the same numbers (by
/// ordinary stores, after the fence).
#[cfg(target_arch = "x86_64")]
fn cover(
    n: usize,
    lead: usize,
    streams: bool,
    mut kernel: impl FnMut(usize, usize, bool) -> usize,
) {
    debug_assert!(n >= 8 && lead + 8 <= n.max(8));
    if lead > 0 {
        kernel(0, 8, false);
    }
    let done = lead + kernel(lead, n, streams);
    if streams {
        fence_streams();
    }
    if done < n {
        kernel(n - 8, n, false);
    }
}

/// Whether the SIMD kernels may run (they do where the processor has them); see
/// [`set_simd`].
static SIMD_ALLOWED: AtomicBool = AtomicBool::new(true);

/// Allows (the default) or forbids the AVX2+FMA kernels for this process: with `false`
/// every method runs its portable scalar kernel, and SBS solves its rotation centres one by
/// one, as on a processor without AVX2 — to test or measure that fallback on any machine.
/// Takes effect at the next job.
pub fn set_simd(allowed: bool) {
    SIMD_ALLOWED.store(allowed, Ordering::Relaxed);
}

/// Whether the AVX-512 code may run; see [`set_avx512`].
static AVX512_ALLOWED: AtomicBool = AtomicBool::new(true);

/// Allows (the default) or forbids the AVX-512 code for this process: DIB's sixteen-vertex
/// AVX-512F kernel, the other kernels' builds with AVX-512F and VL's 32 registers
/// (module `avx2::registers`) and SBS's centre solve eight clusters at a time
/// (`rotation_centre`). With `false` the SIMD paths run the AVX2+FMA code alone, as
/// on a processor without AVX-512 — to compare the two, or to test that path, on any
/// machine. Each vertex gets the same numbers either way. Takes effect at the next job.
pub fn set_avx512(allowed: bool) {
    AVX512_ALLOWED.store(allowed, Ordering::Relaxed);
}

/// Whether jobs on a rig of `k` influences run the AVX-512 code here (DIB sixteen vertices
/// at a time, the other methods built with 32 registers, SBS's centres eight clusters at a
/// time): the SIMD kernels run ([`uses_simd`]), the processor has AVX-512F and AVX-512VL,
/// and [`set_avx512`] has not forbidden it.
pub fn uses_avx512(k: usize) -> bool {
    simd(k) && avx512()
}

/// Whether the AVX-512 code is allowed and the processor has AVX-512F and AVX-512VL (every
/// processor with AVX-512 but the Xeon Phi has both): DIB's sixteen-vertex kernel and the
/// other kernels' builds with 32 registers (`avx2::registers`).
fn avx512() -> bool {
    #[cfg(target_arch = "x86_64")]
    if AVX512_ALLOWED.load(Ordering::Relaxed)
        && std::is_x86_feature_detected!("avx512f")
        && std::is_x86_feature_detected!("avx512vl")
    {
        return true;
    }
    false
}

/// Whether jobs on a rig of `k` influences run the SIMD kernels here: x86-64 with AVX2 and
/// FMA, 4 or 8 influences (the layouts they are written for), and not forbidden by
/// [`set_simd`].
pub fn uses_simd(k: usize) -> bool {
    simd(k)
}

/// Whether the AVX2+FMA kernels run here: x86-64 with both features, 4 or 8 influences
/// (the layouts they are written for: whole groups of four weights), and allowed.
fn simd(k: usize) -> bool {
    #[cfg(target_arch = "x86_64")]
    if (k == 4 || k == 8)
        && SIMD_ALLOWED.load(Ordering::Relaxed)
        && std::is_x86_feature_detected!("avx2")
        && std::is_x86_feature_detected!("fma")
    {
        return true;
    }
    let _ = k;
    false
}

/// A per-vertex kernel, as a type so that every loop is monomorphized and inlined.
trait Kernel<const K: usize> {
    type Joint: Sync;
    /// What the SIMD kernel reads besides the joints, made once per pose (not per chunk).
    type Table: Sync;
    fn table(joints: &[Self::Joint], vertices: usize) -> Self::Table;
    fn vertex(v: &Vertex<K>, joints: &[Self::Joint]) -> Out;
    /// The AVX2+FMA kernel (x86-64 only), if the method has one.
    #[cfg(target_arch = "x86_64")]
    const AVX2: Option<SimdKernel<K, Self::Joint, Self::Table>>;
    /// Whether the SIMD kernel runs faster on vertices grouped by influence count
    /// (DIB's: [`grouped`]); a kernel whose every vertex costs the same says no.
    const GROUPED: bool = false;
    /// A chunk of vertices (joint indices already checked against `joints`): the SIMD kernel
    /// where `simd` says so (streaming its output where `stream` asks and the output's
    /// alignment allows), the scalar kernel for a chunk of under eight (only in a mesh of
    /// under eight vertices, `job`'s grid).
    fn chunk(
        mut o: Dest<'_>,
        v: &[Vertex<K>],
        joints: &[Self::Joint],
        table: &Self::Table,
        simd: bool,
        stream: bool,
    ) {
        #[cfg(target_arch = "x86_64")]
        if let (true, Some(kernel), true) = (simd, Self::AVX2, v.len() >= 8) {
            let (lead, streams) = simd_start(&o, stream);
            cover(v.len(), lead, streams, |from, to, s| {
                // SAFETY: `simd` is only true when K is 4 or 8 and the processor has AVX2
                // and FMA (see `simd`); the joint indices were checked against the joint
                // count when the FastRig was built and `run` checked that `joints` has that
                // many entries; `table` was made from `joints`; `o` is as long as `v`;
                // `simd_start` streams only where `o` is packed and `o[lead]` 32-byte
                // aligned.
                unsafe { kernel(&v[from..to], joints, table, o.range(from, to), s) }
            });
            return;
        }
        let _ = (simd, table, stream);
        for (i, v) in v.iter().enumerate() {
            o.put(i, Self::vertex(v, joints));
        }
    }
}

struct LbsKernel;
impl<const K: usize> Kernel<K> for LbsKernel {
    type Joint = [f32; 12];
    type Table = ();
    fn table(_: &[[f32; 12]], _: usize) {}
    #[cfg(target_arch = "x86_64")]
    const AVX2: Option<SimdKernel<K, [f32; 12], ()>> = Some(avx2::lbs::<K>);
    #[inline(always)]
    fn vertex(v: &Vertex<K>, joints: &[[f32; 12]]) -> Out {
        lbs_vertex(v, joints)
    }
}

struct DqsKernel;
impl<const K: usize> Kernel<K> for DqsKernel {
    type Joint = [f32; 8];
    type Table = Antipodes;
    fn table(joints: &[[f32; 8]], vertices: usize) -> Antipodes {
        Antipodes::copies(joints, vertices)
    }
    #[cfg(target_arch = "x86_64")]
    const AVX2: Option<SimdKernel<K, [f32; 8], Antipodes>> = Some(avx2::dqs::<K>);
    #[inline(always)]
    fn vertex(v: &Vertex<K>, joints: &[[f32; 8]]) -> Out {
        dqs_vertex(v, joints)
    }
}

/// The sizes every fast skinning checks: one output per vertex, one transform per joint.
fn check<const K: usize>(rig: &FastRig<K>, joints: usize, out: usize) -> Result<()> {
    same_count(FAST_RIG, "output vertices", rig.vertices.len(), out)?;
    same_count(FAST_RIG, "joint transforms", rig.joints(), joints)
}

fn run<const K: usize, F: Kernel<K>>(
    rig: &FastRig<K>,
    joints: &[F::Joint],
    out: Output<'_>,
    parallel: bool,
) -> Result<()> {
    let (_, table) = pose_table::<K, F>(joints, rig.vertices.len());
    run_with::<K, F>(rig, joints, &table, out, parallel)
}

/// [`run`] with the pose's table made already (a [`Palette`]'s).
fn run_with<const K: usize, F: Kernel<K>>(
    rig: &FastRig<K>,
    joints: &[F::Joint],
    table: &F::Table,
    out: Output<'_>,
    parallel: bool,
) -> Result<()> {
    check(rig, joints.len(), out.vertices()?)?;
    let simd = simd(K);
    if F::GROUPED && simd {
        if let Some(g) = rig.dib_groups() {
            grouped::run::<K, F>(g, joints, table, out, parallel);
            return Ok(());
        }
    }
    let big = rig.vertices.len() >= STREAM_VERTICES;
    for_chunks(out, &rig.vertices, parallel, |_, o, v| {
        F::chunk(o, v, joints, table, simd, big)
    });
    Ok(())
}

/// Whether the SIMD kernels run here, and the per-pose table of kernel `F` for `joints`
/// (made only for them: the scalar kernels do not read it).
fn pose_table<const K: usize, F: Kernel<K>>(
    joints: &[F::Joint],
    vertices: usize,
) -> (bool, F::Table) {
    let simd = simd(K);
    (simd, F::table(if simd { joints } else { &[] }, vertices))
}

/// Linear blend skinning into `out`, on all threads when `parallel`.
pub fn lbs<const K: usize>(
    rig: &FastRig<K>,
    m: &[[f32; 12]],
    out: &mut [Out],
    parallel: bool,
) -> Result<()> {
    run::<K, LbsKernel>(rig, m, out.into(), parallel)
}

/// Dual quaternion skinning into `out`, on all threads when `parallel`.
pub fn dqs<const K: usize>(
    rig: &FastRig<K>,
    d: &[[f32; 8]],
    out: &mut [Out],
    parallel: bool,
) -> Result<()> {
    run::<K, DqsKernel>(rig, d, out.into(), parallel)
}

/// The largest difference between two outputs' six numbers.
#[cfg(test)]
fn max_diff(a: &Out, b: &Out) -> f32 {
    (0..6).map(|k| (a[k] - b[k]).abs()).fold(0f32, f32::max)
}

#[cfg(all(test, target_arch = "x86_64"))]
mod tests;
