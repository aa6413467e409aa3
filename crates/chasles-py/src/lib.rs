//! # chasles-py — the Python package `chasles`
//!
//! PyO3 bindings of the chasles libraries on numpy arrays, built by maturin (see this
//! crate's README and `pyproject.toml`). Every function wraps the Rust library — the math
//! is not written again here — and is batched over leading dimensions: arrays in, arrays
//! out, float32 and float64 kept as given, the GIL released while the library works, all
//! cores (rayon) for large batches ([`arrays`]).
//!
//! * [`convert`] — `chasles::convert`: Euler angles (24 conventions), matrices, rotation
//!   vectors, axis–angle;
//! * [`quat`] — `chasles::Quat`: product, conjugate, inverse, `exp`/`log`/powers, rotation;
//! * [`dualquat`] — `chasles::DualQuat` and `chasles::Screw`: rigid motions;
//! * [`interp`] — `chasles::interp`: Slerp, Squad, Spring and every method of `chasles interp`;
//! * [`blend`] — `chasles::blend`: every method of `chasles blend`, and ScLERP;
//! * [`skin`] — `chasles_skin`: rigs (glTF, JSON, the built-in models), poses, and
//!   skinning through the typed fast job (`fast::SkinningJob` with a `fast::Palette`);
//! * [`pickle`] — rigs and poses cross processes (Dask) by pickling;
//! * [`simd`] — the library's batch loops compiled for AVX2 too, chosen at run time.
//!
//! It is not a member of the root workspace: a PyO3 extension module is linked by the
//! Python that loads it, so `cargo test --workspace` could not link it; maturin builds it
//! and `.ci/run` checks it with `cargo fmt`/`cargo clippy --manifest-path` and pytest.

// No unsafe code but `simd`'s calls of the AVX2 builds, each behind its feature check.
#![deny(unsafe_code)]

use pyo3::prelude::*;

pub mod arrays;
pub mod average;
pub mod blend;
pub mod convert;
pub mod dualquat;
pub mod interp;
pub mod pickle;
pub mod quat;
pub mod rig;
pub mod rigid;
pub mod simd;
pub mod skin;
pub mod spring;

/// Rotations and rigid motions on numpy arrays: quaternions ``[w, x, y, z]``, dual
/// quaternions, interpolation (Slerp, Squad, Spring), rigid blending (DLB, DIB, …) and
/// skeletal skinning — the chasles Rust library, batched over leading dimensions, with the
/// GIL released.
#[pymodule]
#[pyo3(name = "_chasles")]
fn chasles_module(m: &Bound<'_, PyModule>) -> PyResult<()> {
    use pyo3::wrap_pyfunction as w;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    for f in [
        w!(convert::quat_from_euler, m)?,
        w!(convert::quat_to_euler, m)?,
        w!(convert::quat_from_matrix, m)?,
        w!(convert::quat_to_matrix, m)?,
        w!(convert::quat_from_rotvec, m)?,
        w!(convert::quat_to_rotvec, m)?,
        w!(convert::quat_from_axis_angle, m)?,
        w!(convert::quat_to_axis_angle, m)?,
        w!(quat::quat_mul, m)?,
        w!(quat::quat_conj, m)?,
        w!(quat::quat_inv, m)?,
        w!(quat::quat_normalize, m)?,
        w!(quat::quat_log, m)?,
        w!(quat::quat_exp, m)?,
        w!(quat::quat_pow, m)?,
        w!(quat::quat_angle, m)?,
        w!(quat::rotate, m)?,
        w!(dualquat::dq_from_rt, m)?,
        w!(dualquat::dq_to_rt, m)?,
        w!(dualquat::dq_from_matrix, m)?,
        w!(dualquat::dq_to_matrix, m)?,
        w!(dualquat::dq_transform, m)?,
        w!(dualquat::dq_mul, m)?,
        w!(dualquat::dq_inv, m)?,
        w!(dualquat::dq_normalize, m)?,
        w!(dualquat::dq_pow, m)?,
        w!(dualquat::screw, m)?,
        w!(dualquat::dq_from_screw, m)?,
        w!(interp::slerp, m)?,
        w!(interp::interpolate, m)?,
        w!(interp::squad, m)?,
        w!(interp::spring, m)?,
        w!(rigid::interpolate_rigid_py, m)?,
        w!(blend::blend, m)?,
        w!(average::average, m)?,
        w!(blend::sclerp, m)?,
        w!(skin::skin, m)?,
        w!(rig::models, m)?,
        w!(rig::model_bytes, m)?,
        w!(simd::_set_simd, m)?,
    ] {
        m.add_function(f)?;
    }
    m.add_class::<rig::PyRig>()?;
    m.add_class::<rig::PyPose>()?;
    Ok(())
}
