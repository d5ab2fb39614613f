// Handles (seed 4.1.2–4.1.8, 4.2.3): every spatial value of the scene that a
// graphical viewer can show and edit, built from the session's parameters.
//
//   kind       element  param     drawn as                         drag
//   position   body     init_pos  octahedron at the start          moves in the screen plane
//   rotation   body     init_rot  knob on a spoke from the body    turns the body about the view axis
//   velocity   body     init_dpos arrow from the centre of mass    tip moves in the screen plane
//   angvel     body     init_drot arrow through the centre of mass tip moves in the screen plane
//   force      force#i  vector    arrow from the point of application (constant forces)
//   torque     torque#i vector    arrow along the axis from the point of application (also force -torque 1)
//   offset     force#i  offset    ball on the body                 held on the body's surface
//   link ends  link#i   offset1/2 ball on each body, line between  held on the surface (Shift: free)
//              link#i   vector    ball at an object-to-point link's fixed point
//   light      light    pos, dir  ball at the light, arrow along a directional light's direction
//   knot       trajectory points  ball at each control point      moves in the screen plane (its time kept)
//                                 (-state dpos, drot, rot: the tip of an arrow from the body where it is at that time)
//   view       view     center    ball at the centre of rotation   moves in the screen plane
//              view     pos       knob above the point looked at   moves in the screen plane
//              view     rot       knob on a spoke toward the eye   turns the view
//              view     scale     knob on a spoke along the right  its length / 0.3 radius is the scale
//
// While a handle is dragged, 'z' pushes it away from the viewer and 'x'
// pulls it nearer (seed 4.1.3).
//
// A handle whose value is not a literal the session can rewrite (an
// expression — a view's -pos, -rot or -scale of time or state is placed by
// the core's camera at the frame shown —, a command made in a loop …) is read-only: drawn grey and
// hollow, its reason shown on hover.  Values edit through the session's
// set_parameter exactly like the text would (one literal rewritten).
import * as THREE from 'three';

export const round = (v, digits = 1000) => Math.round(v * digits) / digits;
const vec = (a) => new THREE.Vector3(a[0], a[1], a[2]);

// Numbers of a literal's text, or null when it is not `count` numbers.
export function numbers(text, counts = [3]) {
  if (typeof text !== 'string') return null;
  const parts = text.replace(/[{}]/g, ' ').trim().split(/\s+/).filter((s) => s.length);
  const v = parts.map(Number);
  return counts.includes(v.length) && v.every(Number.isFinite) ? v : null;
}

// -init_rot: a rotation vector (axis × angle) or a unit quaternion {w x y z}.
export function rotationOf(value) {
  if (!value) return new THREE.Quaternion();
  if (value.length === 4) return new THREE.Quaternion(value[1], value[2], value[3], value[0]).normalize();
  const axis = vec(value);
  const angle = axis.length();
  return angle > 0 ? new THREE.Quaternion().setFromAxisAngle(axis.divideScalar(angle), angle) : new THREE.Quaternion();
}

// The rotation written the way the literal was (3 numbers or 4).
export function rotationLiteral(q, count) {
  const s = q.w < 0 ? -1 : 1;
  const w = s * q.w, x = s * q.x, y = s * q.y, z = s * q.z;
  if (count === 4) return [w, x, y, z].map((v) => round(v, 10000));
  const n = Math.hypot(x, y, z);
  const angle = 2 * Math.atan2(n, w);
  const k = n > 1e-12 ? angle / n : 2;
  return [x * k, y * k, z * k].map((v) => round(v, 10000));
}

const COLORS = {
  position: 0xffa000, rotation: 0xc040c0, velocity: 0x2070ff, angvel: 0x10a0a0,
  force: 0xe03030, torque: 0xa05010, offset: 0xe03030, link: 0x209020, light: 0xd0a000, knot: 0x3060d0, view: 0x7040e0,
};
// Which toggle shows a kind (the viewer's element-type check boxes).
export const GROUPS = {
  position: 'handles', rotation: 'handles', velocity: 'velocities', angvel: 'velocities',
  force: 'forces', torque: 'forces', offset: 'forces', link: 'links', light: 'lights', knot: 'trajectories', view: 'views',
};
// Coincident handles: the lower wins the pick.
const PRIORITY = { position: 0, rotation: 1, offset: 2, link: 2, light: 2, force: 3, torque: 3, velocity: 4, angvel: 5, knot: 6, view: 7 };

// The session's view of one element's parameters.
export class ParameterIndex {
  constructor(parameters, elements) {
    this.params = new Map();
    for (const p of parameters || []) this.params.set(`${p.element}\u0000${p.param}`, p);
    this.elements = new Map((elements || []).map((e) => [e.element, e]));
    this.parameters = parameters || [];
  }
  get(element, param) { return this.params.get(`${element}\u0000${param}`) || null; }
  text(element, param, fallback = '') { const p = this.get(element, param); return p ? p.value : fallback; }
  ofKind(kind) {
    return [...this.elements.values()].filter((e) => e.kind === kind).map((e) => e.element);
  }
  // {value, editable, reason} of a vector parameter: `words` are the option
  // words it spans (one, or -x -y -z), `counts` the lengths it may have.
  vector(element, param, { words = [param], counts = [3], fallback = [0, 0, 0] } = {}) {
    const e = this.elements.get(element);
    if (!e) return { value: null, editable: false, reason: 'not in the scene' };
    if (!e.editable) return { value: this.literal(element, words, counts) || fallback, editable: false, reason: e.reason };
    if (words.length > 1) {
      const value = [];
      for (const w of words) {
        const p = this.get(element, w);
        const n = p ? numbers(p.value, [1]) : [0];
        if (p && !p.editable) return { value: null, editable: false, reason: `-${w}: ${p.reason}` };
        if (!n) return { value: null, editable: false, reason: `-${w} is not a number` };
        value.push(n[0]);
      }
      return { value, editable: true, reason: '' };
    }
    const p = this.get(element, param);
    if (!p) return { value: fallback.slice(), editable: true, reason: '' };  // appended when edited
    if (!p.editable) return { value: numbers(p.value, counts), editable: false, reason: p.reason };
    const value = numbers(p.value, counts);
    if (!value) return { value: null, editable: false, reason: `not ${counts.join(' or ')} numbers` };
    return { value, editable: true, reason: '' };
  }
  literal(element, words, counts) {
    if (words.length === 1) return numbers(this.text(element, words[0]), counts);
    const v = words.map((w) => numbers(this.text(element, w, '0'), [1]));
    return v.every((x) => x) ? v.map((x) => x[0]) : null;
  }
}

// One handle.  `spec` gives kind, element, param, words, the value and its
// editability, and three functions of the viewer:
//   anchor()        the world point an arrow starts from (null: no arrow)
//   where()         the handle's world position for the current value
//   valueFrom(p, d) the value for a dragged handle at world point p
//                   (d: the drag's start {value, point})
export class Handle {
  constructor(spec, size) {
    Object.assign(this, spec);
    this.id = spec.id || `${spec.element}.${spec.param}`;
    const color = spec.editable ? COLORS[spec.kind] : 0x606060;
    const geometry = spec.kind === 'position' ? new THREE.OctahedronGeometry(size * 1.25)
      : new THREE.SphereGeometry(size * (spec.kind === 'rotation' ? 0.9 : 0.8), 14, 10);
    this.mesh = new THREE.Mesh(geometry, new THREE.MeshBasicMaterial({
      color, depthTest: false, transparent: true, opacity: spec.editable ? 0.8 : 0.9, wireframe: !spec.editable,
    }));
    this.mesh.renderOrder = 10;
    this.mesh.userData.handle = this;
    this.color = color;
    this.shape = spec.kind === 'position' ? 'octahedron' : spec.kind === 'rotation' ? 'knob' : 'ball';
    this.object = new THREE.Group();
    this.object.add(this.mesh);
    if (spec.anchor) {
      // The arrow from the anchor to the handle (a spoke for a rotation).
      this.arrow = new THREE.ArrowHelper(new THREE.Vector3(1, 0, 0), new THREE.Vector3(), 1, color, size * 2, size * 1.2);
      this.arrow.line.material.depthTest = false;
      this.arrow.cone.material.depthTest = false;
      this.arrow.renderOrder = 9;
      this.object.add(this.arrow);
    }
    // Picked and placed here, drawn by a HandleBatch.
    this.object.traverse((o) => o.layers.set(HANDLE_LAYER));
    this.size = size;
  }
  // The name of the value as the text writes it.
  label() {
    if (this.kind === 'knot') return `${this.element} -points #${this.knot + 1} (t = ${this.t})`;
    const words = this.words && this.words.length > 1 ? this.words.map((w) => `-${w}`).join(' ') : `-${this.param}`;
    return `${this.element} ${words}`;
  }
  valueText() {
    if (!this.value) return '(not a literal)';
    const text = this.value.map((v) => round(v, 10000)).join(' ');
    return this.value.length === 1 ? text : `{${text}}`;
  }
  place() {
    const p = this.where();
    this.mesh.visible = !!p;
    if (p) this.mesh.position.copy(p);
    if (!this.arrow) return;
    const a = this.anchor();
    const d = a && p ? p.clone().sub(a) : null;
    const length = d ? d.length() : 0;
    this.arrow.visible = !!a && length > this.size * 0.5 && !this.stubbed;
    if (this.arrow.visible) {
      this.arrow.position.copy(a);
      this.arrow.setDirection(d.divideScalar(length));
      this.arrow.setLength(length, Math.min(this.size * 2, length * 0.4), Math.min(this.size * 1.2, length * 0.3));
    }
  }
  priority() { return PRIORITY[this.kind] ?? 9; }
}

// The layer of the handles' own objects: placed and picked, not drawn (the
// viewer's camera sees layer 0 only); a HandleBatch draws them.
export const HANDLE_LAYER = 1;

const HIDDEN = new THREE.Matrix4().makeScale(0, 0, 0);
const ORIGIN = new THREE.Vector3(), TIP = new THREE.Vector3();

// All handles in a few draws: an instanced mesh per shape and editability
// (each handle's colour per instance, its matrix its own mesh's), the
// arrows' shafts as one set of line segments and their heads as one more
// instanced mesh.  A hundred bodies have some 400 handles, each of them
// three draws (knob, shaft, head) when drawn one by one: about 1300 draw
// calls a frame, where software WebGL spent most of a frame.
export class HandleBatch {
  constructor(parent) {
    this.group = new THREE.Group();
    parent.add(this.group);
    this.sets = [];
    this.arrows = [];
    // Kept across builds: a material disposed of takes its compiled shader
    // program with it (tens of milliseconds to make again in software).
    const knob = (editable) => new THREE.MeshBasicMaterial({
      depthTest: false, transparent: true, opacity: editable ? 0.8 : 0.9, wireframe: !editable,
    });
    this.materials = {
      true: knob(true), false: knob(false),
      shaft: new THREE.LineBasicMaterial({ vertexColors: true, depthTest: false, toneMapped: false }),
      head: new THREE.MeshBasicMaterial({ depthTest: false, toneMapped: false }),
    };
  }

  // A new set of handles (all of one size).
  build(handles, size) {
    for (const o of this.group.children) {
      o.geometry.dispose();
      if (o.dispose) o.dispose();  // an instanced mesh's instance buffers
    }
    this.group.clear();
    this.sets = [];
    // (Balls of 10 × 7 segments: a handle is a few pixels across, and a
    // hundred bodies' handles were 110 000 triangles at 14 × 10.)
    const geometry = {
      octahedron: () => new THREE.OctahedronGeometry(size * 1.25),
      knob: () => new THREE.SphereGeometry(size * 0.9, 10, 7),
      ball: () => new THREE.SphereGeometry(size * 0.8, 10, 7),
    };
    const groups = new Map();
    for (const h of handles) {
      const key = `${h.shape} ${h.editable}`;
      if (!groups.has(key)) groups.set(key, []);
      groups.get(key).push(h);
    }
    const color = new THREE.Color();
    for (const list of groups.values()) {
      const { shape, editable } = list[0];
      const mesh = new THREE.InstancedMesh(geometry[shape](), this.materials[editable], list.length);
      list.forEach((h, i) => mesh.setColorAt(i, color.set(h.color)));
      mesh.renderOrder = 10;
      mesh.frustumCulled = false;
      this.group.add(mesh);
      this.sets.push({ mesh, list });
    }
    this.arrows = handles.filter((h) => h.arrow);
    const n = this.arrows.length;
    if (!n) return;
    const lines = new THREE.BufferGeometry();
    lines.setAttribute('position', new THREE.BufferAttribute(new Float32Array(6 * n), 3));
    const colors = new Float32Array(6 * n);
    this.arrows.forEach((h, i) => {
      color.set(h.color);
      for (const k of [0, 3]) colors.set([color.r, color.g, color.b], 6 * i + k);
    });
    lines.setAttribute('color', new THREE.BufferAttribute(colors, 3));
    this.shafts = new THREE.LineSegments(lines, this.materials.shaft);
    const cone = new THREE.CylinderGeometry(0, 0.5, 1, 5, 1).translate(0, -0.5, 0);
    this.heads = new THREE.InstancedMesh(cone, this.materials.head, n);
    this.arrows.forEach((h, i) => this.heads.setColorAt(i, color.set(h.color)));
    for (const o of [this.shafts, this.heads]) {
      o.renderOrder = 9;
      o.frustumCulled = false;
      this.group.add(o);
    }
  }

  // The handles where their own objects are (world matrices up to date).
  update() {
    for (const { mesh, list } of this.sets) {
      list.forEach((h, i) => mesh.setMatrixAt(i, shown(h) && h.mesh.visible ? h.mesh.matrixWorld : HIDDEN));
      mesh.instanceMatrix.needsUpdate = true;
    }
    if (!this.arrows.length) return;
    const position = this.shafts.geometry.attributes.position;
    this.arrows.forEach((h, i) => {
      const on = shown(h) && h.arrow.visible;
      ORIGIN.set(0, 0, 0);
      TIP.set(0, on ? 1 : 0, 0);
      ORIGIN.applyMatrix4(h.arrow.line.matrixWorld);
      TIP.applyMatrix4(h.arrow.line.matrixWorld);
      position.setXYZ(2 * i, ORIGIN.x, ORIGIN.y, ORIGIN.z);
      position.setXYZ(2 * i + 1, TIP.x, TIP.y, TIP.z);
      this.heads.setMatrixAt(i, on ? h.arrow.cone.matrixWorld : HIDDEN);
    });
    position.needsUpdate = true;
    this.heads.instanceMatrix.needsUpdate = true;
  }
}

// Whether a handle's object and the groups holding it are visible.
function shown(h) {
  for (let o = h.object; o; o = o.parent) if (!o.visible) return false;
  return true;
}
