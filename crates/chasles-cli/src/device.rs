//! `chasles skin --device cpu|gpu|auto`: where a pose is skinned. `gpu` takes any adapter
//! (a software one too) and fails with the reason when there is none or the method has no
//! shader; `auto` takes a hardware GPU when one exists and the method has a shader (LBS,
//! DQS, DIB), the CPU otherwise — a software adapter is correct but no faster than the CPU.

use anyhow::{bail, Result};
use chasles_skin::fast::Skinner;
use chasles_skin::{joint_transforms, Method, Pose, Rig, Skinned};

/// The `--device` choice.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum Device {
    /// The CPU: the fast path on all cores.
    Cpu,
    /// The GPU (wgpu compute), any adapter.
    Gpu,
    /// A hardware GPU when there is one and the method has a shader, else the CPU.
    Auto,
}

/// Where skinning runs, set up for one rig.
pub enum Engine {
    /// On the CPU, the rig laid out for the fast path.
    Cpu(Box<Skinner>),
    /// On the GPU, the mesh uploaded.
    #[cfg(feature = "gpu")]
    Gpu(Box<chasles_skin::gpu::GpuSkinner>),
}

/// Mesa's software Vulkan prints "XDG_RUNTIME_DIR is invalid" three times while the
/// adapters are listed when that variable is unset (containers, CI). Called once at start,
/// before any thread exists, it points the variable at a private temporary folder (one per
/// user, reused).
pub fn quiet_vulkan_loader() {
    if std::env::var_os("XDG_RUNTIME_DIR").is_none() {
        let user = std::env::var("USER").unwrap_or_default();
        let dir = std::env::temp_dir().join(format!("chasles-runtime-{user}"));
        if std::fs::create_dir_all(&dir).is_ok() {
            #[cfg(unix)]
            {
                use std::os::unix::fs::PermissionsExt;
                let _ = std::fs::set_permissions(&dir, std::fs::Permissions::from_mode(0o700));
            }
            std::env::set_var("XDG_RUNTIME_DIR", &dir);
        }
    }
}

impl Engine {
    /// The engine for `rig` and `method` under `device`.
    pub fn new(device: Device, rig: &Rig, method: Method) -> Result<Self> {
        let cpu = || Ok(Engine::Cpu(Box::new(Skinner::new(rig)?)));
        if device == Device::Cpu {
            return cpu();
        }
        #[cfg(feature = "gpu")]
        {
            let shader = matches!(method, Method::Lbs | Method::Dqs | Method::Dib);
            if device == Device::Gpu && !shader {
                bail!(
                    "{} has no GPU path (lbs, dqs and dib do); use --device cpu",
                    method.name()
                );
            }
            if shader {
                match chasles_skin::gpu::GpuSkinner::new(rig) {
                    Ok(g) if device == Device::Gpu || !g.is_software() => {
                        return Ok(Engine::Gpu(Box::new(g)))
                    }
                    Ok(_) => {}
                    Err(e) if device == Device::Gpu => bail!("--device gpu: {e}"),
                    Err(_) => {}
                }
            }
            cpu()
        }
        #[cfg(not(feature = "gpu"))]
        {
            let _ = method;
            if device == Device::Gpu {
                bail!("this chasles was built without the `gpu` feature");
            }
            cpu()
        }
    }

    /// Words for where it runs.
    pub fn describe(&self) -> String {
        match self {
            Engine::Cpu(_) => "the CPU".to_string(),
            #[cfg(feature = "gpu")]
            Engine::Gpu(g) => format!("the GPU ({})", g.adapter()),
        }
    }

    /// `rig` in `pose` skinned by `method`.
    pub fn skin(&self, rig: &Rig, pose: &Pose, method: Method) -> Result<Skinned> {
        match self {
            Engine::Cpu(s) => Ok(s.skin(rig, &joint_transforms(rig, pose)?, method)?),
            #[cfg(feature = "gpu")]
            Engine::Gpu(g) => Ok(g.skin(&joint_transforms(rig, pose)?, method)?),
        }
    }
}

/// `chasles skin --bench --device gpu`: vertices per second of the LBS, DQS and DIB shaders on
/// synthetic meshes (54 joints, 4 influences) of 10⁵, 10⁶ and 10⁷ vertices — the shader
/// alone (median of 51 passes on the GPU's clock where it has timestamps) and with the
/// upload of the joints and the read-back of positions and normals into reused host
/// vectors (median of 7, host clock) — the DQS/LBS ratio, and the share of the adapter's
/// memory bandwidth reached at 96 bytes per vertex (64 read, 32 written), against a copy
/// shader over two 256 MiB buffers.
#[cfg(feature = "gpu")]
pub fn bench_gpu() -> Result<()> {
    use crate::skin::median_secs;
    use chasles_skin::gpu::GpuSkinner;
    use chasles_skin::synthetic;
    const BYTES_PER_VERTEX: f64 = 96.0;
    println!(
        "| vertices | method | M vertices/s (shader) | GB/s moved | share of bandwidth | M vertices/s with upload + read-back |"
    );
    println!("|---|---|---|---|---|---|");
    let mut facts = None;
    let mut ratios = Vec::new();
    for n in [100_000usize, 1_000_000, 10_000_000] {
        let rig = synthetic::rig(n, 54, 7);
        let jt = synthetic::joints(54, 7);
        let gpu = match GpuSkinner::from_fast(&rig) {
            Ok(g) => g,
            Err(e) => {
                println!("| {n} | — | skipped: {e} | | | |");
                continue;
            }
        };
        // The adapter's facts and its bandwidth, once (the first mesh the GPU takes).
        let bandwidth = match facts {
            Some((_, _, b)) => b,
            None => {
                let b = gpu.stream_rate(256 << 20, 51)?;
                facts = Some((gpu.adapter().to_string(), gpu.clock(), b));
                b
            }
        };
        let mut out = Skinned {
            positions: Vec::new(),
            normals: Vec::new(),
        };
        let mut rate = |m: Method| -> Result<(f64, f64)> {
            let mut t = gpu.shader_seconds(&jt, m, 51)?;
            t.sort_by(f64::total_cmp);
            let full = median_secs(7, || {
                gpu.dispatch(&jt, m)?;
                gpu.read_into(&mut out)?;
                Ok(())
            })?;
            Ok((n as f64 / t[t.len() / 2], n as f64 / full))
        };
        let (l, lr) = rate(Method::Lbs)?;
        let (d, dr) = rate(Method::Dqs)?;
        let (b, br) = rate(Method::Dib)?;
        for (name, s, r) in [("lbs", l, lr), ("dqs", d, dr), ("dib", b, br)] {
            println!(
                "| {n} | {name} | {:.0} | {:.1} | {:.2} | {:.1} |",
                s / 1e6,
                s * BYTES_PER_VERTEX / 1e9,
                s * BYTES_PER_VERTEX / bandwidth,
                r / 1e6,
            );
        }
        ratios.push((n, l / d));
    }
    println!();
    if let Some((adapter, clock, bandwidth)) = facts {
        println!("adapter: {adapter}; shader times by {}", clock.name());
        println!(
            "bandwidth: a copy shader over two 256 MiB buffers moves {:.0} GB/s (read + written)",
            bandwidth / 1e9
        );
        println!("(10⁵ vertices, 9.6 MB, can stay in a large GPU's last-level cache: shares over 1 there mean the cache, not the memory)");
    }
    for (n, r) in ratios {
        println!("{n} vertices: DQS costs {r:.2}× LBS on the GPU");
    }
    Ok(())
}

/// Without the `gpu` feature there is no GPU benchmark.
#[cfg(not(feature = "gpu"))]
pub fn bench_gpu() -> Result<()> {
    bail!("this chasles was built without the `gpu` feature")
}
