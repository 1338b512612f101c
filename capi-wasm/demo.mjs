// Loads capdiv's WebAssembly module with node (no npm dependencies) and runs
// sample polar nets through its C ABI (src/lib.rs).
//
//   node capi-wasm/demo.mjs [path/to/capdiv_capi_wasm.wasm]
//
// Prints one block per case, every f64 as the 16 hex digits of its bits, so a
// host test can recompute each case with the native kernel and compare bit for
// bit (embedded-tests/tests/wasm_node.rs). The module is instantiated with no
// imports: a panic path left in it would be an import, and this fails.
import { readFileSync } from "node:fs";
import { fileURLToPath } from "node:url";
import { dirname, join } from "node:path";

const here = dirname(fileURLToPath(import.meta.url));
const path =
  process.argv[2] ??
  join(here, "target/wasm32-unknown-unknown/release/capdiv_capi_wasm.wasm");
const { instance } = await WebAssembly.instantiate(readFileSync(path), {});
const w = instance.exports;

// Caller-owned buffers: the module allocates nothing above __heap_base.
const F64 = 8;
let base = (w.__heap_base.value + 7) & ~7;
function ensure(bytes) {
  const need = base + bytes - w.memory.buffer.byteLength;
  if (need > 0) w.memory.grow(Math.ceil(need / 65536));
}
function put(values, at) {
  new Float64Array(w.memory.buffer, at, values.length).set(values);
}
function get(at, count) {
  return Array.from(new Float64Array(w.memory.buffer, at, count));
}
const bits = new Float64Array(1);
const bitsU = new BigUint64Array(bits.buffer);
function hex(x) {
  bits[0] = x;
  return bitsU[0].toString(16).padStart(16, "0");
}
const line = (tag, xs) => console.log([tag, ...xs.map(hex)].join(" "));

// A deterministic generator (LCG) for perturbations.
let seed = 12345;
function rand() {
  seed = (seed * 1103515245 + 12345) % 2147483648;
  return seed / 2147483648 - 0.5;
}

// Links of radius ~i on a paraboloid, perturbed.
function net(valence, links) {
  const pole = [0.05 * rand(), 0.05 * rand(), 0.1 * rand()];
  const coords = [];
  for (let i = 1; i <= links; i++) {
    for (let j = 0; j < valence; j++) {
      const t = (2 * Math.PI * j) / valence;
      const r = i * (1 + 0.1 * rand());
      coords.push(r * Math.cos(t), r * Math.sin(t), 0.25 * i * i + 0.1 * rand());
    }
  }
  return { pole, coords };
}

const cases = [];
for (const valence of [3, 4, 5, 6, 7, 12]) {
  for (const links of [2, 3, 5, 7]) {
    for (const steps of [0, 1, 3, 6]) {
      cases.push({ valence, steps, plain: (valence + steps) % 2, ...net(valence, links) });
    }
  }
}
// Errors: too small a valence, beyond capacity, a non-finite coordinate,
// a ragged coordinate list, an unsupported valence.
cases.push({ valence: 2, steps: 1, plain: 0, ...net(2, 3) });
cases.push({ valence: 7, steps: 9, plain: 0, ...net(7, 5) });
const bad = net(5, 3);
bad.coords[7] = NaN;
cases.push({ valence: 5, steps: 1, plain: 0, ...bad });
const ragged = net(4, 3);
ragged.coords.pop();
cases.push({ valence: 4, steps: 1, plain: 0, ...ragged });
cases.push({ valence: 131, steps: 0, plain: 0, ...net(131, 2) });

const cap = w.capdiv_capacity();
let count = 0;
for (const c of cases) {
  const outLen = 5 + 3 * 5 * cap;
  const poleAt = base;
  const coordsAt = poleAt + 3 * F64;
  const outAt = coordsAt + c.coords.length * F64;
  const jetAt = outAt + outLen * F64;
  ensure(jetAt + 25 * F64 - base);
  put(c.pole, poleAt);
  put(c.coords, coordsAt);
  console.log(`case ${count} ${c.valence} ${c.steps} ${c.plain} ${c.coords.length}`);
  line("pole", c.pole);
  line("coords", c.coords);
  const r = w.capdiv_c2ps_refine(poleAt, coordsAt, c.coords.length, c.valence, c.steps, c.plain, outAt, outLen);
  line(`refine ${r}`, r > 0 ? get(outAt, r) : []);
  const j = w.capdiv_c2ps_jet(poleAt, coordsAt, c.coords.length, c.valence, c.steps, c.plain, jetAt);
  line(`jet ${j}`, j > 0 ? get(jetAt, j) : []);
  count++;
}
// EG (docs/math/eg.md): c-nets of valence n, sector s spanned by the directions at
// 2πs/n and 2π(s+1)/n, nodes in the §1 order, on a perturbed paraboloid.
const order = [[1, 0], [2, 0], [1, 1], [2, 1], [1, 2], [2, 2]];
function cnet(n) {
  const center = [0.05 * rand(), 0.05 * rand(), 0.05 * rand()];
  const nodes = [];
  for (let s = 0; s < n; s++) {
    const a0 = (2 * Math.PI * s) / n;
    const a1 = (2 * Math.PI * (s + 1)) / n;
    for (const [x, y] of order) {
      const px = x * Math.cos(a0) + y * Math.cos(a1) + 0.05 * rand();
      const py = x * Math.sin(a0) + y * Math.sin(a1) + 0.05 * rand();
      nodes.push(px, py, 0.2 * (px * px + py * py) + 0.05 * rand());
    }
  }
  return { center, nodes };
}
const egCases = [];
for (const n of [3, 4, 5]) {
  for (const steps of [0, 1, 4]) egCases.push({ steps, ...cnet(n) });
}
// Errors: valence 6 has no built-in rule; 2 sectors; a ragged node list.
egCases.push({ steps: 1, ...cnet(6) });
egCases.push({ steps: 1, ...cnet(2) });
const raggedEg = cnet(3);
raggedEg.nodes.pop();
egCases.push({ steps: 1, ...raggedEg });

let egCount = 0;
for (const c of egCases) {
  const outLen = 225 * 10;
  const centerAt = base;
  const nodesAt = centerAt + 3 * F64;
  const outAt = nodesAt + c.nodes.length * F64;
  ensure(outAt + outLen * F64 - base);
  put(c.center, centerAt);
  put(c.nodes, nodesAt);
  console.log(`egcase ${egCount} ${c.steps} ${c.nodes.length}`);
  line("center", c.center);
  line("nodes", c.nodes);
  const r = w.capdiv_eg_refine(centerAt, nodesAt, c.nodes.length, c.steps, outAt, outLen);
  line(`egrefine ${r}`, r > 0 ? get(outAt, r) : []);
  const g = w.capdiv_eg_ring(centerAt, nodesAt, c.nodes.length, c.steps, outAt, outLen);
  line(`egring ${g}`, g > 0 ? get(outAt, g) : []);
  egCount++;
}
console.log(`done ${count} ${egCount}`);
