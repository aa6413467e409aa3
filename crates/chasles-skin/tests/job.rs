//! The skinning job (`fast::SkinningJob`): every method through one call, into packed,
//! interleaved and split buffers the caller owns, the same numbers as the per-method
//! functions bit for bit, palettes made from a pose's matrices equal to those made from joint
//! transforms, bad shapes refused before anything is written — and no allocation while a
//! job runs (counted by this test binary's allocator, per thread).

use chasles_skin::fast::{
    dib, dqs, dual_quats8, lbs, log, matrices12, qlb, sbs, twists, FastRig, Joints, Output,
    Palette, SkinningJob,
};
use chasles_skin::pose::skinning_matrices;
use chasles_skin::{gltf_load, joint_transforms, Method, Pose, SkinError};
use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;

/// The system allocator, counting the allocations of each thread.
struct Counting;

thread_local! {
    static ALLOCATIONS: Cell<usize> = const { Cell::new(0) };
}

// SAFETY: every call is passed to the system allocator unchanged; the count is a
// thread-local cell with a const initializer, which never allocates.
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        ALLOCATIONS.with(|c| c.set(c.get() + 1));
        // SAFETY: the caller's layout, as GlobalAlloc requires.
        unsafe { System.alloc(layout) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        // SAFETY: ptr came from System.alloc with this layout.
        unsafe { System.dealloc(ptr, layout) }
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        ALLOCATIONS.with(|c| c.set(c.get() + 1));
        // SAFETY: as for alloc and dealloc.
        unsafe { System.realloc(ptr, layout, new_size) }
    }
}

#[global_allocator]
static GLOBAL: Counting = Counting;

/// Allocations this thread makes while `f` runs.
fn allocations(f: impl FnOnce()) -> usize {
    let before = ALLOCATIONS.with(Cell::get);
    f();
    ALLOCATIONS.with(Cell::get) - before
}

/// CesiumMan mid-walk: its rig, fast layouts for 4 and 8 influences, and the pose.
fn cesium() -> (chasles_skin::Rig, Pose) {
    let m = chasles_models::CESIUM_MAN;
    let rig = gltf_load::load_slice(m.bytes, m.file).unwrap();
    let pose = Pose::animated(&rig, 0, 0.7).unwrap();
    (rig, pose)
}

/// The per-method function's output (the kernels called without a job).
fn direct<const K: usize>(
    f: &FastRig<K>,
    jt: &chasles_skin::JointTransforms,
    method: Method,
    parallel: bool,
) -> Vec<[f32; 6]> {
    let mut out = vec![[0f32; 6]; f.vertices().len()];
    let d = &jt.dual_quats;
    let (m12, d8) = (matrices12(jt), dual_quats8(jt));
    match method {
        Method::Lbs => lbs(f, &m12, &mut out, parallel),
        Method::Dqs => dqs(f, &d8, &mut out, parallel),
        Method::Dib => dib(f, d, &mut out, parallel),
        Method::Log => log(f, &twists(jt).unwrap(), &mut out, parallel),
        Method::Qlb => qlb(f, d, &mut out, parallel),
        Method::Sbs => sbs(f, f.clusters(), d, &mut out, parallel),
    }
    .unwrap();
    out
}

fn every_layout<const K: usize>(rig: &chasles_skin::Rig, pose: &Pose) {
    let f = FastRig::<K>::new(rig).unwrap();
    let n = f.vertices().len();
    let jt = joint_transforms(rig, pose).unwrap();
    let matrices = skinning_matrices(rig, pose).unwrap();
    assert_eq!(matrices, jt.matrices);
    for method in Method::ALL {
        let palette = Palette::from_joint_transforms(method, &f, &jt, false).unwrap();
        assert_eq!(palette.method(), method);
        assert_eq!(palette.joints(), rig.joints.len());
        // From the matrices alone: the same palette, bit for bit.
        let from_matrices = Palette::from_matrices(method, &f, &matrices, true).unwrap();
        assert_eq!(from_matrices, palette, "{} K = {K}", method.name());
        for parallel in [false, true] {
            let want = direct(&f, &jt, method, parallel);
            let job = |output: Output<'_>| {
                SkinningJob {
                    rig: &f,
                    palette: &palette,
                    output,
                    parallel,
                }
                .run()
                .unwrap()
            };
            let mut packed = vec![[f32::NAN; 6]; n];
            job(Output::Packed(&mut packed));
            assert_eq!(packed, want, "{} packed, K = {K}", method.name());
            // Strides 7 and 8: more floats a vertex (say texture coordinates) left untouched;
            // at 7 every other vertex starts at an odd float, its stores only 4-byte aligned.
            for stride in [7, 8] {
                let mut inter = vec![7.5f32; n * stride];
                job(Output::Interleaved {
                    data: &mut inter,
                    stride,
                });
                for (v, w) in inter.chunks(stride).zip(&want) {
                    assert_eq!(&v[..6], w, "{} interleaved, stride {stride}", method.name());
                    assert!(v[6..].iter().all(|x| *x == 7.5), "stride {stride}: {v:?}");
                }
            }
            let mut six = vec![0f32; n * 6];
            job(Output::Interleaved {
                data: &mut six,
                stride: 6,
            });
            assert_eq!(six, want.concat());
            let (mut p, mut nr) = (vec![[0f32; 3]; n], vec![[0f32; 3]; n]);
            job(Output::Split {
                positions: &mut p,
                normals: &mut nr,
            });
            for ((p, nr), w) in p.iter().zip(&nr).zip(&want) {
                assert_eq!(p, &[w[0], w[1], w[2]]);
                assert_eq!(nr, &[w[3], w[4], w[5]]);
            }
        }
    }
}

#[test]
fn every_method_and_layout_through_the_job_is_the_direct_kernel_bit_for_bit() {
    let (rig, pose) = cesium();
    every_layout::<4>(&rig, &pose);
    every_layout::<8>(&rig, &pose);
    // A mesh whose size is no multiple of a chunk (4096 vertices).
    let fox = chasles_models::FOX;
    let rig = gltf_load::load_slice(fox.bytes, fox.file).unwrap();
    let pose = Pose::animated(&rig, 2, 0.3).unwrap();
    assert_ne!(rig.mesh.positions.len() % 4096, 0);
    every_layout::<4>(&rig, &pose);
    // 259 vertices: 3 past the last whole block of 8, which every layout skins as the
    // chunk's last 8 (a block overlapping the one before), with the same numbers.
    let mut small = rig.clone();
    let n = 259;
    let ends = small.influences.start[n] as usize;
    small.mesh.positions.truncate(n);
    small.mesh.normals.truncate(n);
    small
        .mesh
        .triangles
        .retain(|t| t.iter().all(|&v| (v as usize) < n));
    small.influences.start.truncate(n + 1);
    small.influences.joints.truncate(ends);
    small.influences.weights.truncate(ends);
    every_layout::<4>(&small, &pose);
    every_layout::<8>(&small, &pose);
}

#[test]
fn a_job_and_a_palette_update_allocate_nothing() {
    // The counter counts: a vector is one allocation.
    assert_eq!(allocations(|| drop(std::hint::black_box(vec![1u8; 10]))), 1);
    let (rig, pose) = cesium();
    let f = FastRig::<4>::new(&rig).unwrap();
    let n = f.vertices().len();
    let matrices = skinning_matrices(&rig, &pose).unwrap();
    let later = skinning_matrices(&rig, &Pose::animated(&rig, 0, 1.1).unwrap()).unwrap();
    // Made once per rig, on first use or ahead: SBS's clusters, DIB's grouped vertices
    // (CesiumMan's are grouped).
    let _ = f.clusters();
    assert!(f.groups_dib() || !chasles_skin::fast::uses_simd(4));
    let (mut packed, mut inter) = (vec![[0f32; 6]; n], vec![0f32; n * 10]);
    let (mut p, mut nr) = (vec![[0f32; 3]; n], vec![[0f32; 3]; n]);
    for method in Method::ALL {
        let mut palette = Palette::from_matrices(method, &f, &matrices, false).unwrap();
        let update = allocations(|| palette.update(&f, &later, false).unwrap());
        if method != Method::Sbs {
            assert_eq!(update, 0, "{}: palette update allocated", method.name());
        }
        assert_eq!(
            palette,
            Palette::from_matrices(method, &f, &later, false).unwrap()
        );
        let outputs: [Output<'_>; 3] = [
            Output::Packed(&mut packed),
            Output::Interleaved {
                data: &mut inter,
                stride: 10,
            },
            Output::Split {
                positions: &mut p,
                normals: &mut nr,
            },
        ];
        for output in outputs {
            let job = SkinningJob {
                rig: &f,
                palette: &palette,
                output,
                parallel: false,
            };
            assert_eq!(allocations(|| job.run().unwrap()), 0, "{}", method.name());
        }
    }
}

#[test]
fn bad_shapes_are_refused_before_anything_is_written() {
    let (rig, pose) = cesium();
    let f = FastRig::<4>::new(&rig).unwrap();
    let n = f.vertices().len();
    let jt = joint_transforms(&rig, &pose).unwrap();
    let palette = Palette::from_joint_transforms(Method::Dqs, &f, &jt, false).unwrap();
    let run = |palette: &Palette, output: Output<'_>| {
        SkinningJob {
            rig: &f,
            palette,
            output,
            parallel: true,
        }
        .run()
    };
    let mut short = vec![[9f32; 6]; n - 1];
    assert!(matches!(
        run(&palette, Output::Packed(&mut short)),
        Err(SkinError::Count {
            what: "output vertices",
            ..
        })
    ));
    assert!(short.iter().all(|v| v == &[9.0; 6]), "nothing written");
    for (len, stride) in [(n * 5, 5), (n * 8 + 3, 8), (n * 7, 0)] {
        let mut data = vec![9f32; len];
        let e = run(
            &palette,
            Output::Interleaved {
                data: &mut data,
                stride,
            },
        )
        .unwrap_err();
        assert!(matches!(e, SkinError::Stride { .. }), "{e}");
        assert!(data.iter().all(|x| *x == 9.0));
    }
    let (mut p, mut nr) = (vec![[0f32; 3]; n], vec![[0f32; 3]; n + 1]);
    assert!(matches!(
        run(
            &palette,
            Output::Split {
                positions: &mut p,
                normals: &mut nr
            }
        ),
        Err(SkinError::Count {
            what: "normals",
            ..
        })
    ));
    let mut out = vec![[0f32; 6]; n];
    // Joint data of another rig, and an SBS palette short of centres: typed errors, no
    // out-of-range read in the SIMD kernels.
    let Joints::Dqs(d) = palette.data() else {
        unreachable!()
    };
    assert!(matches!(
        Palette::from_joints(&f, Joints::Dqs(d[1..].to_vec())),
        Err(SkinError::Count {
            what: "joint transforms",
            ..
        })
    ));
    let fox = gltf_load::load_slice(chasles_models::FOX.bytes, "fox").unwrap();
    let other = FastRig::<4>::new(&fox).unwrap();
    let fox_jt = chasles_skin::synthetic::joints(other.joints(), 3);
    let fox_palette = Palette::from_joint_transforms(Method::Dqs, &other, &fox_jt, false).unwrap();
    assert!(matches!(
        run(&fox_palette, Output::Packed(&mut out)),
        Err(SkinError::Count {
            what: "joint transforms",
            ..
        })
    ));
    let sbs_palette = Palette::from_joint_transforms(Method::Sbs, &f, &jt, false).unwrap();
    let Joints::Sbs { joints, centres } = sbs_palette.data().clone() else {
        unreachable!()
    };
    let short = Joints::Sbs {
        joints: joints.clone(),
        centres: centres[1..].to_vec(),
    };
    assert!(matches!(
        Palette::from_joints(&f, short),
        Err(SkinError::Count {
            what: "rotation centres",
            ..
        })
    ));
    // Joint data made elsewhere, whole: the same palette.
    let rebuilt = Palette::from_joints(&f, Joints::Sbs { joints, centres }).unwrap();
    assert_eq!(rebuilt, sbs_palette);
    // An empty rig takes an empty buffer of any stride (no chunk size is computed from it).
    let empty = FastRig::<4>::from_vertices(Vec::new(), f.centres().to_vec()).unwrap();
    let none = Palette::from_joint_transforms(Method::Lbs, &empty, &jt, false).unwrap();
    let job = SkinningJob {
        rig: &empty,
        palette: &none,
        output: Output::Interleaved {
            data: &mut [],
            stride: usize::MAX,
        },
        parallel: true,
    };
    assert!(job.run().is_ok());
    // Matrices for another rig.
    assert!(matches!(
        Palette::from_matrices(Method::Lbs, &f, &jt.matrices[1..], false),
        Err(SkinError::Count {
            what: "joint transforms",
            ..
        })
    ));
}
