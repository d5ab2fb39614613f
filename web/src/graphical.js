// The graphical viewer (seed 4.1): the bodies' meshes drawn by three.js from
// poses streamed once per simulation, so playback, the time slider, rotation
// and zoom need no server round trip.  Handles (seed 4.2.3): each body's
// initial position, drawn where the body starts; dragging one changes the
// `-init_pos` literal through the session while dragging, and re-simulates on
// release.  A read-only value's handle is grey and says why on hover.
import * as THREE from 'three';
import { OrbitControls } from 'three/examples/jsm/controls/OrbitControls.js';

const round = (v) => Math.round(v * 1000) / 1000;

export class GraphicalViewer {
  constructor(canvas, ui) {
    this.canvas = canvas;
    this.ui = ui;
    this.renderer = new THREE.WebGLRenderer({ canvas, antialias: true, preserveDrawingBuffer: true });
    this.renderer.setPixelRatio(window.devicePixelRatio || 1);
    this.scene = new THREE.Scene();
    this.scene.background = new THREE.Color(0xffffff);
    this.camera = new THREE.PerspectiveCamera(35, 1, 0.1, 1000);
    this.camera.position.set(0, 0, 60);
    this.controls = new OrbitControls(this.camera, canvas);  // rotate, zoom, pan
    this.controls.addEventListener('change', () => this.draw());
    this.scene.add(new THREE.HemisphereLight(0xffffff, 0x666666, 1.6));
    const sun = new THREE.DirectionalLight(0xffffff, 1.4);
    sun.position.set(30, 50, 40);
    this.scene.add(sun);
    this.bodies = new Map();   // name → {group, index, static}
    this.handles = new Map();  // name → {mesh, value, baseValue, basePos, editable, reason}
    this.handleGroup = new THREE.Group();
    this.scene.add(this.handleGroup);
    this.parameters = [];
    this.poses = null;
    this.t = 0;
    this.playing = false;
    this.fitted = false;
    this.raycaster = new THREE.Raycaster();
    this.setupEvents();
    new ResizeObserver(() => this.resize()).observe(canvas);
    this.resize();
  }

  resize() {
    const w = this.canvas.clientWidth || 400, h = this.canvas.clientHeight || 300;
    this.renderer.setSize(w, h, false);
    this.camera.aspect = w / h;
    this.camera.updateProjectionMatrix();
    this.draw();
  }

  // meshes: {bodies: [{name, static, pieces}]}; poses: {times, bodies, poses}.
  setScene(meshes, poses) {
    for (const b of this.bodies.values()) this.scene.remove(b.group);
    this.bodies.clear();
    meshes.bodies.forEach((b) => {
      const group = new THREE.Group();
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
        group.add(mesh);
        const edges = new THREE.LineSegments(new THREE.EdgesGeometry(geometry, 20),
          new THREE.LineBasicMaterial({ color: 0x333333 }));
        group.add(edges);
      }
      group.name = b.name;
      this.scene.add(group);
      this.bodies.set(b.name, { group, index: poses.bodies.indexOf(b.name), static: b.static });
    });
    this.poses = poses;
    this.ui.slider.max = String(Math.max(1, poses.times.length - 1));
    if (!this.fitted || this.startsOutOfView()) this.fit();
    this.resetHandles();
    this.seek(Math.min(this.t, poses.t1));
  }

  // The session's parameters: which initial positions are editable.
  setParameters(parameters) {
    this.parameters = parameters;
    this.resetHandles();
    this.draw();
  }

  parameterEdited(element, param, values) {
    if (param !== 'init_pos') return;
    const h = this.handles.get(element);
    if (!h || this.dragging === h) return;
    h.value = values.slice();
    this.placeHandle(h);
    this.draw();
  }

  resetHandles() {
    if (!this.poses) return;
    this.handleGroup.clear();
    this.handles.clear();
    for (const [name, b] of this.bodies) {
      if (b.static || b.index < 0) continue;
      const p = this.parameters.find((q) => q.element === name && q.param === 'init_pos');
      const value = p ? p.value.trim().split(/\s+/).map(Number) : null;
      const editable = !!(p && p.editable && value && value.length === 3 && value.every(Number.isFinite));
      const mesh = new THREE.Mesh(new THREE.OctahedronGeometry(this.handleSize),
        new THREE.MeshBasicMaterial({ color: editable ? 0xffa000 : 0x999999, depthTest: false,
          transparent: true, opacity: 0.55 }));
      mesh.renderOrder = 10;
      const f = this.poses.poses[0];
      const basePos = new THREE.Vector3(f[7 * b.index], f[7 * b.index + 1], f[7 * b.index + 2]);
      const h = {
        name, mesh, editable, value: editable ? value : null, baseValue: editable ? value.slice() : null,
        basePos, reason: p ? (p.reason || '') : 'no -init_pos option',
      };
      mesh.userData.handle = h;
      this.handleGroup.add(mesh);
      this.handles.set(name, h);
      this.placeHandle(h);
    }
  }

  placeHandle(h) {
    h.mesh.position.copy(h.basePos);
    if (h.value && h.baseValue)
      h.mesh.position.add(new THREE.Vector3(h.value[0] - h.baseValue[0], h.value[1] - h.baseValue[1], h.value[2] - h.baseValue[2]));
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
    const sphere = box.getBoundingSphere(new THREE.Sphere());
    const r = Math.max(sphere.radius, 1);
    this.handleSize = r * 0.035;
    this.controls.target.copy(sphere.center);
    // The framing sphere fits the narrower of the two fields of view.
    const half = (this.camera.fov * Math.PI) / 360;
    const halfX = Math.atan(Math.tan(half) * this.camera.aspect);
    const d = (r / Math.sin(Math.min(half, halfX))) * 1.05;
    this.camera.position.copy(sphere.center).add(new THREE.Vector3(0.35, 0.25, 1).normalize().multiplyScalar(d));
    this.camera.near = d / 100;
    this.camera.far = d * 10;
    this.camera.updateProjectionMatrix();
    this.controls.update();
    this.fitted = true;
  }

  // Interpolated poses at time t (linear positions, slerped rotations).
  seek(t) {
    if (!this.poses) return;
    const { times, poses } = this.poses;
    t = Math.min(Math.max(t, times[0]), times[times.length - 1]);
    this.t = t;
    let i = 0;
    while (i + 1 < times.length - 1 && times[i + 1] <= t) ++i;
    const j = Math.min(i + 1, times.length - 1);
    const s = j > i && times[j] > times[i] ? (t - times[i]) / (times[j] - times[i]) : 0;
    const qa = new THREE.Quaternion(), qb = new THREE.Quaternion();
    for (const b of this.bodies.values()) {
      if (b.index < 0) continue;
      const a = poses[i], c = poses[j], k = 7 * b.index;
      b.group.position.set(a[k] + s * (c[k] - a[k]), a[k + 1] + s * (c[k + 1] - a[k + 1]), a[k + 2] + s * (c[k + 2] - a[k + 2]));
      qa.set(a[k + 3], a[k + 4], a[k + 5], a[k + 6]);
      qb.set(c[k + 3], c[k + 4], c[k + 5], c[k + 6]);
      b.group.quaternion.slerpQuaternions(qa, qb, s);
    }
    // While a handle is dragged the body sits at its new initial position.
    if (this.dragging && t === times[0]) {
      const b = this.bodies.get(this.dragging.name);
      if (b) b.group.position.copy(this.dragging.mesh.position);
    }
    this.ui.slider.value = String(i + (s > 0.5 ? 1 : 0));
    this.ui.clock.textContent = `t = ${t.toFixed(2)}`;
    this.draw();
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
        this.seek(times[times.length - 1]);
        this.play();
        return;
      }
      this.seek(t);
      requestAnimationFrame(step);
    };
    requestAnimationFrame(step);
  }

  draw() { this.renderer.render(this.scene, this.camera); }

  pointer(ev) {
    const r = this.canvas.getBoundingClientRect();
    return new THREE.Vector2(((ev.clientX - r.left) / r.width) * 2 - 1, -((ev.clientY - r.top) / r.height) * 2 + 1);
  }

  pick(ev) {
    this.raycaster.setFromCamera(this.pointer(ev), this.camera);
    const hit = this.raycaster.intersectObjects(this.handleGroup.children, false)[0];
    return hit ? hit.object.userData.handle : null;
  }

  setupEvents() {
    this.ui.slider.addEventListener('input', () => {
      if (!this.poses) return;
      this.seek(this.poses.times[Number(this.ui.slider.value)] ?? 0);
    });
    this.ui.play.addEventListener('click', () => this.play());
    this.canvas.addEventListener('pointerdown', (ev) => {
      const h = this.pick(ev);
      if (!h) return;
      if (!h.editable) { this.showLabel(`${h.name}.init_pos is read-only: ${h.reason}`); return; }
      ev.preventDefault();
      this.controls.enabled = false;
      this.canvas.setPointerCapture(ev.pointerId);
      this.dragging = h;
      this.dragStart = { point: h.mesh.position.clone(), value: h.value.slice() };
      const normal = this.camera.getWorldDirection(new THREE.Vector3());
      this.plane = new THREE.Plane().setFromNormalAndCoplanarPoint(normal, h.mesh.position);
      this.grab = null;
      this.raycaster.setFromCamera(this.pointer(ev), this.camera);
      this.grab = this.raycaster.ray.intersectPlane(this.plane, new THREE.Vector3());
      if (this.playing) this.play();
      this.seek(this.poses.times[0]);
    });
    this.canvas.addEventListener('pointermove', (ev) => {
      if (!this.dragging) {
        const h = this.pick(ev);
        this.canvas.style.cursor = h ? (h.editable ? 'grab' : 'not-allowed') : '';
        if (h && !h.editable) this.showLabel(`${h.name}.init_pos is read-only: ${h.reason}`);
        else if (!h) this.showLabel('');
        return;
      }
      this.raycaster.setFromCamera(this.pointer(ev), this.camera);
      const p = this.raycaster.ray.intersectPlane(this.plane, new THREE.Vector3());
      if (!p || !this.grab) return;
      const d = p.sub(this.grab);
      const h = this.dragging;
      h.value = this.dragStart.value.map((v, k) => round(v + d.getComponent(k)));
      this.placeHandle(h);
      this.seek(this.poses.times[0]);
      this.showLabel(`${h.name} -init_pos {${h.value.join(' ')}}`);
      this.sendDrag(h);
    });
    const end = async (ev) => {
      if (!this.dragging) return;
      const h = this.dragging;
      this.dragging = null;
      this.controls.enabled = true;
      try { this.canvas.releasePointerCapture(ev.pointerId); } catch { /* released */ }
      await this.flushDrag(h);
      this.showLabel('');
      this.ui.dragEnd();
    };
    this.canvas.addEventListener('pointerup', end);
    this.canvas.addEventListener('pointercancel', end);
  }

  // One edit in flight at a time; the latest value wins.
  sendDrag(h) {
    this.latest = h.value.slice();
    if (this.inFlight) return;
    const values = this.latest;
    this.latest = null;
    this.inFlight = this.ui.drag(h.name, 'init_pos', values).catch(() => {}).then(() => {
      this.inFlight = null;
      if (this.latest) this.sendDrag({ ...h, value: this.latest });
    });
  }

  async flushDrag(h) {
    while (this.inFlight) await this.inFlight;
    if (this.latest) { this.sendDrag({ ...h, value: this.latest }); while (this.inFlight) await this.inFlight; }
  }

  showLabel(text) {
    this.ui.label.textContent = text;
    this.ui.label.style.display = text ? 'block' : 'none';
  }

  // Test and tool hooks.
  bodyNames() { return [...this.bodies.keys()]; }
  handleScreenPos(name) {
    const h = this.handles.get(name);
    if (!h) return null;
    const v = h.mesh.position.clone().project(this.camera);
    const r = this.canvas.getBoundingClientRect();
    return { x: r.left + ((v.x + 1) / 2) * r.width, y: r.top + ((1 - v.y) / 2) * r.height };
  }
  bodyPosition(name, frame = 0) {
    const b = this.bodies.get(name);
    if (!b || !this.poses) return null;
    const f = this.poses.poses[frame], k = 7 * b.index;
    return [f[k], f[k + 1], f[k + 2]];
  }
}
