// Handles over a live WebGL rendition of the document view (seed 6.2.4,
// 4.2.3): the editor's own graphical viewer (graphical.js, handles.js) on a
// transparent canvas laid over the player's (player.js), its bodies hidden
// (still there to be hit: a link end or force offset held on a surface), its
// camera the player's at every draw.  So the handles — initial position and
// rotation, velocity and angular velocity, forces and torques, link ends,
// lights — are the editor's, built from the session's parameters the
// document view's WebSocket brings, and drawn at the clock's time with no
// server round trip; a drag goes through the same session (set_parameter
// while dragging, a simulation at the end), so every editor and the saved
// text follow.  A press off every handle turns the player's camera (its
// trackball, wheel and double-click, as without handles); a click on a body
// selects it.  Trajectories' paths and points and the views' handles are
// shown too.
import { GraphicalViewer } from './graphical.js';

// A GraphicalViewer drawing only handles, in the camera of `player`.
class OverlayViewer extends GraphicalViewer {
  constructor(canvas, ui, player) {
    // The canvas's context made first, with alpha: the renderer takes the
    // context the canvas already has, so what it does not draw is clear.
    canvas.getContext('webgl2', { alpha: true, premultipliedAlpha: true, antialias: true, preserveDrawingBuffer: true });
    super(canvas, ui);
    this.player = player;
    this.scene.background = null;
    this.renderer.setClearColor(0xffffff, 0);
    this.shown.bodies = false;  // the player draws them
    this.shown.links = false;   // and the links (the ends' handles stay)
    // Trajectories' paths and points, and the views' handles, as the
    // editor draws them when their toggles are on (the document view has
    // no toggles).
    this.shown.trajectories = true;
    this.shown.views = true;
    // The player's camera moves; this one's controls never take a press.
    Object.defineProperty(this.controls, 'enabled', { get: () => false, set: () => {} });
  }

  // The player's camera, as three.js takes it.
  followPlayer() {
    if (!this.player) return;
    const c = this.player.camera();
    this.camera.fov = (c.fovY * 180) / Math.PI;
    this.camera.aspect = c.width / c.height;
    this.camera.near = c.near;
    this.camera.far = c.far;
    this.camera.updateProjectionMatrix();
    this.camera.position.set(...c.eye);
    this.camera.up.set(...c.up);
    this.camera.lookAt(...c.target);
    this.camera.updateMatrixWorld();
    this.controls.target.set(...c.target);
  }

  render() {
    this.followPlayer();
    super.render();
  }

  // A click selects a body the player draws (this viewer's are hidden).
  pickable(b) { return b.index >= 0; }

  // Picking and dragging use the camera too (between draws).
  pointer(ev) {
    this.followPlayer();
    return super.pointer(ev);
  }
}

export class HandleOverlay {
  // `actions`: drag(element, param, values) → Promise (while dragging),
  // dragStart() (the clock goes to the start), dragEnd() (re-simulate).
  constructor(player, actions) {
    this.player = player;
    this.actions = actions;
    const under = player.canvas;
    // A box around the player's canvas that the overlay fills.
    this.box = document.createElement('span');
    this.box.className = 'asgard-handles-box';
    this.box.style.cssText = 'position:relative;display:inline-block;line-height:0;vertical-align:top';
    under.before(this.box);
    this.box.appendChild(under);
    const canvas = document.createElement('canvas');
    canvas.className = 'asgard-handles';
    canvas.style.cssText = `position:absolute;left:0;top:0;width:${under.style.width};height:${under.style.height};touch-action:none`;
    this.box.appendChild(canvas);
    this.canvas = canvas;
    const label = document.createElement('div');
    label.className = 'handle-label';
    label.style.cssText = 'position:absolute;left:4px;top:4px;display:none;background:rgba(255,255,255,0.85);' +
      'font:12px sans-serif;line-height:normal;padding:1px 4px;pointer-events:none;max-width:95%';
    this.box.appendChild(label);
    const idle = (tag) => document.createElement(tag);  // the editor's controls this view has not
    this.viewer = new OverlayViewer(canvas, {
      label, slider: idle('input'), clock: idle('span'), play: idle('button'),
      drag: (element, param, values) => actions.drag(element, param, values),
      dragEnd: () => this.endDrag(),
      prompt: () => {},
      // A click on a body selects it (the box around it, as in the
      // editor); the figure says which, for readers and tests.
      selected: (name) => {
        const figure = this.box.closest('figure');
        if (figure) figure.dataset.selected = name || '';
      },
    }, player);
    this.setupCamera();
  }

  // A press off every handle turns the player's camera; the wheel zooms it,
  // a double-click sends it home.
  setupCamera() {
    const c = this.canvas, v = this.viewer;
    let last = null;
    // (After the viewer's own listener: a press on a handle has started a drag.)
    c.addEventListener('pointerdown', (ev) => {
      if (v.dragging) { this.startDrag(); return; }
      last = [ev.clientX, ev.clientY];
      c.setPointerCapture(ev.pointerId);
    });
    c.addEventListener('pointermove', (ev) => {
      if (v.dragging) { this.placeBody(); return; }
      if (!last) return;
      this.player.orbit(ev.clientX - last[0], ev.clientY - last[1]);
      last = [ev.clientX, ev.clientY];
      v.render();
    });
    const up = () => { last = null; };
    c.addEventListener('pointerup', up);
    c.addEventListener('pointercancel', up);
    c.addEventListener('wheel', (ev) => { ev.preventDefault(); this.player.zoom(Math.pow(1.0015, ev.deltaY)); v.render(); }, { passive: false });
    c.addEventListener('dblclick', () => { this.player.home(); v.render(); });
  }

  startDrag() {
    this.actions.dragStart();
    this.placeBody();
  }

  // While a body's handle is dragged the player draws the body at its new
  // start, as the editor's viewer does.
  placeBody() {
    const h = this.viewer.dragging;
    if (!h || !this.viewer.bodies.has(h.element)) return;
    const s = this.viewer.start(h.element);
    if (!s) return;
    this.player.place(h.element, [s.p.x, s.p.y, s.p.z, s.q.x, s.q.y, s.q.z, s.q.w]);
    this.placed = h.element;
    this.player.draw();
  }

  async endDrag() {
    if (this.placed) this.player.place(this.placed, null);
    this.placed = null;
    await this.actions.dragEnd();
  }

  show(on) {
    this.canvas.style.display = on ? '' : 'none';
    if (!on) this.viewer.showLabel('');
  }

  setScene(meshes, poses) { this.viewer.setScene(meshes, poses); }
  setParameters(state) { this.viewer.setParameters(state.parameters, state.elements, state.prescribed); }
  parameterEdited(element, param, values) { this.viewer.parameterEdited(element, param, values); }
  // A tick of the document's clock: drawn at once, with the player's frame.
  seek(t) { this.viewer.seek(t, true); }
}
