//! `chasles skin --device cpu|gpu|auto`: where a pose is skinned. `gpu` takes any adapter
//! (a software one too) and fails with the reason when there is none or the method has no
//! shader; `auto` takes a hardware GPU when one exists and the method has a shader (LBS,
//! DQS), the CPU otherwise — a software adapter is correct but no faster than the CPU.

use anyhow::{bail, Result};
use chasles_skin::{joint_transforms, skin, Method, Pose, Rig, Skinned};

/// The `--device` choice.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum Device {
    /// The CPU reference path.
    Cpu,
    /// The GPU (wgpu compute), any adapter.
    Gpu,
    /// A hardware GPU when there is one and the method has a shader, else the CPU.
    Auto,
}

/// Where skinning runs, set up for one rig.
pub enum Engine {
    /// On the CPU.
    Cpu,
    /// On the GPU, the mesh uploaded.
    #[cfg(feature = "gpu")]
    Gpu(Box<chasles_skin::gpu::GpuSkinner>),
}

impl Engine {
    /// The engine for `rig` and `method` under `device`.
    pub fn new(device: Device, rig: &Rig, method: Method) -> Result<Self> {
        if device == Device::Cpu {
            return Ok(Engine::Cpu);
        }
        #[cfg(feature = "gpu")]
        {
            let shader = matches!(method, Method::Lbs | Method::Dqs);
            if device == Device::Gpu && !shader {
                bail!(
                    "{} has no GPU path (lbs and dqs do); use --device cpu",
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
            Ok(Engine::Cpu)
        }
        #[cfg(not(feature = "gpu"))]
        {
            let _ = (rig, method);
            if device == Device::Gpu {
                bail!("this chasles was built without the `gpu` feature");
            }
            Ok(Engine::Cpu)
        }
    }

    /// Words for where it runs.
    pub fn describe(&self) -> String {
        match self {
            Engine::Cpu => "the CPU".to_string(),
            #[cfg(feature = "gpu")]
            Engine::Gpu(g) => format!("the GPU ({})", g.adapter()),
        }
    }

    /// `rig` in `pose` skinned by `method`.
    pub fn skin(&self, rig: &Rig, pose: &Pose, method: Method) -> Result<Skinned> {
        match self {
            Engine::Cpu => Ok(skin(rig, pose, method)?),
            #[cfg(feature = "gpu")]
            Engine::Gpu(g) => Ok(g.skin(&joint_transforms(rig, pose)?, method)?),
        }
    }
}
