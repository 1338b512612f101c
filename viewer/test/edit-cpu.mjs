// Edit cost of the viewer's WASM module in CPU time, not wall time: the same
// module and edit pattern as the page's benchmark (viewer.test.mjs), run in
// node's V8 (chromium's engine) and timed by process.cpuUsage(), so that a
// loaded machine's preemption does not count. No WebGL upload (the page's
// table has it). Run after viewer/build.sh: node viewer/test/edit-cpu.mjs [edits]
import fs from 'node:fs';
import { fileURLToPath } from 'node:url';

const wasmPath = fileURLToPath(new URL('../build/capdiv_viewer.wasm', import.meta.url));
const { instance } = await WebAssembly.instantiate(fs.readFileSync(wasmPath), {});
const w = instance.exports;
const text = () => new TextDecoder().decode(new Uint8Array(w.memory.buffer, w.viewer_text_ptr(), w.viewer_text_len()));
const reps = Number(process.argv[2] || 100);
const cpu = () => {
  const u = process.cpuUsage();
  return (u.user + u.system) / 1000;
};

console.log(`CPU ms per edit (evaluate + re-sample + paint in WASM), depth 4, automatic grid, ${2 * reps} edits:`);
console.log('| mesh | median | 95 % | max |\n|---|---:|---:|---:|');
for (let s = 0; s < w.viewer_sample_count(); s++) {
  w.viewer_sample_text(s, 0);
  const name = text();
  if (w.viewer_load_sample(s, 4, 0, 0, 0) !== 0) throw new Error(`${name}: ${text()}`);
  const n = w.viewer_control_count();
  const edges = new Uint32Array(w.memory.buffer, w.viewer_edges(), 2 * w.viewer_edge_count()).slice();
  const degree = new Uint32Array(n);
  for (const v of edges) degree[v]++;
  const points = [];
  for (let k = 0; k < 8; k++) points.push(Math.floor((k * n) / 8));
  points.push(degree.indexOf(Math.max(...degree)));
  const lo = [0, 1, 2].map((k) => w.viewer_bounds(k));
  const hi = [0, 1, 2].map((k) => w.viewer_bounds(3 + k));
  const nudge = 0.01 * Math.max(...[0, 1, 2].map((k) => hi[k] - lo[k]));
  const times = [];
  for (let r = 0; r < reps; r++) {
    const i = points[r % points.length];
    const c = new Float32Array(w.memory.buffer, w.viewer_control_points(), 3 * n);
    const p = [c[3 * i], c[3 * i + 1], c[3 * i + 2]];
    for (const x of [p[0] + nudge, p[0]]) {
      const t0 = cpu();
      if (w.viewer_move_vertex(i, x, p[1], p[2]) !== 0) throw new Error(`${name}: ${text()}`);
      times.push(cpu() - t0);
    }
  }
  times.sort((a, b) => a - b);
  const at = (q) => times[Math.min(times.length - 1, Math.floor(q * times.length))].toFixed(2);
  console.log(`| ${name} | ${at(0.5)} | ${at(0.95)} | ${at(1)} |`);
}
