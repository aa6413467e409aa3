// The page: its state (set by the URL fragment, #method=lbs|dqs|both&clip=NAME&time=T&heat=1,
// and twist=DEG&bend=DEG for the cylinder), the controls, the orbit camera, the play loop
// and the debug hooks the tests read (window.__chasles; #debug=readback or #debug=bench
// writes a JSON report into <pre id="chasles-debug">).

const $ = (id) => document.getElementById(id);
const data = JSON.parse($('chasles-data').textContent);
const grid = data.grid;
const COLOURS = { lbs: [0.86, 0.6, 0.42, 0], dqs: [0.45, 0.66, 0.9, 0] };
const NAMES = { lbs: 'LBS: linear blend skinning', dqs: 'DQS: dual quaternion skinning' };
const palettes = data.palettes.map((p) => decode(p, Float32Array));
const perFrame = data.joints * 20;
// About 24 checker cells along the bind pose's longest side.
const checkerCells = 24 / Math.max(1e-9, ...data.bounds[1].map((hi, i) => hi - data.bounds[0][i]));
const state = { method: 'both', clip: data.clip, time: 0, heat: false, checker: !!grid, playing: true, speed: 1, twist: 180, bend: 0 };
const camera = { yaw: 0, pitch: 0, distance: 1, target: [0, 0, 0] };
let renderer = null;
const errors = [];

/** The index of the frame shown: a clip's frame, or the cylinder's grid pose. */
function frame() {
  if (grid) {
    const near = (list, x) => list.reduce((b, v, i) => (Math.abs(v - x) < Math.abs(list[b] - x) ? i : b), 0);
    return near(grid.bend, state.bend) * grid.twist.length + near(grid.twist, state.twist);
  }
  const c = data.clips[state.clip];
  return Math.max(0, Math.min(c.times.length - 1, Math.round(state.time * c.fps)));
}

function frameFloats() {
  const f = frame();
  const p = grid ? palettes[0] : palettes[state.clip];
  return p.subarray(f * perFrame, (f + 1) * perFrame);
}

function minDet() {
  return grid ? grid.min_det[frame()] : data.clips[state.clip].min_det[frame()];
}

/** The camera that frames the bounds' sphere in a pane, looking from the front and above. */
function resetCamera() {
  const [lo, hi] = data.bounds, c = $('view');
  camera.target = [0, 1, 2].map((i) => (lo[i] + hi[i]) / 2);
  const radius = Math.hypot(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]) / 2 || 1;
  const panes = state.method === 'both' ? 2 : 1;
  const aspect = c.clientWidth / panes / Math.max(1, c.clientHeight) || 1;
  const half = Math.PI / 9, halfX = Math.atan(aspect * Math.tan(half));
  camera.distance = (radius / Math.sin(Math.min(half, halfX))) * 0.92;
  camera.yaw = grid ? 0.35 : 0.6;
  camera.pitch = grid ? 0.35 : 0.15;
  camera.moved = false;
}

function matrices(aspect) {
  const c = camera, t = c.target;
  const eye = [t[0] + c.distance * Math.cos(c.pitch) * Math.sin(c.yaw), t[1] + c.distance * Math.sin(c.pitch),
    t[2] + c.distance * Math.cos(c.pitch) * Math.cos(c.yaw)];
  const view = M4.lookAt(eye, t);
  const proj = M4.perspective((2 * Math.PI) / 9, aspect, c.distance / 100, c.distance * 10);
  return { clip: M4.mul(proj, view), view };
}

/** Draws the state: one pane, or LBS | DQS side by side with one camera. */
function draw() {
  if (!renderer) return;
  const canvas = renderer.canvas, w = canvas.width, h = canvas.height;
  renderer.clear();
  renderer.setPalette(frameFloats());
  const methods = state.method === 'both' ? ['lbs', 'dqs'] : [state.method];
  const paneW = Math.floor(w / methods.length);
  const m = matrices(paneW / Math.max(1, h));
  methods.forEach((method, i) => {
    const colour = COLOURS[method].slice();
    if (state.heat) colour[3] = 1;
    renderer.draw(method, i, [i * paneW, 0, paneW, h], m.clip, m.view, colour, state.checker ? checkerCells : 0);
  });
  $('left-label').textContent = NAMES[methods[0]];
  $('right-label').textContent = methods[1] ? NAMES[methods[1]] : '';
  $('right-label').hidden = !methods[1];
  $('legend').hidden = !state.heat;
  status();
}

function status() {
  const f = frame(), d = minDet();
  const where = grid
    ? `twist ${grid.twist[f % grid.twist.length]}°, bend ${grid.bend[Math.floor(f / grid.twist.length)]}°`
    : `frame ${f + 1}/${data.clips[state.clip].times.length}, t = ${data.clips[state.clip].times[f].toFixed(3)} s`;
  $('status').textContent = `${where} · LBS keeps ${d.toFixed(3)} of the local volume at its worst vertex here (DQS: 1)`;
  if (grid) {
    $('twist-text').textContent = `${state.twist}°`;
    $('bend-text').textContent = `${state.bend}°`;
  } else {
    $('time-text').textContent = `${state.time.toFixed(2)} s`;
  }
}

/** The state as the URL fragment (the time only when paused). */
function writeFragment() {
  const p = new URLSearchParams();
  p.set('method', state.method);
  if (grid) {
    p.set('twist', state.twist);
    p.set('bend', state.bend);
  } else {
    p.set('clip', data.clips[state.clip].name);
    if (!state.playing) p.set('time', +state.time.toFixed(4));
  }
  if (state.heat) p.set('heat', 1);
  if (state.checker !== !!grid) p.set('checker', state.checker ? 1 : 0);
  if (state.speed !== 1) p.set('speed', state.speed);
  history.replaceState(null, '', '#' + p.toString());
}

function readFragment() {
  const p = new URLSearchParams(location.hash.slice(1));
  if (['lbs', 'dqs', 'both'].includes(p.get('method'))) state.method = p.get('method');
  // A clip by name, or by index.
  let c = data.clips.findIndex((x) => x.name === p.get('clip'));
  if (c < 0 && /^\d+$/.test(p.get('clip') || '') && +p.get('clip') < data.clips.length) c = +p.get('clip');
  if (c >= 0) state.clip = c;
  const num = (k) => (p.has(k) && isFinite(+p.get(k)) ? +p.get(k) : null);
  if (num('time') !== null) { state.time = Math.max(0, num('time')); state.playing = false; }
  if (num('twist') !== null) { state.twist = Math.max(0, Math.min(360, num('twist'))); state.playing = false; }
  if (num('bend') !== null) { state.bend = Math.max(0, Math.min(180, num('bend'))); state.playing = false; }
  if (num('speed') !== null && num('speed') > 0) state.speed = num('speed');
  state.heat = p.get('heat') === '1';
  if (p.has('checker')) state.checker = p.get('checker') === '1';
  if (p.get('play') === '1') state.playing = true;
  if (p.get('play') === '0') state.playing = false;
  document.body.classList.toggle('bare', p.get('ui') === '0');
  return p;
}

function syncControls() {
  $('method').value = state.method;
  $('heat').checked = state.heat;
  $('checker').checked = state.checker;
  $('play').textContent = state.playing ? 'pause' : 'play';
  $('sweep').textContent = state.playing ? 'stop' : 'sweep';
  $('speed').value = String(state.speed);
  if (grid) {
    $('twist').value = state.twist;
    $('bend').value = state.bend;
  } else {
    const c = data.clips[state.clip];
    $('clip').value = String(state.clip);
    $('time').max = c.duration;
    $('time').step = 1 / c.fps;
    $('time').value = state.time;
  }
}

function changed() {
  syncControls();
  writeFragment();
  draw();
}

function controls() {
  $('clip-controls').hidden = !!grid;
  $('cylinder-controls').hidden = !grid;
  if (grid) {
    const step = grid.twist[1] - grid.twist[0];
    $('twist').step = step;
    $('bend').step = step;
  }
  data.clips.forEach((c, i) => $('clip').add(new Option(c.name, String(i))));
  $('method').onchange = () => { state.method = $('method').value; resetCamera(); changed(); };
  $('clip').onchange = () => { state.clip = +$('clip').value; state.time = 0; changed(); };
  $('play').onclick = $('sweep').onclick = () => {
    state.playing = !state.playing;
    state.sweep = state.twist; // a sweep goes on from the twist shown
    changed();
  };
  $('speed').onchange = () => { state.speed = +$('speed').value; changed(); };
  $('time').oninput = () => { state.time = +$('time').value; state.playing = false; changed(); };
  $('twist').oninput = () => { state.twist = +$('twist').value; state.playing = false; changed(); };
  $('bend').oninput = () => { state.bend = +$('bend').value; changed(); };
  $('heat').onchange = () => { state.heat = $('heat').checked; changed(); };
  $('checker').onchange = () => { state.checker = $('checker').checked; changed(); };
  $('worst').onclick = () => {
    const c = data.clips[state.clip];
    state.time = c.times[c.worst];
    state.playing = false;
    changed();
  };
  window.addEventListener('hashchange', () => { readFragment(); changed(); });
  window.addEventListener('keydown', (e) => {
    // Space on a focused button or checkbox is that control's own click.
    const own = e.target.tagName === 'BUTTON' || e.target.tagName === 'SELECT' || e.target.type === 'checkbox';
    if (e.key === ' ' && !own) { state.playing = !state.playing; e.preventDefault(); changed(); }
    if (e.key === 'h' || e.key === 'H') { state.heat = !state.heat; changed(); }
    if (e.key === 'c' || e.key === 'C') { state.checker = !state.checker; changed(); }
  });
  orbit($('view'));
}

/** Orbit (drag), pan (shift- or right-drag), zoom (wheel), reset (double-click). */
function orbit(canvas) {
  let last = null;
  canvas.addEventListener('contextmenu', (e) => e.preventDefault());
  canvas.addEventListener('pointerdown', (e) => {
    last = { x: e.clientX, y: e.clientY, pan: e.shiftKey || e.button === 2 };
    canvas.setPointerCapture(e.pointerId);
  });
  canvas.addEventListener('pointerup', () => { last = null; });
  canvas.addEventListener('pointermove', (e) => {
    if (!last) return;
    const dx = e.clientX - last.x, dy = e.clientY - last.y;
    last.x = e.clientX;
    last.y = e.clientY;
    camera.moved = true;
    if (last.pan) {
      const s = camera.distance / canvas.clientHeight, v = matrices(1).view;
      for (let i = 0; i < 3; i++) camera.target[i] += s * (-dx * v[i * 4] + dy * v[i * 4 + 1]);
    } else {
      camera.yaw -= dx * 0.008;
      camera.pitch = Math.max(-1.5, Math.min(1.5, camera.pitch + dy * 0.008));
    }
    draw();
  });
  canvas.addEventListener('wheel', (e) => {
    camera.distance *= Math.exp(e.deltaY * 0.001);
    camera.moved = true;
    e.preventDefault();
    draw();
  }, { passive: false });
  canvas.addEventListener('dblclick', () => { resetCamera(); draw(); });
}

function resize() {
  const c = $('view'), r = window.devicePixelRatio || 1;
  const w = Math.max(1, Math.round(c.clientWidth * r)), h = Math.max(1, Math.round(c.clientHeight * r));
  if (c.width !== w || c.height !== h) { c.width = w; c.height = h; }
  if (!camera.moved) resetCamera();
  draw();
}

let before = null;
function tick(now) {
  if (state.playing && before !== null) {
    const dt = Math.min(0.1, (now - before) / 1000) * state.speed;
    if (grid) {
      // Twist back and forth over 0°–360°, one way in 4 s at 1×.
      state.sweep = ((state.sweep || 0) + dt * 90) % 720;
      const step = grid.twist[1] - grid.twist[0];
      state.twist = Math.round((state.sweep < 360 ? state.sweep : 720 - state.sweep) / step) * step;
    } else {
      const c = data.clips[state.clip];
      state.time = c.duration > 0 ? (state.time + dt) % c.duration : 0;
    }
    syncControls();
    draw();
  }
  before = now;
  requestAnimationFrame(tick);
}

/** What the tests read: the frame shown, and each method's skinned positions. */
function report(p) {
  const out = { ready: !!renderer, errors, compiled: renderer ? renderer.compiled : {}, state: { ...state } };
  out.frame = frame();
  if (grid) {
    out.twist = grid.twist[out.frame % grid.twist.length];
    out.bend = grid.bend[Math.floor(out.frame / grid.twist.length)];
  } else {
    out.clip = data.clips[state.clip].name;
    out.time = data.clips[state.clip].times[out.frame];
  }
  out.min_det = minDet();
  out.load_ms = window.__chasles.loadMs;
  if (renderer && p.get('debug') === 'readback') {
    for (const m of state.method === 'both' ? ['lbs', 'dqs'] : [state.method]) {
      const r = window.__chasles.skinned(m);
      out[m] = Array.from(r.positions);
      out[m + '_det'] = Array.from(r.det);
    }
  }
  if (renderer && p.get('debug') === 'bench') out.bench = window.__chasles.bench(+(p.get('frames') || 120));
  $('chasles-debug').textContent = JSON.stringify(out);
}

window.__chasles = {
  state, data, errors, frame,
  /** The skinned positions and dets of `method` for the frame shown. */
  skinned(method) {
    renderer.setPalette(frameFloats());
    return renderer.readback(method);
  },
  /** Draws `frames` frames of the clip (or the sweep) as fast as it can; frames a second. */
  bench(frames) {
    const t0 = performance.now();
    for (let i = 0; i < frames; i++) {
      if (grid) state.twist = (i * 5) % 365;
      else state.time = (i / data.clips[state.clip].fps) % Math.max(1e-6, data.clips[state.clip].duration);
      draw();
      renderer.finish();
    }
    const ms = performance.now() - t0;
    return { frames, ms, fps: (1000 * frames) / ms, width: renderer.canvas.width, height: renderer.canvas.height };
  },
};

$('credit').textContent = `${data.title}: ${data.credit}. Skinning after Kavan, Collins, Žára & O'Sullivan 2006, §6; vertex shaders translated by naga from chasles' WGSL compute shaders.`;
if (grid) state.playing = false; // the candy wrapper at 180° first; "sweep" plays
const fragment = readFragment();
controls();
try {
  // Multisampling costs a software rasterizer about 2.5× a frame: on by default below 10⁵
  // triangles, else off; #aa=0|1 decides.
  const aa = fragment.has('aa') ? fragment.get('aa') === '1' : data.triangles < 100000;
  renderer = new Renderer($('view'), data, aa);
} catch (e) {
  errors.push(String(e.message || e));
  $('message').textContent = String(e.message || e);
  $('message').hidden = false;
}
resetCamera();
syncControls();
resize();
window.addEventListener('resize', resize);
if (window.ResizeObserver) new ResizeObserver(resize).observe($('view'));
window.__chasles.ready = !!renderer;
window.__chasles.loadMs = performance.now();
if (fragment.has('debug')) report(fragment);
requestAnimationFrame(tick);
