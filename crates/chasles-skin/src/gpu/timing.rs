//! Timing the skinning shaders honestly (Kavan et al. 2006, §6 compare LBS and DQS on the
//! GPU by speed): the GPU's own clock where the adapter has timestamp queries, so launch,
//! submission and wake-up latencies stay out of the figure (on a fast GPU they are larger
//! than the shader itself at 10⁵ vertices); and a bandwidth yardstick, a plain copy shader
//! over buffers much larger than any cache, timed the same way.

use super::{bind_buffers, grid, GpuError, GpuSkinner};
use crate::{JointTransforms, Method};
use wgpu::util::DeviceExt;

/// Which clock timed a run.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Clock {
    /// The GPU's timestamps at the start and end of the compute pass.
    Gpu,
    /// The host's clock from submission to completion (the adapter has no timestamp
    /// queries): includes the submission and wake-up latency.
    Host,
}

impl Clock {
    /// "GPU timestamps" or "host clock".
    pub fn name(self) -> &'static str {
        match self {
            Clock::Gpu => "GPU timestamps",
            Clock::Host => "host clock",
        }
    }
}

/// Most timed passes in one batch (two timestamps each, wgpu's query-set limit of 4096).
const MAX_RUNS: usize = 2048;

impl GpuSkinner {
    /// The clock [`GpuSkinner::shader_seconds`] and [`GpuSkinner::stream_rate`] use.
    pub fn clock(&self) -> Clock {
        if self.timestamps {
            Clock::Gpu
        } else {
            Clock::Host
        }
    }

    /// Seconds each of `runs` skinning passes of `method` took, one after another on the
    /// GPU after a warm-up pass; the joint transforms are uploaded once. See
    /// [`GpuSkinner::clock`] for what is timed.
    pub fn shader_seconds(
        &self,
        jt: &JointTransforms,
        method: Method,
        runs: usize,
    ) -> Result<Vec<f64>, GpuError> {
        let pipeline = self.prepare(jt, method)?;
        self.timed(runs, |encoder, stamps| {
            self.encode(encoder, pipeline, stamps)
        })
    }

    /// Bytes per second (read plus written) that a copy shader moves between two buffers of
    /// `bytes` each (clamped to the adapter's binding limit), the median of `runs` passes:
    /// the memory-bandwidth yardstick for the skinning shaders. Take `bytes` well above the
    /// GPU's last-level cache (hundreds of MiB) to measure the memory, not the cache.
    pub fn stream_rate(&self, bytes: u64, runs: usize) -> Result<f64, GpuError> {
        let limits = self.device.limits();
        let limit = u64::from(limits.max_storage_buffer_binding_size).min(limits.max_buffer_size);
        let count = (bytes.min(limit) / 16).clamp(1, u64::from(u32::MAX)) as u32;
        let size = u64::from(count) * 16;
        let pattern = |i: usize| (i % 1_000_003) as f32;
        let source: Vec<f32> = (0..count as usize * 4).map(pattern).collect();
        let src = self
            .device
            .create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("stream source"),
                contents: bytemuck::cast_slice(&source),
                usage: wgpu::BufferUsages::STORAGE,
            });
        drop(source);
        let dst = self.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("stream destination"),
            size,
            usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
            mapped_at_creation: false,
        });
        // 1024 vec4s a workgroup (see stream.wgsl).
        let groups = grid(count, 1024, limits.max_compute_workgroups_per_dimension);
        let params = self
            .device
            .create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("stream params"),
                contents: bytemuck::cast_slice(&[count, groups.0, 0, 0]),
                usage: wgpu::BufferUsages::UNIFORM,
            });
        let module = self
            .device
            .create_shader_module(wgpu::include_wgsl!("stream.wgsl"));
        let pipeline = self
            .device
            .create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
                label: Some("stream"),
                layout: None,
                module: &module,
                entry_point: Some("stream"),
                compilation_options: Default::default(),
                cache: None,
            });
        let bind_group = bind_buffers(
            &self.device,
            "stream",
            &pipeline.get_bind_group_layout(0),
            &[&src, &dst, &params],
        );
        let mut times = self.timed(runs, |encoder, stamps| {
            let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
                label: Some("stream"),
                timestamp_writes: stamps,
            });
            pass.set_pipeline(&pipeline);
            pass.set_bind_group(0, &bind_group, &[]);
            pass.dispatch_workgroups(groups.0, groups.1, 1);
        })?;
        // A yardstick that skipped bytes would flatter itself: check every one arrived.
        let check = self.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("stream check"),
            size,
            usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let mut encoder = self.device.create_command_encoder(&Default::default());
        encoder.copy_buffer_to_buffer(&dst, 0, &check, 0, size);
        self.queue.submit([encoder.finish()]);
        let wrong = self.map_read(&check, size, |data| {
            let copied: &[f32] = bytemuck::cast_slice(data);
            copied
                .iter()
                .enumerate()
                .position(|(i, x)| *x != pattern(i))
        })?;
        if let Some(i) = wrong {
            return Err(GpuError::Device(format!(
                "the bandwidth copy shader wrote a wrong value at float {i}"
            )));
        }
        times.sort_by(f64::total_cmp);
        Ok(2.0 * size as f64 / times[times.len() / 2])
    }

    /// Runs `record` once to warm up, then `runs` times (at most [`MAX_RUNS`]), each a
    /// compute pass, and returns each timed pass's seconds.
    fn timed(
        &self,
        runs: usize,
        mut record: impl FnMut(&mut wgpu::CommandEncoder, Option<wgpu::ComputePassTimestampWrites<'_>>),
    ) -> Result<Vec<f64>, GpuError> {
        let runs = runs.clamp(1, MAX_RUNS);
        let mut warm = self.device.create_command_encoder(&Default::default());
        record(&mut warm, None);
        self.queue.submit([warm.finish()]);
        self.wait()?;
        if !self.timestamps {
            return (0..runs)
                .map(|_| {
                    let start = std::time::Instant::now();
                    let mut encoder = self.device.create_command_encoder(&Default::default());
                    record(&mut encoder, None);
                    self.queue.submit([encoder.finish()]);
                    self.wait()?;
                    Ok(start.elapsed().as_secs_f64())
                })
                .collect();
        }
        let queries = 2 * runs as u32;
        let set = self.device.create_query_set(&wgpu::QuerySetDescriptor {
            label: Some("pass times"),
            ty: wgpu::QueryType::Timestamp,
            count: queries,
        });
        let bytes = u64::from(queries) * 8;
        let resolved = self.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("resolved times"),
            size: bytes,
            usage: wgpu::BufferUsages::QUERY_RESOLVE | wgpu::BufferUsages::COPY_SRC,
            mapped_at_creation: false,
        });
        let readable = self.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("times"),
            size: bytes,
            usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let mut encoder = self.device.create_command_encoder(&Default::default());
        for k in 0..runs as u32 {
            record(
                &mut encoder,
                Some(wgpu::ComputePassTimestampWrites {
                    query_set: &set,
                    beginning_of_pass_write_index: Some(2 * k),
                    end_of_pass_write_index: Some(2 * k + 1),
                }),
            );
        }
        encoder.resolve_query_set(&set, 0..queries, &resolved, 0);
        encoder.copy_buffer_to_buffer(&resolved, 0, &readable, 0, bytes);
        self.queue.submit([encoder.finish()]);
        let period = f64::from(self.queue.get_timestamp_period()) * 1e-9;
        self.map_read(&readable, bytes, |data| {
            let ticks: &[u64] = bytemuck::cast_slice(data);
            ticks
                .chunks_exact(2)
                .map(|t| t[1].wrapping_sub(t[0]) as f64 * period)
                .collect()
        })
    }
}
