// The bandwidth yardstick for the skinning shaders: a plain copy. Each workgroup of 256
// copies a run of 1024 vec4s (16 KiB), each invocation four of them 256 apart, so every
// load is coalesced and four are in flight per invocation, as the skinning shaders have
// (a vertex is four vec4s). Workgroups are laid out in rows of `groups_x`.

struct Params {
    count: u32,
    groups_x: u32,
    pad0: u32,
    pad1: u32,
};

@group(0) @binding(0) var<storage, read> src: array<vec4<f32>>;
@group(0) @binding(1) var<storage, read_write> dst: array<vec4<f32>>;
@group(0) @binding(2) var<uniform> params: Params;

@compute @workgroup_size(256)
fn stream(@builtin(workgroup_id) group: vec3<u32>, @builtin(local_invocation_index) t: u32) {
    let base = (group.x + group.y * params.groups_x) * 1024u + t;
    for (var k = 0u; k < 4u; k = k + 1u) {
        let i = base + k * 256u;
        if (i < params.count) {
            dst[i] = src[i];
        }
    }
}
