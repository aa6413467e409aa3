// The viewer's shaders (Kavan et al. 2006, §6): skinning in the vertex shader, one entry
// point per method, on the functions of chasles_skin::shader::SKINNING_WGSL (put before
// this file, shared with the compute shaders). naga translates each entry point to GLSL ES
// 3.00 for WebGL2 when the page is written.

struct View {
    // Projection times camera: model space to clip space.
    clip: mat4x4<f32>,
    // The camera (model space to view space); normals turn by its rotation part.
    camera: mat4x4<f32>,
    // The surface's colour (rgb); a = 1 colours LBS's local volume loss instead.
    colour: vec4<f32>,
    // x: checker cells per unit of the bind pose (0: none), to see the skin turn and stretch.
    pattern: vec4<f32>,
};

@group(0) @binding(0) var<uniform> view: View;
// One row a joint: texels 0–2 its LBS rows (Affine3x4), texels 3–4 its dual quaternion
// (UnitDualQuat: real, dual), for the frame shown.
@group(0) @binding(1) var palette: texture_2d<f32>;

struct Bind {
    @location(0) p: vec3<f32>,
    @location(1) n: vec3<f32>,
    @location(2) j: vec4<u32>,
    @location(3) w: vec4<f32>,
};

struct Shaded {
    @builtin(position) position: vec4<f32>,
    // The normal in view space.
    @location(0) normal: vec3<f32>,
    @location(1) colour: vec3<f32>,
    // The skinned position in model space (read back by transform feedback).
    @location(2) skinned: vec3<f32>,
    // The determinant of the blended 3×3 (LBS's local volume; 1 for DQS).
    @location(3) det: f32,
    // The bind position, for the checker.
    @location(4) bind: vec3<f32>,
};

fn rows_of(j: u32) -> Rows {
    let y = i32(j);
    return Rows(
        textureLoad(palette, vec2<i32>(0, y), 0),
        textureLoad(palette, vec2<i32>(1, y), 0),
        textureLoad(palette, vec2<i32>(2, y), 0),
    );
}

fn dq_of(j: u32) -> Dq {
    let y = i32(j);
    return Dq(textureLoad(palette, vec2<i32>(3, y), 0), textureLoad(palette, vec2<i32>(4, y), 0));
}

// The heat map: grey where the local volume is kept (det 1), through orange to red where
// it falls to half or less.
fn heat(det: f32) -> vec3<f32> {
    let loss = clamp((1.0 - det) * 2.0, 0.0, 1.0);
    let kept = vec3<f32>(0.78, 0.78, 0.76);
    let half = vec3<f32>(0.98, 0.62, 0.12);
    let lost = vec3<f32>(0.80, 0.06, 0.04);
    if (loss < 0.5) {
        return mix(kept, half, loss * 2.0);
    }
    return mix(half, lost, loss * 2.0 - 1.0);
}

fn shade(m: Moved, bind: vec3<f32>, det: f32) -> Shaded {
    var out: Shaded;
    out.position = view.clip * vec4<f32>(m.p, 1.0);
    out.normal = (view.camera * vec4<f32>(m.n, 0.0)).xyz;
    out.colour = view.colour.rgb;
    if (view.colour.a > 0.5) {
        out.colour = heat(det);
    }
    out.skinned = m.p;
    out.det = det;
    out.bind = bind;
    return out;
}

@vertex
fn lbs(v: Bind) -> Shaded {
    let b = lbs_blend(rows_of(v.j.x), rows_of(v.j.y), rows_of(v.j.z), rows_of(v.j.w), v.w);
    let det = determinant(mat3x3<f32>(b.a.xyz, b.b.xyz, b.c.xyz));
    return shade(lbs_move(b, v.p, v.n), v.p, det);
}

@vertex
fn dqs(v: Bind) -> Shaded {
    let b = dqs_blend(dq_of(v.j.x), dq_of(v.j.y), dq_of(v.j.z), dq_of(v.j.w), v.w);
    return shade(rigid_move(b, v.p, v.n), v.p, 1.0);
}

// Two lights fixed to the camera, both faces lit; the checker of the bind pose darkens
// every other cell.
@fragment
fn surface(s: Shaded, @builtin(front_facing) front: bool) -> @location(0) vec4<f32> {
    var n = normalize(s.normal);
    if (!front) {
        n = -n;
    }
    let key = max(dot(n, normalize(vec3<f32>(0.35, 0.55, 0.75))), 0.0);
    let fill = max(dot(n, normalize(vec3<f32>(-0.6, -0.1, 0.5))), 0.0);
    var colour = s.colour;
    if (view.pattern.x > 0.0) {
        let c = floor(s.bind * view.pattern.x);
        if (fract((c.x + c.y + c.z) * 0.5) > 0.25) {
            colour = colour * 0.72;
        }
    }
    return vec4<f32>(colour * (0.25 + 0.65 * key + 0.2 * fill), 1.0);
}
