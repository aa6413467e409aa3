//! A vertex order for DIB's SIMD blocks (Kavan et al. 2006, §4, the box "DIB", and §6:
//! its cost in skinning). The fast path skins vertices in blocks of eight or sixteen, one
//! vertex a lane (`fast::lane::dib`), and a block pays for DIB's iteration — an update and
//! the pass of logarithms that shows it converged — wherever one of its lanes has three
//! influences or more; a block whose lanes all have one or two makes no update (a lane of
//! two takes ScLERP in closed form, Lemma 3). On a character the vertices of few and many influences are mixed
//! along the mesh, so many blocks iterate for one or two of their lanes.
//!
//! [`by_influence_count`] gives the order that sorts the vertices by their influence count
//! (one, two, three, four, …) within each window of [`WINDOW`] vertices, so that a
//! window's vertices of three or more sit side by side, those of three before (or after)
//! those of four: a block of three influences takes three logarithms a pass, one of four
//! four (`fast::lane::dib`, `update`; until 2026-12-05 counts of three and more were one
//! kind, when a block of three took four); windows alternate between rising
//! and falling counts, so that neighbouring windows meet with like vertices (which matters
//! where blocks start off a window's edge: in a job of 2¹⁸ vertices or more into a packed
//! output, whose chunks after the first start up to seven vertices past a multiple of
//! 4096). [`Rig::reordered`] applies it (positions, normals, influences, the triangles
//! renumbered). Each vertex's result does not depend on its block-mates (the kernels'
//! tests shift every block and compare bits), so a reordered rig skins every vertex to the
//! same bits, in the new order.
//!
//! The fast path makes the same order itself, for DIB alone, on a rig where it gains
//! (`fast::grouped`: a copy of the vertices in this order, each vertex's result stored
//! straight to its place in the rig's order). Applying the order to an asset once, when it
//! is built (like an order for a GPU's vertex cache; the windows keep neighbours near each
//! other), saves that copy and the scattered stores (2–3 % of DIB's time on the
//! characters).
//!
//! Measured (2026-12-05, a 2-core Intel Xeon with AVX-512F, one core; blocks of sixteen
//! that iterate, before → after: the Fox 26 → 5 of 108, RiggedFigure 22 → 13 of 24,
//! CesiumMan 145 → 77 of 205). `cargo run --release -p chasles-skin --example
//! dib_grouping` (best of 20 runs over the characters' clips, two rounds, M vertices/s),
//! DIB in the rig's order (the fast path's grouping turned off) → grouped by the fast path
//! → on the reordered rig: the Fox 73.7–75.7 → 88.9–91.1 → 99.3–99.4; RiggedFigure
//! 62.0–63.6 → 67.1–69.0 → 71.8; CesiumMan 65.3–66.1 → 72.7–73.0 → 78.3. Sorted within
//! windows of 64 vertices (rising in every window, a scratch run) the Fox kept about half
//! the gain (69.5 → 81.6, against 88.7 with 256) and CesiumMan two thirds (58.6 → 67.7,
//! against 74.7); windows of 1024 or the whole mesh gained as much as 256. Sorted over
//! the whole mesh CesiumMan still has 72 blocks that iterate (its vertices of three
//! influences or more fill them), so it cannot go much further. The other methods'
//! kernels take every vertex alike, whatever its count, and are unchanged. Once a vertex of
//! two influences took ScLERP in closed form (a block of one and two makes no update; the
//! same command, two runs): the Fox 86.1–86.5 → 131.3–134.7 → 136.3–139.9, RiggedFigure
//! 49.5–50.8 → 72.3–74.4 → 74.4–76.4, CesiumMan 56.5–57.2 → 79.7–80.3 → 82.4–82.9.
//!
//! Not kept (when three influences and more were one kind of the order): ordering each
//! window two, one, three or more (rather than one, two, three or more), so that the block at the edge of a window's vertices of three or more meets
//! vertices of one and takes no ScLERP. By `fast::grouped`'s cost model it saves 0.7 % on
//! CesiumMan (2871 → 2851), 0.5 % on the Fox (882 → 878) and nothing on RiggedFigure (a
//! scratch computation, 2026-12-05): within the timings' noise, for a change of this
//! documented order.

use crate::error::{Result, SkinError};
use crate::rig::{Influences, Mesh, Rig};
use std::cmp::Reverse;

/// The vertices sorted together by [`by_influence_count`]: sixteen blocks of sixteen.
pub const WINDOW: usize = 256;

/// The order that groups the vertices of `rig` by influence count (module docs): `order[i]`
/// is the index of the vertex that comes i-th. Within each window of [`WINDOW`] vertices
/// the vertices are sorted by how many positive weights they have (1, 2, 3, 4, …), rising
/// in even windows and falling in odd ones, and otherwise keep their
/// order; every vertex stays in its window. An error where the rig's public fields were
/// changed into an inconsistent rig ([`Rig::validate`]).
pub fn by_influence_count(rig: &Rig) -> Result<Vec<u32>> {
    rig.validate()?;
    let influences = &rig.influences;
    Ok(by_kind(influences.vertices(), |v| {
        influences.of(v).filter(|&(_, w)| w > 0.0).count()
    }))
}

/// The order of [`by_influence_count`] for `n` vertices (at most `u32::MAX`: a rig's, whose
/// influence rows are indexed by u32, or a fast layout's that `fast` checked) with
/// `count(v)` influences of positive weight each.
pub(crate) fn by_kind(n: usize, count: impl Fn(usize) -> usize) -> Vec<u32> {
    debug_assert!(n <= u32::MAX as usize, "vertices are named by u32 indices");
    let kind = |v: u32| count(v as usize);
    let mut order: Vec<u32> = (0..n as u32).collect();
    for (i, window) in order.chunks_mut(WINDOW).enumerate() {
        if i % 2 == 0 {
            window.sort_by_key(|&v| kind(v));
        } else {
            window.sort_by_key(|&v| Reverse(kind(v)));
        }
    }
    order
}

/// The inverse of the vertex order `order` of a mesh of `vertices` vertices:
/// `inverse[order[i]] = i`, the new index of each old vertex (what a triangle's corners
/// become). An error unless `order` names each of the `vertices` vertices once.
pub fn inverse(order: &[u32], vertices: usize) -> Result<Vec<u32>> {
    if vertices > u32::MAX as usize {
        return Err(SkinError::Parameter {
            what: "the vertex order",
            value: format!("of {vertices} vertices"),
            reason: "must have at most 2^32 - 1 (they are named by u32 indices)",
        });
    }
    if order.len() != vertices {
        return Err(SkinError::Count {
            rig: "the vertex order".into(),
            what: "vertices",
            expected: vertices,
            got: order.len(),
        });
    }
    let mut inverse = vec![u32::MAX; vertices];
    for (i, &v) in order.iter().enumerate() {
        let slot = inverse.get_mut(v as usize).ok_or(SkinError::OutOfRange {
            rig: "the vertex order".into(),
            what: format!("entry {i} names vertex"),
            index: v as usize,
            count: vertices,
        })?;
        if *slot != u32::MAX {
            return Err(SkinError::Parameter {
                what: "the vertex order",
                value: format!("names vertex {v} at positions {} and {i}:", *slot),
                reason: "must name each vertex once",
            });
        }
        *slot = i as u32;
    }
    Ok(inverse)
}

impl Rig {
    /// This rig with its vertices in `order` (`order[i]` is the vertex that becomes vertex
    /// i, as [`by_influence_count`] gives it): positions, normals and influences moved, the
    /// triangles' corners renumbered, the skeleton and clips as they are. Skinning it gives
    /// each vertex the same result, bit for bit, at its new index. An error unless `order`
    /// names each vertex once ([`inverse`]), or where the rig's public fields were changed
    /// into an inconsistent rig ([`Rig::validate`]).
    pub fn reordered(&self, order: &[u32]) -> Result<Rig> {
        self.validate()?;
        let n = self.mesh.positions.len();
        let new_of = inverse(order, n)?;
        let moved = |v: &[chasles::Vec3<f32>]| order.iter().map(|&o| v[o as usize]).collect();
        let triangles = self
            .mesh
            .triangles
            .iter()
            .map(|t| t.map(|c| new_of[c as usize]))
            .collect();
        let mut influences = Influences {
            start: Vec::with_capacity(n + 1),
            joints: Vec::with_capacity(self.influences.joints.len()),
            weights: Vec::with_capacity(self.influences.weights.len()),
        };
        influences.start.push(0);
        for &o in order {
            let row = self.influences.start[o as usize] as usize
                ..self.influences.start[o as usize + 1] as usize;
            influences
                .joints
                .extend_from_slice(&self.influences.joints[row.clone()]);
            influences
                .weights
                .extend_from_slice(&self.influences.weights[row]);
            influences.start.push(influences.joints.len() as u32);
        }
        Rig::new(
            self.name.clone(),
            Mesh {
                positions: moved(&self.mesh.positions),
                normals: moved(&self.mesh.normals),
                triangles,
            },
            self.nodes.clone(),
            self.joints.clone(),
            self.inverse_bind.clone(),
            influences,
            self.animations.clone(),
        )
    }
}

#[cfg(test)]
pub(crate) mod tests;
