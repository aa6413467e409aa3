//! The eight-vertex kernels compiled twice: for AVX2 and FMA, and, for processors with
//! AVX-512F and AVX-512VL (chosen at run time; `set_avx512` forbids it), with those as well —
//! the same source and the same 256-bit operations, so the same numbers bit for bit (the
//! tests compare every method's output both ways), but 32 vector registers where AVX2 has
//! 16, and the EVEX encodings. Each kernel's loop keeps a block's blends, positions and
//! normals, the transform's terms and the stores' shuffles alive at once; in sixteen
//! registers the compiler spills some of them to the stack and reloads them, one store and
//! one load each, in a loop that is bound by how many instructions it issues a cycle, not by
//! its arithmetic (the DQS loop: 359 instructions a block of eight on AVX2, 334–338 with
//! the wider register file).
//!
//! Each build must hold its own copy of the loop: the kernels' loops and [`by_target!`]'s
//! closures are `#[inline(always)]`. With plain closures the compiler left QLB's as one
//! function that both builds called, compiled for AVX2 alone, and an array's `map` in LBS's
//! loop stayed a call; the `avx512` test (every method both ways, bit for bit) runs either
//! way, so only the speed shows it.
//!
//! Measured on a 2-core Intel Xeon (family 6, model 167, AVX-512F and VL), one core, 54
//! joints, four influences, each kernel alone on the synthetic mesh (a scratch loop; the two
//! builds in turn by `set_avx512`, four runs of 40 passes, medians), 2026-12-04, M
//! vertices/s at 2.5·10⁴ vertices (in the second-level cache), 10⁵ and 2·10⁵: DQS 348–349 →
//! 358–361, 328–332 → 340–353 and 309–318 → 314–335; LBS 267–268 → 289–294, 257–263 →
//! 281–288 and 236–257 → 259–280; Log 287–288 → 298–304, 274–281 → 290–294 and 260–281 →
//! 269–274; QLB and SBS's loop 147–155 → 163–169, 148–153 → 158–166 and 144–152 → 154–163.
//! DIB keeps its own sixteen-lane kernel (`avx512`) where the processor has AVX-512; its
//! eight-lane kernel, which runs there only for a chunk's last eight, is built for AVX2
//! alone.
//!
//! Wide registers, not wide lanes: the 512-bit kernels for these methods would halve the
//! lane work, but a block's blend is one 256-bit register a vertex either way, and on Intel
//! 512-bit operations issue on two ports where 256-bit ones issue on three.

/// Runs `f` in code compiled for AVX2 and FMA (the closure, and what it inlines).
///
/// # Safety
/// The processor must have AVX2 and FMA.
#[target_feature(enable = "avx2,fma")]
pub(in crate::fast) unsafe fn narrow<R>(f: impl FnOnce() -> R) -> R {
    f()
}

/// Runs `f` in code compiled for AVX2, FMA, AVX-512F and AVX-512VL.
///
/// # Safety
/// The processor must have all four.
#[target_feature(enable = "avx2,fma,avx512f,avx512vl")]
pub(in crate::fast) unsafe fn wide<R>(f: impl FnOnce() -> R) -> R {
    f()
}

/// `by_layout!($o, $s => $body)` compiled by [`wide`] where the processor has AVX-512F
/// and AVX-512VL and they are allowed (`fast::avx512`), else by [`narrow`]: a kernel's loop
/// made once per register file and layout, the one for this processor and `$o` run.
/// Unsafe: the processor must have AVX2 and FMA.
macro_rules! by_target {
    ($o:expr, $s:ident => $body:expr) => {
        if $crate::fast::avx512() {
            $crate::fast::avx2::registers::wide(#[inline(always)] || $crate::fast::avx2::by_layout!($o, $s => $body))
        } else {
            $crate::fast::avx2::registers::narrow(#[inline(always)] || $crate::fast::avx2::by_layout!($o, $s => $body))
        }
    };
}
pub(in crate::fast) use by_target;
