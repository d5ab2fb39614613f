// The WebGL player of an exported page (dochost convert DOC -o OUT.html):
// the bodies' meshes and their poses per frame, embedded in the page by
// host-shim/html.cc, drawn in WebGL 1 without any library, so the page
// stays small and needs no network.  The camera starts where asgard
// render's is (the poster's view); a drag turns it about the target (a
// virtual trackball), the wheel zooms, a double-click goes back.  The page's
// frames player (html.cc) calls window.asgardPlayer(figure, canvas, data)
// and, when it answers (WebGL is there), draws through it at any time with
// the poses interpolated between frames; otherwise it shows the
// pre-rendered frames.
//
// data: {t0, t1, n, camera: {eye, target, up, tan_half_fov}, lights:
// [{directional, position, direction, color, intensity}], bodies: [{name,
// pieces: [{color, sphere: [cx cy cz r]} | {color, v: base64 float32 xyz,
// i: base64 uint16 or uint32 (i32: true)}], pose: [x y z qx qy qz qw] |
// track: k}], poses: base64 float32, n frames × tracks × 7, links: base64
// float32, n frames × links × [ax ay az bx by bz] (the attachment points),
// arrows: base64 float32, n frames × forces × [bx by bz fx fy fz] (point of
// application and force), arrow_length: the longest force's drawn length,
// cameras: base64 float32, n frames × [eye, target, up] when the view moves
// (its -pos, -rot or -scale an expression, -follow, -trajectory)}.  A moving
// view's camera is interpolated between frames until the reader turns it.
//
// Links are drawn as lines between their two ends and forces as arrows from
// their points of application (the colours of asgard render's overlays), over
// the bodies, with the ends interpolated linearly between frames as the
// bodies' positions are.  The longest force of the whole motion is drawn
// arrow_length long, the others in proportion.

const VERTEX = `
attribute vec3 position; attribute vec3 normal;
uniform mat4 model, viewProj; varying vec3 vNormal; varying vec3 vWorld;
void main() {
  vec4 w = model * vec4(position, 1.0);
  vWorld = w.xyz; vNormal = mat3(model) * normal;
  gl_Position = viewProj * w;
}`;

const FRAGMENT = `
precision mediump float;
uniform vec3 color, ambient, eye; uniform int count;
uniform vec4 lightPos[4]; uniform vec3 lightColor[4];
varying vec3 vNormal; varying vec3 vWorld;
void main() {
  vec3 n = normalize(vNormal), v = normalize(eye - vWorld); vec3 sum = ambient, shine = vec3(0.0);
  for (int k = 0; k < 4; ++k) {
    if (k >= count) break;
    vec3 l = lightPos[k].w > 0.5 ? normalize(lightPos[k].xyz - vWorld) : normalize(-lightPos[k].xyz);
    float d = dot(n, l);
    sum += lightColor[k] * max(d, 0.0);
    if (d > 0.0) shine += 0.35 * lightColor[k] * pow(max(dot(n, normalize(l + v)), 0.0), 40.0);
  }
  gl_FragColor = vec4(min(color * sum + shine, vec3(1.0)), 1.0);
}`;

// Overlays (links, force arrows): flat-coloured triangles whose vertices are
// given in clip coordinates, worked out on the CPU at each draw.
const FLAT_VERTEX = 'attribute vec4 clip; void main() { gl_Position = clip; }';
const FLAT_FRAGMENT = 'precision mediump float; uniform vec3 color; void main() { gl_FragColor = vec4(color, 1.0); }';
const LINK_COLOR = [0.1, 0.55, 0.2], FORCE_COLOR = [0.8, 0.1, 0.1];

function bytes(base64) {
  const s = atob(base64);
  const out = new Uint8Array(s.length);
  for (let i = 0; i < s.length; ++i) out[i] = s.charCodeAt(i);
  return out.buffer;
}

// 3-vector and quaternion helpers on plain arrays.
const sub = (a, b) => [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
const add = (a, b) => [a[0] + b[0], a[1] + b[1], a[2] + b[2]];
const scale = (a, s) => [a[0] * s, a[1] * s, a[2] * s];
const dot = (a, b) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
const cross = (a, b) => [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
const unit = (a) => scale(a, 1 / (Math.hypot(a[0], a[1], a[2]) || 1));

// Rotates v by the unit quaternion q = [x y z w].
function rotate(q, v) {
  const u = [q[0], q[1], q[2]];
  const t = scale(cross(u, v), 2);
  return add(add(v, scale(t, q[3])), cross(u, t));
}

// Rotation of v about the unit axis by angle (Rodrigues).
function turn(v, axis, angle) {
  const c = Math.cos(angle), s = Math.sin(angle);
  return add(add(scale(v, c), scale(cross(axis, v), s)), scale(axis, dot(axis, v) * (1 - c)));
}

// Column-major 4×4 of the pose (p, q).
function poseMatrix(p, q) {
  const [x, y, z, w] = q;
  return new Float32Array([
    1 - 2 * (y * y + z * z), 2 * (x * y + z * w), 2 * (x * z - y * w), 0,
    2 * (x * y - z * w), 1 - 2 * (x * x + z * z), 2 * (y * z + x * w), 0,
    2 * (x * z + y * w), 2 * (y * z - x * w), 1 - 2 * (x * x + y * y), 0,
    p[0], p[1], p[2], 1]);
}

function multiply(a, b) {
  const m = new Float32Array(16);
  for (let c = 0; c < 4; ++c)
    for (let r = 0; r < 4; ++r) {
      let s = 0;
      for (let k = 0; k < 4; ++k) s += a[k * 4 + r] * b[c * 4 + k];
      m[c * 4 + r] = s;
    }
  return m;
}

// A UV sphere (smooth normals) as a triangle list: positions and normals.
function sphereMesh(c, r, slices = 24, stacks = 16) {
  const pos = [], nor = [];
  const at = (i, j) => {
    const th = (Math.PI * i) / stacks, ph = (2 * Math.PI * j) / slices;
    return [Math.sin(th) * Math.cos(ph), Math.cos(th), Math.sin(th) * Math.sin(ph)];
  };
  for (let i = 0; i < stacks; ++i)
    for (let j = 0; j < slices; ++j) {
      const a = at(i, j), b = at(i + 1, j), d = at(i, j + 1), e = at(i + 1, j + 1);
      for (const n of [a, b, e, a, e, d]) { nor.push(...n); pos.push(...add(c, scale(n, r))); }
    }
  return { pos, nor };
}

// A hull's triangles (flat shaded): positions and face normals.
function hullMesh(vertices, triangles) {
  const pos = [], nor = [];
  const v = (k) => [vertices[3 * k], vertices[3 * k + 1], vertices[3 * k + 2]];
  for (let t = 0; t + 2 < triangles.length; t += 3) {
    const a = v(triangles[t]), b = v(triangles[t + 1]), c = v(triangles[t + 2]);
    const n = unit(cross(sub(b, a), sub(c, a)));
    for (const p of [a, b, c]) { pos.push(...p); nor.push(...n); }
  }
  return { pos, nor };
}

function program(gl, vertex = VERTEX, fragment = FRAGMENT) {
  const shader = (type, src) => {
    const s = gl.createShader(type);
    gl.shaderSource(s, src);
    gl.compileShader(s);
    return gl.getShaderParameter(s, gl.COMPILE_STATUS) ? s : null;
  };
  const vs = shader(gl.VERTEX_SHADER, vertex), fs = shader(gl.FRAGMENT_SHADER, fragment);
  if (!vs || !fs) return null;
  const p = gl.createProgram();
  gl.attachShader(p, vs);
  gl.attachShader(p, fs);
  gl.linkProgram(p);
  return gl.getProgramParameter(p, gl.LINK_STATUS) ? p : null;
}

// Numbers given as base64 of the typed array (an exported page) or as a
// plain array (the editor server's pose stream).
const floats = (x) => (typeof x === 'string' ? new Float32Array(bytes(x)) : Float32Array.from(x || []));
const indices = (x, i32) => (typeof x === 'string' ? (i32 ? new Uint32Array(bytes(x)) : new Uint16Array(bytes(x)))
  : Uint32Array.from(x || []));

export function createPlayer(figure, fallback, data) {
  // The fallback's size as written (a picture not yet loaded has none of its own).
  const width = Number(fallback.getAttribute('width')) || fallback.width;
  const height = Number(fallback.getAttribute('height')) || fallback.height;
  const canvas = document.createElement('canvas');
  const ratio = window.devicePixelRatio || 1;
  canvas.width = Math.round(width * ratio);
  canvas.height = Math.round(height * ratio);
  canvas.style.width = `${width}px`;
  canvas.style.height = `${height}px`;
  canvas.className = 'asgard-webgl';
  canvas.setAttribute('aria-label', `${fallback.getAttribute('aria-label') || fallback.getAttribute('alt') || 'animation'} (WebGL)`);
  let gl = null;
  try { gl = canvas.getContext('webgl', { antialias: true, preserveDrawingBuffer: true }); } catch { gl = null; }
  const prog = gl && program(gl);
  const flat = prog && program(gl, FLAT_VERTEX, FLAT_FRAGMENT);
  if (!prog || !flat) return null;
  const flatColor = gl.getUniformLocation(flat, 'color'), aClip = gl.getAttribLocation(flat, 'clip');
  const overlayBuffer = gl.createBuffer();
  const loc = (n) => gl.getUniformLocation(prog, n);
  const u = { model: loc('model'), viewProj: loc('viewProj'), color: loc('color'), ambient: loc('ambient'), eye: loc('eye'),
    count: loc('count'), lightPos: loc('lightPos'), lightColor: loc('lightColor') };
  const aPos = gl.getAttribLocation(prog, 'position'), aNor = gl.getAttribLocation(prog, 'normal');

  // The scene (replaced by setScene when the motion changes): meshes in
  // body coordinates, the poses per frame and the lights.
  let bodies = [], poses = new Float32Array(0), tracks = 0, times = null;
  let links = new Float32Array(0), arrows = new Float32Array(0), longest = 0, arrowLength = 0;
  let cameras = null;  // a moving view's camera per frame
  const lightPos = new Float32Array(16), lightColor = new Float32Array(12);
  let count = 0, ambient = [0.5, 0.5, 0.5];
  function load(d) {
    for (const b of bodies) for (const piece of b.pieces) gl.deleteBuffer(piece.buffer);
    bodies = d.bodies.map((b) => ({
      name: b.name, pose: b.pose, track: b.track,
      pieces: b.pieces.map((p) => {
        const m = p.sphere ? sphereMesh(p.sphere.slice(0, 3), p.sphere[3]) : hullMesh(floats(p.v), indices(p.i, p.i32));
        const buffer = gl.createBuffer();
        const interleaved = new Float32Array(m.pos.length * 2);
        for (let k = 0; k < m.pos.length / 3; ++k) interleaved.set([...m.pos.slice(3 * k, 3 * k + 3), ...m.nor.slice(3 * k, 3 * k + 3)], 6 * k);
        gl.bindBuffer(gl.ARRAY_BUFFER, buffer);
        gl.bufferData(gl.ARRAY_BUFFER, interleaved, gl.STATIC_DRAW);
        return { buffer, count: m.pos.length / 3, color: p.color };
      }),
    }));
    poses = floats(d.poses);
    tracks = bodies.reduce((n, b) => Math.max(n, b.track === undefined ? 0 : b.track + 1), 0);
    times = d.times && d.times.length === d.n ? d.times : null;  // uneven frame times
    links = floats(d.links);
    arrows = floats(d.arrows);
    cameras = floats(d.cameras);
    if (cameras.length !== 9 * d.n) cameras = null;
    if (links.length % (6 * d.n)) links = new Float32Array(0);
    if (arrows.length % (6 * d.n)) arrows = new Float32Array(0);
    longest = 0;
    for (let k = 0; k + 5 < arrows.length; k += 6) longest = Math.max(longest, Math.hypot(arrows[k + 3], arrows[k + 4], arrows[k + 5]));
    arrowLength = Number(d.arrow_length) || 0;
    // Lights as the editor's viewer has them: the scene's, or a sky and a sun.
    const lights = (d.lights && d.lights.length ? d.lights : null);
    lightPos.fill(0);
    lightColor.fill(0);
    count = 0;
    if (lights) {
      ambient = [0.5, 0.5, 0.5];
      for (const l of lights.slice(0, 4)) {
        lightPos.set(l.directional ? [...l.direction, 0] : [...l.position, 1], 4 * count);
        lightColor.set(scale(l.color, 0.8 * l.intensity), 3 * count);
        ++count;
      }
    } else {
      ambient = [0.4, 0.4, 0.42];
      lightPos.set([-30, -50, -40, 0, 20, 10, 30, 0], 0);
      lightColor.set([0.6, 0.6, 0.58, 0.15, 0.15, 0.17], 0);
      count = 2;
    }
    data = d;
  }
  load(data);

  // The camera: asgard render's (the poster's), then turned and zoomed.
  let home = { eye: data.camera.eye, target: data.camera.target, up: unit(data.camera.up) };
  let cam = { ...home }, turned = false;
  const fovY = () => {
    const aspect = width / height, fit = data.camera.tan_half_fov;
    return 2 * Math.atan(aspect >= 1 ? fit : fit / aspect);
  };
  function viewProj() {
    const f = unit(sub(cam.target, cam.eye));
    const s = unit(cross(f, cam.up)), up = cross(s, f);
    const d = Math.hypot(...sub(cam.target, cam.eye));
    const view = new Float32Array([s[0], up[0], -f[0], 0, s[1], up[1], -f[1], 0, s[2], up[2], -f[2], 0,
      -dot(s, cam.eye), -dot(up, cam.eye), dot(f, cam.eye), 1]);
    const near = d / 50, far = d * 20, t = 1 / Math.tan(fovY() / 2);
    const proj = new Float32Array([t / (width / height), 0, 0, 0, 0, t, 0, 0,
      0, 0, (far + near) / (near - far), -1, 0, 0, (2 * far * near) / (near - far), 0]);
    return multiply(proj, view);
  }

  // The frames i and j around time t and the fraction s of the way from i to j.
  function frameAt(t) {
    const n = data.n, span = data.t1 - data.t0;
    let i, j, s;
    if (times) {  // the frame before t (by bisection) and the one after
      let lo = 0, hi = n - 1;
      while (hi - lo > 1) { const mid = (lo + hi) >> 1; if (times[mid] <= t) lo = mid; else hi = mid; }
      i = lo; j = Math.min(lo + 1, n - 1);
      s = j > i && times[j] > times[i] ? Math.min(Math.max((t - times[i]) / (times[j] - times[i]), 0), 1) : 0;
    } else {
      const x = n > 1 && span > 0 ? Math.min(Math.max((t - data.t0) / span, 0), 1) * (n - 1) : 0;
      i = Math.min(Math.floor(x), n - 1); j = Math.min(i + 1, n - 1); s = x - i;
    }
    return { i, j, s };
  }

  // A body's pose at time t: its fixed pose, or its track interpolated
  // between the two frames around t (positions linearly, rotations by a
  // normalized linear mix along the shorter arc).
  function poseAt(b, t) {
    if (b.track === undefined) return { p: b.pose.slice(0, 3), q: b.pose.slice(3, 7) };
    const { i, j, s } = frameAt(t);
    const at = (f, k) => poses[(f * tracks + b.track) * 7 + k];
    const p = [0, 1, 2].map((k) => at(i, k) * (1 - s) + at(j, k) * s);
    const sign = [3, 4, 5, 6].reduce((acc, k) => acc + at(i, k) * at(j, k), 0) < 0 ? -1 : 1;
    let q = [3, 4, 5, 6].map((k) => at(i, k) * (1 - s) + sign * at(j, k) * s);
    const len = Math.hypot(...q) || 1;
    q = q.map((v) => v / len);
    return { p, q };
  }

  // The overlays at time t in world coordinates: links [[a, b]] and force
  // arrows [[base, tip]] (zero forces left out), interpolated between frames.
  function overlaysAt(t) {
    const { i, j, s } = frameAt(t);
    const segments = (list) => {
      const per = list.length / data.n, out = [];
      for (let e = 0; e < per; e += 6) {
        const v = [0, 1, 2, 3, 4, 5].map((c) => list[i * per + e + c] * (1 - s) + list[j * per + e + c] * s);
        out.push([v.slice(0, 3), v.slice(3, 6)]);
      }
      return out;
    };
    const arrowsNow = longest > 0 && arrowLength > 0 ? segments(arrows).filter(([, f]) => Math.hypot(...f) > 1e-9 * longest)
      .map(([base, f]) => [base, add(base, scale(f, arrowLength / longest))]) : [];
    return { links: segments(links), arrows: arrowsNow };
  }

  // Clip coordinates of world point p under the matrix m.
  const clipOf = (m, p) => [0, 1, 2, 3].map((r) => m[r] * p[0] + m[4 + r] * p[1] + m[8 + r] * p[2] + m[12 + r]);

  // Triangles (clip coordinates, 4 numbers a vertex) of a band `w` device
  // pixels wide from a to b, and of an arrow head at b when `head` > 0
  // (its length in device pixels); nothing when an end is behind the eye.
  function band(m, a, b, w, head, out) {
    const ca = clipOf(m, a), cb = clipOf(m, b);
    if (ca[3] <= 1e-6 || cb[3] <= 1e-6) return;
    const hw = canvas.width / 2, hh = canvas.height / 2;
    const pa = [(ca[0] / ca[3]) * hw, (ca[1] / ca[3]) * hh], pb = [(cb[0] / cb[3]) * hw, (cb[1] / cb[3]) * hh];
    const len = Math.hypot(pb[0] - pa[0], pb[1] - pa[1]);
    if (len < 1e-6) return;
    const d = [(pb[0] - pa[0]) / len, (pb[1] - pa[1]) / len], n = [-d[1], d[0]];
    // A point `along` pixels past the end c (clip cc) and `across` to the side.
    const at = (cc, along, across) => [cc[0] + ((d[0] * along + n[0] * across) / hw) * cc[3],
      cc[1] + ((d[1] * along + n[1] * across) / hh) * cc[3], cc[2], cc[3]];
    const h = head > 0 ? Math.min(head, 0.4 * len) : 0;
    const a0 = at(ca, 0, -w / 2), a1 = at(ca, 0, w / 2), b0 = at(cb, -h, -w / 2), b1 = at(cb, -h, w / 2);
    out.push(...a0, ...a1, ...b1, ...a0, ...b1, ...b0);
    if (h > 0) out.push(...cb, ...at(cb, -h, 0.45 * h), ...at(cb, -h, -0.45 * h));
  }

  function drawOverlays(m, t) {
    const o = overlaysAt(t);
    if (!o.links.length && !o.arrows.length) return;
    const ratio = canvas.width / width;
    gl.disable(gl.DEPTH_TEST);  // over the bodies, as asgard render draws them
    gl.useProgram(flat);
    gl.bindBuffer(gl.ARRAY_BUFFER, overlayBuffer);
    gl.enableVertexAttribArray(aClip);
    for (const [list, color, w, head] of [[o.links, LINK_COLOR, 2, 0], [o.arrows, FORCE_COLOR, 2.5, 12]]) {
      const v = [];
      for (const [a, b] of list) band(m, a, b, w * ratio, head * ratio, v);
      if (!v.length) continue;
      gl.bufferData(gl.ARRAY_BUFFER, new Float32Array(v), gl.DYNAMIC_DRAW);
      gl.vertexAttribPointer(aClip, 4, gl.FLOAT, false, 16, 0);
      gl.uniform3fv(flatColor, color);
      gl.drawArrays(gl.TRIANGLES, 0, v.length / 4);
    }
    gl.disableVertexAttribArray(aClip);
  }

  // Bodies drawn at a given pose instead of their motion's (a handle being
  // dragged over the rendition moves its body's start): name → [x y z qx qy qz qw].
  const placed = new Map();
  function place(name, pose) {
    if (pose) placed.set(name, pose); else placed.delete(name);
  }
  function poseOf(b, t) {
    const at = placed.get(b.name);
    return at ? { p: at.slice(0, 3), q: at.slice(3, 7) } : poseAt(b, t);
  }

  let shown = data.t0;
  // A moving view's camera at time t: eye and target linearly between the
  // frames around t, up normalized.
  function cameraAt(t) {
    const { i, j, s } = frameAt(t);
    const v = (k) => [0, 1, 2].map((c) => cameras[9 * i + k + c] * (1 - s) + cameras[9 * j + k + c] * s);
    return { eye: v(0), target: v(3), up: unit(v(6)) };
  }

  function draw(t = shown) {
    shown = t;
    if (cameras && !turned) cam = cameraAt(t);
    gl.viewport(0, 0, canvas.width, canvas.height);
    gl.clearColor(0.949, 0.949, 0.961, 1);
    gl.clear(gl.COLOR_BUFFER_BIT | gl.DEPTH_BUFFER_BIT);
    gl.enable(gl.DEPTH_TEST);
    gl.useProgram(prog);
    const m = viewProj();
    gl.uniformMatrix4fv(u.viewProj, false, m);
    gl.uniform3fv(u.ambient, ambient);
    gl.uniform3fv(u.eye, cam.eye);
    gl.uniform1i(u.count, count);
    gl.uniform4fv(u.lightPos, lightPos);
    gl.uniform3fv(u.lightColor, lightColor);
    for (const b of bodies) {
      const { p, q } = poseOf(b, t);
      gl.uniformMatrix4fv(u.model, false, poseMatrix(p, q));
      for (const piece of b.pieces) {
        gl.uniform3fv(u.color, piece.color);
        gl.bindBuffer(gl.ARRAY_BUFFER, piece.buffer);
        gl.enableVertexAttribArray(aPos);
        gl.vertexAttribPointer(aPos, 3, gl.FLOAT, false, 24, 0);
        gl.enableVertexAttribArray(aNor);
        gl.vertexAttribPointer(aNor, 3, gl.FLOAT, false, 24, 12);
        gl.drawArrays(gl.TRIANGLES, 0, piece.count);
      }
    }
    drawOverlays(m, t);
  }

  // Where a body's centre of mass is drawn at time t, in CSS pixels from
  // the canvas's top left (for tests and for readers of the page).
  const toScreen = (m, p) => {
    const c = clipOf(m, p);
    return [((c[0] / c[3] + 1) / 2) * width, ((1 - c[1] / c[3]) / 2) * height];
  };
  function project(name, t = shown) {
    const b = bodies.find((x) => x.name === name);
    if (!b) return null;
    return toScreen(viewProj(), poseOf(b, t).p);
  }
  // The links' ends and the force arrows' base and tip at time t, in CSS
  // pixels as project gives them: {links: [[ax, ay, bx, by]], arrows: [...]}.
  function overlays(t = shown) {
    const m = viewProj(), o = overlaysAt(t);
    const flatten = (list) => list.map(([a, b]) => [...toScreen(m, a), ...toScreen(m, b)]);
    return { links: flatten(o.links), arrows: flatten(o.arrows) };
  }

  // Virtual trackball: a drag of the pointer by (dx, dy) pixels turns the
  // eye about the target, about the axis in the screen plane perpendicular
  // to the drag, by the drag's length over the canvas's half height in
  // radians; the wheel moves the eye toward the target.
  function orbit(dx, dy) {
    const f = unit(sub(cam.target, cam.eye)), s = unit(cross(f, cam.up)), up = cross(s, f);
    const len = Math.hypot(dx, dy);
    if (!len) return;
    const axis = unit(add(scale(up, -dx / len), scale(s, -dy / len)));
    const angle = len / (height / 2);
    cam = { eye: add(cam.target, turn(sub(cam.eye, cam.target), axis, angle)), target: cam.target, up: unit(turn(up, axis, angle)) };
    turned = true;
    draw();
  }
  function zoom(factor) {
    cam = { ...cam, eye: add(cam.target, scale(sub(cam.eye, cam.target), factor)) };
    turned = true;
    draw();
  }
  let last = null;
  canvas.addEventListener('pointerdown', (e) => { last = [e.clientX, e.clientY]; canvas.setPointerCapture(e.pointerId); });
  canvas.addEventListener('pointermove', (e) => {
    if (!last) return;
    orbit(e.clientX - last[0], e.clientY - last[1]);
    last = [e.clientX, e.clientY];
  });
  canvas.addEventListener('pointerup', () => { last = null; });
  canvas.addEventListener('wheel', (e) => { e.preventDefault(); zoom(Math.pow(1.0015, e.deltaY)); }, { passive: false });
  function goHome() { cam = { ...home }; turned = false; draw(); }
  canvas.addEventListener('dblclick', goHome);
  // The camera as drawn: eye, target and up, the vertical field of view
  // (radians), the near and far planes and the canvas's CSS size.
  function camera() {
    const d = Math.hypot(...sub(cam.target, cam.eye));
    return { eye: cam.eye.slice(), target: cam.target.slice(), up: cam.up.slice(), fovY: fovY(), near: d / 50, far: d * 20, width, height };
  }

  fallback.style.display = 'none';
  fallback.parentNode.insertBefore(canvas, fallback);
  figure.dataset.renderer = 'webgl';
  draw(data.t0);
  // A new motion of the same animation (an edit, a recompute): the camera
  // stays where the reader turned it.
  function setScene(d) {
    load(d);
    // Not turned by the reader: the new motion's camera (its framing).
    if (!turned) cam = home = { eye: d.camera.eye, target: d.camera.target, up: unit(d.camera.up) };
    player.times = { t0: d.t0, t1: d.t1, n: d.n };
    draw(Math.min(Math.max(shown, d.t0), d.t1));
  }
  const player = { canvas, draw, project, overlays, orbit, zoom, home: goHome, camera, place, setScene,
    times: { t0: data.t0, t1: data.t1, n: data.n } };
  return player;
}

window.asgardPlayer = function (figure, fallback, data) {
  try {
    return createPlayer(figure, fallback, data);
  } catch (e) {
    figure.dataset.webglError = String(e);
    return null;
  }
};
