//! Skinning on the GPU (Kavan et al. 2006, §6: "DLB … can be easily implemented on the
//! GPU"): WGSL compute shaders for linear blend skinning, dual quaternion skinning (with
//! the antipodality fix against each vertex's heaviest influence) and DIB (§5: from DLB,
//! at most 8 updates, the CPU's stopping rule), run through wgpu without a window. The mesh stays on the GPU; per frame only the joint transforms go up —
//! 12 floats a joint for LBS (three rows of the matrix), 8 for DQS (the dual quaternion),
//! as the paper notes — and the skinned positions and normals come back.
//!
//! Up to four influences per vertex (glTF's usual `JOINTS_0`); a rig with more is refused
//! with [`GpuError::Rig`]. Meshes larger than the adapter's storage-binding
//! limit are split into chunks, one dispatch each. Any Vulkan, Metal, DX12 or GL adapter works,
//! software ones included (Mesa's lavapipe), so the tests run on machines without a GPU.

mod job;
mod timing;

pub use timing::Clock;

use crate::fast::palette::{affine, unit};
use crate::fast::Joints;
use crate::{JointTransforms, Method, Rig, Skinned};
use chasles::Vec3;
use rayon::prelude::*;
use wgpu::util::DeviceExt;

/// Why the GPU path cannot run.
#[derive(Debug, thiserror::Error)]
pub enum GpuError {
    /// No adapter: no GPU and no software driver.
    #[error("no GPU adapter: {0}")]
    NoAdapter(String),
    /// The device could not be opened or rejected the work.
    #[error("GPU device: {0}")]
    Device(String),
    /// A method with no GPU shader yet.
    #[error("{0} has no GPU path (lbs, dqs and dib do)")]
    Unsupported(&'static str),
    /// A rig the four-influence layout cannot hold (more than 4 influences a vertex).
    #[error(transparent)]
    Rig(#[from] crate::SkinError),
    /// Transforms for another rig.
    #[error("{given} joint transforms for a rig of {joints} joints")]
    JointCount {
        /// Transforms given.
        given: usize,
        /// Joints of the rig.
        joints: usize,
    },
    /// The shader produced a non-finite position or normal (e.g. DQS weights cancelling out).
    #[error("the GPU produced a non-finite position or normal at vertex {0}")]
    NonFinite(usize),
}

const WORKGROUP: u32 = 64;

/// The compute shaders: the shared skinning math ([`crate::shader::SKINNING_WGSL`]), then
/// the entry points that fetch each vertex's joints and store its result.
const SHADER: &str = concat!(
    include_str!("gpu/skinning.wgsl"),
    include_str!("gpu/skin.wgsl")
);

/// The WGSL override constants of DIB's shader: the CPU's precision, stall factor and most
/// updates (`skin.wgsl` writes none of them).
fn dib_constants() -> [(&'static str, f64); 3] {
    [
        ("dib_precision", f64::from(crate::skinning::DIB_PRECISION)),
        ("dib_stall", chasles::blend::STALL_FACTOR),
        ("dib_updates", crate::skinning::DIB_UPDATES as f64),
    ]
}

/// A rig uploaded to a GPU, ready to skin pose after pose.
pub struct GpuSkinner {
    device: wgpu::Device,
    queue: wgpu::Queue,
    lbs: wgpu::ComputePipeline,
    dqs: wgpu::ComputePipeline,
    dib: wgpu::ComputePipeline,
    chunks: Vec<Chunk>,
    matrices: wgpu::Buffer,
    dual_quats: wgpu::Buffer,
    readback: wgpu::Buffer,
    joints: usize,
    adapter: String,
    software: bool,
    timestamps: bool,
}

/// A run of vertices small enough for one storage binding: meshes larger than the
/// adapter's binding limit are skinned in several dispatches.
struct Chunk {
    bind_group: wgpu::BindGroup,
    skinned: wgpu::Buffer,
    vertices: usize,
    groups: (u32, u32),
}

/// One vertex as the shader reads it: position, normal, 4 joints (heaviest first), weights.
#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct GpuVertex {
    p: [f32; 4],
    n: [f32; 4],
    j: [u32; 4],
    w: [f32; 4],
}

/// Workgroups for `count` invocations of `size`-wide groups: a row of at most `max` groups
/// (the adapter's per-dimension limit), as many rows as needed.
fn grid(count: u32, size: u32, max: u32) -> (u32, u32) {
    let needed = count.div_ceil(size).max(1);
    let max = max.max(1);
    (needed.min(max), needed.div_ceil(max))
}

/// A bind group of whole buffers, bound at 0, 1, 2, … in the order given.
fn bind_buffers(
    device: &wgpu::Device,
    label: &str,
    layout: &wgpu::BindGroupLayout,
    buffers: &[&wgpu::Buffer],
) -> wgpu::BindGroup {
    device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some(label),
        layout,
        entries: &buffers
            .iter()
            .enumerate()
            .map(|(i, b)| wgpu::BindGroupEntry {
                binding: i as u32,
                resource: b.as_entire_binding(),
            })
            .collect::<Vec<_>>(),
    })
}

fn storage(binding: u32, read_only: bool) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::COMPUTE,
        ty: wgpu::BindingType::Buffer {
            ty: wgpu::BufferBindingType::Storage { read_only },
            has_dynamic_offset: false,
            min_binding_size: None,
        },
        count: None,
    }
}

impl GpuSkinner {
    /// Opens the default adapter (a high-performance one when there is a choice) and
    /// uploads `rig`'s mesh and influences.
    pub fn new(rig: &Rig) -> Result<Self, GpuError> {
        // The fast path's layout: four influences at most, heaviest first.
        Self::from_fast(&crate::fast::FastRig::<4>::new(rig)?)
    }

    /// Uploads a fast-path rig (four influences, heaviest first, indices checked) — the
    /// benchmarks' synthetic meshes.
    pub fn from_fast(rig: &crate::fast::FastRig<4>) -> Result<Self, GpuError> {
        Self::from_fast_in_chunks(rig, usize::MAX)
    }

    /// As [`GpuSkinner::from_fast`], with at most `per_chunk` vertices a dispatch (fewer
    /// where the adapter's binding limit says so): bounds each dispatch's buffers.
    pub fn from_fast_in_chunks(
        rig: &crate::fast::FastRig<4>,
        per_chunk: usize,
    ) -> Result<Self, GpuError> {
        let verts: Vec<GpuVertex> = rig
            .vertices()
            .iter()
            .map(|v| GpuVertex {
                p: [v.p[0], v.p[1], v.p[2], 1.0],
                n: [v.n[0], v.n[1], v.n[2], 0.0],
                j: v.j.map(u32::from),
                w: v.w,
            })
            .collect();
        Self::upload(&verts, rig.joints(), per_chunk)
    }

    fn upload(verts: &[GpuVertex], rig_joints: usize, per_chunk: usize) -> Result<Self, GpuError> {
        let instance = wgpu::Instance::new(&wgpu::InstanceDescriptor::default());
        let adapter = pollster::block_on(instance.request_adapter(&wgpu::RequestAdapterOptions {
            power_preference: wgpu::PowerPreference::HighPerformance,
            ..Default::default()
        }))
        .map_err(|e| GpuError::NoAdapter(e.to_string()))?;
        let info = adapter.get_info();
        let (device, queue) = pollster::block_on(adapter.request_device(&wgpu::DeviceDescriptor {
            label: Some("chasles skinning"),
            required_limits: adapter.limits(),
            // GPU-side pass times for the benchmark, where the adapter has them.
            required_features: adapter.features() & wgpu::Features::TIMESTAMP_QUERY,
            ..Default::default()
        }))
        .map_err(|e| GpuError::Device(e.to_string()))?;
        let n = verts.len();
        let limit = u64::from(device.limits().max_storage_buffer_binding_size)
            .min(device.limits().max_buffer_size);
        let per_chunk = ((limit / std::mem::size_of::<GpuVertex>() as u64).max(1) as usize)
            .min(per_chunk.max(1));
        let joints = rig_joints.max(1);
        let usage = wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST;
        let buffer = |label, size: usize, usage| {
            device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size: size.max(16) as u64,
                usage,
                mapped_at_creation: false,
            })
        };
        let matrices = buffer("matrices", joints * 48, usage);
        let dual_quats = buffer("dual quaternions", joints * 32, usage);
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("skinning"),
            entries: &[
                storage(0, true),
                storage(1, true),
                storage(2, true),
                storage(3, false),
                wgpu::BindGroupLayoutEntry {
                    binding: 4,
                    visibility: wgpu::ShaderStages::COMPUTE,
                    ty: wgpu::BindingType::Buffer {
                        ty: wgpu::BufferBindingType::Uniform,
                        has_dynamic_offset: false,
                        min_binding_size: None,
                    },
                    count: None,
                },
            ],
        });
        let max_groups = device.limits().max_compute_workgroups_per_dimension.max(1);
        let mut chunks = Vec::new();
        for part in verts.chunks(per_chunk) {
            let m = part.len();
            let vertex_buf = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("vertices"),
                contents: bytemuck::cast_slice(part),
                usage: wgpu::BufferUsages::STORAGE,
            });
            let skinned = buffer(
                "skinned",
                m * 32,
                wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
            );
            let groups = grid(m as u32, WORKGROUP, max_groups);
            let params: [u32; 4] = [m as u32, groups.0 * WORKGROUP, 0, 0];
            let params_buf = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("params"),
                contents: bytemuck::cast_slice(&params),
                usage: wgpu::BufferUsages::UNIFORM,
            });
            let bind_group = bind_buffers(
                &device,
                "skinning",
                &layout,
                &[&vertex_buf, &matrices, &dual_quats, &skinned, &params_buf],
            );
            chunks.push(Chunk {
                bind_group,
                skinned,
                vertices: m,
                groups,
            });
        }
        let readback = buffer(
            "readback",
            n.min(per_chunk) * 32,
            wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
        );
        let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("skinning"),
            bind_group_layouts: &[&layout],
            push_constant_ranges: &[],
        });
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("skin.wgsl"),
            source: wgpu::ShaderSource::Wgsl(SHADER.into()),
        });
        // DIB's stopping rule, from the constants the CPU paths read.
        let constants = dib_constants();
        let pipeline = |entry: &str| {
            device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
                label: Some(entry),
                layout: Some(&pipeline_layout),
                module: &module,
                entry_point: Some(entry),
                compilation_options: wgpu::PipelineCompilationOptions {
                    constants: &constants,
                    ..Default::default()
                },
                cache: None,
            })
        };
        let (lbs, dqs, dib) = (pipeline("lbs"), pipeline("dqs"), pipeline("dib"));
        let timestamps = device.features().contains(wgpu::Features::TIMESTAMP_QUERY);
        Ok(GpuSkinner {
            device,
            queue,
            lbs,
            dqs,
            dib,
            chunks,
            matrices,
            dual_quats,
            readback,
            joints: rig_joints,
            adapter: format!("{} ({:?}, {:?})", info.name, info.device_type, info.backend),
            software: info.device_type == wgpu::DeviceType::Cpu,
            timestamps,
        })
    }

    /// The adapter's name, type and backend.
    pub fn adapter(&self) -> &str {
        &self.adapter
    }

    /// Whether the adapter is a software rasterizer on the CPU (lavapipe, llvmpipe, WARP):
    /// correct, but no faster than the CPU path.
    pub fn is_software(&self) -> bool {
        self.software
    }

    /// Uploads the joint transforms `method` needs and runs its shader, leaving the result
    /// on the GPU (see [`GpuSkinner::read`]).
    pub fn dispatch(&self, jt: &JointTransforms, method: Method) -> Result<(), GpuError> {
        let pipeline = self.prepare(jt, method)?;
        self.submit(pipeline);
        Ok(())
    }

    /// Checks `jt` against the rig, queues the upload of the joint transforms `method`
    /// reads (12 floats a joint for LBS, 8 for DQS and DIB) and returns its pipeline.
    fn prepare(
        &self,
        jt: &JointTransforms,
        method: Method,
    ) -> Result<&wgpu::ComputePipeline, GpuError> {
        if jt.matrices.len() != self.joints || jt.dual_quats.len() != self.joints {
            return Err(GpuError::JointCount {
                given: jt.matrices.len(),
                joints: self.joints,
            });
        }
        crate::reach::check_joints("the GPU's rig", &jt.matrices, Some(&jt.dual_quats))?;
        let joints = match method {
            Method::Lbs => Joints::Lbs(jt.matrices.iter().map(affine).collect()),
            Method::Dqs => Joints::Dqs(jt.dual_quats.iter().map(unit).collect()),
            Method::Dib => Joints::Dib(jt.dual_quats.iter().map(unit).collect()),
            other => return Err(GpuError::Unsupported(other.name())),
        };
        self.upload_joints(&joints)
    }

    /// Checks `joints` against the rig, queues their upload as they are (the palette types
    /// are the shaders' layout) and returns their method's pipeline.
    fn upload_joints(&self, joints: &Joints) -> Result<&wgpu::ComputePipeline, GpuError> {
        if joints.len() != self.joints {
            return Err(GpuError::JointCount {
                given: joints.len(),
                joints: self.joints,
            });
        }
        let write = |buffer, bytes: &[u8]| self.queue.write_buffer(buffer, 0, bytes);
        Ok(match joints {
            Joints::Lbs(a) => {
                write(&self.matrices, bytemuck::cast_slice(a));
                &self.lbs
            }
            Joints::Dqs(d) => {
                write(&self.dual_quats, bytemuck::cast_slice(d));
                &self.dqs
            }
            Joints::Dib(d) => {
                write(&self.dual_quats, bytemuck::cast_slice(d));
                &self.dib
            }
            other => return Err(GpuError::Unsupported(other.method().name())),
        })
    }

    /// Records and submits one skinning pass with `pipeline`.
    fn submit(&self, pipeline: &wgpu::ComputePipeline) {
        let mut encoder = self.device.create_command_encoder(&Default::default());
        self.encode(&mut encoder, pipeline, None);
        self.queue.submit([encoder.finish()]);
    }

    /// Records one compute pass that skins every chunk with `pipeline`, with the pass's
    /// start and end time stamped when `timestamps` is given.
    fn encode(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        pipeline: &wgpu::ComputePipeline,
        timestamps: Option<wgpu::ComputePassTimestampWrites<'_>>,
    ) {
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some("skinning"),
            timestamp_writes: timestamps,
        });
        pass.set_pipeline(pipeline);
        for c in &self.chunks {
            pass.set_bind_group(0, &c.bind_group, &[]);
            pass.dispatch_workgroups(c.groups.0, c.groups.1, 1);
        }
    }

    /// Waits for the last dispatch and brings the skinned positions and normals back.
    pub fn read(&self) -> Result<Skinned, GpuError> {
        let mut out = Skinned {
            positions: Vec::new(),
            normals: Vec::new(),
        };
        self.read_into(&mut out)?;
        Ok(out)
    }

    /// As [`GpuSkinner::read`], into `out`'s vectors (replacing what they held): a clip
    /// read frame after frame reuses one allocation instead of touching fresh pages.
    pub fn read_into(&self, out: &mut Skinned) -> Result<(), GpuError> {
        let n: usize = self.chunks.iter().map(|c| c.vertices).sum();
        out.positions.clear();
        out.normals.clear();
        out.positions.reserve(n);
        out.normals.reserve(n);
        // Split into positions and normals on all cores: one core's copy out of the mapped
        // buffer is what limits a read-back of millions of vertices.
        self.read_chunks(|_, skinned| {
            out.positions
                .par_extend(skinned.par_iter().map(|v| Vec3::new(v[0], v[1], v[2])));
            out.normals
                .par_extend(skinned.par_iter().map(|v| Vec3::new(v[4], v[5], v[6])));
        })
    }

    /// Copies each chunk's skinned vertices (8 floats: position, 0, normal, 0) back and hands
    /// them to `put(index of the chunk's first vertex, vertices)`, in order; then
    /// [`GpuError::NonFinite`] names the first vertex whose position or normal is not finite
    /// (the CPU paths' rule).
    fn read_chunks(&self, mut put: impl FnMut(usize, &[[f32; 8]])) -> Result<(), GpuError> {
        let mut first = 0;
        for c in &self.chunks {
            let size = c.vertices as u64 * 32;
            let mut encoder = self.device.create_command_encoder(&Default::default());
            if size > 0 {
                encoder.copy_buffer_to_buffer(&c.skinned, 0, &self.readback, 0, size);
            }
            self.queue.submit([encoder.finish()]);
            let bad = self.map_read(&self.readback, size.max(16), |data| {
                let skinned: &[[f32; 8]] = bytemuck::cast_slice(&data[..size as usize]);
                put(first, skinned);
                skinned
                    .par_iter()
                    .position_first(|v| !v[..3].iter().chain(&v[4..7]).all(|x| x.is_finite()))
            })?;
            if let Some(v) = bad {
                return Err(GpuError::NonFinite(first + v));
            }
            first += c.vertices;
        }
        Ok(())
    }

    /// Maps the first `size` bytes of the mappable `buffer` once the GPU is done with it,
    /// hands them to `f` and unmaps.
    fn map_read<R>(
        &self,
        buffer: &wgpu::Buffer,
        size: u64,
        f: impl FnOnce(&[u8]) -> R,
    ) -> Result<R, GpuError> {
        let slice = buffer.slice(..size);
        let (tx, rx) = std::sync::mpsc::channel();
        slice.map_async(wgpu::MapMode::Read, move |r| {
            let _ = tx.send(r);
        });
        self.wait()?;
        rx.recv()
            .map_err(|e| GpuError::Device(e.to_string()))?
            .map_err(|e| GpuError::Device(e.to_string()))?;
        let result = f(&slice.get_mapped_range());
        buffer.unmap();
        Ok(result)
    }

    /// Waits until the GPU has finished everything submitted.
    pub fn wait(&self) -> Result<(), GpuError> {
        self.device
            .poll(wgpu::PollType::wait_indefinitely())
            .map(|_| ())
            .map_err(|e| GpuError::Device(e.to_string()))
    }

    /// [`GpuSkinner::dispatch`] then [`GpuSkinner::read`].
    pub fn skin(&self, jt: &JointTransforms, method: Method) -> Result<Skinned, GpuError> {
        self.dispatch(jt, method)?;
        self.read()
    }
}
