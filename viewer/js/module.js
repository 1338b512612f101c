// The WASM module (viewer/wasm, crate capdiv-viewer) behind a small JS API.
// Plain WebAssembly.instantiate, no imports, no wasm-bindgen: every export
// takes and returns numbers; buffers are read through fresh typed-array
// views into the module's memory after each call (memory may grow).

const SHADINGS = ['plain', 'highlight', 'gaussian', 'mean'];

export class ModuleError extends Error {}

export class Viewer {
  static async load(url) {
    const response = await fetch(url);
    if (!response.ok) throw new ModuleError(`${url}: HTTP ${response.status} (build it: bash viewer/build.sh)`);
    const bytes = await response.arrayBuffer();
    const { instance } = await WebAssembly.instantiate(bytes, {});
    return new Viewer(instance.exports, bytes);
  }

  constructor(exports, bytes) {
    this.w = exports;
    this.bytes = bytes;
  }

  // After a trap (a bug in the module) its state is unusable: a new instance.
  async restart() {
    const { instance } = await WebAssembly.instantiate(this.bytes, {});
    this.w = instance.exports;
  }

  text() {
    const w = this.w;
    return new TextDecoder().decode(new Uint8Array(w.memory.buffer, w.viewer_text_ptr(), w.viewer_text_len()));
  }

  // Runs an export returning a status: throws the module's message on -1.
  check(status) {
    if (status < 0) throw new ModuleError(this.text());
  }

  samples() {
    const out = [];
    for (let i = 0; i < this.w.viewer_sample_count(); i++) {
      this.w.viewer_sample_text(i, 0);
      const name = this.text();
      this.w.viewer_sample_text(i, 1);
      out.push({ name, about: this.text() });
    }
    return out;
  }

  static shadingCode(name) {
    const code = SHADINGS.indexOf(name);
    if (code < 0) throw new ModuleError(`unknown shading ${name}`);
    return code;
  }

  loadSample(index, o) {
    this.check(this.w.viewer_load_sample(index, o.depth, o.catmullClark ? 1 : 0, o.grid, Viewer.shadingCode(o.shading)));
  }

  loadText(text, o) {
    const bytes = new TextEncoder().encode(text);
    const ptr = this.w.viewer_text_alloc(bytes.length);
    new Uint8Array(this.w.memory.buffer, ptr, bytes.length).set(bytes);
    this.check(this.w.viewer_load_text(o.depth, o.catmullClark ? 1 : 0, o.grid, Viewer.shadingCode(o.shading)));
  }

  setOptions(o) {
    this.check(this.w.viewer_set_options(o.depth, o.catmullClark ? 1 : 0, o.grid));
  }

  setShading(name) {
    this.check(this.w.viewer_set_shading(Viewer.shadingCode(name)));
  }

  moveVertex(i, p) {
    this.check(this.w.viewer_move_vertex(i, p[0], p[1], p[2]));
  }

  // The axis shown upward: 'z' or 'y' (the light lines' plane lies above).
  setUp(axis) {
    const code = { z: 0, y: 1 }[axis];
    if (code === undefined) throw new ModuleError(`up axis ${axis}: z or y`);
    this.check(this.w.viewer_set_up(code));
  }

  // The view the highlight lines are spaced in: the orbit target, the world
  // length the picture's height spans at its depth, and the line spacings
  // across it. Under the highlight shading only the stripe buffer changes.
  setView(target, height, lines) {
    this.check(this.w.viewer_set_view(target[0], target[1], target[2], height, lines));
  }

  // Light-line spacings across the picture's height by default (the CLI's).
  defaultLines() {
    return this.w.viewer_default_lines();
  }

  // Wavefront OBJ text of the control mesh as edited ('mesh') or of the
  // shown surface ('surface').
  exportObj(what) {
    const code = { mesh: 0, surface: 1 }[what];
    if (code === undefined) throw new ModuleError(`export ${what}: mesh or surface`);
    this.check(this.w.viewer_export_obj(code));
    return this.text();
  }

  rescale() {
    this.check(this.w.viewer_rescale());
  }

  reset() {
    this.check(this.w.viewer_reset());
  }

  summary() {
    this.w.viewer_summary();
    return JSON.parse(this.text());
  }

  scale() {
    return this.w.viewer_scale();
  }

  bounds() {
    const b = [];
    for (let k = 0; k < 6; k++) b.push(this.w.viewer_bounds(k));
    return { lo: b.slice(0, 3), hi: b.slice(3) };
  }

  // Typed views of the surface's buffers (valid until the next call).
  surface() {
    const w = this.w;
    const m = w.memory.buffer;
    const n = w.viewer_vertex_count();
    return {
      vertices: n,
      positions: new Float32Array(m, w.viewer_positions(), 3 * n),
      normals: new Float32Array(m, w.viewer_normals(), 3 * n),
      colors: new Uint8Array(m, w.viewer_colors(), 4 * n),
      stripes: new Float32Array(m, w.viewer_stripes(), n),
      indices: new Uint32Array(m, w.viewer_indices(), w.viewer_index_count()),
      dirty: [w.viewer_dirty_first(), w.viewer_dirty_end()],
    };
  }

  control() {
    const w = this.w;
    const m = w.memory.buffer;
    const n = w.viewer_control_count();
    return {
      count: n,
      points: new Float32Array(m, w.viewer_control_points(), 3 * n),
      edges: new Uint32Array(m, w.viewer_edges(), 2 * w.viewer_edge_count()),
    };
  }
}
