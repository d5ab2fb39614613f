// The graphical viewer's camera controls (seed 4.1.3): rotation with a
// virtual sphere (Chen, Mountford and Sellen 1988), translation, zoom and a
// settable centre of rotation.
//
//   left drag               rotate: the pointer drags a point of a sphere
//                           that fills 0.9 of the canvas's smaller side and
//                           is centred on it; outside the sphere the drag
//                           turns about the view axis
//   right drag, Ctrl+left   translate in the screen plane (the centre moves along)
//   wheel                   zoom toward the centre of rotation
//   double-click on a body  the point clicked becomes the centre of rotation
//
// The camera turns about `target`, which need not be on the line of sight
// (after a double-click the picture does not jump).  `onChange` is called
// whenever the camera moves.
import * as THREE from 'three';

// A canvas point (pixels from its top left) on the unit virtual sphere, in
// camera coordinates: inside the disc the sphere's front, outside it the
// rim (so motion there is a turn about the view axis).
export function spherePoint(x, y, width, height) {
  const r = 0.45 * Math.min(width, height);
  const v = new THREE.Vector3((x - width / 2) / r, (height / 2 - y) / r, 0);
  const d = v.x * v.x + v.y * v.y;
  if (d <= 1) v.z = Math.sqrt(1 - d);
  else v.divideScalar(Math.sqrt(d));
  return v;
}

// The rotation (camera coordinates) that carries the sphere point under
// (x0, y0) to the one under (x1, y1).
export function sphereRotation(x0, y0, x1, y1, width, height) {
  const a = spherePoint(x0, y0, width, height), b = spherePoint(x1, y1, width, height);
  return new THREE.Quaternion().setFromUnitVectors(a, b);
}

export class SphereControls {
  constructor(camera, canvas, { pickPoint } = {}) {
    this.camera = camera;
    this.canvas = canvas;
    this.target = new THREE.Vector3();  // the centre of rotation
    this.enabled = true;
    this.onChange = () => {};
    this.onStart = () => {};
    this.pickPoint = pickPoint;  // (ev) → a world point under the pointer, or null
    this.drag = null;
    canvas.addEventListener('pointerdown', (ev) => this.down(ev));
    canvas.addEventListener('pointermove', (ev) => this.move(ev));
    canvas.addEventListener('pointerup', (ev) => this.up(ev));
    canvas.addEventListener('pointercancel', (ev) => this.up(ev));
    canvas.addEventListener('wheel', (ev) => this.wheel(ev), { passive: false });
    canvas.addEventListener('dblclick', (ev) => this.centreAt(ev));
    canvas.addEventListener('contextmenu', (ev) => ev.preventDefault());
  }

  local(ev) {
    const r = this.canvas.getBoundingClientRect();
    return { x: ev.clientX - r.left, y: ev.clientY - r.top, width: r.width, height: r.height };
  }

  down(ev) {
    if (!this.enabled || this.drag) return;
    const pan = ev.button === 2 || (ev.button === 0 && ev.ctrlKey);
    if (ev.button !== 0 && !pan) return;
    this.drag = { pan, last: this.local(ev), id: ev.pointerId };
    this.onStart();
  }

  move(ev) {
    if (!this.drag || ev.pointerId !== this.drag.id) return;
    if (!this.enabled) { this.drag = null; return; }
    const p = this.local(ev), last = this.drag.last;
    this.drag.last = p;
    if (p.x === last.x && p.y === last.y) return;
    if (this.drag.pan) this.pan(p.x - last.x, p.y - last.y, p.height);
    else this.rotate(sphereRotation(last.x, last.y, p.x, p.y, p.width, p.height));
  }

  up(ev) { if (this.drag && ev.pointerId === this.drag.id) this.drag = null; }

  // The scene turns by `q` (camera coordinates) about the centre: the camera
  // turns by q⁻¹ about it.
  rotate(q) {
    const cam = this.camera;
    const world = cam.quaternion.clone().multiply(q.clone().invert()).multiply(cam.quaternion.clone().invert());
    cam.position.sub(this.target).applyQuaternion(world).add(this.target);
    cam.quaternion.premultiply(world).normalize();
    cam.updateMatrixWorld();
    this.onChange();
  }

  // Pixels dragged → scene units at the centre's depth, so the point under
  // the pointer there follows it.
  pan(dx, dy, height) {
    const cam = this.camera;
    const depth = this.target.clone().sub(cam.position).dot(cam.getWorldDirection(new THREE.Vector3()));
    const perPixel = (2 * Math.max(depth, 1e-6) * Math.tan((cam.fov * Math.PI) / 360)) / height;
    const right = new THREE.Vector3(1, 0, 0).applyQuaternion(cam.quaternion);
    const up = new THREE.Vector3(0, 1, 0).applyQuaternion(cam.quaternion);
    const move = right.multiplyScalar(-dx * perPixel).add(up.multiplyScalar(dy * perPixel));
    cam.position.add(move);
    this.target.add(move);
    cam.updateMatrixWorld();
    this.onChange();
  }

  // Zoom: the camera moves toward the centre by a factor per wheel notch.
  zoom(factor) {
    const cam = this.camera;
    cam.position.sub(this.target).multiplyScalar(factor).add(this.target);
    cam.updateMatrixWorld();
    this.onChange();
  }

  wheel(ev) {
    if (!this.enabled) return;
    ev.preventDefault();
    this.zoom(Math.pow(1.0015, Math.max(-300, Math.min(300, ev.deltaY))));
  }

  centreAt(ev) {
    if (!this.enabled || !this.pickPoint) return;
    const p = this.pickPoint(ev);
    if (p) this.setCentre(p);
  }

  setCentre(p) {
    this.target.copy(p);
    this.onChange();
  }

  // Looks at the centre from where the camera is (Fit, a chosen view).
  update() {
    this.camera.lookAt(this.target);
    this.camera.updateMatrixWorld();
    this.onChange();
  }
}
