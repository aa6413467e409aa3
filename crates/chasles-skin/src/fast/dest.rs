//! Where the kernels write: a chunk of the caller's output in any of the job's three
//! layouts ([`super::Output`]), seen as two pointers and a stride, so that the SIMD
//! kernels store each block of eight vertices straight into an interleaved vertex buffer
//! or into split position and normal arrays as they do into the packed one — no stage on
//! the stack and no copy after it (Kavan et al. 2006, §6: the skinned vertices go to the
//! buffer that draws them). Hand-written: it is a view of the caller's slices with the
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
}

/// A mutable view of `len` vertices' outputs: vertex i's position at `pos + i·stride`,
/// its normal at `nrm + i·stride` (3 floats each). Made only from slices that hold every
/// float it names ([`Dest::packed`], [`Dest::interleaved`], [`Dest::split`]), so a write
/// through it to a vertex below `len` stays inside the caller's buffers.
#[derive(Debug)]
pub(super) struct Dest<'a> {
    pos: *mut f32,
    nrm: *mut f32,
    stride: usize,
    len: usize,
    layout: Layout,
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
            _out: PhantomData,
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
        Dest {
            pos: self.pos.wrapping_add(from * self.stride),
            nrm: self.nrm.wrapping_add(from * self.stride),
            stride: self.stride,
            len: to - from,
            layout: self.layout,
            _out: PhantomData,
        }
    }

    /// Writes vertex `i`'s position and normal (`o[0..3]`, `o[3..6]`), as values: copied
    /// from a pointer into `o`, each vertex went through a copy on the stack whose 12-byte
    /// halves were read back across the copy's two stores, which stalls each read (DIB's
    /// grouped path, `super::grouped`, spent a third of its time putting its stage out).
    #[inline(always)]
    pub(super) fn put(&mut self, i: usize, o: Out) {
        assert!(i < self.len, "vertex {i} of {}", self.len);
        // SAFETY: vertex i < len of a Dest made from slices that hold it (see the type);
        // the writes are unaligned (an interleaved buffer's floats are only 4-byte aligned).
        unsafe {
            let (p, n) = self.at(i);
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
    /// `i < len`.
    pub(super) unsafe fn at(&self, i: usize) -> (*mut f32, *mut f32) {
        debug_assert!(i < self.len);
        // SAFETY: vertex i's floats lie in the slices the Dest was made from.
        unsafe { (self.pos.add(i * self.stride), self.nrm.add(i * self.stride)) }
    }

    /// The address of vertex 0's position (alignment checks for streaming).
    pub(super) fn addr(&self) -> usize {
        self.pos as usize
    }
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
    #[should_panic(expected = "vertex 2 of 2")]
    fn a_vertex_past_the_end_is_refused() {
        let mut p = vec![[0f32; 6]; 4];
        Dest::packed(&mut p).range(1, 3).put(2, [0.0; 6]);
    }
}
