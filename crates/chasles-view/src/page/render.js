'use strict';
// WebGL2: the programs naga wrote from the skinning WGSL, the mesh, the joint palette as a
// float texture (one row a joint: LBS's three rows, then the dual quaternion), drawing into
// panes, and the read-back of the skinned positions by transform feedback.

/** Bytes of a base64 string, as a typed array of `Type`. */
function decode(b64, Type) {
  const text = atob(b64);
  const bytes = new Uint8Array(text.length);
  for (let i = 0; i < text.length; i++) bytes[i] = text.charCodeAt(i);
  return new Type(bytes.buffer);
}

/** 4×4 matrices, column-major (as GLSL reads them). */
const M4 = {
  mul(a, b) {
    const o = new Float32Array(16);
    for (let c = 0; c < 4; c++)
      for (let r = 0; r < 4; r++) {
        let s = 0;
        for (let k = 0; k < 4; k++) s += a[k * 4 + r] * b[c * 4 + k];
        o[c * 4 + r] = s;
      }
    return o;
  },
  perspective(fovy, aspect, near, far) {
    const f = 1 / Math.tan(fovy / 2), o = new Float32Array(16);
    o[0] = f / aspect; o[5] = f; o[10] = (far + near) / (near - far); o[11] = -1;
    o[14] = 2 * far * near / (near - far);
    return o;
  },
  /** The camera of an orbit: `eye` looking at `target`, `up` the y axis. */
  lookAt(eye, target) {
    const sub = (a, b) => [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
    const norm = (v) => { const l = Math.hypot(v[0], v[1], v[2]) || 1; return [v[0] / l, v[1] / l, v[2] / l]; };
    const cross = (a, b) => [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
    const z = norm(sub(eye, target)), x = norm(cross([0, 1, 0], z)), y = cross(z, x);
    const dot = (a, b) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    return new Float32Array([x[0], y[0], z[0], 0, x[1], y[1], z[1], 0, x[2], y[2], z[2], 0,
      -dot(x, eye), -dot(y, eye), -dot(z, eye), 1]);
  },
};

class Renderer {
  constructor(canvas, data, antialias) {
    const gl = canvas.getContext('webgl2', { antialias, preserveDrawingBuffer: true });
    if (!gl) throw new Error('this browser has no WebGL2');
    this.gl = gl;
    this.canvas = canvas;
    this.glsl = data.glsl;
    this.joints = data.joints;
    this.vertices = data.vertices;
    this.compiled = {};
    const fs = this.shader(gl.FRAGMENT_SHADER, data.glsl.surface, 'surface');
    this.programs = {};
    for (const m of ['lbs', 'dqs']) this.programs[m] = this.link(m, this.shader(gl.VERTEX_SHADER, data.glsl[m], m), fs);
    this.mesh(data.mesh);
    this.palette = gl.createTexture();
    gl.bindTexture(gl.TEXTURE_2D, this.palette);
    gl.texStorage2D(gl.TEXTURE_2D, 1, gl.RGBA32F, 5, Math.max(1, this.joints));
    for (const p of [gl.TEXTURE_MIN_FILTER, gl.TEXTURE_MAG_FILTER]) gl.texParameteri(gl.TEXTURE_2D, p, gl.NEAREST);
    // One uniform buffer a pane (and one for the read-back): a buffer rewritten between two
    // draws of a frame would make the second wait for the first.
    this.ubos = [0, 1, 2].map(() => {
      const b = gl.createBuffer();
      gl.bindBuffer(gl.UNIFORM_BUFFER, b);
      gl.bufferData(gl.UNIFORM_BUFFER, 40 * 4, gl.DYNAMIC_DRAW);
      return b;
    });
    gl.enable(gl.DEPTH_TEST);
  }

  shader(type, source, name) {
    const gl = this.gl, s = gl.createShader(type);
    gl.shaderSource(s, source);
    gl.compileShader(s);
    if (!gl.getShaderParameter(s, gl.COMPILE_STATUS)) throw new Error(`the ${name} shader does not compile:\n${gl.getShaderInfoLog(s)}`);
    this.compiled[name] = true;
    return s;
  }

  link(name, vs, fs) {
    const gl = this.gl, p = gl.createProgram();
    gl.attachShader(p, vs);
    gl.attachShader(p, fs);
    gl.transformFeedbackVaryings(p, [this.glsl.skinned, this.glsl.det], gl.SEPARATE_ATTRIBS);
    gl.linkProgram(p);
    if (!gl.getProgramParameter(p, gl.LINK_STATUS)) throw new Error(`the ${name} program does not link:\n${gl.getProgramInfoLog(p)}`);
    for (const block of this.glsl.blocks) {
      const i = gl.getUniformBlockIndex(p, block);
      if (i !== gl.INVALID_INDEX) gl.uniformBlockBinding(p, i, 0);
    }
    gl.useProgram(p);
    gl.uniform1i(gl.getUniformLocation(p, this.glsl.palette), 0);
    return p;
  }

  mesh(m) {
    const gl = this.gl;
    this.vao = gl.createVertexArray();
    gl.bindVertexArray(this.vao);
    const attribute = (loc, array, size, integer) => {
      gl.bindBuffer(gl.ARRAY_BUFFER, gl.createBuffer());
      gl.bufferData(gl.ARRAY_BUFFER, array, gl.STATIC_DRAW);
      gl.enableVertexAttribArray(loc);
      if (integer) gl.vertexAttribIPointer(loc, size, gl.UNSIGNED_SHORT, 0, 0);
      else gl.vertexAttribPointer(loc, size, gl.FLOAT, false, 0, 0);
    };
    attribute(0, decode(m.positions, Float32Array), 3, false);
    attribute(1, decode(m.normals, Float32Array), 3, false);
    attribute(2, decode(m.joints, Uint16Array), 4, true);
    attribute(3, decode(m.weights, Float32Array), 4, false);
    const triangles = decode(m.triangles, Uint32Array);
    gl.bindBuffer(gl.ELEMENT_ARRAY_BUFFER, gl.createBuffer());
    gl.bufferData(gl.ELEMENT_ARRAY_BUFFER, triangles, gl.STATIC_DRAW);
    this.indices = triangles.length;
    gl.bindVertexArray(null);
  }

  /** The joints of one frame: `joints × 20` floats. */
  setPalette(floats) {
    const gl = this.gl;
    gl.bindTexture(gl.TEXTURE_2D, this.palette);
    gl.texSubImage2D(gl.TEXTURE_2D, 0, 0, 0, 5, this.joints, gl.RGBA, gl.FLOAT, floats);
  }

  /** The View uniform: clip and camera matrices, colour (a: heat map), checker cells a unit. */
  uniforms(slot, clip, camera, colour, checker) {
    const u = new Float32Array(40);
    u.set(clip, 0);
    u.set(camera, 16);
    u.set(colour, 32);
    u[36] = checker;
    const gl = this.gl;
    gl.bindBuffer(gl.UNIFORM_BUFFER, this.ubos[slot]);
    gl.bufferSubData(gl.UNIFORM_BUFFER, 0, u);
    gl.bindBufferBase(gl.UNIFORM_BUFFER, 0, this.ubos[slot]);
  }

  /** Clears the canvas to the background. */
  clear() {
    const gl = this.gl;
    gl.viewport(0, 0, this.canvas.width, this.canvas.height);
    gl.disable(gl.SCISSOR_TEST);
    gl.clearColor(0.118, 0.125, 0.149, 1);
    gl.clear(gl.COLOR_BUFFER_BIT | gl.DEPTH_BUFFER_BIT);
  }

  /** Draws the mesh skinned by `method` into pane number `slot`, `[x, y, w, h]` (pixels). */
  draw(method, slot, pane, clip, camera, colour, checker) {
    const gl = this.gl;
    gl.viewport(...pane);
    this.uniforms(slot, clip, camera, colour, checker);
    gl.useProgram(this.programs[method]);
    gl.activeTexture(gl.TEXTURE0);
    gl.bindTexture(gl.TEXTURE_2D, this.palette);
    gl.bindVertexArray(this.vao);
    gl.drawElements(gl.TRIANGLES, this.indices, gl.UNSIGNED_INT, 0);
    gl.bindVertexArray(null);
  }

  /** The vertex shader's skinned positions and determinants for the palette set, read back
   *  by transform feedback (one point a vertex, nothing rasterized). */
  readback(method) {
    const gl = this.gl, n = this.vertices;
    const positions = new Float32Array(3 * n), det = new Float32Array(n);
    const buffers = [positions, det].map((a) => {
      const b = gl.createBuffer();
      gl.bindBuffer(gl.TRANSFORM_FEEDBACK_BUFFER, b);
      gl.bufferData(gl.TRANSFORM_FEEDBACK_BUFFER, a.byteLength, gl.STREAM_READ);
      return b;
    });
    this.uniforms(2, new Float32Array(16), new Float32Array(16), [0, 0, 0, 0], 0);
    gl.useProgram(this.programs[method]);
    gl.activeTexture(gl.TEXTURE0);
    gl.bindTexture(gl.TEXTURE_2D, this.palette);
    gl.bindVertexArray(this.vao);
    const tf = gl.createTransformFeedback();
    gl.bindTransformFeedback(gl.TRANSFORM_FEEDBACK, tf);
    buffers.forEach((b, i) => gl.bindBufferBase(gl.TRANSFORM_FEEDBACK_BUFFER, i, b));
    gl.enable(gl.RASTERIZER_DISCARD);
    gl.beginTransformFeedback(gl.POINTS);
    gl.drawArrays(gl.POINTS, 0, n);
    gl.endTransformFeedback();
    gl.disable(gl.RASTERIZER_DISCARD);
    buffers.forEach((_, i) => gl.bindBufferBase(gl.TRANSFORM_FEEDBACK_BUFFER, i, null));
    gl.bindTransformFeedback(gl.TRANSFORM_FEEDBACK, null);
    gl.bindVertexArray(null);
    [positions, det].forEach((a, i) => {
      gl.bindBuffer(gl.TRANSFORM_FEEDBACK_BUFFER, buffers[i]);
      gl.getBufferSubData(gl.TRANSFORM_FEEDBACK_BUFFER, 0, a);
      gl.deleteBuffer(buffers[i]);
    });
    gl.deleteTransformFeedback(tf);
    return { positions, det };
  }

  /** Waits for the GPU (one pixel read). */
  finish() {
    const px = new Uint8Array(4), gl = this.gl;
    gl.readPixels(0, 0, 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, px);
  }
}
