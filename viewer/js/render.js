// WebGL2 drawing of the surface and its control net, and the orbit camera.
// Shading is per pixel from per-vertex attributes the WASM module computed:
// exact normals, colours (curvature maps) and the highlight-line parameter.

// ---- 4×4 matrices, column-major (as WebGL wants them) ----

function perspective(fovy, aspect, near, far) {
  const f = 1 / Math.tan(fovy / 2);
  const nf = 1 / (near - far);
  return new Float32Array([f / aspect, 0, 0, 0, 0, f, 0, 0, 0, 0, (far + near) * nf, -1, 0, 0, 2 * far * near * nf, 0]);
}

function sub(a, b) { return [a[0] - b[0], a[1] - b[1], a[2] - b[2]]; }
function cross(a, b) { return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]; }
function dot(a, b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
function unit(a) { const l = Math.hypot(a[0], a[1], a[2]) || 1; return [a[0] / l, a[1] / l, a[2] / l]; }

function lookAt(eye, target, up) {
  const z = unit(sub(eye, target));
  const x = unit(cross(up, z));
  const y = cross(z, x);
  return new Float32Array([x[0], y[0], z[0], 0, x[1], y[1], z[1], 0, x[2], y[2], z[2], 0,
    -dot(x, eye), -dot(y, eye), -dot(z, eye), 1]);
}

function multiply(a, b) {
  const o = new Float32Array(16);
  for (let c = 0; c < 4; c++) for (let r = 0; r < 4; r++) {
    let s = 0;
    for (let k = 0; k < 4; k++) s += a[k * 4 + r] * b[c * 4 + k];
    o[c * 4 + r] = s;
  }
  return o;
}

// Orbit camera about a target, z or y up. With y up the orbit is z up's
// turned with the model: z up's x, y, z are y up's x, −z, y.
export class Camera {
  constructor() {
    this.yaw = -0.9;
    this.pitch = 0.35;
    this.distance = 4;
    this.target = [0, 0, 0];
    this.fovy = (40 * Math.PI) / 180;
    this.up = 'z';
  }

  upVector() {
    return this.up === 'y' ? [0, 1, 0] : [0, 0, 1];
  }

  frame(lo, hi) {
    this.target = [0, 1, 2].map((k) => 0.5 * (lo[k] + hi[k]));
    const r = 0.5 * Math.hypot(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]) || 1;
    this.radius = r;
    this.distance = (0.8 * r) / Math.sin(this.fovy / 2);
  }

  eye() {
    const cp = Math.cos(this.pitch);
    const d = this.distance;
    const [a, b, h] = [d * cp * Math.cos(this.yaw), d * cp * Math.sin(this.yaw), d * Math.sin(this.pitch)];
    const off = this.up === 'y' ? [a, h, -b] : [a, b, h];
    return [0, 1, 2].map((k) => this.target[k] + off[k]);
  }

  // Unit vectors of the screen's right and up directions in the world.
  axes() {
    const z = unit(sub(this.eye(), this.target));
    const x = unit(cross(this.upVector(), z));
    return { right: x, up: cross(z, x), back: z };
  }

  matrix(aspect) {
    const r = this.radius || 1;
    const near = Math.max(this.distance - 3 * r, this.distance * 0.01);
    const far = this.distance + 3 * r;
    return multiply(perspective(this.fovy, aspect, near, far), lookAt(this.eye(), this.target, this.upVector()));
  }

  // World length the picture's height spans at the target's depth.
  visibleHeight() {
    return 2 * this.distance * Math.tan(this.fovy / 2);
  }

  // World length of one pixel at the depth of point p.
  pixelSize(p, heightPx) {
    const depth = dot(sub(this.eye(), p), this.axes().back);
    return (2 * depth * Math.tan(this.fovy / 2)) / heightPx;
  }
}

// Screen position (CSS pixels from the top left) of world point p.
export function project(mvp, p, width, height) {
  const x = mvp[0] * p[0] + mvp[4] * p[1] + mvp[8] * p[2] + mvp[12];
  const y = mvp[1] * p[0] + mvp[5] * p[1] + mvp[9] * p[2] + mvp[13];
  const w = mvp[3] * p[0] + mvp[7] * p[1] + mvp[11] * p[2] + mvp[15];
  if (w <= 0) return null;
  return [((x / w) * 0.5 + 0.5) * width, (0.5 - (y / w) * 0.5) * height];
}

const SURFACE_VS = `#version 300 es
in vec3 aPos; in vec3 aNrm; in vec4 aCol; in float aStripe;
uniform mat4 uMvp;
out vec3 vPos; out vec3 vNrm; out vec4 vCol; out float vStripe;
void main() {
  vPos = aPos; vNrm = aNrm; vCol = aCol; vStripe = aStripe;
  gl_Position = uMvp * vec4(aPos, 1.0);
}`;

// uMode: 0 plain, 1 highlight lines, 2 and 3 curvature maps.
// Highlight stripes: intensity 1 − d/w within w of an integer parameter
// (capdiv_mesh::shade::HighlightLines::intensity), averaged over the pixel:
// with the parameter linear across the pixel square (its screen-space
// derivatives a, b: dFdx, dFdy), its values there are spread as the
// convolution of two boxes of widths |a| and |b|, and the stripe function's
// mean under that spread follows exactly from its second integral. Where
// lines are wider than a pixel this is the stripe itself, softened by a pixel
// at its edges; where many lines fall into one pixel (normals nearly
// parallel to the light plane, as on the sides of tall objects) it is their
// mean, w — never moiré. uFilter = 0 samples the stripe function once per
// pixel instead (the anti-aliasing test's control).
const SURFACE_FS = `#version 300 es
precision highp float;
in vec3 vPos; in vec3 vNrm; in vec4 vCol; in float vStripe;
uniform int uMode; uniform vec3 uEye; uniform vec3 uUp; uniform float uWidth; uniform int uFilter;
out vec4 outColor;
// G(x) = ∫₀ˣ F, F(y) = ∫₀ʸ stripe, for the stripe function of width w and
// period 1 (the tent's right half on [0, w), its left half on (1 − w, 1)):
// F rises by w per period, G(k) = w·k²/2; h is ∫ₖˣ (F − F(k)) within a period.
float stripeIntegral2(float x, float w) {
  float k = floor(x);
  float t = x - k;
  float h = t < w ? t * t / 2.0 - t * t * t / (6.0 * w) : w * w / 3.0 + (t - w) * w / 2.0;
  float b = max(t - (1.0 - w), 0.0);
  h += b * b * b / (6.0 * w);
  return w * k * k / 2.0 + k * w * t + h;
}
// The stripe function's mean over a pixel where the parameter is s at the
// centre with derivatives g. Derivatives under 0.01 (lines 100 pixels or
// more apart) are taken as 0.01, so that the float32 differences stay
// accurate (to about 1e-3).
float stripePixel(float s, vec2 g, float w) {
  float a = max(abs(g.x), 0.01);
  float b = max(abs(g.y), 0.01);
  return (stripeIntegral2(s + 0.5 * (a + b), w) - stripeIntegral2(s + 0.5 * (a - b), w)
    - stripeIntegral2(s - 0.5 * (a - b), w) + stripeIntegral2(s - 0.5 * (a + b), w)) / (a * b);
}
void main() {
  vec3 v = normalize(uEye - vPos);
  vec3 n = dot(vNrm, vNrm) > 0.0 ? normalize(vNrm) : v;
  if (dot(n, v) < 0.0) n = -n;
  vec3 l = normalize(v + 0.6 * normalize(cross(v, uUp) + 0.8 * uUp));
  float diffuse = max(dot(n, l), 0.0);
  float spec = pow(max(dot(reflect(-l, n), v), 0.0), 40.0);
  vec3 c = vCol.rgb;
  vec3 col;
  if (uMode >= 2) {
    col = c * (0.6 + 0.4 * diffuse);
  } else {
    col = c * (0.22 + 0.78 * diffuse) + 0.2 * spec;
  }
  if (uMode == 1) {
    // From the line below, so that the integrals keep their precision.
    float s = vStripe - floor(vStripe);
    float intensity;
    if (uFilter != 0) {
      intensity = stripePixel(s, vec2(dFdx(vStripe), dFdy(vStripe)), uWidth);
    } else {
      float d = min(s, 1.0 - s);
      intensity = d >= uWidth ? 0.0 : 1.0 - d / uWidth;
    }
    col = mix(col, vec3(0.05, 0.05, 0.12), intensity);
  }
  outColor = vec4(col, 1.0);
}`;

const NET_VS = `#version 300 es
in vec3 aPos;
uniform mat4 uMvp; uniform float uSize;
void main() { gl_Position = uMvp * vec4(aPos, 1.0); gl_PointSize = uSize; }`;

const NET_FS = `#version 300 es
precision mediump float;
uniform vec4 uColor;
out vec4 outColor;
void main() { outColor = uColor; }`;

function compile(gl, vs, fs) {
  const program = gl.createProgram();
  for (const [type, src] of [[gl.VERTEX_SHADER, vs], [gl.FRAGMENT_SHADER, fs]]) {
    const s = gl.createShader(type);
    gl.shaderSource(s, src);
    gl.compileShader(s);
    if (!gl.getShaderParameter(s, gl.COMPILE_STATUS)) throw new Error(gl.getShaderInfoLog(s));
    gl.attachShader(program, s);
  }
  gl.linkProgram(program);
  if (!gl.getProgramParameter(program, gl.LINK_STATUS)) throw new Error(gl.getProgramInfoLog(program));
  return program;
}

export const BACKGROUND = [0.16, 0.17, 0.2];
export const STRIPE_WIDTH = 0.15;

export class Renderer {
  constructor(canvas) {
    const gl = canvas.getContext('webgl2', { antialias: true, preserveDrawingBuffer: true });
    if (!gl) throw new Error('this browser has no WebGL2');
    this.gl = gl;
    this.canvas = canvas;
    this.surface = compile(gl, SURFACE_VS, SURFACE_FS);
    this.net = compile(gl, NET_VS, NET_FS);
    this.buffers = {};
    for (const name of ['pos', 'nrm', 'col', 'stripe', 'index', 'netPos', 'netIndex', 'pick']) this.buffers[name] = gl.createBuffer();
    this.indexCount = 0;
    this.vertexCount = 0;
    this.netEdges = 0;
    this.netPoints = 0;
    this.selected = -1;
    // Highlight stripes filtered over the pixel (see SURFACE_FS).
    this.filterStripes = true;

    this.surfaceVao = gl.createVertexArray();
    gl.bindVertexArray(this.surfaceVao);
    const attrib = (program, name, buffer, size, type, normalized) => {
      const loc = gl.getAttribLocation(program, name);
      gl.bindBuffer(gl.ARRAY_BUFFER, buffer);
      gl.enableVertexAttribArray(loc);
      gl.vertexAttribPointer(loc, size, type, normalized, 0, 0);
    };
    attrib(this.surface, 'aPos', this.buffers.pos, 3, gl.FLOAT, false);
    attrib(this.surface, 'aNrm', this.buffers.nrm, 3, gl.FLOAT, false);
    attrib(this.surface, 'aCol', this.buffers.col, 4, gl.UNSIGNED_BYTE, true);
    attrib(this.surface, 'aStripe', this.buffers.stripe, 1, gl.FLOAT, false);
    gl.bindBuffer(gl.ELEMENT_ARRAY_BUFFER, this.buffers.index);
    this.netVao = gl.createVertexArray();
    gl.bindVertexArray(this.netVao);
    attrib(this.net, 'aPos', this.buffers.netPos, 3, gl.FLOAT, false);
    gl.bindBuffer(gl.ELEMENT_ARRAY_BUFFER, this.buffers.netIndex);
    gl.bindVertexArray(null);
  }

  // The whole surface (after a load, new options or shading).
  uploadSurface(s) {
    const gl = this.gl;
    gl.bindVertexArray(null);
    for (const [name, data] of [['pos', s.positions], ['nrm', s.normals], ['col', s.colors], ['stripe', s.stripes]]) {
      gl.bindBuffer(gl.ARRAY_BUFFER, this.buffers[name]);
      gl.bufferData(gl.ARRAY_BUFFER, data, gl.DYNAMIC_DRAW);
    }
    gl.bindBuffer(gl.ELEMENT_ARRAY_BUFFER, this.buffers.index);
    gl.bufferData(gl.ELEMENT_ARRAY_BUFFER, s.indices, gl.STATIC_DRAW);
    this.indexCount = s.indices.length;
    this.vertexCount = s.vertices;
  }

  // The vertices an edit rewrote (s.dirty = [first, end)).
  uploadDirty(s) {
    const gl = this.gl;
    const [a, b] = s.dirty;
    if (b <= a) return;
    for (const [name, data, per, bytes] of [['pos', s.positions, 3, 4], ['nrm', s.normals, 3, 4], ['col', s.colors, 4, 1], ['stripe', s.stripes, 1, 4]]) {
      gl.bindBuffer(gl.ARRAY_BUFFER, this.buffers[name]);
      gl.bufferSubData(gl.ARRAY_BUFFER, a * per * bytes, data, a * per, (b - a) * per);
    }
  }

  // The highlight parameters only (after a new view).
  uploadStripes(s) {
    const gl = this.gl;
    gl.bindVertexArray(null);
    gl.bindBuffer(gl.ARRAY_BUFFER, this.buffers.stripe);
    gl.bufferSubData(gl.ARRAY_BUFFER, 0, s.stripes);
  }

  uploadNet(c, full) {
    const gl = this.gl;
    gl.bindVertexArray(null);
    gl.bindBuffer(gl.ARRAY_BUFFER, this.buffers.netPos);
    gl.bufferData(gl.ARRAY_BUFFER, c.points, gl.DYNAMIC_DRAW);
    if (full) {
      gl.bindBuffer(gl.ELEMENT_ARRAY_BUFFER, this.buffers.netIndex);
      gl.bufferData(gl.ELEMENT_ARRAY_BUFFER, c.edges, gl.STATIC_DRAW);
      this.netEdges = c.edges.length;
    }
    this.netPoints = c.count;
  }

  resize() {
    const c = this.canvas;
    const dpr = window.devicePixelRatio || 1;
    const w = Math.max(1, Math.round(c.clientWidth * dpr));
    const h = Math.max(1, Math.round(c.clientHeight * dpr));
    if (c.width !== w || c.height !== h) {
      c.width = w;
      c.height = h;
    }
  }

  draw(camera, mode, showNet) {
    const gl = this.gl;
    this.resize();
    gl.viewport(0, 0, this.canvas.width, this.canvas.height);
    gl.clearColor(...BACKGROUND, 1);
    gl.clear(gl.COLOR_BUFFER_BIT | gl.DEPTH_BUFFER_BIT);
    const mvp = camera.matrix(this.canvas.width / this.canvas.height);
    this.mvp = mvp;
    gl.enable(gl.DEPTH_TEST);
    if (this.indexCount > 0) {
      gl.useProgram(this.surface);
      gl.uniformMatrix4fv(gl.getUniformLocation(this.surface, 'uMvp'), false, mvp);
      gl.uniform3fv(gl.getUniformLocation(this.surface, 'uEye'), camera.eye());
      gl.uniform1i(gl.getUniformLocation(this.surface, 'uMode'), mode);
      gl.uniform1f(gl.getUniformLocation(this.surface, 'uWidth'), STRIPE_WIDTH);
      gl.uniform3fv(gl.getUniformLocation(this.surface, 'uUp'), camera.upVector());
      gl.uniform1i(gl.getUniformLocation(this.surface, 'uFilter'), this.filterStripes ? 1 : 0);
      gl.bindVertexArray(this.surfaceVao);
      gl.enable(gl.POLYGON_OFFSET_FILL);
      gl.polygonOffset(1, 1);
      gl.drawElements(gl.TRIANGLES, this.indexCount, gl.UNSIGNED_INT, 0);
      gl.disable(gl.POLYGON_OFFSET_FILL);
    }
    if (showNet && this.netPoints > 0) {
      gl.useProgram(this.net);
      gl.uniformMatrix4fv(gl.getUniformLocation(this.net, 'uMvp'), false, mvp);
      gl.bindVertexArray(this.netVao);
      const color = gl.getUniformLocation(this.net, 'uColor');
      const size = gl.getUniformLocation(this.net, 'uSize');
      gl.enable(gl.BLEND);
      gl.blendFunc(gl.SRC_ALPHA, gl.ONE_MINUS_SRC_ALPHA);
      gl.depthMask(false);
      // Hidden parts of the net faintly, visible parts stronger.
      for (const [depthFunc, alpha] of [[gl.GREATER, 0.18], [gl.LEQUAL, 0.8]]) {
        gl.depthFunc(depthFunc);
        gl.uniform4f(color, 0.95, 0.75, 0.25, alpha);
        gl.uniform1f(size, 1);
        gl.drawElements(gl.LINES, this.netEdges, gl.UNSIGNED_INT, 0);
        gl.uniform1f(size, 5 * (window.devicePixelRatio || 1));
        gl.drawArrays(gl.POINTS, 0, this.netPoints);
      }
      gl.depthFunc(gl.LESS);
      if (this.selected >= 0 && this.selected < this.netPoints) {
        gl.disable(gl.DEPTH_TEST);
        gl.uniform4f(color, 1.0, 0.3, 0.2, 1.0);
        gl.uniform1f(size, 9 * (window.devicePixelRatio || 1));
        gl.drawArrays(gl.POINTS, this.selected, 1);
        gl.enable(gl.DEPTH_TEST);
      }
      gl.depthMask(true);
      gl.disable(gl.BLEND);
    }
    gl.bindVertexArray(null);
  }
}
