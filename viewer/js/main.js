// The page: selectors, orbit/zoom, control-point drag, file drop, messages.
import { Viewer, ModuleError } from './module.js';
import { Camera, Renderer, project } from './render.js';

const $ = (id) => document.getElementById(id);
const SHADING_CODES = { plain: 0, highlight: 1, gaussian: 2, mean: 3 };
const PICK_RADIUS = 12; // CSS pixels

const ui = {
  canvas: $('view'),
  sample: $('sample'),
  scheme: $('scheme'),
  depth: $('depth'),
  grid: $('grid'),
  shading: $('shading'),
  up: $('up'),
  lines: $('lines'),
  net: $('net'),
  reset: $('reset'),
  file: $('file'),
  message: $('message'),
  status: $('status'),
  legend: $('legend'),
  edit: $('edit'),
  saveMesh: $('save-mesh'),
  saveSurface: $('save-surface'),
};

const state = {
  viewer: null,
  renderer: null,
  camera: new Camera(),
  source: { kind: 'sample', index: 0 },
  file: null,
  drag: null,
  pending: null,
  frame: 0,
  lastEdit: null,
  // The view last given to the module for the light lines.
  viewKey: null,
};

function options() {
  return {
    depth: Number(ui.depth.value),
    catmullClark: ui.scheme.value === 'catmull-clark',
    grid: Number(ui.grid.value),
    shading: ui.shading.value,
  };
}

function showMessage(text, kind = 'error') {
  ui.message.textContent = text;
  ui.message.className = kind;
  ui.message.hidden = !text;
}

function describeError(e) {
  if (e instanceof ModuleError) return e.message;
  if (e instanceof WebAssembly.RuntimeError) return `internal error in the WASM module (${e.message}); it was restarted`;
  return String(e && e.message ? e.message : e);
}

// Runs f against the module; a module error becomes the page's message and
// leaves the previous surface; a trap restarts the module.
async function guarded(f) {
  try {
    f();
    return true;
  } catch (e) {
    showMessage(describeError(e));
    if (e instanceof WebAssembly.RuntimeError) {
      await state.viewer.restart();
      try {
        reloadSource();
      } catch (e2) {
        showMessage(describeError(e2));
      }
    }
    return false;
  }
}

function reloadSource() {
  const o = options();
  if (state.source.kind === 'sample') state.viewer.loadSample(state.source.index, o);
  else state.viewer.loadText(state.source.text, o);
  state.viewer.setUp(ui.up.value);
  afterLoad(true);
}

// The mesh list names what is shown: after a file, an entry with its name
// (choosing it again reloads the file).
function listFile(name) {
  let o = ui.sample.querySelector('option[value="file"]');
  if (!o) {
    o = document.createElement('option');
    o.value = 'file';
    ui.sample.append(o);
  }
  o.textContent = name;
  ui.sample.value = 'file';
}

// Light-line spacings across the picture's height: the control's value, or
// the module's default while the control holds no valid number (an integer
// in its range).
function lineCount() {
  return ui.lines.value !== '' && ui.lines.checkValidity() ? Number(ui.lines.value) : state.viewer.defaultLines();
}

// The light lines follow the view: lineCount() spacings across the
// picture's height at the orbit target's depth, line 0 through the target.
// Gives the module the current view when the target, the zoom or the count
// changed (or always, with force); returns whether it did. The module then
// rewrites only the highlight parameters.
function syncView(force) {
  const c = state.camera;
  const height = c.visibleHeight();
  const lines = lineCount();
  const key = [...c.target, height, lines].join(' ');
  if (!force && key === state.viewKey) return false;
  state.viewer.setView(c.target, height, lines);
  state.viewKey = key;
  return true;
}

function uploadAll(frame) {
  const v = state.viewer;
  if (frame) {
    const b = v.bounds();
    if (b.lo.every(Number.isFinite) && b.hi.every(Number.isFinite)) state.camera.frame(b.lo, b.hi);
  }
  syncView(true);
  state.renderer.uploadSurface(v.surface());
  state.renderer.uploadNet(v.control(), true);
  updateStatus();
  requestDraw();
}

function afterLoad(frame) {
  state.renderer.selected = -1;
  uploadAll(frame);
}

function formatNumber(x) {
  if (x === 0) return '0';
  const a = Math.abs(x);
  return a >= 1e4 || a < 1e-2 ? x.toExponential(2) : x.toPrecision(3);
}

function updateStatus() {
  const s = state.viewer.summary();
  if (!s) return;
  const kinds = Object.entries(s.patches).filter(([, n]) => n > 0).map(([k, n]) => `${n} ${k}`).join(', ');
  const caps = s.caps.map((c) => `${c.count}× ${c.scheme} n=${c.valence}`).join(', ') || 'none';
  const uncovered = s.uncovered_faces ? ` · ${s.uncovered_faces} faces uncovered` : '';
  const refined = s.refinement_steps ? ` · refined ${s.refinement_steps}×` : '';
  const name = state.source.kind === 'text' ? state.source.name : s.name;
  ui.status.textContent = `${name}: ${s.vertices} control points, ${s.faces} faces${refined}${uncovered} · patches: ${kinds} · caps: ${caps} · ${s.surface_vertices} samples (grid ${s.grid})`;
  const shading = ui.shading.value;
  const curvature = shading === 'gaussian' || shading === 'mean';
  ui.legend.hidden = !curvature;
  if (curvature) {
    const m = state.viewer.scale();
    ui.legend.querySelector('.title').textContent = shading === 'gaussian' ? 'Gaussian curvature K' : 'mean curvature H';
    ui.legend.querySelector('.lo').textContent = formatNumber(-m);
    ui.legend.querySelector('.hi').textContent = formatNumber(m);
  }
}

function requestDraw() {
  if (state.frame) return;
  state.frame = requestAnimationFrame(() => {
    state.frame = 0;
    if (state.pending) applyPendingEdit();
    // A zoom or pan moves the light lines: at most once a frame.
    try {
      if (syncView(false) && ui.shading.value === 'highlight') state.renderer.uploadStripes(state.viewer.surface());
    } catch (e) {
      showMessage(describeError(e));
    }
    state.renderer.draw(state.camera, SHADING_CODES[ui.shading.value], ui.net.checked);
  });
}

// One edit: WASM evaluate (+ re-sample, paint) and the buffer upload.
function edit(i, p, split) {
  const t0 = performance.now();
  state.viewer.moveVertex(i, p);
  if (split) split.push(performance.now() - t0);
  const s = state.viewer.surface();
  state.renderer.uploadDirty(s);
  state.renderer.uploadNet(state.viewer.control(), false);
  const t1 = performance.now();
  return t1 - t0;
}

function applyPendingEdit() {
  const { i, p } = state.pending;
  state.pending = null;
  try {
    const ms = edit(i, p);
    state.lastEdit = ms;
    ui.edit.textContent = `edit → surface ${ms.toFixed(2)} ms`;
  } catch (e) {
    showMessage(describeError(e));
  }
}

// ---- mouse: drag a control point, or orbit; wheel zooms ----

function controlPoint(i) {
  const pts = state.viewer.control().points;
  return [pts[3 * i], pts[3 * i + 1], pts[3 * i + 2]];
}

function screenOf(p) {
  const r = ui.canvas.getBoundingClientRect();
  const mvp = state.camera.matrix(ui.canvas.width / ui.canvas.height);
  return project(mvp, p, r.width, r.height);
}

function pick(x, y) {
  if (!ui.net.checked) return -1;
  const c = state.viewer.control();
  const r = ui.canvas.getBoundingClientRect();
  const mvp = state.camera.matrix(ui.canvas.width / ui.canvas.height);
  let best = -1;
  let bestD = PICK_RADIUS;
  let bestDepth = Infinity;
  for (let i = 0; i < c.count; i++) {
    const p = [c.points[3 * i], c.points[3 * i + 1], c.points[3 * i + 2]];
    const s = project(mvp, p, r.width, r.height);
    if (!s) continue;
    const d = Math.hypot(s[0] - x, s[1] - y);
    const eye = state.camera.eye();
    const depth = Math.hypot(p[0] - eye[0], p[1] - eye[1], p[2] - eye[2]);
    if (d < bestD - 2 || (d <= bestD + 2 && depth < bestDepth)) {
      best = i;
      bestD = Math.min(d, bestD);
      bestDepth = depth;
    }
  }
  return best;
}

ui.canvas.addEventListener('pointerdown', (ev) => {
  const r = ui.canvas.getBoundingClientRect();
  const x = ev.clientX - r.left;
  const y = ev.clientY - r.top;
  const i = pick(x, y);
  ui.canvas.setPointerCapture(ev.pointerId);
  if (i >= 0) {
    const p = controlPoint(i);
    state.drag = { kind: 'point', i, start: p, x, y, size: state.camera.pixelSize(p, r.height), axes: state.camera.axes() };
    state.renderer.selected = i;
  } else if (ev.shiftKey || ev.button === 2) {
    state.drag = { kind: 'pan', x, y, target: state.camera.target.slice(), size: state.camera.pixelSize(state.camera.target, r.height), axes: state.camera.axes() };
  } else {
    state.drag = { kind: 'orbit', x, y, yaw: state.camera.yaw, pitch: state.camera.pitch };
  }
  requestDraw();
});

ui.canvas.addEventListener('pointermove', (ev) => {
  const d = state.drag;
  if (!d) return;
  const r = ui.canvas.getBoundingClientRect();
  const dx = ev.clientX - r.left - d.x;
  const dy = ev.clientY - r.top - d.y;
  if (d.kind === 'orbit') {
    state.camera.yaw = d.yaw - dx * 0.01;
    state.camera.pitch = Math.max(-1.5, Math.min(1.5, d.pitch + dy * 0.01));
  } else if (d.kind === 'pan') {
    const { right, up } = d.axes;
    state.camera.target = [0, 1, 2].map((k) => d.target[k] - d.size * (dx * right[k] - dy * up[k]));
  } else {
    const { right, up } = d.axes;
    const p = [0, 1, 2].map((k) => d.start[k] + d.size * (dx * right[k] - dy * up[k]));
    state.pending = { i: d.i, p };
  }
  requestDraw();
});

function endDrag() {
  const d = state.drag;
  state.drag = null;
  if (d && d.kind === 'point') {
    if (state.pending) applyPendingEdit();
    // The colour scale and light lines follow the new surface.
    guarded(() => {
      state.viewer.rescale();
      uploadAll(false);
    });
  }
}
ui.canvas.addEventListener('pointerup', endDrag);
ui.canvas.addEventListener('contextmenu', (ev) => ev.preventDefault());
ui.canvas.addEventListener('pointercancel', endDrag);

ui.canvas.addEventListener('wheel', (ev) => {
  ev.preventDefault();
  state.camera.distance *= Math.exp(ev.deltaY * 0.001);
  requestDraw();
}, { passive: false });

// ---- selectors ----

function listedSource() {
  return state.source.kind === 'sample' ? String(state.source.index) : 'file';
}

ui.sample.addEventListener('change', async () => {
  const ok = await guarded(() => {
    if (ui.sample.value === 'file') {
      state.viewer.loadText(state.file.text, options());
      state.source = state.file;
    } else {
      const index = Number(ui.sample.value);
      state.viewer.loadSample(index, options());
      state.source = { kind: 'sample', index };
    }
    state.viewer.setUp(ui.up.value);
    showMessage('');
    afterLoad(true);
  });
  if (!ok) ui.sample.value = listedSource();
});

function optionSelector(el) {
  let previous = el.value;
  el.addEventListener('change', async () => {
    const ok = await guarded(() => {
      state.viewer.setOptions(options());
      showMessage('');
      afterLoad(false);
    });
    if (ok) previous = el.value;
    else el.value = previous;
  });
}
optionSelector(ui.scheme);
optionSelector(ui.depth);
optionSelector(ui.grid);

ui.shading.addEventListener('change', () => {
  guarded(() => {
    state.viewer.setShading(ui.shading.value);
    uploadAll(false);
  });
});
ui.up.addEventListener('change', () => {
  guarded(() => {
    state.viewer.setUp(ui.up.value);
    state.camera.up = ui.up.value;
    uploadAll(false);
  });
});
ui.net.addEventListener('change', requestDraw);
ui.lines.addEventListener('input', requestDraw);

// ---- export: Wavefront OBJ downloads ----

function sourceStem() {
  const name = state.source.kind === 'text' ? state.source.name : state.viewer.summary().name;
  return name.replace(/\.[^.]*$/, '') || 'mesh';
}

function download(name, text) {
  const url = URL.createObjectURL(new Blob([text], { type: 'model/obj' }));
  const a = document.createElement('a');
  a.href = url;
  a.download = name;
  document.body.append(a);
  a.click();
  a.remove();
  setTimeout(() => URL.revokeObjectURL(url), 1000);
}

ui.saveMesh.addEventListener('click', () => guarded(() => {
  download(`${sourceStem()}-mesh.obj`, state.viewer.exportObj('mesh'));
}));
ui.saveSurface.addEventListener('click', () => guarded(() => {
  download(`${sourceStem()}-surface.obj`, state.viewer.exportObj('surface'));
}));
ui.reset.addEventListener('click', () => guarded(() => {
  state.viewer.reset();
  uploadAll(false);
}));

// ---- files: drop or open ----

async function loadFile(file) {
  let text;
  try {
    text = await file.text();
  } catch (e) {
    showMessage(`${file.name}: cannot be read (${describeError(e)})`);
    return;
  }
  await guarded(() => {
    try {
      state.viewer.loadText(text, options());
    } catch (e) {
      if (e instanceof ModuleError) throw new ModuleError(`${file.name}: ${e.message}`);
      throw e;
    }
    state.viewer.setUp(ui.up.value);
    state.source = { kind: 'text', text, name: file.name };
    state.file = state.source;
    listFile(file.name);
    showMessage(`${file.name} loaded`, 'info');
    afterLoad(true);
  });
}

document.addEventListener('dragover', (ev) => {
  ev.preventDefault();
  document.body.classList.add('dropping');
});
document.addEventListener('dragleave', () => document.body.classList.remove('dropping'));
document.addEventListener('drop', (ev) => {
  ev.preventDefault();
  document.body.classList.remove('dropping');
  const file = ev.dataTransfer && ev.dataTransfer.files[0];
  if (file) loadFile(file);
});
ui.file.addEventListener('change', () => {
  if (ui.file.files[0]) loadFile(ui.file.files[0]);
  ui.file.value = '';
});
window.addEventListener('resize', requestDraw);

// ---- start ----

async function start() {
  state.renderer = new Renderer(ui.canvas);
  state.viewer = await Viewer.load(new URL('build/capdiv_viewer.wasm', document.baseURI));
  ui.lines.value = String(state.viewer.defaultLines());
  state.viewer.samples().forEach((s, i) => {
    const o = document.createElement('option');
    o.value = String(i);
    o.textContent = s.name;
    o.title = s.about;
    ui.sample.append(o);
  });
  state.viewer.loadSample(0, options());
  afterLoad(true);
}

// What the browser test uses: readiness, screen positions of control points,
// and the edit timing loop (performance.now() around evaluate + upload).
window.capdiv = {
  ready: start().then(() => true, (e) => {
    showMessage(describeError(e));
    throw e;
  }),
  controlPointOnScreen(i) {
    return screenOf(controlPoint(i));
  },
  controlPoint(i) {
    return controlPoint(i);
  },
  controlPointCount() {
    return state.viewer.control().count;
  },
  summary() {
    return state.viewer.summary();
  },
  // The control net's edges as 'a-b' (a < b).
  netEdges() {
    const e = state.viewer.control().edges;
    const out = [];
    for (let k = 0; k < e.length; k += 2) out.push(`${Math.min(e[k], e[k + 1])}-${Math.max(e[k], e[k + 1])}`);
    return out;
  },
  bounds() {
    return state.viewer.bounds();
  },
  cameraUp() {
    return state.camera.upVector();
  },
  // The orbit camera: yaw, pitch (radians), distance, target, and the
  // world length the picture's height spans at the target's depth.
  camera() {
    const c = state.camera;
    return { yaw: c.yaw, pitch: c.pitch, distance: c.distance, target: c.target.slice(), height: c.visibleHeight() };
  },
  // Sets some of yaw, pitch, distance and target.
  setCamera(o) {
    for (const k of ['yaw', 'pitch', 'distance', 'target']) if (o[k] !== undefined) state.camera[k] = o[k];
    requestDraw();
  },
  exportObj(what) {
    return state.viewer.exportObj(what);
  },
  // Highlight stripes filtered over each pixel (true, the page's way) or
  // sampled once per pixel (false: the anti-aliasing test's control).
  setStripeFilter(on) {
    state.renderer.filterStripes = on;
    requestDraw();
  },
  // Edits control points `count` times (a ±1 % nudge of the box size along
  // x and back, cycling through points spread over the mesh and the point
  // of the largest cap); returns the edit-to-surface times in ms (`times`)
  // and their WASM part (`wasm`).
  benchmarkEdits(count) {
    const c = state.viewer.control();
    const b = state.viewer.bounds();
    const nudge = 0.01 * Math.max(...[0, 1, 2].map((k) => b.hi[k] - b.lo[k]));
    const points = [];
    for (let k = 0; k < 8; k++) points.push(Math.floor((k * c.count) / 8));
    // The point of highest valence: the centre of the largest cap.
    const degree = new Uint32Array(c.count);
    for (const v of c.edges) degree[v]++;
    points.push(degree.indexOf(Math.max(...degree)));
    const times = [];
    const wasm = [];
    for (let r = 0; r < count; r++) {
      const i = points[r % points.length];
      const p = controlPoint(i);
      times.push(edit(i, [p[0] + nudge, p[1], p[2]], wasm));
      times.push(edit(i, p, wasm));
    }
    state.viewer.rescale();
    uploadAll(false);
    return { times, wasm };
  },
};
