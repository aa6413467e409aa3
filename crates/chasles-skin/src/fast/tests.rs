//! The fast path's SIMD kernels against the scalar ones (x86-64 with AVX2 and FMA; elsewhere
//! there is nothing to compare).

use super::*;
use crate::synthetic;
use dest::Dest;

/// A SIMD kernel's output on the whole blocks of `rig` (checked to be all of them but
/// the last few vertices), and the scalar kernel's on the same vertices.
fn both<const K: usize, F: Kernel<K>>(
    rig: &FastRig<K>,
    joints: &[F::Joint],
    kernel: SimdKernel<K, F::Joint, F::Table>,
) -> [Vec<Out>; 2] {
    let n = rig.vertices.len();
    let mut simd = vec![[f32::NAN; 6]; n];
    // SAFETY: the callers check `simd(K)`; the rig's joint indices are below its joint
    // count, which is `joints.len()`; the table is made from `joints`; `simd` is as
    // long as the vertices.
    let done = unsafe {
        kernel(
            &rig.vertices,
            joints,
            &F::table(joints, n),
            Dest::packed(&mut simd),
            false,
        )
    };
    assert_eq!(done, n / 8 * 8, "the SIMD kernel did every whole block");
    simd.truncate(done);
    let scalar = rig.vertices[..done]
        .iter()
        .map(|v| F::vertex(v, joints))
        .collect();
    [simd, scalar]
}

/// The largest difference of two outputs, and the share of vertices within `tol`.
fn apart(a: &[Out], b: &[Out], tol: f32) -> (f32, f64) {
    let d: Vec<f32> = a.iter().zip(b).map(|(a, b)| max_diff(a, b)).collect();
    let within = d.iter().filter(|x| **x <= tol).count() as f64 / d.len() as f64;
    (d.iter().copied().fold(0f32, f32::max), within)
}

/// 8 influences: the SIMD kernels are the scalar ones to rounding (DIB within the stopping
/// rule's reach of it), SBS included.
#[test]
fn the_simd_kernels_take_8_influences() {
    if !simd(8) {
        eprintln!("no AVX2+FMA here: nothing to compare");
        return;
    }
    let rig = synthetic::rig_with::<8>(1003, 54, 7);
    let jt = synthetic::joints(54, 7);
    let d8 = dual_quats8(&jt);
    let [a, b] = both::<8, LbsKernel>(&rig, &matrices12(&jt), avx2::lbs);
    assert!(
        apart(&a, &b, 2e-6).1 == 1.0,
        "LBS {:?}",
        apart(&a, &b, 2e-6)
    );
    let [a, b] = both::<8, DqsKernel>(&rig, &d8, avx2::dqs);
    assert!(
        apart(&a, &b, 2e-6).1 == 1.0,
        "DQS {:?}",
        apart(&a, &b, 2e-6)
    );
    let t = log::rows(&twists(&jt).unwrap());
    let [a, b] = both::<8, log::LogKernel>(&rig, &t, avx2::log::log);
    assert!(
        apart(&a, &b, 2e-6).1 == 1.0,
        "Log {:?}",
        apart(&a, &b, 2e-6)
    );
    let rows = qlb::rows(&jt.dual_quats, rig.centres());
    let [a, b] = both::<8, qlb::QlbKernel>(&rig, &rows, avx2::qlb::qlb);
    assert!(
        apart(&a, &b, 4e-6).1 == 1.0,
        "QLB {:?}",
        apart(&a, &b, 4e-6)
    );
    let [a, b] = both::<8, dib::DibKernel>(&rig, &d8, avx2::dib::dib);
    // DIB: the SIMD kernel's second-order step and the scalar kernel's plain one end at
    // different points within the stopping rule's reach of the exact blend
    // (`avx2::dib`'s tests hold both against it).
    let (most, _) = apart(&a, &b, 2e-6);
    assert!(most < 1e-4, "DIB {most}");
    // SBS: the SIMD kernel against the scalar one about the same cluster centres.
    let cl = clusters(&rig);
    let padded = qlb::padded_centres(&cl, &jt.dual_quats, rig.centres(), false);
    let mut o = vec![[f32::NAN; 6]; 1003];
    let table = Antipodes::rows(&rows, 1003);
    // SAFETY: as in `both`, and every cluster index is below `padded.len()`.
    let done = unsafe {
        avx2::qlb::about::<_, true>(
            &rig.vertices,
            &rows,
            &table,
            cl.of_vertex(),
            &padded,
            Dest::packed(&mut o),
            false,
        )
    };
    assert_eq!(done, 1000);
    let want: Vec<Out> = rig.vertices[..done]
        .iter()
        .zip(cl.of_vertex())
        .map(|(v, c)| {
            let [x, y, z, _] = padded[*c as usize];
            qlb::about(v, &qlb::blend(v, &rows), [x, y, z])
        })
        .collect();
    let (most, within) = apart(&o[..done], &want, 4e-6);
    assert!(within == 1.0, "SBS {most}");
}

/// Every SIMD kernel writes the same numbers by non-temporal stores (into 32-byte aligned
/// output) as by ordinary ones, and into interleaved buffers (strides 6 — the packed
/// layout — 7, 8 and 11) and split arrays, bit for bit; in those it writes each vertex's
/// six floats and nothing else (the other floats of a vertex, and everything past the
/// blocks, keep their marks). With 4 and 8 influences, and with the antipodality signs
/// from dot products (1003 vertices: too few for a table of 54 joints) and from the
/// table (4099).
#[test]
fn every_layout_gets_the_stored_output_and_nothing_else_is_written() {
    if !simd(4) {
        eprintln!("no AVX2+FMA here: nothing to compare");
        return;
    }
    for n in [1003, 4099] {
        layouts::<4>(n);
        layouts::<8>(n);
    }
}

/// [`every_layout_gets_the_stored_output_and_nothing_else_is_written`] on a synthetic rig
/// of `n` vertices with K influences.
fn layouts<const K: usize>(n: usize) {
    let rig = synthetic::rig_with::<K>(n, 54, 7);
    let jt = synthetic::joints(54, 7);
    let d8 = dual_quats8(&jt);
    let m12 = matrices12(&jt);
    let t = log::rows(&twists(&jt).unwrap());
    let rows = qlb::rows(&jt.dual_quats, rig.centres());
    let cl = clusters(&rig);
    let padded = qlb::padded_centres(&cl, &jt.dual_quats, rig.centres(), false);
    let sbs = |v: &[Vertex<K>], rows: &[qlb::Row], table: &Antipodes, o: Dest<'_>, s| {
        // SAFETY: as in `both`, and every cluster index is below `padded.len()`.
        unsafe { avx2::qlb::about::<_, true>(v, rows, table, cl.of_vertex(), &padded, o, s) }
    };
    let mut buf = vec![[f32::NAN; 6]; n + 4];
    let (lead, streams) = simd_start(&Dest::packed(&mut buf), true);
    assert!(
        streams,
        "a heap buffer is 8-byte aligned: some vertex of the first four is 32"
    );
    let mark = f32::from_bits(0x7fc0_1234); // a NaN no kernel writes
    let marked = |x: &f32| x.to_bits() == mark.to_bits();
    let mut run = |k: &dyn Fn(Dest<'_>, bool) -> usize| {
        let stored = {
            let mut o = vec![[f32::NAN; 6]; n];
            let done = k(Dest::packed(&mut o), false);
            o.truncate(done);
            o
        };
        let done = stored.len();
        let o = &mut buf[lead..lead + n];
        o.fill([mark; 6]);
        assert_eq!(k(Dest::packed(o), true), done);
        fence_streams();
        assert_eq!(&o[..done], &stored[..], "streamed output differs");
        assert!(
            o[done..].iter().flatten().all(marked),
            "wrote past the blocks"
        );
        for stride in [6, 7, 8, 11] {
            let mut d = vec![mark; n * stride];
            assert_eq!(k(Dest::interleaved(&mut d, stride), false), done);
            for (l, v) in d.chunks_exact(stride).enumerate() {
                if l < done {
                    assert_eq!(v[..6], stored[l], "stride {stride}, vertex {l}");
                    assert!(
                        v[6..].iter().all(marked),
                        "stride {stride}: wrote past vertex {l}"
                    );
                } else {
                    assert!(
                        v.iter().all(marked),
                        "stride {stride}: wrote past the blocks"
                    );
                }
            }
        }
        let (mut p, mut nr) = (vec![[mark; 3]; n], vec![[mark; 3]; n]);
        assert_eq!(k(Dest::split(&mut p, &mut nr), false), done);
        for (l, s) in stored.iter().enumerate() {
            assert_eq!(
                (&p[l][..], &nr[l][..]),
                (&s[..3], &s[3..]),
                "split, vertex {l}"
            );
        }
        let rest = p[done..].iter().chain(&nr[done..]).flatten();
        assert!(rest.clone().all(marked), "split: wrote past the blocks");
    };
    let copies = Antipodes::copies(&d8, n);
    let qcopies = Antipodes::rows(&rows, n);
    assert_eq!(
        (copies.is_empty(), qcopies.is_empty()),
        (n < 54 * 54, n < 54 * 54)
    );
    // SAFETY (each kernel): the processor has AVX2 and FMA (`simd`), the synthetic rig's joint
    // indices are below 54 = every joint table's length, the antipodality tables are made
    // from the joints they are used with, outputs are as long as the vertices, and a streamed output
    // starts 32-byte aligned (`simd_start`).
    let v = rig.vertices();
    run(&|o, s| unsafe { avx2::lbs(v, &m12, &(), o, s) });
    run(&|o, s| unsafe { avx2::dqs(v, &d8, &copies, o, s) });
    run(&|o, s| unsafe { avx2::log::log(v, &t, &(), o, s) });
    run(&|o, s| unsafe { avx2::qlb::qlb(v, &rows, &qcopies, o, s) });
    run(&|o, s| unsafe { avx2::dib::dib(v, &d8, &(), o, s) });
    run(&|o, s| sbs(v, &rows, &qcopies, o, s));
    let units = vec![(); 54];
    run(&|o, s| unsafe { avx2::traffic::traffic(v, &units, &(), o, s) });
}

/// A mesh big enough to stream ([`STREAM_VERTICES`]): every method's job writes the same
/// numbers, bit for bit and to every vertex, into a packed output (streamed; its first
/// vertices and last few by overlapping blocks of ordinary stores) at each of its eight
/// offsets from a 64-byte line (each shifts the grid of chunks, job.rs's `Grid`) and into
/// an interleaved one of stride 6 (packed too) as into one of stride 7 (written in place,
/// not streamed), on all threads; with the grid from 0 its last chunk would hold 4
/// vertices (joined to the one before).
#[test]
fn big_meshes_stream_the_same_numbers() {
    use crate::Method;
    let n = STREAM_VERTICES + 4;
    let rig = synthetic::rig(n, 54, 3);
    let jt = synthetic::joints(54, 3);
    let mut buffer = vec![[0f32; 6]; n + 8];
    let mut inter = vec![0f32; n * 7];
    let bits = |v: &[f32]| v.iter().map(|x| x.to_bits()).collect::<Vec<u32>>();
    for m in Method::ALL {
        let palette = Palette::from_joint_transforms(m, &rig, &jt, true).unwrap();
        let job = |output: Output<'_>| {
            SkinningJob {
                rig: &rig,
                palette: &palette,
                output,
                parallel: true,
            }
            .run()
            .unwrap()
        };
        inter.fill(f32::NAN);
        job(Output::Interleaved {
            data: &mut inter,
            stride: 7,
        });
        let want: Vec<u32> = inter.chunks_exact(7).flat_map(|v| bits(&v[..6])).collect();
        // Packed at offsets 0-7, then stride 6 at offset 3.
        for (offset, six) in (0..8).map(|o| (o, false)).chain([(3, true)]) {
            buffer.fill([f32::NAN; 6]);
            let out = &mut buffer[offset..offset + n];
            job(if six {
                Output::Interleaved {
                    data: bytemuck::cast_slice_mut(out),
                    stride: 6,
                }
            } else {
                Output::Packed(out)
            });
            let got = bits(bytemuck::cast_slice(&buffer[offset..offset + n]));
            let bad = got.iter().zip(&want).position(|(a, b)| a != b);
            assert_eq!(
                bad,
                None,
                "{}, offset {offset}, stride 6 {six}: first float apart",
                m.name()
            );
        }
    }
}

/// A mesh whose last chunk would hold 1–7 vertices skins them through the SIMD kernel, as
/// it does every other vertex: each method's job gives every vertex of a mesh of
/// `2 CHUNK + 3` the same bits as the same vertices with eight more after them (whose last
/// chunk is 11 long), on one thread and on all. With the last 3 on their own, they went
/// through the scalar kernel, whose bits differ.
#[test]
fn the_last_few_vertices_get_the_simd_kernels_numbers() {
    use crate::Method;
    if !simd(4) {
        eprintln!("skipped: no AVX2 and FMA here");
        return;
    }
    let n = 2 * CHUNK + 3;
    let longer = synthetic::rig(n + 8, 54, 5);
    let rig =
        FastRig::<4>::from_vertices(longer.vertices()[..n].to_vec(), longer.centres().to_vec())
            .unwrap();
    let jt = synthetic::joints(54, 5);
    for m in Method::ALL {
        for parallel in [false, true] {
            let skin = |rig: &FastRig<4>| {
                let palette = Palette::from_joint_transforms(m, rig, &jt, true).unwrap();
                let mut out = vec![[f32::NAN; 6]; rig.vertices().len()];
                SkinningJob {
                    rig,
                    palette: &palette,
                    output: Output::Packed(&mut out),
                    parallel,
                }
                .run()
                .unwrap();
                out
            };
            let (short, long) = (skin(&rig), skin(&longer));
            assert_eq!(short[..], long[..n], "{}, parallel {parallel}", m.name());
        }
    }
}

/// The kernels whose loop takes the next block ahead before it ends this one (DQS, LBS,
/// Log, QLB and SBS) on the first n vertices of a rig, n = 0 … 24 (no block, one, two and
/// three, each with a few after): each does the whole blocks, writes the very bits it
/// writes for those vertices in a run over the whole rig, and nothing past them. DQS, QLB
/// and SBS with and without their antipodality tables, 4 and 8 influences. (A read past
/// the n vertices would not show here: the slice lies within the rig's vertices.)
#[test]
fn the_blocks_ahead_end_where_the_mesh_ends() {
    if !simd(4) {
        eprintln!("no AVX2+FMA here: nothing to compare");
        return;
    }
    short_meshes::<4>();
    short_meshes::<8>();
}

/// [`the_blocks_ahead_end_where_the_mesh_ends`] with K influences.
fn short_meshes<const K: usize>() {
    let rig = synthetic::rig_with::<K>(4099, 54, 9);
    let jt = synthetic::joints(54, 9);
    let (d8, m12) = (dual_quats8(&jt), matrices12(&jt));
    let t = log::rows(&twists(&jt).unwrap());
    let (copies, none) = (Antipodes::copies(&d8, 4099), Antipodes::default());
    let rows = qlb::rows(&jt.dual_quats, rig.centres());
    let qcopies = Antipodes::rows(&rows, 4099);
    assert!(!copies.is_empty() && !qcopies.is_empty());
    let cl = clusters(&rig);
    let padded = qlb::padded_centres(&cl, &jt.dual_quats, rig.centres(), false);
    let mark = f32::from_bits(0x7fc0_1234); // a NaN no kernel writes
    type Run<'a, const K: usize> = Box<dyn Fn(&[Vertex<K>], Dest<'_>) -> usize + 'a>;
    // SAFETY (each kernel): the processor has AVX2 and FMA (`simd`), the synthetic rig's
    // joint indices are below 54 = every joint table's length, the tables are made from
    // the joints they are used with, each output is as long as the vertices, and every
    // cluster index is below `padded.len()`.
    let kernels: [(&str, Run<'_, K>); 8] = [
        (
            "QLB",
            Box::new(|v, o| unsafe { avx2::qlb::qlb(v, &rows, &qcopies, o, false) }),
        ),
        (
            "QLB, no table",
            Box::new(|v, o| unsafe { avx2::qlb::qlb(v, &rows, &none, o, false) }),
        ),
        (
            "SBS",
            Box::new(|v, o| unsafe {
                avx2::qlb::about::<_, true>(v, &rows, &qcopies, cl.of_vertex(), &padded, o, false)
            }),
        ),
        (
            "SBS, no table",
            Box::new(|v, o| unsafe {
                avx2::qlb::about::<_, true>(v, &rows, &none, cl.of_vertex(), &padded, o, false)
            }),
        ),
        (
            "LBS",
            Box::new(|v, o| unsafe { avx2::lbs(v, &m12, &(), o, false) }),
        ),
        (
            "DQS",
            Box::new(|v, o| unsafe { avx2::dqs(v, &d8, &copies, o, false) }),
        ),
        (
            "DQS, no table",
            Box::new(|v, o| unsafe { avx2::dqs(v, &d8, &none, o, false) }),
        ),
        (
            "Log",
            Box::new(|v, o| unsafe { avx2::log::log(v, &t, &(), o, false) }),
        ),
    ];
    for (name, k) in &kernels {
        let mut all = vec![[f32::NAN; 6]; 4099];
        assert_eq!(k(rig.vertices(), Dest::packed(&mut all)), 4096);
        for n in 0..=24 {
            let mut o = vec![[mark; 6]; n];
            let done = k(&rig.vertices()[..n], Dest::packed(&mut o));
            assert_eq!(done, n / 8 * 8, "{name}, {n} vertices");
            let bits = |v: &[Out]| v.iter().flatten().map(|x| x.to_bits()).collect::<Vec<_>>();
            assert_eq!(bits(&o[..done]), bits(&all[..done]), "{name}, {n} vertices");
            assert!(
                o[done..]
                    .iter()
                    .flatten()
                    .all(|x| x.to_bits() == mark.to_bits()),
                "{name}, {n} vertices: wrote past the blocks"
            );
        }
    }
}

/// [`take_ahead`] ends every item once, with what its own `take` made, in order; ahead, item
/// k + 1 is taken before item k ends (and never one past the last), otherwise each is taken
/// in its own turn just before it ends: the calls in order, written out.
#[test]
fn take_ahead_takes_the_next_item_before_it_ends_this_one() {
    use std::cell::RefCell;
    let calls = |count: usize, ahead: bool| {
        let calls = RefCell::new(Vec::new());
        take_ahead(
            count,
            ahead,
            |k| {
                calls.borrow_mut().push(format!("take {k}"));
                10 * k + 7
            },
            |k, t| calls.borrow_mut().push(format!("end {k} with {t}")),
        );
        calls.into_inner()
    };
    for ahead in [false, true] {
        assert!(calls(0, ahead).is_empty());
        assert_eq!(calls(1, ahead), ["take 0", "end 0 with 7"]);
    }
    let ahead = [
        "take 0",
        "take 1",
        "end 0 with 7",
        "take 2",
        "end 1 with 17",
        "end 2 with 27",
    ];
    assert_eq!(calls(3, true), ahead);
    let turn = [
        "take 0",
        "end 0 with 7",
        "take 1",
        "end 1 with 17",
        "take 2",
        "end 2 with 27",
    ];
    assert_eq!(calls(3, false), turn);
}
