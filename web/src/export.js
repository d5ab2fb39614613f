// Exports of the control panel (seed Figure 4.1), as downloads: the picture
// of the graphical viewer (PNG), the scene at the shown time as glTF 2.0
// (three.js's GLTFExporter: one node per body with its pose, its meshes,
// the buffers embedded as data URIs), and a movie made by the server with
// the core's own movie export (`asgard render` through ffmpeg), seen as the
// viewer shows the scene.
import * as THREE from 'three';
import { GLTFExporter } from 'three/examples/jsm/exporters/GLTFExporter.js';

// Saves `blob` (or a URL) as a download called `name`.
export function download(what, name) {
  const a = document.createElement('a');
  const url = typeof what === 'string' ? what : URL.createObjectURL(what);
  a.href = url;
  a.download = name;
  document.body.appendChild(a);
  a.click();
  a.remove();
  if (typeof what !== 'string') setTimeout(() => URL.revokeObjectURL(url), 10000);
}

// The picture as drawn (the canvas keeps its drawing buffer).
export function imageBlob(viewer) {
  viewer.render();
  return new Promise((resolve, reject) =>
    viewer.canvas.toBlob((b) => (b ? resolve(b) : reject(new Error('the picture cannot be encoded'))), 'image/png'));
}

// The bodies at the shown time: a node per body (its name, position and
// rotation), holding its pieces' meshes in body coordinates.  Handles,
// edges and lights are the editor's and are left out.
export function gltfText(viewer) {
  const root = new THREE.Scene();
  root.name = 'asgard';
  for (const [name, b] of viewer.bodies) {
    if (b.index < 0) continue;
    const node = new THREE.Group();
    node.name = name;
    node.position.copy(b.group.position);
    node.quaternion.copy(b.group.quaternion);
    b.meshes.forEach((m, k) => {
      const mesh = new THREE.Mesh(m.geometry, m.material);
      mesh.name = `${name} piece ${k + 1}`;
      node.add(mesh);
    });
    root.add(node);
  }
  root.userData = { time: viewer.t };
  return new Promise((resolve, reject) => {
    new GLTFExporter().parse(root, (gltf) => resolve(JSON.stringify(gltf)), reject, { binary: false, onlyVisible: false, trs: true });
  });
}

// The movie request for the view shown: the scene's view element when one
// is chosen, else the free camera expressed in asgard render's view options
// (render/view.cc: a point p is seen at k·(R(p − c) + pan), the eye at
// distance E/k on the view axis, E and the field of view fixed).  R is the
// camera's rotation inverted, c the centre of rotation; the pan puts the
// point on the line of sight at the centre's depth in the middle of the
// picture, and k makes that depth's half height the viewer's (the
// viewer's field of view is vertical).
export function movieRequest(viewer, width, height) {
  const request = { width: Math.round(width), height: Math.round(height) };
  if (viewer.viewName) return { ...request, view: viewer.viewName };
  const framing = viewer.poses && viewer.poses.framing;
  if (!framing) return request;
  const cam = viewer.camera, c = viewer.controls.target;
  const r = cam.quaternion.clone().invert();
  const e = cam.position.clone().sub(c).applyQuaternion(r);  // the eye, view axes
  const tanHalf = Math.tan((cam.fov * Math.PI) / 360);
  // A picture taller than wide: asgard render fits the width, so its
  // vertical field is wider by the aspect ratio.
  const aspect = Math.min(1, width / height);
  const k = (framing.eye_distance * framing.tan_half_fov) / (aspect * e.z * tanHalf);
  const angle = 2 * Math.acos(Math.min(1, Math.abs(r.w)));
  const axis = new THREE.Vector3(r.x, r.y, r.z);
  const rot = axis.lengthSq() > 0 ? axis.normalize().multiplyScalar(((r.w < 0 ? -1 : 1) * angle * 180) / Math.PI) : axis;
  return { ...request, rot: rot.toArray(), center: c.toArray(), pan: [-e.x, -e.y, 0], scale: k * framing.radius };
}
