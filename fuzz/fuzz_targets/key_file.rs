//! Text as a key file (the first byte picks TOML or JSON), read by the CLI's own module
//! (`crates/chasles-cli/src/keyfile.rs`, compiled in by path: the binary's modules are not
//! a library): keys or a typed error, never a panic. Keys that load are interpolated by
//! every piecewise method (the curves past the report too, with the keys' own
//! Kochanek–Bartels parameters), as rigid motions by every rigid curve, and by Spring (its iterations and frames clamped so that one
//! input stays well under libFuzzer's timeout); every frame must be finite or an error.
#![no_main]

#[allow(dead_code)]
#[path = "../../crates/chasles-cli/src/json.rs"]
mod json;
#[allow(dead_code)]
#[path = "../../crates/chasles-cli/src/keyfile.rs"]
mod keyfile;
#[allow(dead_code)]
#[path = "../../crates/chasles-cli/src/repr.rs"]
mod repr;
#[allow(dead_code)]
#[path = "../../crates/chasles-cli/src/spring_args.rs"]
mod spring_args;

use chasles::interp::{
    interpolate, interpolate_rigid, spring, Hemisphere, KeyFrames, Method, RigidEnergy,
    RigidKeys, RigidMethod, RigidSpringConfig, SpringConfig, Tcb, Timing,
};
use chasles::{DualQuat, EulerOrder};
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let Some((&pick, rest)) = data.split_first() else {
        return;
    };
    let Ok(text) = std::str::from_utf8(rest) else {
        return;
    };
    let ext = if pick & 1 == 0 { "toml" } else { "json" };
    let Ok(keys) = keyfile::from_text(text, ext, "fuzz") else {
        return;
    };
    if keys.quats.len() > 64 {
        return;
    }
    let kf = match &keys.euler {
        Some((order, triples)) => {
            KeyFrames::from_euler(*order, triples, keys.times.as_deref(), Hemisphere::Chain)
        }
        None => KeyFrames::new(&keys.quats, keys.times.as_deref(), Hemisphere::Chain),
    };
    let Ok(kf) = kf else { return };
    // Key velocities, where the file gives them (Squad and the converged Spring honour them).
    let kf = match &keys.velocities {
        Some(v) => match kf.with_velocities(v) {
            Ok(k) => k,
            Err(_) => return,
        },
        None => kf,
    };
    // The keys' own Kochanek–Bartels parameters were checked by the reader.
    let kf = match keys.tcb.clone() {
        Some(per_key) => kf.with_tcb(per_key).expect("checked by the key file reader"),
        None => kf,
    };
    let frames = 4 * kf.len() + 1 + usize::from(pick >> 4);
    let timing = [Timing::Uniform, Timing::Angle][usize::from(pick >> 1) % 2];
    let order = keys.euler.as_ref().map_or(EulerOrder::DAM, |e| e.0);
    for m in [
        Method::LinEuler(order),
        Method::LinMat,
        Method::Lerp,
        Method::Nlerp,
        Method::Slerp,
        Method::Squad,
        Method::CatmullRom,
        Method::KochanekBartels(Tcb::CATMULL_ROM),
        Method::Bezier,
        Method::C2,
    ] {
        if let Ok(f) = interpolate(m, &kf, frames, timing) {
            assert!(
                f.iter().all(|f| f.q.is_finite()),
                "{m:?}: a frame that is not finite"
            );
        }
    }
    // The keys as rigid motions (translation, matrix or dq keys; the others at the
    // origin) by the rigid curves, Spring with both energies and few steps.
    let poses: Vec<DualQuat<f64>> = keys.poses.clone().unwrap_or_else(|| {
        keys.quats.iter().map(|q| DualQuat::from_rotation(*q)).collect()
    });
    if let Ok(rk) = RigidKeys::new(&poses, keys.times.as_deref()) {
        let few = |energy| RigidSpringConfig {
            energy,
            max_iterations: 20,
            ..Default::default()
        };
        for m in [
            RigidMethod::ScLerp,
            RigidMethod::Squad,
            RigidMethod::Spring(few(RigidEnergy::Split)),
            RigidMethod::Spring(few(RigidEnergy::Screw)),
        ] {
            if let Ok(f) = interpolate_rigid(&m, &rk, frames.min(200)) {
                assert!(
                    f.iter().all(|f| f.dq.is_finite()),
                    "rigid {m:?}: a pose that is not finite"
                );
            }
        }
    }
    let preset = SpringConfig::spring();
    if let Ok((cfg, total)) = spring_args::configure(
        preset.clone(),
        spring_args::SolverArg::Converged,
        keys.spring.as_ref(),
        &Default::default(),
        None,
        frames,
        kf.len(),
    ) {
        if total <= 400 {
            if let Ok(r) = spring(&kf, total, timing, &cfg, &mut |_| {}) {
                assert!(
                    r.frames.iter().all(|f| f.q.is_finite()),
                    "converged Spring: a frame that is not finite"
                );
            }
        }
    }
    let Ok((mut cfg, total)) = spring_args::configure(
        preset,
        spring_args::SolverArg::Report,
        keys.spring.as_ref(),
        &Default::default(),
        None,
        frames,
        kf.len(),
    ) else {
        return;
    };
    if total > 400 {
        return;
    }
    for l in &mut cfg.levels {
        l.iterations = l.iterations.min(20);
    }
    if let Ok(r) = spring(&kf, total, timing, &cfg, &mut |_| {}) {
        assert!(
            r.frames.iter().all(|f| f.q.is_finite()),
            "Spring: a frame that is not finite"
        );
    }
});
