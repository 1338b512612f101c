// capdiv's glTF output checked by its real clients: the Khronos glTF
// validator (npm gltf-validator) and three.js's GLTFLoader (npm three) in
// Debian's chromium, headless, driven by playwright-core.
//
// Run by scripts/ci-exchange.sh: EXCHANGE_DIR holds, per case, NAME.glb and
// NAME.gltf written by `capdiv surface --format glb|gltf`, and NAME.expect,
// the counts capdiv reported writing: `nodes vertices triangles`, and
// optionally a second line with the node names the input's objects give
// (may be empty) and a third line `uv` when the meshes carry TEXCOORD_0.
// Env: CHROMIUM (default /usr/bin/chromium); EXCHANGE_SCREENSHOT=path.png
// saves the rendering of case EXCHANGE_SCREENSHOT_CASE (default hand.glb).
import { test } from 'node:test';
import assert from 'node:assert/strict';
import fs from 'node:fs/promises';
import http from 'node:http';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import validator from 'gltf-validator';
import { chromium } from 'playwright-core';

const HERE = path.dirname(fileURLToPath(import.meta.url));
const DIR = process.env.EXCHANGE_DIR;
const CHROMIUM = process.env.CHROMIUM || '/usr/bin/chromium';
const BACKGROUND = [255, 255, 255];

const names = (await fs.readdir(DIR)).filter((f) => f.endsWith('.expect')).map((f) => f.slice(0, -7)).sort();

async function expected(name) {
  const [counts, nodeNames, uv] = (await fs.readFile(path.join(DIR, `${name}.expect`), 'utf8')).split('\n');
  const [nodes, vertices, triangles] = counts.trim().split(/\s+/).map(Number);
  return {
    nodes, vertices, triangles,
    names: nodeNames && nodeNames.trim() ? nodeNames.trim().split(/\s+/) : null,
    uv: (uv || '').trim() === 'uv',
  };
}

test('there are cases', () => {
  assert.ok(names.length >= 6, `cases: ${names.join(', ')}`);
});

test('the Khronos validator: no error, no warning', async (t) => {
  for (const name of names) {
    for (const ext of ['glb', 'gltf']) {
      await t.test(`${name}.${ext}`, async () => {
        const bytes = new Uint8Array(await fs.readFile(path.join(DIR, `${name}.${ext}`)));
        const report = await validator.validateBytes(bytes, { uri: `${name}.${ext}`, maxIssues: 0 });
        const { numErrors, numWarnings, numInfos, numHints } = report.issues;
        const shown = report.issues.messages.filter((m) => m.severity <= 1).slice(0, 5)
          .map((m) => `${m.code} ${m.pointer || ''}: ${m.message}`);
        console.log(`validator ${name}.${ext}: ${numErrors} errors, ${numWarnings} warnings, ${numInfos} infos, ${numHints} hints`);
        assert.equal(numErrors, 0, shown.join('; '));
        assert.equal(numWarnings, 0, shown.join('; '));
        const e = await expected(name);
        assert.equal(report.info.drawCallCount, e.nodes);
        assert.equal(report.info.totalVertexCount, e.vertices);
        assert.equal(report.info.totalTriangleCount, e.triangles);
      });
    }
  }
});

// Serves this folder (three's modules under node_modules/), the page below
// and the case files, on loopback.
function serve() {
  const page = `<!doctype html><html><body style="margin:0;background:#fff">
<canvas id="view" width="480" height="360"></canvas>
<script type="importmap">{"imports": {"three": "/node_modules/three/build/three.module.js",
 "three/addons/": "/node_modules/three/examples/jsm/"}}</script>
<script type="module">
import * as THREE from 'three';
import { GLTFLoader } from 'three/addons/loaders/GLTFLoader.js';
window.load = async (url) => {
  const gltf = await new GLTFLoader().loadAsync(url);
  const stats = { meshes: 0, vertices: 0, triangles: 0, names: [] };
  gltf.scene.traverse((o) => {
    if (o.isMesh) {
      stats.meshes++;
      stats.vertices += o.geometry.attributes.position.count;
      stats.triangles += o.geometry.index.count / 3;
      stats.names.push(o.name);
      stats.hasNormals = !!o.geometry.attributes.normal;
      stats.hasUv = !!o.geometry.attributes.uv;
    }
  });
  const canvas = document.getElementById('view');
  const renderer = new THREE.WebGLRenderer({ canvas, preserveDrawingBuffer: true, antialias: false });
  renderer.setClearColor(0xffffff, 1);
  const scene = new THREE.Scene();
  scene.add(gltf.scene);
  scene.add(new THREE.AmbientLight(0xffffff, 0.3));
  const light = new THREE.DirectionalLight(0xffffff, 2.5);
  light.position.set(1, 2, 3);
  scene.add(light);
  const box = new THREE.Box3().setFromObject(gltf.scene);
  const centre = box.getCenter(new THREE.Vector3());
  const radius = box.getSize(new THREE.Vector3()).length() / 2;
  const camera = new THREE.PerspectiveCamera(40, canvas.width / canvas.height, radius / 100, radius * 100);
  camera.position.copy(centre).add(new THREE.Vector3(0.6, 0.5, 1).normalize().multiplyScalar(radius * 2.2));
  camera.lookAt(centre);
  renderer.render(scene, camera);
  const gl = renderer.getContext();
  const px = new Uint8Array(canvas.width * canvas.height * 4);
  gl.readPixels(0, 0, canvas.width, canvas.height, gl.RGBA, gl.UNSIGNED_BYTE, px);
  let covered = 0;
  const colours = new Set();
  for (let i = 0; i < px.length; i += 4) {
    if (Math.abs(px[i] - 255) + Math.abs(px[i + 1] - 255) + Math.abs(px[i + 2] - 255) > 12) {
      covered++;
      colours.add((px[i] >> 3) * 1024 + (px[i + 1] >> 3) * 32 + (px[i + 2] >> 3));
    }
  }
  renderer.dispose();
  stats.covered = covered / (canvas.width * canvas.height);
  stats.shades = colours.size;
  return stats;
};
window.ready = true;
</script></body></html>`;
  const server = http.createServer(async (req, res) => {
    const url = new URL(req.url, 'http://localhost');
    try {
      if (url.pathname === '/favicon.ico') {
        res.writeHead(204);
        return res.end();
      }
      if (url.pathname === '/') {
        res.writeHead(200, { 'content-type': 'text/html; charset=utf-8' });
        return res.end(page);
      }
      const [base, rel] = url.pathname.startsWith('/cases/')
        ? [DIR, url.pathname.slice(7)]
        : [HERE, url.pathname.slice(1)];
      const file = path.normalize(path.join(base, decodeURIComponent(rel)));
      if (!file.startsWith(path.resolve(base))) throw Object.assign(new Error('outside'), { code: 'ENOENT' });
      const body = await fs.readFile(file);
      const type = file.endsWith('.js') ? 'text/javascript; charset=utf-8' : 'application/octet-stream';
      res.writeHead(200, { 'content-type': type });
      res.end(body);
    } catch (e) {
      res.writeHead(404, { 'content-type': 'text/plain' });
      res.end(String(e.code || e));
    }
  });
  return new Promise((resolve) => server.listen(0, '127.0.0.1', () => resolve(server)));
}

test('three.js GLTFLoader in headless chromium', async (t) => {
  const server = await serve();
  const origin = `http://127.0.0.1:${server.address().port}`;
  const browser = await chromium.launch({
    executablePath: CHROMIUM,
    args: ['--no-sandbox', '--use-angle=swiftshader', '--enable-unsafe-swiftshader', '--ignore-gpu-blocklist'],
  });
  const errors = [];
  try {
    const page = await browser.newPage({ viewport: { width: 480, height: 360 } });
    page.on('console', (m) => { if (m.type() === 'error') errors.push(`console: ${m.text()}`); });
    page.on('pageerror', (e) => errors.push(`page: ${e.message}`));
    await page.goto(`${origin}/`);
    await page.waitForFunction(() => window.ready === true);
    const shot = process.env.EXCHANGE_SCREENSHOT_CASE || 'hand.glb';
    for (const name of names) {
      for (const ext of ['glb', 'gltf']) {
        await t.test(`${name}.${ext}`, async () => {
          const s = await page.evaluate((u) => window.load(u), `/cases/${name}.${ext}`);
          const e = await expected(name);
          console.log(`three.js ${name}.${ext}: ${s.meshes} meshes, ${s.vertices} vertices, ${s.triangles} triangles; ` +
            `${(100 * s.covered).toFixed(1)} % of the canvas covered, ${s.shades} shades`);
          assert.deepEqual(errors, []);
          assert.equal(s.meshes, e.nodes);
          assert.equal(s.vertices, e.vertices);
          assert.equal(s.triangles, e.triangles);
          assert.equal(s.hasNormals, true);
          assert.equal(s.hasUv, e.uv);
          if (e.names) assert.deepEqual(s.names, e.names);
          // Not blank: the surface covers a good part of the view, lit (many shades).
          assert.ok(s.covered > 0.05, `covered ${s.covered}`);
          assert.ok(s.shades > 20, `shades ${s.shades}`);
          if (`${name}.${ext}` === shot && process.env.EXCHANGE_SCREENSHOT) {
            await page.locator('#view').screenshot({ path: process.env.EXCHANGE_SCREENSHOT });
          }
        });
      }
    }
  } finally {
    await browser.close();
    server.close();
  }
});
