// The shape editor (seed Figure 4.3): a shape_set's pieces in shape
// coordinates in a viewer of their own.  A hull piece's points are handles
// (dragged in the screen plane, 'z'/'x' as in the main viewer are not
// needed here: the camera turns); its convex hull is recomputed live and the
// points inside it are drawn hollow and grey.  A sphere piece has a handle at
// its centre and one on its surface (the radius is their distance).  Add
// vertex puts a point where the next click hits the plane through the
// piece's centre facing the viewer; Delete vertex removes the chosen point
// (a hull keeps four); Add sphere adds a sphere piece; Snap rounds dragged
// and added points to the grid.  Every change is written back as the
// shape_set's -desc literal, one `-sub {…}` per piece (faces and boxes
// become -vertices: only the hull's points matter), through the session on
// every move of a drag (one undo step), re-simulated when it ends.
import * as THREE from 'three';
import { ConvexHull } from 'three/examples/jsm/math/ConvexHull.js';
import { SphereControls } from './camera.js';

// A Tcl list's elements (braces group, backslash escapes one character).
export function tclList(text) {
  const out = [];
  let i = 0;
  const n = text.length;
  while (i < n) {
    while (i < n && /\s/.test(text[i])) ++i;
    if (i >= n) break;
    if (text[i] === '{') {
      let depth = 1, j = i + 1;
      while (j < n && depth) {
        if (text[j] === '\\') j += 2;
        else { if (text[j] === '{') ++depth; else if (text[j] === '}') --depth; ++j; }
      }
      if (depth) throw new Error('unbalanced braces');
      out.push(text.slice(i + 1, j - 1));
      i = j;
    } else {
      let j = i;
      while (j < n && !/\s/.test(text[j])) j += text[j] === '\\' ? 2 : 1;
      out.push(text.slice(i, j));
      i = j;
    }
  }
  return out;
}

const vector = (s, what) => {
  const v = tclList(s).map(Number);
  if (v.length !== 3 || !v.every(Number.isFinite)) throw new Error(`${what} is not three numbers`);
  return v;
};

// A piece from its `-key value` list: {pos, sphere (radius or null),
// points (relative to pos), color}.
function parsePiece(items, into = { pos: [0, 0, 0], sphere: null, points: [], color: null }) {
  if (items.length % 2) throw new Error('a key without a value');
  for (let k = 0; k < items.length; k += 2) {
    const key = items[k], value = items[k + 1];
    if (key === '-pos') into.pos = vector(value, '-pos');
    else if (key === '-sphere') into.sphere = Number(value);
    else if (key === '-color') into.color = value;
    else if (key === '-vertices') for (const p of tclList(value)) into.points.push(vector(p, 'a vertex'));
    else if (key === '-face') {
      const f = tclList(value);
      for (let j = 0; j < f.length; ++j) {
        if (f[j] === '-color') { if (!into.color) into.color = f[j + 1]; ++j; continue; }
        into.points.push(vector(f[j], 'a face point'));
      }
    } else if (key === '-box') {
      const [x, y, z] = vector(value, '-box').map((v) => v / 2);
      for (const sx of [-x, x]) for (const sy of [-y, y]) for (const sz of [-z, z]) into.points.push([sx, sy, sz]);
    } else throw new Error(`unknown key ${key}`);
  }
  if (into.sphere !== null && !(into.sphere > 0)) throw new Error('-sphere needs a radius above 0');
  return into;
}

// A -desc literal's pieces (as core/lang/shapes.cc reads them).
export function parseDesc(text) {
  const items = tclList(text), pieces = [], rest = [];
  for (let k = 0; k < items.length; k += 2) {
    if (items[k] === '-sub') pieces.push(parsePiece(tclList(items[k + 1] ?? '')));
    else rest.push(items[k], items[k + 1] ?? '');
  }
  if (rest.length) pieces.unshift(parsePiece(rest));
  return pieces;
}

const num = (v) => String(Math.round(v * 1e4) / 1e4);
const vec = (v) => `{${v.map(num).join(' ')}}`;

export function writeDesc(pieces) {
  return pieces.map((p) => {
    const body = p.sphere !== null ? `-sphere ${num(p.sphere)}` : `-vertices {${p.points.map(vec).join(' ')}}`;
    return `-sub {-pos ${vec(p.pos)} ${body}${p.color ? ` -color ${/\s/.test(p.color) ? `{${p.color}}` : p.color}` : ''}}`;
  }).join(' ');
}

// Which of `points` lie on their convex hull (the rest are inside it), and
// the hull's triangles; null when the points span no volume.
export function hullOf(points) {
  if (points.length < 4) return null;
  const vs = points.map((p) => new THREE.Vector3(...p));
  const hull = new ConvexHull().setFromPoints(vs);
  if (!hull.faces.length) return null;
  const onHull = new Set(), triangles = [];
  for (const face of hull.faces) {
    let edge = face.edge;
    const loop = [];
    do { loop.push(edge.head().point); edge = edge.next; } while (edge !== face.edge);
    for (const p of loop) onHull.add(vs.indexOf(p));
    for (let k = 1; k + 1 < loop.length; ++k) triangles.push([loop[0], loop[k], loop[k + 1]]);
  }
  return { onHull, triangles };
}

export class ShapeEditor {
  // root: the panel; ui: {shapes() → [{element, value, editable, reason}],
  // write(element, desc), status(text)}.
  constructor(root, ui) {
    this.root = root;
    this.ui = ui;
    this.select = root.querySelector('select');
    this.canvas = root.querySelector('canvas');
    this.info = root.querySelector('.info');
    this.snap = root.querySelector('input.snap');
    this.grid = root.querySelector('input.grid');
    this.renderer = new THREE.WebGLRenderer({ canvas: this.canvas, antialias: true, preserveDrawingBuffer: true });
    this.scene = new THREE.Scene();
    this.scene.background = new THREE.Color(0xfafafa);
    this.camera = new THREE.PerspectiveCamera(35, 2, 0.05, 500);
    const sun = new THREE.DirectionalLight(0xffffff, 1.3);
    sun.position.set(3, 5, 4);
    this.scene.add(new THREE.HemisphereLight(0xffffff, 0x666666, 1.5), sun, new THREE.AxesHelper(0.5));
    this.group = new THREE.Group();
    this.scene.add(this.group);
    this.handles = [];     // {mesh, piece, index (point) | 'centre' | 'surface'}
    this.pieces = [];
    this.element = '';
    this.chosen = null;    // {piece, index} of the point last pressed
    this.adding = false;
    this.written = new Set();  // the words this editor wrote (their echoes are not followed)
    this.raycaster = new THREE.Raycaster();
    this.setupEvents();
    // After setupEvents: a press on a handle disables the controls first.
    this.controls = new SphereControls(this.camera, this.canvas);
    this.controls.onChange = () => this.draw();
    this.select.onchange = () => this.open(this.select.value);
    root.querySelector('.add').onclick = () => { this.adding = true; this.say('Add vertex: click where the point goes (in the plane through the piece facing you)'); };
    root.querySelector('.delete').onclick = () => this.deletePoint();
    root.querySelector('.sphere').onclick = () => this.addSphere();
    root.querySelector('.close').onclick = () => this.show(false);
  }

  say(text) { this.info.textContent = text; }

  show(on) {
    this.root.style.display = on ? 'block' : 'none';
    if (on) this.refresh();
  }

  shown() { return this.root.style.display === 'block'; }

  // The scene's shape sets changed (a new state): offer them, reopen this one.
  refresh() {
    if (!this.shown() || this.drag) return;
    const shapes = this.ui.shapes();
    const current = this.element;
    this.select.textContent = '';
    for (const s of shapes) this.select.appendChild(new Option(s.element, s.element));
    const name = shapes.some((s) => s.element === current) ? current : (shapes[0] && shapes[0].element) || '';
    this.select.value = name;
    this.open(name, name !== current);
  }

  // Another view's edit of the open shape's -desc word (a drag in another
  // tab's shape editor, as it goes): reread it, keeping the camera.  The
  // echoes of this editor's own writes are not followed.
  follow(element, param, word) {
    if (!this.shown() || this.drag || this.reason || element !== this.element || param !== 'desc') return;
    if (this.written.has(word) || word === writeDesc(this.pieces)) return;
    this.open(element, false, word);
  }

  open(element, frame = true, word = null) {
    const found = this.ui.shapes().find((x) => x.element === element);
    const s = found && word !== null ? { ...found, value: word } : found;
    // A sphere's surface point keeps its direction across a reread.
    const surfaces = element === this.element ? this.pieces.map((p) => p.surface) : [];
    this.element = element;
    this.pieces = [];
    this.reason = '';
    if (!s) this.reason = 'no shape set';
    else if (!s.editable) this.reason = s.reason;
    else {
      try { this.pieces = parseDesc(s.value); } catch (e) { this.reason = `its -desc is not a literal list of pieces: ${e.message}`; }
      this.pieces.forEach((p, i) => { if (p.sphere !== null && surfaces[i]) p.surface = surfaces[i]; });
    }
    if (this.reason) this.say(`${element}: read-only: ${this.reason}`);
    else this.say(`${element}: ${this.pieces.length} piece(s)`);
    this.build();
    if (frame) this.fit();
  }

  fit() {
    const box = new THREE.Box3().setFromObject(this.group);
    const c = box.isEmpty() ? new THREE.Vector3() : box.getCenter(new THREE.Vector3());
    const r = box.isEmpty() ? 1 : Math.max(0.5, box.getSize(new THREE.Vector3()).length() / 2);
    this.controls.target.copy(c);
    this.camera.position.copy(c).add(new THREE.Vector3(0.6, 0.5, 1).normalize().multiplyScalar(r * 3.2));
    this.camera.lookAt(c);
    this.size = r;
    this.draw();
  }

  // Meshes and handles of every piece, from this.pieces.
  build() {
    this.group.clear();
    this.handles = [];
    const size = Math.max(0.03, (this.size || 1) * 0.045);
    const ball = (at, colour, hollow) => {
      const m = new THREE.Mesh(new THREE.SphereGeometry(size, 12, 8), new THREE.MeshBasicMaterial({ color: colour, wireframe: hollow, depthTest: false, transparent: true, opacity: 0.9 }));
      m.position.set(...at);
      m.renderOrder = 10;
      this.group.add(m);
      return m;
    };
    this.pieces.forEach((piece, pi) => {
      const colour = new THREE.Color(0x8899bb);
      if (piece.sphere !== null) {
        const mesh = new THREE.Mesh(new THREE.SphereGeometry(piece.sphere, 24, 16), new THREE.MeshStandardMaterial({ color: colour, transparent: true, opacity: 0.55 }));
        mesh.position.set(...piece.pos);
        this.group.add(mesh);
        if (!piece.surface) piece.surface = [1, 0, 0];
        const surface = piece.pos.map((v, k) => v + piece.surface[k] * piece.sphere);
        this.handles.push({ mesh: ball(piece.pos, 0xd06000, !!this.reason), piece: pi, index: 'centre' });
        this.handles.push({ mesh: ball(surface, 0x2080d0, !!this.reason), piece: pi, index: 'surface' });
        return;
      }
      const abs = piece.points.map((p) => p.map((v, k) => v + piece.pos[k]));
      const hull = hullOf(abs);
      piece.inside = abs.map((_, i) => !hull || !hull.onHull.has(i));
      if (hull) {
        const positions = [];
        for (const t of hull.triangles) for (const v of t) positions.push(v.x, v.y, v.z);
        const g = new THREE.BufferGeometry();
        g.setAttribute('position', new THREE.Float32BufferAttribute(positions, 3));
        g.computeVertexNormals();
        this.group.add(new THREE.Mesh(g, new THREE.MeshStandardMaterial({ color: colour, flatShading: true, transparent: true, opacity: 0.55, side: THREE.DoubleSide })));
        this.group.add(new THREE.LineSegments(new THREE.EdgesGeometry(g, 1), new THREE.LineBasicMaterial({ color: 0x333333 })));
      }
      // The piece's -pos: dragging it moves the whole piece.
      this.handles.push({ mesh: ball(piece.pos, 0x20a040, !!this.reason), piece: pi, index: 'pos' });
      abs.forEach((p, i) => {
        const inside = piece.inside[i];
        const chosen = this.chosen && this.chosen.piece === pi && this.chosen.index === i;
        this.handles.push({ mesh: ball(p, this.reason || inside ? 0x808080 : chosen ? 0xff2060 : 0xffa000, !!this.reason || inside), piece: pi, index: i });
      });
    });
    this.draw();
  }

  draw() {
    const w = this.canvas.clientWidth || 400, h = this.canvas.clientHeight || 200;
    if (this.canvas.width !== w || this.canvas.height !== h) this.renderer.setSize(w, h, false);
    this.camera.aspect = w / h;
    this.camera.updateProjectionMatrix();
    this.renderer.render(this.scene, this.camera);
  }

  pointer(ev) {
    const r = this.canvas.getBoundingClientRect();
    return new THREE.Vector2(((ev.clientX - r.left) / r.width) * 2 - 1, -((ev.clientY - r.top) / r.height) * 2 + 1);
  }

  snapped(v) {
    if (!this.snap.checked) return v;
    const g = Number(this.grid.value) > 0 ? Number(this.grid.value) : 0.1;
    return v.map((x) => Math.round(x / g) * g);
  }

  // The plane through `point` facing the viewer, and its point under ev.
  planePoint(ev, plane) {
    this.raycaster.setFromCamera(this.pointer(ev), this.camera);
    return this.raycaster.ray.intersectPlane(plane, new THREE.Vector3());
  }

  setupEvents() {
    this.canvas.addEventListener('pointerdown', (ev) => {
      if (this.reason || ev.button !== 0) return;
      if (this.adding) { this.controls.enabled = false; this.addAt(ev); return; }
      this.raycaster.setFromCamera(this.pointer(ev), this.camera);
      // A vertex before a piece's position where both are under the pointer
      // (the position is often inside the hull, behind or on a vertex).
      const hits = this.raycaster.intersectObjects(this.handles.map((x) => x.mesh), false)
        .map((x) => this.handles.find((y) => y.mesh === x.object));
      const h = hits.find((x) => x.index !== 'pos') || hits[0];
      if (!h) return;
      this.controls.enabled = false;
      this.canvas.setPointerCapture(ev.pointerId);
      const normal = this.camera.getWorldDirection(new THREE.Vector3());
      const plane = new THREE.Plane().setFromNormalAndCoplanarPoint(normal, h.mesh.position);
      this.drag = { h, plane, grab: this.planePoint(ev, plane), start: h.mesh.position.clone() };
      if (typeof h.index === 'number') { this.chosen = { piece: h.piece, index: h.index }; this.build(); this.drag.h = this.handles.find((x) => x.piece === h.piece && x.index === h.index); }
      this.say(this.describe(h));
    });
    this.canvas.addEventListener('pointermove', (ev) => {
      if (!this.drag) return;
      const p = this.planePoint(ev, this.drag.plane);
      if (!p || !this.drag.grab) return;
      const at = this.snapped(this.drag.start.clone().add(p.sub(this.drag.grab)).toArray());
      this.moveHandle(this.drag.h, at);
      this.drag.moved = true;
      this.build();
      this.write(false);
      this.drag.h = this.handles.find((x) => x.piece === this.drag.h.piece && x.index === this.drag.h.index);
      this.say(this.describe(this.drag.h));
    });
    const end = () => {
      this.controls.enabled = true;
      if (!this.drag) return;
      const moved = this.drag.moved;
      this.drag = null;
      this.controls.enabled = true;
      if (moved) this.write();  // a press alone only chooses the point
    };
    this.canvas.addEventListener('pointerup', end);
    this.canvas.addEventListener('pointercancel', end);
    new ResizeObserver(() => this.draw()).observe(this.canvas);
  }

  // A handle's piece after moving the handle to `at` (shape coordinates).
  moveHandle(h, at) {
    const piece = this.pieces[h.piece];
    if (h.index === 'centre' || h.index === 'pos') piece.pos = at.map((v) => Math.round(v * 1e4) / 1e4);
    else if (h.index === 'surface') {
      const d = at.map((v, k) => v - piece.pos[k]), r = Math.hypot(...d);
      if (r > 1e-3) { piece.sphere = Math.round(r * 1e4) / 1e4; piece.surface = d.map((v) => v / r); }
    } else piece.points[h.index] = at.map((v, k) => Math.round((v - piece.pos[k]) * 1e4) / 1e4);
  }

  describe(h) {
    const piece = this.pieces[h.piece];
    if (h.index === 'centre') return `${this.element} piece ${h.piece + 1}: sphere centre ${vec(piece.pos)}`;
    if (h.index === 'pos') return `${this.element} piece ${h.piece + 1}: position ${vec(piece.pos)} (moves the piece)`;
    if (h.index === 'surface') return `${this.element} piece ${h.piece + 1}: radius ${num(piece.sphere)}`;
    return `${this.element} piece ${h.piece + 1} vertex ${h.index + 1} ${vec(piece.points[h.index])}${piece.inside[h.index] ? ' (inside the hull)' : ''}`;
  }

  // The piece a new vertex goes to: the chosen point's, else the first hull.
  hullPiece() {
    if (this.chosen && this.pieces[this.chosen.piece] && this.pieces[this.chosen.piece].sphere === null) return this.chosen.piece;
    return this.pieces.findIndex((p) => p.sphere === null);
  }

  addAt(ev) {
    this.adding = false;
    const pi = this.hullPiece();
    if (pi < 0) { this.say('no hull piece to add a vertex to'); return; }
    const piece = this.pieces[pi];
    const abs = piece.points.map((p) => p.map((v, k) => v + piece.pos[k]));
    const centre = abs.reduce((a, p) => a.map((v, k) => v + p[k] / abs.length), [0, 0, 0]);
    const plane = new THREE.Plane().setFromNormalAndCoplanarPoint(this.camera.getWorldDirection(new THREE.Vector3()), new THREE.Vector3(...centre));
    const p = this.planePoint(ev, plane);
    if (!p) return;
    const at = this.snapped(p.toArray());
    piece.points.push(at.map((v, k) => Math.round((v - piece.pos[k]) * 1e4) / 1e4));
    this.chosen = { piece: pi, index: piece.points.length - 1 };
    this.build();
    this.say(this.describe(this.handles.find((x) => x.piece === pi && x.index === piece.points.length - 1)));
    this.write();
  }

  deletePoint() {
    const c = this.chosen;
    const piece = c && this.pieces[c.piece];
    if (!piece || piece.sphere !== null || c.index >= piece.points.length) { this.say('choose a vertex first (press it)'); return; }
    if (piece.points.length <= 4) { this.say('a hull keeps at least four points'); return; }
    piece.points.splice(c.index, 1);
    this.chosen = null;
    this.build();
    this.write();
  }

  addSphere() {
    if (this.reason) return;
    const c = this.controls.target.toArray().map((v) => Math.round(v * 1000) / 1000);
    this.pieces.push({ pos: c, sphere: Math.round((this.size || 1) * 250) / 1000, points: [], color: null, surface: [1, 0, 0] });
    this.build();
    this.write();
  }

  // The pieces as the -desc word: while dragging (done false), or a change
  // that is finished (re-simulated).
  write(done = true) {
    if (this.reason || !this.element) return;
    const word = writeDesc(this.pieces);
    if (this.written.size > 64) this.written.clear();
    this.written.add(word);
    this.ui.write(this.element, word, done);
  }

  // For tests: handles as {piece, index, inside, x, y (page pixels), world}.
  handleList() {
    const r = this.canvas.getBoundingClientRect();
    return this.handles.map((h) => {
      const v = h.mesh.position.clone().project(this.camera);
      const piece = this.pieces[h.piece];
      return { piece: h.piece, index: h.index, inside: typeof h.index === 'number' ? piece.inside[h.index] : false,
        x: r.left + ((v.x + 1) / 2) * r.width, y: r.top + ((1 - v.y) / 2) * r.height, world: h.mesh.position.toArray() };
    });
  }
}
