//! Stack frames of SIMD kernels aligned to a cache line — a performance detail of the
//! kernels in `chasles-skin` and the Python package, not of the papers' mathematics.
//!
//! A kernel compiled for AVX2 (`#[target_feature(enable = "avx2")]`) that keeps more
//! 32-byte vectors alive than there are registers spills some to its stack frame. Rust's
//! frames are 16-byte aligned; the compiler realigns a frame to 32 bytes for some
//! functions and not for others (in one build the DIB kernel's and two of three QLB
//! instances' frames were realigned, LBS's, DQS's and one QLB instance's were not). Where
//! it does not, it writes the spills with unaligned moves, and half the 32-byte slots
//! straddle two cache lines; where the spill area straddles a page boundary — decided by
//! where the stack happens to land (address-space randomization, the size of the
//! environment) — every iteration pays for page-split stores and their reloads. On an AMD
//! EPYC (Zen 4) that ran `chasles-skin`'s QLB, SBS and LBS kernels about 3× slower for a
//! whole run in about one process in five (see the README's Speed section for the
//! measurements). [`align_frame`] makes the compiler align the caller's whole frame to 64
//! bytes in every build, so every spill slot sits inside one line. No crate does this: it
//! is a property of one function's frame, which only a local of that function can ask for.

/// Makes the compiler align the frame of the function it is inlined into to 64 bytes, by
/// giving that frame a cache-line-aligned local whose address escapes (it is never written
/// or read). Call it first in a SIMD kernel that spills vectors; the alignment holds for
/// the whole frame, whatever the local's lifetime. It costs the frame's realignment in the
/// prologue (two instructions a call) and a register (`rbp` holds the frame). Call it in the
/// function whose frame holds the spills: a call in a caller does nothing for a callee that
/// is not inlined into it.
#[inline(always)]
pub fn align_frame() {
    #[repr(C, align(64))]
    struct Line([u8; 64]);
    let mut line = core::mem::MaybeUninit::<Line>::uninit();
    core::hint::black_box(&mut line);
}
