// The trajectory editor's panel (seed 4.1.4, Figure 4.4), below the
// graphical viewer while trajectories are shown: for the chosen trajectory
// the times of its control points on a scale (a marker per point, dragged
// sideways to change its time, kept between its neighbours), and one graph
// per component (x, y, z against time) whose points are dragged up and
// down.  "Add point" puts a control point at the shown time on the curve,
// "Add at click" at the shown time where the user clicks in the viewer,
// "Delete point" removes the chosen one.  Every change is the trajectory's
// whole -points list sent through the session like a handle's drag (the
// literal is rewritten in every language viewer as it moves); releasing or
// adding or deleting re-simulates.  The control points' times are also
// marks above the header's time slider, dragged the same way.
import { TrajectoryCurve } from './trajectory.js';
import { round } from './handles.js';

const SVG = 'http://www.w3.org/2000/svg';
const PAD = 34, SCALE_H = 26, GRAPH_H = 44, GAP = 6;
const COMPONENTS = ['x', 'y', 'z'];
const COLORS = ['#c03030', '#20a040', '#3060d0'];
// Knot times stay this far from their neighbours.
const MIN_GAP = 1e-3;

function el(name, attrs = {}, parent = null) {
  const e = document.createElementNS(SVG, name);
  for (const [k, v] of Object.entries(attrs)) e.setAttribute(k, v);
  if (parent) parent.appendChild(e);
  return e;
}

export class TrajectoryEditor {
  constructor(root, viewer, { edit, end }) {
    this.root = root;
    this.viewer = viewer;
    this.edit = edit;  // (element, [t x y z ...]) while dragging
    this.end = end;    // (element, [t x y z ...] | null) when a change is done
    this.element = '';
    this.selected = -1;  // the chosen control point
    this.select = root.querySelector('select');
    this.add = root.querySelector('.add');
    this.remove = root.querySelector('.delete');
    this.info = root.querySelector('.info');
    this.svg = el('svg', { class: 'graphs' }, root);
    this.select.onchange = () => { this.element = this.select.value; this.selected = -1; this.render(); };
    this.add.onclick = () => this.addPoint();
    this.addClick = root.querySelector('.add-click');
    this.addClick.onclick = () => this.addPointByClick();
    this.remove.onclick = () => this.deletePoint();
    this.svg.addEventListener('pointermove', (ev) => this.move(ev));
    this.svg.addEventListener('pointerup', (ev) => this.release(ev));
    this.svg.addEventListener('pointercancel', (ev) => this.release(ev));
    // The same times as marks on the header's time slider (seed Figure
    // 4.4), dragged sideways like the panel's markers.
    this.slider = viewer.ui.slider;
    this.marks = document.createElement('div');
    this.marks.id = 'time-marks';
    document.body.appendChild(this.marks);
    this.marks.addEventListener('pointermove', (ev) => this.move(ev));
    this.marks.addEventListener('pointerup', (ev) => this.release(ev));
    this.marks.addEventListener('pointercancel', (ev) => this.release(ev));
    window.addEventListener('resize', () => this.drawMarks());
  }

  // Time → page x on the header's slider (its track runs between half a
  // thumb from each end; Chromium's and Firefox's thumbs are 16 px).
  sliderScale() {
    const r = this.slider.getBoundingClientRect(), poses = this.viewer.poses;
    const t0 = poses ? poses.t0 : 0, t1 = poses && poses.t1 > t0 ? poses.t1 : t0 + 1, inset = 8;
    return { r, t0, t1, x: (t) => r.left + inset + ((t - t0) / (t1 - t0)) * (r.width - 2 * inset), perPixel: (t1 - t0) / (r.width - 2 * inset) };
  }

  drawMarks() {
    this.marks.textContent = '';
    if (this.root.style.display !== 'block') return;
    const S = this.sliderScale();
    Object.assign(this.marks.style, { left: `${S.r.left}px`, top: `${S.r.top - 7}px`, width: `${S.r.width}px` });
    this.knots().forEach((h, i) => {
      if (h.t < S.t0 - 1e-9 || h.t > S.t1 + 1e-9) return;
      const m = document.createElement('div');
      m.className = `time-mark${i === this.selected ? ' chosen' : ''}`;
      m.dataset.knot = String(i);
      m.title = `${this.element} point #${i + 1}: t = ${round(h.t, 10000)} (drag sideways)`;
      m.style.left = `${S.x(h.t) - S.r.left - 5}px`;
      m.addEventListener('pointerdown', (ev) => {
        this.press(ev, { kind: 'time', knot: i, perPixel: S.perPixel });
        this.marks.setPointerCapture(ev.pointerId);
      });
      this.marks.appendChild(m);
    });
  }

  // The trajectories the viewer shows with editable control points.
  lines() { return this.viewer.paths.children.filter((l) => l.userData.knots.length && l.userData.knots[0].editable); }
  knots() {
    const line = this.lines().find((l) => l.userData.element === this.element);
    return line ? line.userData.knots : [];
  }
  values() { return this.knots().flatMap((h) => [h.t, ...h.value]); }

  // Rebuilds the panel (new parameters, another view's edit, shown or hidden).
  render() {
    const names = this.lines().map((l) => l.userData.element);
    const visible = this.viewer.shown.trajectories && names.length > 0;
    this.root.style.display = visible ? 'block' : 'none';
    if (!visible) { this.drawMarks(); return; }
    if ([...this.select.options].map((o) => o.value).join('\n') !== names.join('\n')) {
      this.select.textContent = '';
      for (const n of names) this.select.appendChild(new Option(n, n));
    }
    if (!names.includes(this.element)) { this.element = names[0]; this.selected = -1; }
    this.select.value = this.element;
    const knots = this.knots();
    if (this.selected >= knots.length) this.selected = -1;
    this.remove.disabled = this.selected < 0 || knots.length <= 2;
    this.info.textContent = this.selected >= 0
      ? `#${this.selected + 1}: t = ${round(knots[this.selected].t, 10000)}, {${knots[this.selected].value.join(' ')}}` : '';
    this.draw();
    this.drawMarks();
  }

  // Time → x on the panel: the simulated interval and every knot fit.
  layout() {
    const knots = this.knots();
    const poses = this.viewer.poses;
    let t0 = poses ? poses.t0 : 0, t1 = poses ? poses.t1 : 1;
    if (knots.length) { t0 = Math.min(t0, knots[0].t); t1 = Math.max(t1, knots[knots.length - 1].t); }
    if (!(t1 > t0)) t1 = t0 + 1;
    const width = this.root.clientWidth || 600;
    // The value ranges are frozen while dragging (the graph does not run away).
    if (!this.drag || !this.ranges) {
      const samples = knots.length > 1 ? new TrajectoryCurve(knots.map((h) => [h.t, ...h.value])).sample(12) : knots.map((h) => h.value);
      this.ranges = COMPONENTS.map((_, c) => {
        let lo = Math.min(...samples.map((v) => v[c])), hi = Math.max(...samples.map((v) => v[c]));
        const pad = Math.max((hi - lo) * 0.15, 0.5);
        lo -= pad; hi += pad;
        return [lo, hi];
      });
    }
    return { t0, t1, width, x: (t) => PAD + ((t - t0) / (t1 - t0)) * (width - 2 * PAD) };
  }

  graphTop(c) { return SCALE_H + GAP + c * (GRAPH_H + GAP); }
  yOf(c, v) { const [lo, hi] = this.ranges[c]; return this.graphTop(c) + GRAPH_H - ((v - lo) / (hi - lo)) * GRAPH_H; }

  draw() {
    const svg = this.svg;
    svg.textContent = '';
    const L = this.layout();
    const height = this.graphTop(3);
    svg.setAttribute('width', L.width);
    svg.setAttribute('height', height);
    this.L = L;
    const knots = this.knots();
    // The scale of control-point times.
    el('line', { x1: PAD, x2: L.width - PAD, y1: SCALE_H - 6, y2: SCALE_H - 6, stroke: '#555' }, svg);
    for (const t of [L.t0, L.t1]) {
      el('line', { x1: L.x(t), x2: L.x(t), y1: SCALE_H - 9, y2: SCALE_H - 3, stroke: '#555' }, svg);
      el('text', { x: L.x(t), y: SCALE_H + 5, 'font-size': 9, 'text-anchor': 'middle', fill: '#555' }, svg).textContent = String(round(t, 1000));
    }
    knots.forEach((h, i) => {
      const x = L.x(h.t);
      const m = el('path', { d: `M${x - 6} 2 L${x + 6} 2 L${x} ${SCALE_H - 7} Z`, class: 'knot-time', 'data-knot': i,
        fill: i === this.selected ? '#f80' : '#3060d0', cursor: 'ew-resize' }, svg);
      m.addEventListener('pointerdown', (ev) => this.press(ev, { kind: 'time', knot: i }));
    });
    this.cursor = el('line', { y1: 0, y2: height, stroke: '#888', 'stroke-dasharray': '3 3' }, svg);
    this.placeCursor();
    // A graph per component: the curve and its control points.
    COMPONENTS.forEach((name, c) => {
      const top = this.graphTop(c);
      el('rect', { x: PAD, y: top, width: L.width - 2 * PAD, height: GRAPH_H, fill: '#fafafa', stroke: '#ddd' }, svg);
      el('text', { x: 6, y: top + GRAPH_H / 2 + 4, 'font-size': 12, fill: COLORS[c] }, svg).textContent = name;
      if (knots.length > 1) {
        const curve = new TrajectoryCurve(knots.map((h) => [h.t, ...h.value]));
        const points = [];
        for (let k = 0; k <= 120; ++k) {
          const t = L.t0 + ((L.t1 - L.t0) * k) / 120;
          points.push(`${L.x(t).toFixed(1)},${this.yOf(c, curve.value(t)[c]).toFixed(1)}`);
        }
        el('polyline', { points: points.join(' '), fill: 'none', stroke: COLORS[c] }, svg);
      }
      knots.forEach((h, i) => {
        const p = el('circle', { cx: L.x(h.t), cy: this.yOf(c, h.value[c]), r: 5, class: 'knot-value', 'data-knot': i, 'data-component': c,
          fill: i === this.selected ? '#f80' : COLORS[c], cursor: 'ns-resize' }, svg);
        p.addEventListener('pointerdown', (ev) => this.press(ev, { kind: 'value', knot: i, component: c }));
      });
    });
  }

  placeCursor() {
    if (!this.cursor || !this.L) return;
    const x = this.L.x(this.viewer.t);
    this.cursor.setAttribute('x1', x);
    this.cursor.setAttribute('x2', x);
  }

  press(ev, what) {
    ev.preventDefault();
    this.selected = what.knot;
    const h = this.knots()[what.knot];
    this.drag = { ...what, x: ev.clientX, y: ev.clientY, t: h.t, value: h.value.slice() };
    if (!what.perPixel) this.svg.setPointerCapture(ev.pointerId);
    this.render();
  }

  move(ev) {
    const d = this.drag;
    if (!d) return;
    const knots = this.knots(), h = knots[d.knot];
    if (!h) return;
    const L = this.L;
    if (d.kind === 'time') {
      const dt = (ev.clientX - d.x) * (d.perPixel || (L.t1 - L.t0) / (L.width - 2 * PAD));
      const lo = d.knot > 0 ? knots[d.knot - 1].t + MIN_GAP : -Infinity;
      const hi = d.knot + 1 < knots.length ? knots[d.knot + 1].t - MIN_GAP : Infinity;
      h.t = round(Math.min(hi, Math.max(lo, d.t + dt)));
    } else {
      const [lo, hi] = this.ranges[d.component];
      const dv = (-(ev.clientY - d.y) / GRAPH_H) * (hi - lo);
      h.value[d.component] = round(d.value[d.component] + dv);
    }
    this.render();
    this.edit(this.element, this.values());
  }

  release(ev) {
    if (!this.drag) return;
    this.drag = null;
    for (const e of [this.svg, this.marks]) try { e.releasePointerCapture(ev.pointerId); } catch { /* released */ }
    this.render();
    this.end(this.element, null);
  }

  // A control point at the shown time, on the curve (the path keeps its
  // value there); refused on an existing point's time.
  addPoint() {
    const knots = this.knots();
    const t = round(this.viewer.t);
    if (knots.some((h) => Math.abs(h.t - t) < MIN_GAP)) { this.info.textContent = `a point is already at t = ${t}`; return; }
    const curve = new TrajectoryCurve(knots.map((h) => [h.t, ...h.value]));
    this.insertKnot(this.element, t, curve.value(t));
  }

  // The knots with [t, ...value] added (chosen), sent as a new list.
  insertKnot(element, t, value) {
    const list = this.knots().map((h) => [h.t, ...h.value]);
    list.push([t, ...value.map((v) => round(v))]);
    list.sort((a, b) => a[0] - b[0]);
    this.selected = list.findIndex((k) => k[0] === t);
    this.end(element, list.flat());
  }

  // A control point at the shown time where the user clicks in the viewer
  // (seed 4.1.4): in the plane through the curve's point at that time,
  // facing the camera; for a trajectory drawn as arrows, the arrow's tip
  // goes there.  Refused on an existing point's time.
  addPointByClick() {
    const knots = this.knots(), element = this.element;
    const line = this.lines().find((l) => l.userData.element === element);
    if (!line || !knots.length || !knots[0].editable) return;
    const t = round(this.viewer.t);
    if (knots.some((h) => Math.abs(h.t - t) < MIN_GAP)) { this.info.textContent = `a point is already at t = ${t}`; return; }
    const curve = new TrajectoryCurve(knots.map((h) => [h.t, ...h.value]));
    this.viewer.startPick({
      count: 1,
      space: line.userData.place(t, curve.value(t)),
      prompts: [`Click where ${element}'s point at t = ${t} goes (Esc cancels)`],
      done: ([p]) => {
        if (this.element !== element || this.knots().some((h) => Math.abs(h.t - t) < MIN_GAP)) return;
        this.insertKnot(element, t, line.userData.unplace(t, p.world));
      },
    });
  }

  deletePoint() {
    const knots = this.knots();
    if (this.selected < 0 || knots.length <= 2) return;
    const list = knots.filter((_, i) => i !== this.selected).map((h) => [h.t, ...h.value]);
    this.selected = -1;
    this.end(this.element, list.flat());
  }
}
