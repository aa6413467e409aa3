//! The eight-vertex kernels compiled twice (Log's for four influences): for AVX2 and FMA, and, for processors with
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
//! way, so only the speed shows it (a unit test counts the wide build's runs). With eight
//! influences, index arithmetic written as one array (`vx.j.map(…)`) became 512-bit vector
//! code in the wide build (`vpmovzxwd`/`vpslld` on `zmm`: on Intel a 512-bit operation in
//! flight takes port 1's vector unit away from the others), and LBS and Log ran a quarter
//! slower than on AVX2; those blends now widen eight influences' indices where each is
//! used (four's are as they were measured), and no `zmm` register appears in these builds
//! (checked by disassembly). Log with eight influences still ran slower with 32 registers
//! (2.5·10⁴ vertices: 172–182 → 146–162 M vertices/s) and keeps the AVX2 build alone; with
//! eight, DQS (176–187 → 188–212), LBS (131–133 → 133–144) and QLB (72–82 → 91–93) gain.
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
    debug_assert!(
        std::is_x86_feature_detected!("avx512f") && std::is_x86_feature_detected!("avx512vl")
    );
    #[cfg(test)]
    WIDE_RUNS.with(|n| n.set(n.get() + 1));
    f()
}

#[cfg(test)]
thread_local! {
    /// How many times [`wide`] ran on this thread (the tests' evidence of which build ran).
    static WIDE_RUNS: std::cell::Cell<usize> = const { std::cell::Cell::new(0) };
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

#[cfg(test)]
mod tests {
    use super::WIDE_RUNS;
    use crate::fast::{dqs, dual_quats8, lbs, log, matrices12, qlb, sbs, traffic, twists};
    use crate::fast::{set_avx512, simd, uses_avx512, FastRig, Out};
    use crate::synthetic;

    /// How many times `f` ran the AVX-512 build on this thread.
    fn wide_runs(f: impl FnOnce()) -> usize {
        let before = WIDE_RUNS.with(|n| n.get());
        f();
        WIDE_RUNS.with(|n| n.get()) - before
    }

    /// The AVX-512 build runs exactly where `uses_avx512` says, and never once
    /// `set_avx512(false)` forbids it: each kernel on one thread (this one) over one chunk of
    /// 4096 vertices (one kernel call), the runs of [`super::wide`] counted kernel by kernel;
    /// with eight influences Log keeps the AVX2 build and DQS takes the wide one. (Another
    /// test flipping the switch meanwhile would only move its own jobs between two builds
    /// that give the same bits; none does.)
    #[test]
    fn the_wide_build_runs_where_avx512_is_allowed_and_present() {
        if !simd(4) {
            eprintln!("no AVX2+FMA here: no SIMD kernel to count");
            return;
        }
        let rig = synthetic::rig(4096, 54, 3);
        let eight: FastRig<8> = synthetic::rig_with(4096, 54, 3);
        let jt = synthetic::joints(54, 3);
        let (m12, d8, tw) = (matrices12(&jt), dual_quats8(&jt), twists(&jt).unwrap());
        let d = &jt.dual_quats;
        let mut out: Vec<Out> = vec![[0.0; 6]; 4096];
        for allowed in [false, true] {
            set_avx512(allowed);
            let on = usize::from(uses_avx512(4));
            assert!(allowed || on == 0);
            let o = &mut out;
            let runs = [
                wide_runs(|| dqs(&rig, &d8, o, false).unwrap()),
                wide_runs(|| lbs(&rig, &m12, o, false).unwrap()),
                wide_runs(|| log(&rig, &tw, o, false).unwrap()),
                wide_runs(|| qlb(&rig, d, o, false).unwrap()),
                wide_runs(|| sbs(&rig, rig.clusters(), d, o, false).unwrap()),
                wide_runs(|| traffic(&rig, &mut o[..], false).unwrap()),
                wide_runs(|| dqs(&eight, &d8, o, false).unwrap()),
                wide_runs(|| log(&eight, &tw, o, false).unwrap()),
            ];
            assert_eq!(
                runs,
                [on, on, on, on, on, on, on, 0],
                "allowed {allowed}: DQS, LBS, Log, QLB, SBS, traffic; DQS and Log of eight"
            );
        }
    }
}
