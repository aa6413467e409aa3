//! Where the kernels write: a chunk of the caller's output in any of the job's three
//! layouts ([`super::Output`]), seen as two pointers and a stride, so that the SIMD
//! kernels store each block of eight vertices straight into an interleaved vertex buffer
//! or into split position and normal arrays as they do into the packed one — no stage on
//! the stack and no copy after it (Kavan et al. 2006, §6: the skinned vertices go to the
//! buffer that draws them) — and, scattered ([`Dest::scattered`]), each vertex to the slot
//! an order names (DIB's grouped path). Hand-written: it is a view of the caller's slices with the
//! kernels' store patterns in mind, which no crate models.

use super::Out;
use std::marker::PhantomData;

/// How a [`Dest`]'s vertices lie in memory.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Layout {
    /// 6 floats a vertex, back to back (the kernels' own layout; it may be streamed).
    Packed,
    /// `stride > 6` floats a vertex, position and normal in the first 6; the rest is not
    /// the kernels' to touch.
    Interleaved,
    /// Positions and normals in two arrays of 3 floats a vertex.
    Split,
    /// Any of the three, each vertex written to the slot an order names
    /// ([`Dest::scattered`]): DIB's grouped path (`super::grouped`) writes a grouped copy's
    /// results straight to their places in the rig's order.
    Scattered,
}

/// A mutable view of `len` vertices' outputs: vertex i's position at `pos + i·stride`,
/// its normal at `nrm + i·stride` (3 floats each). Made only from slices that hold every
/// float it names ([`Dest::packed`], [`Dest::interleaved`], [`Dest::split`]), so a write
/// through it to a vertex below `len` stays inside the caller's buffers. A scattered view
/// ([`Dest::scattered`]) puts its vertex i in slot `order[i] − base` instead, every one of
/// which its maker vouched lies inside them.
#[derive(Debug)]
pub(super) struct Dest<'a> {
    pos: *mut f32,
    nrm: *mut f32,
    stride: usize,
    len: usize,
    layout: Layout,
    /// [`Layout::Scattered`]: vertex i goes to slot `order[i] − base`; null otherwise.
    order: *const u32,
    base: usize,
    _out: PhantomData<&'a mut [f32]>,
}

impl<'a> Dest<'a> {
    /// The kernels' own layout.
    pub(super) fn packed(o: &'a mut [Out]) -> Self {
        let pos = o.as_mut_ptr() as *mut f32;
        Dest {
            pos,
            nrm: pos.wrapping_add(3),
            stride: 6,
            len: o.len(),
            layout: Layout::Packed,
            order: std::ptr::null(),
            base: 0,
            _out: PhantomData,
        }
    }

    /// `data.len() / stride` vertices of `stride` floats (at least 6; a stride of 6 is
    /// [`Dest::packed`]); a `data` shorter than a whole vertex holds none.
    pub(super) fn interleaved(data: &'a mut [f32], stride: usize) -> Self {
        if stride == 6 {
            let whole = data.len() / 6 * 6;
            return Dest::packed(bytemuck::cast_slice_mut(&mut data[..whole]));
        }
        assert!(
            stride > 6,
            "an interleaved output has at least 6 floats a vertex"
        );
        let pos = data.as_mut_ptr();
        Dest {
            pos,
            nrm: pos.wrapping_add(3),
            stride,
            len: data.len() / stride,
            layout: Layout::Interleaved,
            order: std::ptr::null(),
            base: 0,
            _out: PhantomData,
        }
    }

    /// Positions and normals apart; as many vertices as the shorter holds.
    pub(super) fn split(positions: &'a mut [[f32; 3]], normals: &'a mut [[f32; 3]]) -> Self {
        Dest {
            pos: positions.as_mut_ptr() as *mut f32,
            nrm: normals.as_mut_ptr() as *mut f32,
            stride: 3,
            len: positions.len().min(normals.len()),
            layout: Layout::Split,
            order: std::ptr::null(),
            base: 0,
            _out: PhantomData,
        }
    }

    /// This packed, interleaved or split view with its vertex i written to slot
    /// `order[i] − base`: `order.len()` vertices.
    ///
    /// # Safety
    /// `self` is not scattered already, and every `order[i] − base` lies in `0..self.len()`
    /// (a wrong order must not write outside the caller's buffers; only such a check makes
    /// the view's writes, unchecked by then, sound).
    pub(super) unsafe fn scattered(self, order: &'a [u32], base: usize) -> Self {
        debug_assert!(self.layout != Layout::Scattered);
        debug_assert!(order
            .iter()
            .all(|&o| (o as usize).checked_sub(base).is_some_and(|s| s < self.len)));
        Dest {
            len: order.len(),
            layout: Layout::Scattered,
            order: order.as_ptr(),
            base,
            ..self
        }
    }

    /// How many vertices it holds.
    pub(super) fn len(&self) -> usize {
        self.len
    }

    /// Its layout.
    pub(super) fn layout(&self) -> Layout {
        self.layout
    }

    /// Floats from one vertex to the next.
    pub(super) fn stride(&self) -> usize {
        self.stride
    }

    /// Vertices `from..to` of it, borrowed.
    pub(super) fn range(&mut self, from: usize, to: usize) -> Dest<'_> {
        assert!(from <= to && to <= self.len, "{from}..{to} of {}", self.len);
        if self.layout == Layout::Scattered {
            // The slots stay where they are; the order moves on.
            return Dest {
                order: self.order.wrapping_add(from),
                len: to - from,
                ..*self
            };
        }
        Dest {
            pos: self.pos.wrapping_add(from * self.stride),
            nrm: self.nrm.wrapping_add(from * self.stride),
            len: to - from,
            ..*self
        }
    }

    /// Writes vertex `i`'s position and normal (`o[0..3]`, `o[3..6]`), as values: copied
    /// from a pointer into `o`, each vertex went through a copy on the stack whose 12-byte
    /// halves were read back across the copy's two stores, which stalls each read (DIB's
    /// grouped path, `super::grouped`, once spent a third of its time putting its stage out
    /// so). A scattered view writes it to its slot. Panics past the end, out of line.
    #[inline(always)]
    pub(super) fn put(&mut self, i: usize, o: Out) {
        if i >= self.len {
            past_the_end(i, self.len);
        }
        // SAFETY: vertex i < len of a Dest made from slices that hold it (see the type);
        // the writes are unaligned (an interleaved buffer's floats are only 4-byte aligned).
        unsafe {
            let (p, n) = if self.layout == Layout::Scattered {
                self.slot(i)
            } else {
                self.at(i)
            };
            if self.layout == Layout::Packed {
                // The normal follows the position: one write of six floats.
                p.cast::<Out>().write_unaligned(o);
            } else {
                p.cast::<[f32; 3]>().write_unaligned([o[0], o[1], o[2]]);
                n.cast::<[f32; 3]>().write_unaligned([o[3], o[4], o[5]]);
            }
        }
    }

    /// Vertex `i`'s position and normal pointers, for the SIMD kernels' stores.
    ///
    /// # Safety
    /// `i < len`, and the view is not scattered (a scattered view's `len` counts its order,
    /// not its slots: [`Dest::slot`]).
    pub(super) unsafe fn at(&self, i: usize) -> (*mut f32, *mut f32) {
        debug_assert!(i < self.len && self.layout != Layout::Scattered);
        // SAFETY: vertex i's floats lie in the slices the Dest was made from.
        unsafe { (self.pos.add(i * self.stride), self.nrm.add(i * self.stride)) }
    }

    /// Vertex `i`'s position and normal pointers in a scattered view: those of slot
    /// `order[i] − base`.
    ///
    /// # Safety
    /// `i < len`, the view scattered.
    #[inline(always)]
    pub(super) unsafe fn slot(&self, i: usize) -> (*mut f32, *mut f32) {
        debug_assert!(i < self.len && self.layout == Layout::Scattered);
        // SAFETY: `order` holds `len` entries, each naming a slot of the buffers
        // (`scattered`'s contract).
        unsafe {
            let s = (*self.order.add(i) as usize - self.base) * self.stride;
            (self.pos.add(s), self.nrm.add(s))
        }
    }

    /// The address of vertex 0's position (alignment checks for streaming).
    pub(super) fn addr(&self) -> usize {
        self.pos as usize
    }
}

/// The panic of a write past a [`Dest`]'s end, out of line: its message's arguments are
/// made here, not spilled to the stack on every [`Dest::put`].
#[cold]
#[inline(never)]
fn past_the_end(i: usize, len: usize) -> ! {
    panic!("vertex {i} of {len}")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_layout_puts_a_vertex_where_it_belongs_and_nowhere_else() {
        let o = [1.0, 2.0, 3.0, 4.0, 5.0, 6.0];
        let mut packed = vec![[0f32; 6]; 3];
        Dest::packed(&mut packed).range(1, 3).put(1, o);
        assert_eq!(packed, [[0.0; 6], [0.0; 6], o]);

        let mut inter = vec![-1f32; 3 * 8];
        let mut d = Dest::interleaved(&mut inter, 8);
        assert_eq!(
            (d.len(), d.layout(), d.stride()),
            (3, Layout::Interleaved, 8)
        );
        d.put(1, o);
        let mut want = vec![-1f32; 24];
        want[8..14].copy_from_slice(&o);
        assert_eq!(inter, want);

        let mut six = vec![0f32; 13]; // two whole vertices and a float
        let d = Dest::interleaved(&mut six, 6);
        assert_eq!((d.len(), d.layout()), (2, Layout::Packed));

        let (mut p, mut n) = (vec![[0f32; 3]; 2], vec![[0f32; 3]; 2]);
        Dest::split(&mut p, &mut n).put(0, o);
        assert_eq!(
            (p[0], n[0], p[1], n[1]),
            ([1.0, 2.0, 3.0], [4.0, 5.0, 6.0], [0.0; 3], [0.0; 3])
        );
    }

    #[test]
    fn a_scattered_view_puts_each_vertex_in_its_slot() {
        let o = |k: f32| [k, k + 0.1, k + 0.2, k + 0.3, k + 0.4, k + 0.5];
        // Slots 10..14 of the caller's numbering: vertex i of the view goes to order[i] − 10.
        let order = [12u32, 10, 13, 11];
        let mut packed = vec![[0f32; 6]; 4];
        // SAFETY: every order[i] − 10 is below 4.
        let mut d = unsafe { Dest::packed(&mut packed).scattered(&order, 10) };
        assert_eq!((d.len(), d.layout()), (4, Layout::Scattered));
        for i in 0..4 {
            d.put(i, o(i as f32));
        }
        assert_eq!(packed, [o(1.0), o(3.0), o(0.0), o(2.0)]);
        // A range moves along the order, not the slots.
        let mut inter = vec![-1f32; 4 * 8];
        // SAFETY: as above.
        let mut d = unsafe { Dest::interleaved(&mut inter, 8).scattered(&order, 10) };
        d.range(2, 4).put(1, o(7.0));
        let mut want = vec![-1f32; 32];
        want[8..14].copy_from_slice(&o(7.0));
        assert_eq!(inter, want);
        let (mut p, mut n) = (vec![[0f32; 3]; 4], vec![[0f32; 3]; 4]);
        // SAFETY: as above.
        unsafe { Dest::split(&mut p, &mut n).scattered(&order, 10) }.put(0, o(5.0));
        assert_eq!((p[2], n[2]), ([5.0, 5.1, 5.2], [5.3, 5.4, 5.5]));
        assert_eq!(p.iter().filter(|p| **p == [0.0; 3]).count(), 3);
        assert_eq!(n.iter().filter(|n| **n == [0.0; 3]).count(), 3);
    }

    #[test]
    #[should_panic(expected = "vertex 2 of 2")]
    fn a_vertex_past_the_end_is_refused() {
        let mut p = vec![[0f32; 6]; 4];
        Dest::packed(&mut p).range(1, 3).put(2, [0.0; 6]);
    }
}
