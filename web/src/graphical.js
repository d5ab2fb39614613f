// The graphical viewer (seed 4.1): the bodies' meshes drawn by three.js from
// poses streamed once per simulation, so playback, the time slider, rotation
// and zoom need no server round trip.  Handles (handles.js, seed 4.2.3) edit
// initial positions, rotations, velocities, constant forces, link ends and
// lights: dragging one changes its literal through the session while
// dragging, and re-simulates on release.  A trajectory is drawn as its curve
// with a handle per control point (seed Figure 4.4).  Display styles (shaded,
// lines) and element-type toggles choose what is drawn.  A click on a body
// selects it; element creation asks for clicks on bodies (startPick).  The
// camera turns with a virtual sphere (camera.js) or follows one of the
// scene's `view` elements; the scene's light sources light the picture.
import * as THREE from 'three';
import { SphereControls } from './camera.js';
import { GROUPS, Handle, HandleBatch, ParameterIndex, numbers, round, rotationLiteral, rotationOf } from './handles.js';
import { TrajectoryCurve, knotsText, parseKnots } from './trajectory.js';
import { softwareWebGL } from './webgl.js';

const ZERO = [0, 0, 0];
// Handle kinds whose place depends on the time shown (graphical.placeHandles).
const TIMED = new Set(['force', 'torque', 'offset', 'link', 'view']);
// The arrows (and their scale) of trajectories whose values are not places.
const TRAJECTORY_ARROWS = { dpos: 'velocity', drot: 'angvel', rot: 'angvel' };

// A body's pose between two frames by cubic Hermite interpolation of the
// poses [x y z qx qy qz qw] and velocities [vx vy vz wx wy wz] (ω in world
// axes) at both ends, `dt` apart, at fraction s: positions exactly, the
// quaternion's components with q̇ = ½ (ω, 0) ⊗ q, then normalized.  Set on
// `object` (its position and quaternion).  The pose and velocity of a are
// read from pa at ia and va at iva, b's from pb at ib and vb at ivb (a
// frame's arrays of every body, not copied).
export function hermitePose(pa, va, pb, vb, dt, s, object, ia = 0, iva = 0, ib = ia, ivb = iva) {
  const s2 = s * s, s3 = s2 * s;
  const h00 = 2 * s3 - 3 * s2 + 1, h10 = (s3 - 2 * s2 + s) * dt, h01 = -2 * s3 + 3 * s2, h11 = (s3 - s2) * dt;
  object.position.set(
    h00 * pa[ia] + h10 * va[iva] + h01 * pb[ib] + h11 * vb[ivb],
    h00 * pa[ia + 1] + h10 * va[iva + 1] + h01 * pb[ib + 1] + h11 * vb[ivb + 1],
    h00 * pa[ia + 2] + h10 * va[iva + 2] + h01 * pb[ib + 2] + h11 * vb[ivb + 2]);
  // The quaternions q = [x y z w] at both ends (b's sign chosen nearer a)
  // and their derivatives ½ (ω, 0) ⊗ q, mixed component by component (no
  // arrays: this runs per body per frame of playback).
  const ax = pa[ia + 3], ay = pa[ia + 4], az = pa[ia + 5], aw = pa[ia + 6];
  const sign = ax * pb[ib + 3] + ay * pb[ib + 4] + az * pb[ib + 5] + aw * pb[ib + 6] < 0 ? -1 : 1;
  const bx = sign * pb[ib + 3], by = sign * pb[ib + 4], bz = sign * pb[ib + 5], bw = sign * pb[ib + 6];
  const wax = va[iva + 3], way = va[iva + 4], waz = va[iva + 5];
  const wbx = vb[ivb + 3], wby = vb[ivb + 4], wbz = vb[ivb + 5];
  const x = h00 * ax + h10 * 0.5 * (aw * wax + way * az - waz * ay) + h01 * bx + h11 * 0.5 * (bw * wbx + wby * bz - wbz * by);
  const y = h00 * ay + h10 * 0.5 * (aw * way + waz * ax - wax * az) + h01 * by + h11 * 0.5 * (bw * wby + wbz * bx - wbx * bz);
  const z = h00 * az + h10 * 0.5 * (aw * waz + wax * ay - way * ax) + h01 * bz + h11 * 0.5 * (bw * wbz + wbx * by - wby * bx);
  const w = h00 * aw - h10 * 0.5 * (wax * ax + way * ay + waz * az) + h01 * bw - h11 * 0.5 * (wbx * bx + wby * by + wbz * bz);
  const n = Math.sqrt(x * x + y * y + z * z + w * w) || 1;
  object.quaternion.set(x / n, y / n, z / n, w / n);
}

export class GraphicalViewer {
  constructor(canvas, ui) {
    this.canvas = canvas;
    this.ui = ui;
    this.renderer = new THREE.WebGLRenderer({ canvas, antialias: !softwareWebGL(), preserveDrawingBuffer: true });
    this.renderer.setPixelRatio(window.devicePixelRatio || 1);
    this.scene = new THREE.Scene();
    this.scene.background = new THREE.Color(0xffffff);
    this.camera = new THREE.PerspectiveCamera(35, 1, 0.1, 1000);
    this.camera.position.set(0, 0, 60);
    // Without light sources in the scene: a sky light and a sun.
    this.defaultLights = new THREE.Group();
    const sun = new THREE.DirectionalLight(0xffffff, 1.4);
    sun.position.set(30, 50, 40);
    this.defaultLights.add(new THREE.HemisphereLight(0xffffff, 0x666666, 1.6), sun);
    this.sceneLights = new THREE.Group();
    this.scene.add(this.defaultLights, this.sceneLights);
    this.views = [];      // the scene's view elements' cameras (poses.views)
    this.viewName = '';   // the one shown, or '' for the free camera
    this.bodies = new Map();   // name → {group, meshes, edges, index, static, centroid, radius}
    this.handles = [];         // Handle (handles.js)
    this.handleGroup = new THREE.Group();
    this.linkLines = new THREE.Group();
    this.paths = new THREE.Group();  // trajectories' curves
    this.selectionBox = new THREE.BoxHelper(undefined, 0xff8000);
    this.selectionBox.visible = false;
    this.scene.add(this.handleGroup, this.linkLines, this.paths, this.selectionBox);
    this.handleBatch = new HandleBatch(this.scene);  // draws the handles
    this.scene.matrixWorldAutoUpdate = false;  // render() updates the matrices first
    this.selected = null;  // the selected body's name
    this.selectedElement = null;  // the element last picked (a body, or a handle's element)
    this.mode = null;      // a creation waiting for clicks (startPick)
    this.index = new ParameterIndex([], []);
    this.simValues = new Map();  // "element.param" → the value the shown motion was simulated with
    this.scales = { velocity: 1, angvel: 1, force: 1, torque: 1 };
    this.handleSize = 0.3;
    this.radius = 10;
    this.style = 'shaded';
    this.shown = { bodies: true, handles: true, velocities: true, links: true, forces: true, lights: true, trajectories: false, views: false };
    this.poses = null;
    this.t = 0;
    this.frame = 0;
    this.playing = false;
    this.fitted = false;
    this.raycaster = new THREE.Raycaster();
    this.raycaster.layers.enableAll();  // the handles' layer too
    this.setupEvents();
    // After setupEvents: a press on a handle disables the controls first.
    this.controls = new SphereControls(this.camera, canvas, { pickPoint: (ev) => { const b = this.pickBody(ev); return b && b.world; } });
    this.controls.onChange = () => this.draw();
    this.controls.onStart = () => { if (this.viewName) this.setView(''); };
    // The control points' times, beside them (seed Figure 4.4).
    this.knotLayer = null;
    if (canvas.parentElement) {
      this.knotLayer = document.createElement('div');
      this.knotLayer.className = 'point-times';
      canvas.insertAdjacentElement('afterend', this.knotLayer);  // under the labels and panels
    }
    new ResizeObserver(() => this.resize()).observe(canvas);
    this.resize();
  }

  resize() {
    const w = this.canvas.clientWidth || 400, h = this.canvas.clientHeight || 300;
    this.renderer.setSize(w, h, false);
    this.camera.aspect = w / h;
    this.camera.updateProjectionMatrix();
    if (this.viewName && this.poses) this.seek(this.t);  // the view's field of view follows the aspect
    this.draw();
  }

  // The scene's light sources (meshes.lights, as the core's renderer takes
  // them) replace the default lights: a directional light shines along its
  // direction, a point light from its position without falloff (as
  // OpenGL's default attenuation), and a weak ambient term keeps the unlit
  // sides readable, like the renderer's.
  setLights(lights) {
    this.sceneLights.clear();
    this.defaultLights.visible = !lights.length;
    if (!lights.length) return;
    this.sceneLights.add(new THREE.AmbientLight(0xffffff, 0.5));
    for (const l of lights) {
      const color = new THREE.Color(l.color[0], l.color[1], l.color[2]);
      if (l.directional) {
        const light = new THREE.DirectionalLight(color, 2.5 * l.intensity);
        light.position.set(-l.direction[0], -l.direction[1], -l.direction[2]);
        light.target.position.set(0, 0, 0);
        this.sceneLights.add(light, light.target);
      } else {
        const light = new THREE.PointLight(color, 2.5 * l.intensity, 0, 0);
        light.position.set(...l.position);
        this.sceneLights.add(light);
      }
    }
  }

  // Shows the scene's view element `name` (its camera follows the motion,
  // as asgard render places it), or the free camera for ''.  The free
  // camera starts where the view was.
  setView(name) {
    const view = this.views.find((v) => v.name === name);
    this.viewName = view ? name : '';
    if (!this.viewName) {
      this.camera.fov = 35;
      this.camera.updateProjectionMatrix();
    }
    if (this.ui.view) this.ui.view(this.viewName);
    if (this.poses) this.seek(this.t);
  }

  // The chosen view's camera at frames i, j mixed by s.
  placeViewCamera(i, j, s) {
    const view = this.views.find((v) => v.name === this.viewName);
    if (!view) return;
    const mix = (k) => new THREE.Vector3(...view.cameras[i][k]).lerp(new THREE.Vector3(...view.cameras[j][k]), s);
    const eye = mix(0), target = mix(1), up = mix(2).normalize();
    const tanHalf = Math.tan(view.fov_y / 2) / Math.min(1, this.camera.aspect);
    this.camera.fov = (2 * Math.atan(tanHalf) * 180) / Math.PI;
    const d = eye.distanceTo(target);
    this.camera.near = d / 100;
    this.camera.far = d * 20;
    this.camera.updateProjectionMatrix();
    this.camera.position.copy(eye);
    this.camera.up.copy(up);
    this.controls.target.copy(target);
    this.camera.lookAt(target);
    this.camera.updateMatrixWorld();
  }

  // meshes: {bodies: [{name, static, centroid, radius, pieces}]};
  // poses: {times, bodies, poses, forces}.
  setScene(meshes, poses) {
    // The old bodies' buffers go (not their materials: a material disposed
    // of takes the shader program the new ones share).
    for (const b of this.bodies.values()) {
      this.scene.remove(b.group);
      for (const m of [...b.meshes, ...b.edges]) m.geometry.dispose();
    }
    this.bodies.clear();
    meshes.bodies.forEach((b) => {
      const group = new THREE.Group();
      const parts = { meshes: [], edges: [] };
      for (const p of b.pieces) {
        const color = new THREE.Color(p.color[0], p.color[1], p.color[2]);
        const material = new THREE.MeshStandardMaterial({ color, flatShading: true, roughness: 0.7 });
        let geometry;
        if (p.sphere) {
          geometry = new THREE.SphereGeometry(p.radius, 24, 16);
          geometry.translate(p.center[0], p.center[1], p.center[2]);
        } else {
          geometry = new THREE.BufferGeometry();
          geometry.setAttribute('position', new THREE.Float32BufferAttribute(p.vertices, 3));
          geometry.setIndex(p.triangles);
          geometry = geometry.toNonIndexed();
          geometry.computeVertexNormals();
        }
        const mesh = new THREE.Mesh(geometry, material);
        // A hit on a sphere's polygons is moved to the true surface (localPoint).
        if (p.sphere) mesh.userData.sphere = { center: new THREE.Vector3(...p.center), radius: p.radius };
        // Lines style: a sphere's edges are its wireframe's, a hull's its creases.
        const edges = new THREE.LineSegments(
          p.sphere ? new THREE.WireframeGeometry(new THREE.SphereGeometry(p.radius, 12, 8).translate(p.center[0], p.center[1], p.center[2]))
            : new THREE.EdgesGeometry(geometry, 20),
          new THREE.LineBasicMaterial({ color: 0x333333 }));
        edges.userData.sphere = p.sphere;
        edges.userData.color = color;
        group.add(mesh, edges);
        parts.meshes.push(mesh);
        parts.edges.push(edges);
      }
      group.name = b.name;
      this.scene.add(group);
      this.bodies.set(b.name, {
        group, ...parts, index: poses.bodies.indexOf(b.name), static: b.static,
        centroid: b.centroid ? new THREE.Vector3(...b.centroid) : new THREE.Vector3(), radius: b.radius || 1,
      });
    });
    this.poses = poses;
    this.setLights(meshes.lights || []);
    this.views = poses.views || [];
    if (this.viewName && !this.views.some((v) => v.name === this.viewName)) this.setView('');
    if (this.ui.views) this.ui.views(this.views.map((v) => v.name), this.viewName);
    // The initial values this motion was simulated with (handles of moved
    // bodies are placed relative to them until the next simulation).
    this.simValues.clear();
    for (const name of this.bodies.keys())
      for (const param of ['init_pos', 'init_rot'])
        this.simValues.set(`${name}.${param}`, numbers(this.index.text(name, param), [3, 4]));
    this.ui.slider.max = String(Math.max(1, poses.times.length - 1));
    if (!this.fitted || this.startsOutOfView()) this.fit();
    this.applyStyle();
    this.resetHandles();
    this.seek(Math.min(this.t, poses.t1));
  }

  // The session's parameters and elements (scene_state).
  setParameters(parameters, elements, prescribed = []) {
    this.index = new ParameterIndex(parameters, elements);
    this.prescribed = prescribed;
    this.resetHandles();
    if (this.poses) this.seek(this.t);
  }

  // Another view (or this one) dragged a handle: the new value.
  parameterEdited(element, param, values) {
    const p = this.index.get(element, param);
    if (param === 'points') {
      const knots = [];
      for (let k = 0; k + 3 < values.length; k += 4) knots.push(values.slice(k, k + 4));
      if (p) p.value = knotsText(knots);
      // (Not while this tab's trajectory panel drags them: its values are newer.)
      if (this.panelDrag !== element)
        for (const h of this.handles)
          if (h.kind === 'knot' && h.element === element && h !== this.dragging && knots[h.knot]) {
            h.t = knots[h.knot][0];
            h.value = knots[h.knot].slice(1);
          }
      this.placeHandles();
      this.draw();
      if (this.ui.knots) this.ui.knots();
      return;
    }
    if (p) p.value = values.join(' ');
    const h = this.handles.find((x) => x.element === element && x.param === param);
    if (!h || this.dragging === h || !h.editable) return;
    h.value = values.slice();
    this.placeHandles();
    this.draw();
  }

  // --- where things are -------------------------------------------------

  pose0(name) {
    const b = this.bodies.get(name);
    if (!b || b.index < 0 || !this.poses) return null;
    const f = this.poses.poses[0], k = 7 * b.index;
    return { p: new THREE.Vector3(f[k], f[k + 1], f[k + 2]), q: new THREE.Quaternion(f[k + 3], f[k + 4], f[k + 5], f[k + 6]) };
  }

  // A body's start as its handles' values say (a dragged body moves before
  // it is simulated again).
  start(name) {
    const p0 = this.pose0(name);
    if (!p0) return null;
    const pos = this.bodyHandle(name, 'init_pos'), rot = this.bodyHandle(name, 'init_rot');
    const simPos = this.simValues.get(`${name}.init_pos`) || ZERO;
    if (pos && pos.value) p0.p.add(new THREE.Vector3(...pos.value).sub(new THREE.Vector3(...simPos)));
    if (rot && rot.value) {
      const delta = rotationOf(rot.value).multiply(rotationOf(this.simValues.get(`${name}.init_rot`)).invert());
      p0.q.premultiply(delta);
    }
    return p0;
  }

  bodyHandle(name, param) { return this.handles.find((h) => h.element === name && h.param === param); }

  // A point in a body's shape coordinates, in the world at the shown time.
  onBody(name, point) {
    const b = this.bodies.get(name);
    if (!b || b.index < 0) return null;
    return new THREE.Vector3(...point).sub(b.centroid).applyQuaternion(b.group.quaternion).add(b.group.position);
  }

  // --- handles ------------------------------------------------------------

  resetHandles() {
    if (!this.poses) return;
    // Another view's state while this one drags: rebuilt when the drag ends.
    if (this.dragging) { this.resetPending = true; return; }
    this.resetPending = false;
    this.handleGroup.clear();
    this.linkLines.clear();
    this.paths.clear();
    this.handles = [];
    const add = (spec) => {
      const h = new Handle(spec, this.handleSize);
      this.handles.push(h);
      this.handleGroup.add(h.object);
      return h;
    };
    const ix = this.index;
    const delta = (h, p, d) => d.value.map((v, k) => round(v + (p.getComponent(k) - d.point.getComponent(k)) / h.scale));
    const arrowTip = (h, base, stubAxis) => {
      const v = new THREE.Vector3(...h.value);
      h.stubbed = v.lengthSq() === 0;
      // A zero vector's handle waits beside its anchor.
      return h.stubbed ? base.clone().add(stubAxis.clone().multiplyScalar(this.handleSize * 5)) : base.clone().add(v.multiplyScalar(h.scale));
    };
    const prescribed = this.prescribedAtStart();
    // A body's initial value that a trajectory overrides is read-only.
    const initial = (name, param, options) => {
      const spec = ix.vector(name, param, options), reason = prescribed.get(`${name}.${param}`);
      return reason && spec.editable ? { ...spec, editable: false, reason } : spec;
    };
    for (const [name, b] of this.bodies) {
      if (b.static || b.index < 0) continue;
      const centre = () => this.start(name).p;
      add({ kind: 'position', element: name, param: 'init_pos', ...initial(name, 'init_pos'),
        where: centre, valueFrom: (p, d) => d.value.map((v, k) => round(v + p.getComponent(k) - d.point.getComponent(k))) });
      const rot = initial(name, 'init_rot', { counts: [3, 4] });
      add({ kind: 'rotation', element: name, param: 'init_rot', ...rot,
        anchor: centre,
        where: () => {
          const s = this.start(name);
          return s.p.clone().add(new THREE.Vector3(b.radius + this.handleSize * 3, 0, 0).applyQuaternion(s.q));
        },
        valueFrom: (p, d) => {
          const c = d.anchor, n = this.camera.getWorldDirection(new THREE.Vector3()).negate();
          const a = d.point.clone().sub(c).projectOnPlane(n), e = p.clone().sub(c).projectOnPlane(n);
          const angle = Math.atan2(a.clone().cross(e).dot(n), a.dot(e));
          const q = new THREE.Quaternion().setFromAxisAngle(n, angle).multiply(rotationOf(d.value));
          return rotationLiteral(q, d.value.length === 4 ? 4 : 3);
        } });
      for (const [kind, param, axis] of [['velocity', 'init_dpos', new THREE.Vector3(1, 0, 0)], ['angvel', 'init_drot', new THREE.Vector3(0, 1, 0)]]) {
        const h = add({ kind, element: name, param, ...initial(name, param), scale: this.scales[kind],
          anchor: centre, where: () => h.value ? arrowTip(h, centre(), axis) : centre(), valueFrom: (p, d) => delta(h, p, d) });
      }
    }
    // Forces and torques (`torque`, `force -torque 1`): an arrow from the
    // point of application; a torque's arrow is its axis (right hand).
    for (const kind of ['force', 'torque']) ix.ofKind(kind).forEach((element) => {
      const body = ix.text(element, 'body');
      if (!this.bodies.has(body)) return;
      const index = Number(element.split('#')[1]);
      const offset = ix.get(element, 'offset') ? ix.vector(element, 'offset') : null;
      // The point of application: the offset's handle, else the centre of mass.
      const base = () => this.onBody(body, this.bodyHandleOf(element, 'offset').value || this.bodies.get(body).centroid.toArray());
      const gravitational = ix.text(element, 'gravitational', '0') === '1';
      const h = add({ kind, element, param: 'vector', words: ['x', 'y', 'z'], ...ix.vector(element, 'vector', { words: ['x', 'y', 'z'] }),
        scale: this.scales[kind], note: gravitational ? ' (× mass)' : '', anchor: base,
        where: () => {
          if (h.editable) return arrowTip(h, base(), kind === 'force' ? new THREE.Vector3(0, -1, 0) : new THREE.Vector3(0, 0, 1));
          // Read-only: its value at the shown time, when known.
          const v = kind === 'force' ? this.forceAt(index) : this.torqueAt(index);
          h.stubbed = !v;
          return v ? base().add(new THREE.Vector3(...v).multiplyScalar(h.scale)) : base();
        },
        valueFrom: (p, d) => delta(h, p, d) });
      if (offset) add({ kind: 'offset', element, param: 'offset', ...offset, body, where: () => this.onBody(body, this.bodyHandleOf(element, 'offset').value || ZERO),
        valueFrom: (p, d, ev) => this.onSurface(body, p, d, ev) });
    });
    ix.ofKind('link').forEach((element) => {
      const ends = [];
      for (const [bodyParam, offsetParam] of [['body1', 'offset1'], ['body2', 'offset2']]) {
        const body = ix.text(element, bodyParam);
        if (!this.bodies.has(body)) continue;
        const h = add({ kind: 'link', element, param: offsetParam, body, ...ix.vector(element, offsetParam),
          where: () => this.onBody(body, h.value || ZERO), valueFrom: (p, d, ev) => this.onSurface(body, p, d, ev) });
        ends.push(h);
      }
      if (ends.length === 1 && !ix.get(element, 'body2') && !ix.get(element, 'trajectory')) {
        const point = ix.vector(element, 'vector', { words: ['x', 'y', 'z'] });
        if (!point.value) point.value = ix.literal(element, ['x', 'y', 'z'], [1]);
        const h = add({ kind: 'link', element, param: 'vector', words: ['x', 'y', 'z'], id: `${element}.point`, ...point,
          where: () => (h.value ? new THREE.Vector3(...h.value) : null),
          valueFrom: (p) => [p.x, p.y, p.z].map((v) => round(v)) });
        ends.push(h);
      }
      if (ends.length === 2) {
        const line = new THREE.Line(new THREE.BufferGeometry().setFromPoints([new THREE.Vector3(), new THREE.Vector3()]),
          new THREE.LineBasicMaterial({ color: 0x209020 }));
        line.userData.ends = ends;
        this.linkLines.add(line);
      }
    });
    ix.ofKind('lightsource').forEach((element) => {
      const pos = add({ kind: 'light', element, param: 'pos', ...ix.vector(element, 'pos', { fallback: [0, 0, 10] }),
        where: () => (pos.value ? new THREE.Vector3(...pos.value) : null),
        valueFrom: (p) => [p.x, p.y, p.z].map((v) => round(v)) });
      if (ix.text(element, 'type', 'directional') !== 'directional') return;
      const length = this.radius * 0.3;
      const from = () => (pos.value ? new THREE.Vector3(...pos.value) : null);
      const dir = add({ kind: 'light', element, param: 'dir', ...ix.vector(element, 'dir', { fallback: [0, 0, -1] }),
        anchor: from,
        where: () => {
          const a = from();
          if (!a || !dir.value) return null;
          const v = new THREE.Vector3(...dir.value);
          return v.lengthSq() > 0 ? a.add(v.normalize().multiplyScalar(length)) : a;
        },
        valueFrom: (p) => {
          const v = p.clone().sub(from()).divideScalar(length);
          return [v.x, v.y, v.z].map((x) => round(x));
        } });
    });
    ix.ofKind('trajectory').forEach((element) => this.addTrajectory(element, add));
    ix.ofKind('view').forEach((element, i) => this.addView(element, i, add));
    this.handleBatch.build(this.handles, this.handleSize);
    this.applyVisibility();
    this.placeHandles();
    if (this.ui.knots) this.ui.knots();
  }

  // The bodies' initial values that a trajectory prescribes at the start of
  // the run ("body.init_pos" → why), as the session works them out from the
  // evaluated scene (Session::PrescribedInitials: computed times and points
  // count too).
  prescribedAtStart() {
    return new Map((this.prescribed || []).map((p) => [`${p.body}.${p.param}`, p.reason]));
  }

  // A trajectory (seed Figure 4.4): its curve, and a handle per control
  // point when -points is a literal list the session can rewrite.  Dragging
  // one moves that point in the screen plane (its time is kept) and sends
  // the whole list.  A trajectory whose points are not a literal is drawn
  // from the core's samples of it.
  //
  // A position trajectory (-state pos) is a path in space.  The values of a
  // velocity, spin or rotation trajectory (-state dpos, drot, rot: a
  // velocity, an angular velocity, a rotation vector axis × angle) are not
  // places: each is an arrow from where its body is at that time in the
  // motion shown, at the scale of the bodies' velocity (dpos) or spin arrows
  // (drot, rot); the handle is the arrow's tip, and the curve is drawn
  // through the tips.
  addTrajectory(element, add) {
    const ix = this.index, e = ix.elements.get(element), p = ix.get(element, 'points');
    const knots = p ? parseKnots(p.value) : null;
    const reason = !e.editable ? e.reason : !p ? 'it has no -points' : !p.editable ? p.reason
      : !knots ? 'its -points is not a list of {t x y z} with increasing times' : '';
    const line = new THREE.Line(new THREE.BufferGeometry(), new THREE.LineBasicMaterial({ color: reason ? 0x808080 : 0x3060d0 }));
    line.userData.element = element;
    const forced = this.forceTrajectories().get(element);
    const arrows = forced ? 'force' : TRAJECTORY_ARROWS[ix.text(element, 'state', 'pos')];
    const body = forced || ix.text(element, 'body');
    const scale = () => this.scales[arrows];
    line.userData.place = arrows ? (t, v) => this.bodyAt(body, t).add(new THREE.Vector3(...v).multiplyScalar(scale()))
      : (t, v) => new THREE.Vector3(...v);
    // The value drawn at world point w at time t.
    line.userData.unplace = arrows ? (t, w) => w.clone().sub(this.bodyAt(body, t)).divideScalar(scale()).toArray()
      : (t, w) => w.toArray();
    const handles = [];
    (knots || []).forEach((k, i) => {
      const h = add({ kind: 'knot', element, param: 'points', id: `${element}.points#${i}`, knot: i, t: k[0],
        value: k.slice(1), editable: !reason, reason,
        where: () => line.userData.place(h.t, h.value),
        ...(arrows ? { anchor: () => this.bodyAt(body, h.t), scale: scale() } : {}),
        valueFrom: (q, d) => d.value.map((v, c) => round(v + (q.getComponent(c) - d.point.getComponent(c)) / (arrows ? scale() : 1))),
        payload: () => handles.flatMap((x) => [x.t, ...x.value]) });
      handles.push(h);
    });
    line.userData.knots = handles;
    this.paths.add(line);
  }

  // Trajectories that are a force's vector over time (trajectory → body): a
  // trajectory with no body of its own whose value is all of a force's
  // -x -y -z (`force -body B -x T.x -y T.y -z T.z`, as the Create menu
  // writes it).  Drawn as that force's arrows from B, at the forces' scale.
  forceTrajectories() {
    const ix = this.index;
    if (this.forcedOf === ix) return this.forced;  // once per set of parameters
    const out = new Map();
    const free = new Set(ix.ofKind('trajectory').filter((t) => !ix.text(t, 'body')));
    for (const element of ix.ofKind('force')) {
      const words = ['x', 'y', 'z'].map((c) => (ix.text(element, c) || '').trim());
      const m = /^([A-Za-z_][A-Za-z0-9_]*)\.x$/.exec(words[0]);
      if (m && free.has(m[1]) && words[1] === `${m[1]}.y` && words[2] === `${m[1]}.z` && ix.text(element, 'gravitational', '0') === '0' &&
          ix.text(element, 'torque', '0') === '0')
        out.set(m[1], ix.text(element, 'body'));
    }
    this.forcedOf = ix;
    this.forced = out;
    return out;
  }

  // Where body `name` is at time t of the motion shown (interpolated as
  // playback does; its start before there is a motion).
  bodyAt(name, t) {
    const b = name ? this.bodies.get(name) : null;
    if (!b) return new THREE.Vector3();
    if (!this.poses || b.index < 0) return this.start(name).p.clone();
    const { times } = this.poses;
    t = Math.min(Math.max(t, times[0]), times[times.length - 1]);
    let lo = 0, hi = times.length - 1;
    while (hi - lo > 1) {
      const mid = (lo + hi) >> 1;
      if (times[mid] <= t) lo = mid; else hi = mid;
    }
    const s = hi > lo && times[hi] > times[lo] ? (t - times[lo]) / (times[hi] - times[lo]) : 0;
    const o = this.scratchPose || (this.scratchPose = new THREE.Object3D());
    this.poseBetween(b, lo, hi, s, o);
    return o.position.clone();
  }

  // A `view` element (seed 4.1.7) as asgard render places its camera: the
  // rotation R (-rot, world to view), -pos (scene units after rotation) and
  // -center c put the point looked at at Rᵀ(−pos) + c and the eye along
  // Rᵀ ẑ from it, kEyeDistance framing radii / -scale away.  Four handles:
  // -center (a ball at c; read-only when -follow or -trajectory moves it),
  // -pos (a knob on a spoke from the point looked at along the view's up),
  // -rot (a knob on a spoke from that point toward the eye; dragging it
  // turns the view by the rotation taking the spoke to the pointer), -scale
  // (a knob on a spoke along the view's right, the spoke's length times the
  // scale: dragging it out zooms in).  The spokes are 0.3 of the scene's
  // radius.  An option not written takes the value the core's camera has
  // (poses.views) and is appended when dragged.  An option written as an
  // expression of time or state (the core lists them: `expressions`) has a
  // read-only handle that the core's camera at the frame shown places.
  // `index`: the view's place among views.
  addView(element, index, add) {
    const ix = this.index, core = (this.poses.views || [])[index];
    if (!core || !core.cameras.length) return;
    const expressions = new Set(core.expressions || []);
    const framing = this.poses.framing || { eye_distance: 4, radius: this.radius };
    // The core's camera at the frame shown: [eye, target, up], its rotation
    // (world to view) and its scale.
    const cameraAt = () => (core.cameras[this.frame] || core.cameras[0]).map((v) => new THREE.Vector3(...v));
    const rotationAt = ([eye, target, up]) => {
      const z = eye.clone().sub(target).normalize(), y = up.clone().normalize(), x = y.clone().cross(z);
      return new THREE.Quaternion().setFromRotationMatrix(new THREE.Matrix4().makeBasis(x, y, z)).invert();
    };
    const scaleAt = ([eye, target]) => (framing.eye_distance * framing.radius) / Math.max(1e-12, eye.distanceTo(target));
    const [, target] = cameraAt();
    const fallbackRot = rotationLiteral(rotationAt(cameraAt()), 3);
    const q = () => (expressions.has('rot') ? rotationAt(cameraAt()) : rotationOf(rot.value || fallbackRot));
    const p = () => new THREE.Vector3(...(pos.value || ZERO));
    const c = () => new THREE.Vector3(...centre.value);
    // With an expression the point looked at is where the core's camera looks.
    const looked = () => (expressions.size ? cameraAt()[1] : p().negate().applyQuaternion(q().invert()).add(c()));
    const spoke = () => this.radius * 0.3;
    const rot = add({ kind: 'view', element, param: 'rot', ...this.viewOption(element, 'rot', expressions, { counts: [3, 4], fallback: fallbackRot }),
      anchor: looked,
      where: () => looked().add(new THREE.Vector3(0, 0, spoke()).applyQuaternion(q().invert())),
      valueFrom: (w, d) => {
        const from = d.point.clone().sub(d.anchor).normalize(), to = w.clone().sub(d.anchor);
        if (to.lengthSq() === 0) return d.value.slice();
        const inverse = new THREE.Quaternion().setFromUnitVectors(from, to.normalize()).multiply(rotationOf(d.value).invert());
        return rotationLiteral(inverse.invert(), d.value.length === 4 ? 4 : 3);
      } });
    // The -pos knob stands off the point looked at along the view's up (so
    // that it is not under the centre's ball when -pos is zero); dragging
    // it moves the point looked at as much.
    const upward = () => new THREE.Vector3(0, spoke(), 0).applyQuaternion(q().invert());
    const pos = add({ kind: 'view', element, param: 'pos', ...this.viewOption(element, 'pos', expressions),
      anchor: looked,
      where: () => looked().add(upward()),
      valueFrom: (w) => {
        const v = w.clone().sub(upward()).sub(c()).applyQuaternion(q()).negate();
        return [v.x, v.y, v.z].map((k) => round(k));
      } });
    const rightward = (k) => new THREE.Vector3(spoke() * k, 0, 0).applyQuaternion(q().invert());
    const scale = add({ kind: 'view', element, param: 'scale', ...this.viewOption(element, 'scale', expressions, { counts: [1], fallback: [round(scaleAt(cameraAt()))] }),
      anchor: looked,
      where: () => looked().add(rightward(scale.value ? scale.value[0] : scaleAt(cameraAt()))),
      valueFrom: (w, d) => [round(Math.max(0.01, w.clone().sub(d.anchor).dot(rightward(1)) / (spoke() * spoke())))] });
    // Without -center (or with one that moves) the centre at the start is
    // where the core's camera puts it: the target plus Rᵀ pos; with -pos an
    // expression, the framing centre (a view's default).
    const c0 = expressions.has('pos') ? new THREE.Vector3(...(framing.center || [0, 0, 0])) : target.clone().add(p().applyQuaternion(q().invert()));
    const moving = ix.text(element, 'follow') ? `-follow ${ix.text(element, 'follow')} moves it`
      : ix.text(element, 'trajectory') ? `-trajectory ${ix.text(element, 'trajectory')} moves it` : '';
    const centreSpec = ix.vector(element, 'center', { fallback: [c0.x, c0.y, c0.z] });
    if (moving || !centreSpec.value) Object.assign(centreSpec, { editable: centreSpec.editable && !moving, reason: moving || centreSpec.reason, value: [c0.x, c0.y, c0.z] });
    const centre = add({ kind: 'view', element, param: 'center', ...centreSpec,
      where: c,
      valueFrom: (w, d) => d.value.map((v, k) => round(v + w.getComponent(k) - d.point.getComponent(k))) });
  }

  // {value, editable, reason} of a view's -pos, -rot or -scale: an
  // expression of time or state is read-only (the session's reason), with
  // no value of its own (the core's camera places its handle).
  viewOption(element, param, expressions, options) {
    const spec = this.index.vector(element, param, options);
    if (!expressions.has(param)) return spec;
    const p = this.index.get(element, param);
    return { value: null, editable: false, reason: (p && p.reason) || 'an expression of time or state' };
  }

  // The curve of a trajectory as drawn: through its handles, else the
  // core's samples (at the frame times); an arrow trajectory's through the
  // arrows' tips.
  pathPoints(line) {
    const handles = line.userData.knots, place = line.userData.place;
    if (handles.length) {
      const curve = new TrajectoryCurve(handles.map((h) => [h.t, ...h.value]));
      return curve.sampleTimes().map((t) => place(t, curve.value(t)).toArray());
    }
    const core = this.poses && (this.poses.trajectories || []).find((x) => x.name === line.userData.element);
    return core ? core.values.map((v, i) => place(this.poses.times[i], v).toArray()) : [];
  }

  bodyHandleOf(element, param) { return this.handles.find((h) => h.element === element && h.param === param) || {}; }

  // A force's or torque's evaluated vector at the shown frame (read-only
  // ones), when the core could evaluate it.
  forceAt(i) { return this.evaluatedAt('forces', i); }
  torqueAt(i) { return this.evaluatedAt('torques', i); }
  evaluatedAt(list, i) {
    const f = this.poses && this.poses[list] && this.poses[list][this.frame];
    return f && f[i] ? f[i] : null;
  }

  // A link end or force offset dragged: held on the body's surface (the
  // nearest hit under the pointer; it stays where it was while the pointer
  // is off the body) unless Shift is held, then in the screen plane.
  onSurface(body, p, d, ev) {
    const b = this.bodies.get(body);
    let world = p;
    let mesh = null;
    if (!ev.shiftKey) {
      const hit = this.raycaster.intersectObjects(b.meshes, false)[0];
      world = hit ? hit.point : d.last || d.point;
      mesh = hit ? hit.object : d.lastMesh || null;
    }
    d.last = world.clone();
    d.lastMesh = mesh;
    return this.localPoint(b, world, mesh);
  }

  // A world point in a body's shape coordinates (rounded), on the true
  // surface when `mesh` is one of its spheres.
  localPoint(b, world, mesh) {
    const local = world.clone().sub(b.group.position).applyQuaternion(b.group.quaternion.clone().invert());
    const sphere = mesh && mesh.userData.sphere;
    if (sphere) {
      const r = local.clone().sub(sphere.center);
      if (r.lengthSq() > 0) local.copy(sphere.center).add(r.setLength(sphere.radius));
    }
    local.add(b.centroid);
    return [local.x, local.y, local.z].map((v) => round(v));
  }

  // Places the handles (`timed`: only those that move with the shown time —
  // forces, torques, offsets and link ends on moving bodies, views — when
  // nothing else changed since all were placed) and the lines between them.
  placeHandles(timed = false) {
    for (const h of this.handles) if (!timed || TIMED.has(h.kind)) h.place();
    if (!timed)
      for (const line of this.paths.children)
        line.geometry.setFromPoints(this.pathPoints(line).map((v) => new THREE.Vector3(...v)));
    for (const line of this.linkLines.children) {
      const [a, c] = line.userData.ends.map((h) => h.mesh.visible && h.mesh.position);
      line.visible = !!(a && c);
      if (line.visible) line.geometry.setFromPoints([a, c]);
    }
  }

  // Arrow scales: the longest of each kind reaches a quarter of the scene.
  updateScales() {
    const longest = { velocity: 0, angvel: 0, force: 0, torque: 0 };
    const ix = this.index;
    for (const name of this.bodies.keys()) {
      const v = numbers(ix.text(name, 'init_dpos')), w = numbers(ix.text(name, 'init_drot'));
      if (v) longest.velocity = Math.max(longest.velocity, Math.hypot(...v));
      if (w) longest.angvel = Math.max(longest.angvel, Math.hypot(...w));
    }
    const forced = this.forceTrajectories();
    for (const element of ix.ofKind('trajectory')) {
      const kind = forced.has(element) ? 'force' : TRAJECTORY_ARROWS[ix.text(element, 'state', 'pos')], p = ix.get(element, 'points');
      const knots = kind && p ? parseKnots(p.value) : null;
      for (const k of knots || []) longest[kind] = Math.max(longest[kind], Math.hypot(k[1], k[2], k[3]));
    }
    for (const frame of (this.poses.forces || []).slice(0, 1))
      for (const f of frame) if (f) longest.force = Math.max(longest.force, Math.hypot(...f));
    for (const kind of ['force', 'torque'])
      for (const element of ix.ofKind(kind)) {
        const v = ix.literal(element, ['x', 'y', 'z'], [1]);
        if (v) longest[kind] = Math.max(longest[kind], Math.hypot(...v));
      }
    for (const k of Object.keys(longest)) this.scales[k] = (this.radius * 0.25) / (longest[k] > 0 ? longest[k] : 1);
  }

  // --- display ------------------------------------------------------------

  setStyle(style) {
    this.style = style;
    this.applyStyle();
    this.draw();
  }

  applyStyle() {
    const lines = this.style === 'lines';
    for (const b of this.bodies.values()) {
      for (const m of b.meshes) m.visible = !lines;
      for (const e of b.edges) {
        // Shaded: a hull's creases in grey over its faces; lines: every
        // piece in its own colour (a sphere as its wireframe).
        e.visible = lines || !e.userData.sphere;
        e.material.color.set(lines ? e.userData.color : 0x333333);
      }
    }
  }

  setShown(kind, on) {
    this.shown[kind] = on;
    this.applyVisibility();
    this.draw();
    if (this.ui.knots) this.ui.knots();
  }

  applyVisibility() {
    for (const b of this.bodies.values()) b.group.visible = this.shown.bodies;
    for (const h of this.handles) h.object.visible = this.shown[GROUPS[h.kind]];
    this.linkLines.visible = this.shown.links;
    this.paths.visible = this.shown.trajectories;
  }

  // Whether a body's starting position is outside the picture (after an
  // edit moved it there): then the viewer frames the scene again.
  startsOutOfView() {
    const f = this.poses.poses[0];
    for (const b of this.bodies.values()) {
      if (b.index < 0) continue;
      const v = new THREE.Vector3(f[7 * b.index], f[7 * b.index + 1], f[7 * b.index + 2]).project(this.camera);
      if (Math.abs(v.x) > 0.95 || Math.abs(v.y) > 0.95 || v.z > 1) return true;
    }
    return false;
  }

  fit() {
    const f = this.poses.poses[0];
    const box = new THREE.Box3();
    for (const b of this.bodies.values()) {
      if (b.index < 0) continue;
      b.group.position.set(f[7 * b.index], f[7 * b.index + 1], f[7 * b.index + 2]);
      b.group.quaternion.set(f[7 * b.index + 3], f[7 * b.index + 4], f[7 * b.index + 5], f[7 * b.index + 6]);
      b.group.updateMatrixWorld(true);
      box.expandByObject(b.group);
    }
    // Shown trajectories are framed too.
    if (this.shown.trajectories)
      for (const line of this.paths.children) for (const v of this.pathPoints(line)) box.expandByPoint(new THREE.Vector3(...v));
    const sphere = box.getBoundingSphere(new THREE.Sphere());
    const r = Math.max(sphere.radius, 1);
    this.radius = r;
    this.handleSize = r * 0.03;
    this.updateScales();
    this.controls.target.copy(sphere.center);
    // The framing sphere fits the narrower of the two fields of view.
    const half = (this.camera.fov * Math.PI) / 360;
    const halfX = Math.atan(Math.tan(half) * this.camera.aspect);
    const d = (r / Math.sin(Math.min(half, halfX))) * 1.05;
    if (this.viewName) this.setView('');
    this.camera.up.set(0, 1, 0);
    this.camera.position.copy(sphere.center).add(new THREE.Vector3(0.35, 0.25, 1).normalize().multiplyScalar(d));
    this.camera.near = d / 100;
    this.camera.far = d * 10;
    this.camera.updateProjectionMatrix();
    this.controls.update();
    this.fitted = true;
    this.resetHandles();  // new sizes and arrow scales
  }

  // Interpolated poses at time t (Hermite from the streamed velocities,
  // else linear positions and slerped rotations).  `frame`: a frame of
  // playback (or of the document's clock), which draws at once and moves
  // only what time moves (the handles placed by the bodies' motion, the
  // views' cameras); any other call places every handle and asks for a draw.
  seek(t, frame = false) {
    if (!this.poses) return;
    const { times, poses } = this.poses;
    t = Math.min(Math.max(t, times[0]), times[times.length - 1]);
    this.t = t;
    // The frame before t: from the last one when playing forward.
    let i = this.seekFrame && this.seekFrame < times.length - 1 && times[this.seekFrame] <= t ? this.seekFrame : 0;
    while (i + 1 < times.length - 1 && times[i + 1] <= t) ++i;
    this.seekFrame = i;
    const j = Math.min(i + 1, times.length - 1);
    const s = j > i && times[j] > times[i] ? (t - times[i]) / (times[j] - times[i]) : 0;
    this.frame = s > 0.5 ? j : i;
    for (const b of this.bodies.values()) if (b.index >= 0) this.poseBetween(b, i, j, s, b.group);
    if (this.viewName) this.placeViewCamera(i, j, s);
    // While a body's handle is dragged the body sits at its new start.
    if (this.dragging && t === times[0] && this.bodies.has(this.dragging.element)) {
      const b = this.bodies.get(this.dragging.element), start = this.start(this.dragging.element);
      b.group.position.copy(start.p);
      b.group.quaternion.copy(start.q);
    }
    this.placeHandles(frame);
    this.placeSelection();
    const slider = String(this.frame), clock = `t = ${t.toFixed(2)}`;
    if (this.ui.slider.value !== slider) this.ui.slider.value = slider;
    if (this.ui.clock.textContent !== clock) this.ui.clock.textContent = clock;
    if (this.ui.time) this.ui.time(t);
    if (frame) this.render(); else this.draw();
  }

  // Body b's pose at fraction s from frame i to frame j, set on `object`:
  // Hermite from the streamed velocities, else linear and slerp.
  poseBetween(b, i, j, s, object) {
    const { times, poses, velocities: vel } = this.poses;
    const a = poses[i], c = poses[j], k = 7 * b.index;
    if (vel && j > i) {
      hermitePose(a, vel[i], c, vel[j], times[j] - times[i], s, object, k, 6 * b.index);
      return;
    }
    const qa = this.qa || (this.qa = new THREE.Quaternion()), qb = this.qb || (this.qb = new THREE.Quaternion());
    object.position.set(a[k] + s * (c[k] - a[k]), a[k + 1] + s * (c[k + 1] - a[k + 1]), a[k + 2] + s * (c[k + 2] - a[k + 2]));
    qa.set(a[k + 3], a[k + 4], a[k + 5], a[k + 6]);
    qb.set(c[k + 3], c[k + 4], c[k + 5], c[k + 6]);
    object.quaternion.slerpQuaternions(qa, qb, s);
  }

  play() {
    if (!this.poses) return;
    this.playing = !this.playing;
    this.ui.play.textContent = this.playing ? 'Pause' : 'Play';
    if (!this.playing) return;
    const times = this.poses.times;
    if (this.t >= times[times.length - 1]) this.t = times[0];
    let last = performance.now();
    const step = (now) => {
      if (!this.playing) return;
      const t = this.t + (now - last) / 1000;
      last = now;
      if (t >= times[times.length - 1]) {
        this.seek(times[times.length - 1], true);
        this.play();
        return;
      }
      this.seek(t, true);
      requestAnimationFrame(step);
    };
    requestAnimationFrame(step);
  }

  // Asks for a draw at the next animation frame: the changes of one event
  // (a drag step, a message) are drawn once, after the edit has been sent.
  draw() {
    if (this.drawRequest) return;
    this.drawRequest = requestAnimationFrame(() => {
      this.drawRequest = 0;
      this.render();
    });
  }

  // Draws now (a frame of playback, a picture to export).
  render() {
    if (this.drawRequest) {
      cancelAnimationFrame(this.drawRequest);
      this.drawRequest = 0;
    }
    this.scene.updateMatrixWorld();
    this.handleBatch.update();
    this.renderer.render(this.scene, this.camera);
    this.placeKnotTimes();
  }

  // Each shown trajectory control point's time as a label at its upper
  // right, placed at every draw (HTML over the canvas, so the text is crisp
  // at any zoom and costs no texture).  Points behind the camera or off the
  // canvas have none.
  placeKnotTimes() {
    const layer = this.knotLayer;
    if (!layer) return;
    const knots = this.handles.filter((h) => h.kind === 'knot' && h.object.visible && h.mesh.visible);
    while (layer.children.length < knots.length) {
      const d = document.createElement('div');
      d.className = 'point-time';
      layer.appendChild(d);
    }
    const w = this.canvas.clientWidth, height = this.canvas.clientHeight;
    [...layer.children].forEach((d, i) => {
      const h = knots[i];
      const p = h ? h.mesh.position.clone().project(this.camera) : null;
      const on = !!p && p.z < 1 && Math.abs(p.x) <= 1 && Math.abs(p.y) <= 1;
      if (on) {
        const text = `t = ${h.t}`;
        if (d.textContent !== text) d.textContent = text;
        d.dataset.id = h.id;
        d.classList.toggle('read-only', !h.editable);
        d.style.left = `${this.canvas.offsetLeft + ((p.x + 1) / 2) * w + 7}px`;
        d.style.top = `${this.canvas.offsetTop + ((1 - p.y) / 2) * height - 20}px`;
      }
      d.style.display = on ? 'block' : 'none';
    });
  }

  // The world matrices as the next draw will have them (a seek or a camera
  // move draws at the next animation frame; a pick may come before it).
  syncMatrices() {
    this.scene.updateMatrixWorld();
    this.camera.updateMatrixWorld();
  }

  pointer(ev) {
    this.syncMatrices();
    const r = this.canvas.getBoundingClientRect();
    return new THREE.Vector2(((ev.clientX - r.left) / r.width) * 2 - 1, -((ev.clientY - r.top) / r.height) * 2 + 1);
  }

  // The handle under the pointer: the nearest, and of coincident ones the
  // kind that matters most (a body's position before its velocity).
  pick(ev) {
    this.raycaster.setFromCamera(this.pointer(ev), this.camera);
    const meshes = this.handles.filter((h) => h.object.visible && h.mesh.visible).map((h) => h.mesh);
    const hits = this.raycaster.intersectObjects(meshes, false);
    if (!hits.length) return null;
    const near = hits.filter((x) => x.distance < hits[0].distance + this.handleSize * 2);
    near.sort((x, y) => x.object.userData.handle.priority() - y.object.userData.handle.priority());
    return near[0].object.userData.handle;
  }

  describe(h) {
    return h.editable ? `${h.label()} ${h.valueText()}${h.note || ''}` : `${h.label()} is read-only: ${h.reason}`;
  }

  setupEvents() {
    this.ui.slider.addEventListener('input', () => {
      if (!this.poses) return;
      this.seek(this.poses.times[Number(this.ui.slider.value)] ?? 0);
    });
    this.ui.play.addEventListener('click', () => this.play());
    this.canvas.addEventListener('pointerdown', (ev) => {
      this.downAt = { x: ev.clientX, y: ev.clientY };
      // While a creation waits for clicks on bodies, handles are not picked.
      const h = this.mode ? null : this.pick(ev);
      if (!h) return;
      if (this.bodies.has(h.element)) this.select(h.element);
      else this.selectElement(h.element);
      if (!h.editable || !h.value) { this.showLabel(this.describe(h)); return; }
      ev.preventDefault();
      this.controls.enabled = false;
      this.canvas.setPointerCapture(ev.pointerId);
      if (this.playing) this.play();
      this.dragging = h;
      this.lastDrag = null;
      this.seek(this.poses.times[0]);
      const point = h.mesh.position.clone();
      this.dragStart = { point, value: h.value.slice(), anchor: h.anchor ? h.anchor() : null };
      const normal = this.camera.getWorldDirection(new THREE.Vector3());
      this.plane = new THREE.Plane().setFromNormalAndCoplanarPoint(normal, point);
      this.raycaster.setFromCamera(this.pointer(ev), this.camera);
      this.grab = this.raycaster.ray.intersectPlane(this.plane, new THREE.Vector3());
      this.showLabel(this.describe(h));
    });
    this.canvas.addEventListener('pointermove', (ev) => {
      if (!this.dragging && this.mode) {
        // Waiting for clicks on bodies: the body under the pointer, not handles.
        const b = this.pickBody(ev);
        this.showLabel(b ? `${b.name} {${b.local.join(' ')}}` : '');
        return;
      }
      if (!this.dragging) {
        const h = this.pick(ev);
        this.canvas.style.cursor = h ? (h.editable ? 'grab' : 'not-allowed') : '';
        this.showLabel(h ? this.describe(h) : '');
        return;
      }
      this.dragTo(ev);
    });
    const end = async (ev) => {
      if (!this.dragging) {
        const d = this.downAt;
        this.downAt = null;
        if (ev.type === 'pointerup' && d && Math.hypot(ev.clientX - d.x, ev.clientY - d.y) < 5) this.click(ev);
        return;
      }
      const h = this.dragging;
      this.dragging = null;
      this.controls.enabled = true;
      try { this.canvas.releasePointerCapture(ev.pointerId); } catch { /* released */ }
      // The newest value leaves now and the re-simulation right after it
      // (the server answers one view's requests in order).
      const sent = this.flushDrag(h);
      this.ui.dragEnd();
      await sent;
      if (this.resetPending) this.resetHandles();
      this.showLabel('');
    };
    this.canvas.addEventListener('pointerup', end);
    this.canvas.addEventListener('pointercancel', end);
    window.addEventListener('keydown', (ev) => {
      if (ev.key === 'Escape' && this.mode) this.cancelPick();
      // While dragging (seed 4.1.3): z pushes the handle away from the
      // viewer, x pulls it nearer, by a twentieth of the scene's radius.
      if (this.dragging && this.lastDrag && (ev.key === 'z' || ev.key === 'x')) {
        ev.preventDefault();
        this.pushDepth((ev.key === 'z' ? 1 : -1) * this.depthStep());
      }
    });
  }

  depthStep() { return this.radius / 20; }

  // The dragged handle at the pointer of `ev`: the point of the drag plane
  // under it, moved as the grab point was.
  dragTo(ev) {
    this.lastDrag = { clientX: ev.clientX, clientY: ev.clientY, shiftKey: ev.shiftKey };
    this.raycaster.setFromCamera(this.pointer(ev), this.camera);
    const p = this.raycaster.ray.intersectPlane(this.plane, new THREE.Vector3());
    if (!p || !this.grab) return;
    const h = this.dragging;
    const at = this.dragStart.point.clone().add(p.sub(this.grab));
    h.value = h.valueFrom(at, this.dragStart, this.lastDrag);
    // The edit leaves before anything is redrawn (the draw waits for the
    // next animation frame).
    this.sendDrag(h);
    this.seek(this.poses.times[0]);
    this.showLabel(this.describe(h));
  }

  // Moves the drag plane by `depth` along the view direction: the handle
  // (the plane's point under the pointer, offset as when it was grabbed)
  // goes that much deeper and stays under the pointer.
  pushDepth(depth) {
    this.plane.constant -= depth;
    this.dragTo(this.lastDrag);
  }

  // --- selection and clicks for creating elements (seed 4.1) ---------------

  // Whether a click may pick body b: one that moves and is drawn.
  pickable(b) { return b.index >= 0 && b.group.visible; }

  // The body under the pointer: {name, world, local (shape coordinates)}.
  pickBody(ev) {
    this.raycaster.setFromCamera(this.pointer(ev), this.camera);
    const meshes = [];
    for (const b of this.bodies.values()) if (this.pickable(b)) meshes.push(...b.meshes);
    const hit = this.raycaster.intersectObjects(meshes, false)[0];
    if (!hit) return null;
    const name = hit.object.parent.name, b = this.bodies.get(name);
    return { name, world: hit.point.clone(), local: this.localPoint(b, hit.point, hit.object) };
  }

  // A click (press and release without moving): a pick for the waiting
  // creation, else the body under it becomes the selection.
  click(ev) {
    const hit = this.pickBody(ev);
    if (!this.mode) { this.select(hit ? hit.name : null); return; }
    const m = this.mode;
    const trajectory = !hit && m.trajectory && m.picks.length ? this.pickTrajectory(ev) : null;
    if (m.space) {
      // A point in space, bodies or not.
      const p = this.pointInPlane(ev, m.space);
      if (!p) return;
      m.picks.push({ name: null, world: p, local: null, point: p.toArray() });
    } else if (hit) m.picks.push(hit);
    else if (trajectory) m.picks.push({ name: null, trajectory });
    else if (m.point && m.picks.length) {
      // Off every body: a point in the plane through the view's centre.
      const p = this.pointInPlane(ev, this.controls.target);
      if (!p) return;
      m.picks.push({ name: null, world: p, local: null, point: [p.x, p.y, p.z].map((v) => round(v)) });
    } else return;
    if (m.picks.length < m.count) { this.ui.prompt(m.prompts[m.picks.length]); return; }
    this.cancelPick();
    m.done(m.picks);
  }

  // Where the pointer's ray meets the plane through `through` facing the
  // camera, or null.
  pointInPlane(ev, through) {
    this.raycaster.setFromCamera(this.pointer(ev), this.camera);
    const plane = new THREE.Plane().setFromNormalAndCoplanarPoint(this.camera.getWorldDirection(new THREE.Vector3()), through);
    return this.raycaster.ray.intersectPlane(plane, new THREE.Vector3());
  }

  // The trajectory under the pointer (one of its control points, else its
  // drawn curve, within a handle's size), while trajectories are shown.
  pickTrajectory(ev) {
    if (!this.paths.visible) return null;
    const h = this.pick(ev);
    if (h && h.kind === 'knot') return h.element;
    this.raycaster.setFromCamera(this.pointer(ev), this.camera);
    this.raycaster.params.Line.threshold = this.handleSize;
    const hit = this.raycaster.intersectObjects(this.paths.children, false)[0];
    return hit ? hit.object.userData.element : null;
  }

  // Waits for `count` clicks on bodies (with `point`, the last may be off
  // every body: a point in space; with `trajectory`, on a trajectory shown;
  // with `space`, a point, every click, in the plane through that point
  // facing the camera); `prompts[i]` asks for the i-th.
  startPick({ count, prompts, point = false, trajectory = false, space = null, done }) {
    this.mode = { count, prompts, point, trajectory, space, done, picks: [] };
    this.canvas.style.cursor = 'crosshair';
    this.ui.prompt(prompts[0]);
  }

  cancelPick() {
    this.mode = null;
    this.canvas.style.cursor = '';
    this.ui.prompt('');
    this.showLabel('');
  }

  // A handle's element (a force, torque, link, light or trajectory) picked:
  // the one Delete removes; the selected body stays.
  selectElement(element) {
    this.selectedElement = element;
    if (this.ui.selected) this.ui.selected(this.selected, element);
  }

  select(name) {
    this.selected = name && this.bodies.has(name) ? name : null;
    this.selectedElement = this.selected;
    this.placeSelection();
    this.draw();
    if (this.ui.selected) this.ui.selected(this.selected, this.selectedElement);
  }

  placeSelection() {
    const b = this.selected && this.bodies.get(this.selected);
    this.selectionBox.visible = !!b;
    if (b) this.selectionBox.setFromObject(b.group);
  }

  // The view's centre of rotation (where a new body is placed).
  viewCentre() { return this.controls.target.toArray().map((v) => round(v)); }

  // The trajectory panel changed `element`'s knots (their handles hold the
  // new times and values): redraw, and send the list like a drag.
  knotsEdited(element) {
    this.panelDrag = element;
    this.placeHandles();
    this.draw();
    const line = this.paths.children.find((l) => l.userData.element === element);
    if (line && line.userData.knots.length) this.sendDrag(line.userData.knots[0]);
  }

  // One edit in flight at a time; the latest value wins.
  sendDrag(h) {
    const values = h.payload ? h.payload() : h.value.slice();
    this.latest = { h, values };
    if (!this.inFlight) {
      this.latest = null;
      this.inFlight = this.ui.drag(h.element, h.param, values).catch((e) => this.showLabel(String(e.message || e))).then(() => {
        this.inFlight = null;
        if (this.latest) this.sendDrag(this.latest.h);
      });
    }
    // This tab's language viewers show the value now (after it has left).
    if (this.ui.preview) this.ui.preview(h.element, h.param, values);
  }

  // Sends the newest value now, without waiting for the one in flight (the
  // server takes them in order), and waits for both answers.
  async flushDrag() {
    const before = this.inFlight;
    if (this.latest) {
      const { h, values } = this.latest;
      this.latest = null;
      const last = this.ui.drag(h.element, h.param, values).catch((e) => this.showLabel(String(e.message || e)));
      await before;
      await last;
    }
    while (this.inFlight) await this.inFlight;
  }

  showLabel(text) {
    this.ui.label.textContent = text;
    this.ui.label.style.display = text ? 'block' : 'none';
  }

  // Test and tool hooks.
  bodyNames() { return [...this.bodies.keys()]; }
  toScreen(v) {
    this.camera.updateMatrixWorld();
    const p = v.clone().project(this.camera);
    const r = this.canvas.getBoundingClientRect();
    return { x: r.left + ((p.x + 1) / 2) * r.width, y: r.top + ((1 - p.y) / 2) * r.height };
  }
  // A body's point (shape coordinates; default its centre of mass) on the screen.
  bodyScreenPos(name, local) {
    const b = this.bodies.get(name);
    if (!b) return null;
    return this.toScreen(local ? this.onBody(name, local) : b.group.position.clone());
  }
  // Each trajectory's curve as drawn: {element: [[x y z] ...]}, and the
  // drawn curve's value at time t.
  trajectoryPaths() {
    return Object.fromEntries(this.paths.children.map((l) => [l.userData.element, this.pathPoints(l)]));
  }
  trajectoryValue(element, t) {
    const line = this.paths.children.find((l) => l.userData.element === element);
    return line && line.userData.knots.length ? new TrajectoryCurve(line.userData.knots.map((h) => [h.t, ...h.value])).value(t) : null;
  }
  handleScreenPos(name) {
    const h = this.bodyHandle(name, 'init_pos');
    return h ? this.toScreen(h.mesh.position) : null;
  }
  // Every handle: {id, kind, element, param, value, editable, reason, shown, x, y}.
  handleList() {
    return this.handles.map((h) => ({
      id: h.id, kind: h.kind, element: h.element, param: h.param, value: h.value, editable: h.editable,
      reason: h.reason, shown: h.object.visible && h.mesh.visible, arrow: !!(h.arrow && h.arrow.visible), world: h.mesh.position.toArray(),
      ...this.toScreen(h.mesh.position),
    }));
  }
  bodyPosition(name, frame = 0) {
    const b = this.bodies.get(name);
    if (!b || !this.poses) return null;
    const f = this.poses.poses[frame], k = 7 * b.index;
    return [f[k], f[k + 1], f[k + 2]];
  }
  bodyQuaternion(name, frame = 0) {
    const b = this.bodies.get(name);
    if (!b || !this.poses) return null;
    const f = this.poses.poses[frame], k = 7 * b.index;
    return [f[k + 3], f[k + 4], f[k + 5], f[k + 6]];
  }
}
