// The trajectory editor in headless Chromium (issue 13, seed 4.1.4 and
// Figure 4.4): on trajectory.al, with Trajectories shown, each control point
// of `path` is a handle and the path is drawn as the curve the core
// evaluates; dragging the middle control point rewrites that point of the
// `-points` literal in the language viewer while dragging, the drawn path
// follows it, and after the re-simulation the ball riding the trajectory
// passes through the moved point; Undo puts the point back in one step.  A
// trajectory whose points are computed has read-only handles.  The panel
// below the viewer: a point's value dragged in its component's graph, its
// time dragged on the scale (not past a neighbour), a point added at the
// shown time on the curve and deleted.  A velocity trajectory (-state
// dpos) is drawn as arrows from its body.  "Add at click" puts a point where
// a click meets the plane through the curve at the shown time.  Screenshots go to OUT_DIR.
import { join } from 'node:path';
import { browserTest, dragHandle, handle, openEditor, waitFor } from './common.mjs';

const [asgard, scene, outDir] = process.argv.slice(2);

const text = (page) => page.evaluate(() => window.asgard.languageViewers[0].text());
const knotsOf = (t) => {
  const m = /trajectory path -points \{(.*)\} -body/.exec(t);
  return m ? [...m[1].matchAll(/\{([^{}]*)\}/g)].map((g) => g[1].trim().split(/\s+/).map(Number)) : null;
};
// The largest distance between the viewer's curve and the core's samples of
// `path` at the frame times, and between the core's samples and the rider's
// simulated positions.
const agreement = (page) => page.evaluate(() => {
  const g = window.asgard.graphical, core = g.poses.trajectories.find((x) => x.name === 'path');
  let drawn = 0, ridden = 0;
  g.poses.times.forEach((t, i) => {
    const v = g.trajectoryValue('path', t), c = core.values[i], r = g.bodyPosition('rider', i);
    drawn = Math.max(drawn, ...v.map((x, k) => Math.abs(x - c[k])));
    ridden = Math.max(ridden, ...r.map((x, k) => Math.abs(x - c[k])));
  });
  return { drawn, ridden, frames: g.poses.times.length };
});

await browserTest(asgard, scene, 'trajectory', async ({ check, url, context }) => {
  const { page, errors, ok } = await openEditor(context, url, 'rider');
  check(ok, 'the editor shows trajectory.al');
  const hidden = await handle(page, 'path.points#2');
  check(hidden && !hidden.shown, 'trajectories are hidden until their check box is ticked (seed 4.1.4)');
  await page.check('#toggles input[data-kind="trajectories"]');
  await page.click('#fit');  // frames the shown trajectories too
  const knots = await page.evaluate(() => window.asgard.graphical.handleList().filter((h) => h.kind === 'knot' && h.element === 'path'));
  check(knots.length === 5 && knots.every((h) => h.editable && h.shown),
    `path's five control points are editable handles (${knots.length})`);
  const computed = await page.evaluate(() => window.asgard.graphical.handleList().filter((h) => h.element === 'slanted'));
  check(computed.length === 2 && computed.every((h) => !h.editable && /expression|literal/.test(h.reason)),
    `the computed trajectory's two points are read-only handles (${computed.map((h) => h.reason).join('; ')})`);
  const paths = await page.evaluate(() => window.asgard.graphical.trajectoryPaths());
  check(paths.path && paths.path.length === 4 * 24 + 1, `path is drawn as a curve of ${paths.path?.length} points`);
  check(paths.slanted && paths.slanted.length === 25, 'and drawn as a curve');
  // Two knots {0 0 -2 0} {2 3 -2 0}: the straight line from (0, −2, 0) to (3, −2, 0).
  const s = paths.slanted;
  check(s.every((p) => Math.abs(p[1] + 2) < 1e-9 && Math.abs(p[2]) < 1e-9) && Math.abs(s[s.length - 1][0] - 3) < 1e-9,
    'slanted is the line from (0, −2, 0) to (3, −2, 0)');
  let a = await agreement(page);
  // The core rounds to 1e-6; the rider follows its trajectory within the solver's step.
  check(a.drawn < 2e-6, `the drawn curve is the core's at all ${a.frames} frame times (max difference ${a.drawn.toExponential(1)})`);
  check(a.ridden < 1e-4, `the rider rides it (max difference ${a.ridden.toExponential(1)})`);
  // The rider's initial position and velocity are the trajectory's over
  // [0, 2]: their handles are read-only, with the reason; its rotation and
  // the free ball's position stay editable.
  const riderHandles = await page.evaluate(() => Object.fromEntries(window.asgard.graphical.handleList()
    .filter((h) => h.element === 'rider' || h.element === 'other').map((h) => [h.id, h])));
  const initial = (body, param) => Object.values(riderHandles).find((h) => h.element === body && h.param === param);
  check(initial('rider', 'init_pos') && !initial('rider', 'init_pos').editable &&
    initial('rider', 'init_pos').reason === 'trajectory path prescribes its position from t = 0 to 2',
    `the rider's position handle is read-only: ${initial('rider', 'init_pos')?.reason}`);
  check(initial('rider', 'init_dpos') && !initial('rider', 'init_dpos').editable &&
    /prescribes its velocity/.test(initial('rider', 'init_dpos').reason), 'so is its velocity handle');
  check(initial('rider', 'init_rot')?.editable && initial('other', 'init_pos')?.editable,
    'its rotation and the free ball\'s position are editable');
  // Each control point's time is written beside it (Figure 4.4).
  await page.evaluate(() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r))));
  const times = await page.evaluate(() => [...document.querySelectorAll('.point-time')]
    .filter((d) => d.style.display !== 'none')
    .map((d) => { const r = d.getBoundingClientRect(); return { id: d.dataset.id, text: d.textContent, x: r.left, y: r.bottom }; }));
  const pathTimes = times.filter((l) => l.id.startsWith('path.'));
  check(pathTimes.map((l) => l.text).join(', ') === 't = 0, t = 0.5, t = 1, t = 1.5, t = 2',
    `path's control points are labelled with their times (${pathTimes.map((l) => l.text).join(', ')})`);
  check(times.filter((l) => l.id.startsWith('slanted.')).map((l) => l.text).join(', ') === 't = 0, t = 2',
    'so are the computed trajectory\'s');
  const near = pathTimes.every((l) => {
    const h = knots.find((k) => k.id === l.id);
    return h && Math.abs(l.x - 7 - h.x) < 2 && Math.abs(l.y - h.y) < 20;
  });
  check(near, 'each label sits at the upper right of its point');
  await page.screenshot({ path: join(outDir, '1-trajectory.png') });

  // Drag the middle control point (t = 1, at the origin) up the screen.
  const before = knotsOf(await text(page));
  check(before && before[2].join(' ') === '1 0 0 0', `the middle point is {${before && before[2].join(' ')}}`);
  const pathBefore = paths.path;
  let during = null;
  await dragHandle(page, 'path.points#2', 0, -80, {
    during: async () => {
      // The picture follows the pointer at once; the text one round trip
      // later (one edit in flight at a time).  Compare them once the last
      // step's edit is in, not at whatever instant this runs: on a slow or
      // busy machine the text may still be a step behind.
      await page.evaluate(() => window.asgard.graphical.flushDrag());
      during = {
        label: await page.evaluate(() => document.getElementById('label').textContent),
        knots: knotsOf(await text(page)),
        mid: await page.evaluate(() => window.asgard.graphical.trajectoryValue('path', 1)),
      };
      await page.screenshot({ path: join(outDir, '2-dragging-point.png') });
    },
  });
  check(/^path -points #3 \(t = 1\) \{/.test(during.label), `while dragging, the label shows the point: "${during.label}"`);
  check(during.knots && during.knots[2][2] > 0.3 && during.knots[2][0] === 1,
    `while dragging, the text's point moved up with its time kept: {${during.knots && during.knots[2].join(' ')}}`);
  check(during.mid && during.mid.every((v, k) => Math.abs(v - during.knots[2][k + 1]) < 1e-9),
    'the drawn path passes through the dragged point at its time');
  const after = knotsOf(await text(page));
  check(after && [0, 1, 3, 4].every((i) => after[i].join(' ') === before[i].join(' ')), 'the other points are unchanged');
  check(after[2][2] > 0.3, `after release the middle point is {${after[2].join(' ')}}`);
  const pathAfter = await page.evaluate(() => window.asgard.graphical.trajectoryPaths().path);
  const moved = Math.max(...pathAfter.map((p, i) => Math.hypot(...p.map((v, k) => v - pathBefore[i][k]))));
  check(pathAfter.length === pathBefore.length && moved > 0.3, `the drawn path changed (up to ${moved.toFixed(3)})`);
  // After the re-simulation: the core's curve, the drawn one and the rider agree again.
  check(await waitFor(async () => (await agreement(page)).ridden < 1e-4, 'the re-simulated rider'), 'the re-simulated rider follows the new path');
  a = await agreement(page);
  check(a.drawn < 2e-6, `the drawn curve is the core's new curve (max difference ${a.drawn.toExponential(1)})`);
  const rider = await page.evaluate(() => {
    const g = window.asgard.graphical;
    return g.bodyPosition('rider', g.poses.times.findIndex((t) => Math.abs(t - 1) < 1e-9));
  });
  check(rider.every((v, k) => Math.abs(v - after[2][k + 1]) < 1e-4), `at t = 1 the rider is at the moved point (${rider.map((v) => v.toFixed(3)).join(', ')})`);
  await page.evaluate(() => window.asgard.graphical.seek(1));
  await page.screenshot({ path: join(outDir, '3-after-drag.png') });

  // Undo: the session's undo restores the point and the path.
  await page.click('#undo');
  check(await waitFor(async () => knotsOf(await text(page))?.[2].join(' ') === '1 0 0 0', 'undo'), 'Undo restores the point in the text');
  check(await waitFor(() => page.evaluate(() => {
    const v = window.asgard.graphical.trajectoryValue('path', 1);
    return v && Math.hypot(...v) < 1e-9;
  }), 'undo path'), 'and the drawn path');

  // The trajectory panel (Figure 4.4): the times of the control points on a
  // scale, a graph per component; `path` is chosen (the computed one has no
  // editable points and is not offered).
  const panel = () => page.evaluate(() => ({
    shown: getComputedStyle(document.getElementById('trajectory-editor')).display !== 'none',
    options: [...document.querySelectorAll('#trajectory-editor select option')].map((o) => o.value),
    times: [...document.querySelectorAll('#trajectory-editor .knot-time')].map((m) => { const r = m.getBoundingClientRect(); return { x: r.left + r.width / 2, y: r.top + r.height / 2 }; }),
    points: [...document.querySelectorAll('#trajectory-editor .knot-value')].map((m) => { const r = m.getBoundingClientRect(); return { x: r.left + r.width / 2, y: r.top + r.height / 2, knot: Number(m.dataset.knot), c: Number(m.dataset.component) }; }),
    scale: (() => { const e = window.asgard.trajectories; const L = e.L; return { perSecond: (L.width - 68) / (L.t1 - L.t0), ranges: e.ranges }; })(),
  }));
  let p = await panel();
  check(p.shown && p.options.join(',') === 'path' && p.times.length === 5 && p.points.length === 15,
    `the trajectory panel shows path's 5 point times and 3 × 5 graph points (offered: ${p.options.join(', ')})`);
  const dragBy = async (at, dx, dy) => {
    const n0 = await page.evaluate(() => window.asgard.stateCount);
    await page.mouse.move(at.x, at.y);
    await page.mouse.down();
    for (let i = 1; i <= 5; ++i) await page.mouse.move(at.x + (dx * i) / 5, at.y + (dy * i) / 5);
    await page.mouse.up();
    await waitFor(() => page.evaluate((n) => window.asgard.stateCount > n, n0), 'the state after a panel drag');
  };
  // Point 4's y graph up by 22 pixels: its y grows by 22 px × the graph's scale.
  const y4 = p.points.find((q) => q.knot === 3 && q.c === 1);
  const [ylo, yhi] = p.scale.ranges[1];
  await dragBy(y4, 0, -22);
  let k = knotsOf(await text(page));
  const wantY = 1 + (22 / 44) * (yhi - ylo);
  check(k && Math.abs(k[3][2] - wantY) < 2e-3 && k[3][0] === 1.5 && k[3][1] === 1 && k[3][3] === 0,
    `dragging point 4 up in the y graph makes it {${k && k[3].join(' ')}} (y ≈ ${wantY.toFixed(3)})`);
  check(await waitFor(async () => (await agreement(page)).ridden < 1e-4, 'rider'), 'the rider follows the changed path');
  // The drag's intermediate moves each bring a state (each agreeing with its
  // own path), so the rider is read until the state of the final text comes.
  const riderAt15 = () => page.evaluate(() => { const g = window.asgard.graphical; return g.bodyPosition('rider', g.poses.times.findIndex((t) => Math.abs(t - 1.5) < 1e-9)); });
  let at15 = null;
  await waitFor(async () => { at15 = await riderAt15(); return Math.abs(at15[1] - k[3][2]) < 1e-4; }, 'the rider at t = 1.5');
  check(at15 && Math.abs(at15[1] - k[3][2]) < 1e-4, `at t = 1.5 the rider's y is the point's (${at15 && at15[1].toFixed(4)})`);
  // Point 2's time marker 30 pixels right: its time grows by 30 px / scale.
  p = await panel();
  await dragBy(p.times[1], 30, 0);
  k = knotsOf(await text(page));
  const wantT = 0.5 + 30 / p.scale.perSecond;
  check(k && Math.abs(k[1][0] - wantT) < 2e-3 && k[1][1] === -1 && k[1][2] === 1,
    `dragging point 2's time marker moves it to t = ${k && k[1][0]} (≈ ${wantT.toFixed(3)}), its position kept`);
  // …but never past its neighbour.
  p = await panel();
  await dragBy(p.times[1], 400, 0);
  k = knotsOf(await text(page));
  check(k && k[1][0] < k[2][0] && k[2][0] - k[1][0] <= 1.001e-3 + 1e-9, `dragged far, it stops just before point 3 (t = ${k && k[1][0]} < ${k && k[2][0]})`);
  await page.screenshot({ path: join(outDir, '4-panel-drags.png') });
  // Add a point at the shown time on the curve; delete it again.
  await page.evaluate(() => window.asgard.graphical.seek(1.8));
  const onCurve = await page.evaluate(() => window.asgard.graphical.trajectoryValue('path', 1.8));
  let count = await page.evaluate(() => window.asgard.stateCount);
  await page.click('#trajectory-editor .add');
  await waitFor(() => page.evaluate((n) => window.asgard.stateCount > n, count), 'the state after Add point');
  k = knotsOf(await text(page));
  const added = k && k.find((q) => Math.abs(q[0] - 1.8) < 1e-9);
  check(k && k.length === 6 && added && added.slice(1).every((v, c) => Math.abs(v - onCurve[c]) < 1e-3),
    `Add point puts {${added && added.join(' ')}} at t = 1.8 on the curve (6 points)`);
  check(await waitFor(async () => (await panel()).times.length === 6, 'six markers'), 'the panel shows six time markers');
  await page.screenshot({ path: join(outDir, '5-added-point.png') });
  p = await panel();
  await page.mouse.click(p.times[4].x, p.times[4].y);  // choose the new point (the 5th by time)
  count = await page.evaluate(() => window.asgard.stateCount);
  await page.click('#trajectory-editor .delete');
  await waitFor(() => page.evaluate((n) => window.asgard.stateCount > n, count), 'the state after Delete point');
  k = knotsOf(await text(page));
  check(k && k.length === 5 && !k.some((q) => Math.abs(q[0] - 1.8) < 1e-9), `Delete point removes it (${k && k.map((q) => q[0]).join(', ')})`);

  // The same times as marks on the header's time slider: one per point,
  // where the slider shows that time; point 4's dragged 20 px left.
  const marks = () => page.evaluate(() => {
    const s = document.getElementById('time').getBoundingClientRect(), g = window.asgard.graphical;
    return { slider: { left: s.left, width: s.width }, t0: g.poses.t0, t1: g.poses.t1,
      marks: [...document.querySelectorAll('#time-marks .time-mark')].map((m) => { const r = m.getBoundingClientRect(); return { x: r.left + r.width / 2, y: r.top + r.height / 2, knot: Number(m.dataset.knot) }; }) };
  });
  let sm = await marks();
  k = knotsOf(await text(page));
  const xOf = (t) => sm.slider.left + 8 + ((t - sm.t0) / (sm.t1 - sm.t0)) * (sm.slider.width - 16);
  check(sm.marks.length === 5 && sm.marks.every((m) => Math.abs(m.x - xOf(k[m.knot][0])) < 1),
    `the header's slider has a mark at each of the 5 points' times (${sm.marks.map((m) => m.x.toFixed(0)).join(', ')} px)`);
  const t4 = k[3][0], mark4 = sm.marks.find((m) => m.knot === 3);
  await dragBy(mark4, -20, 0);
  k = knotsOf(await text(page));
  const wantT4 = t4 - (20 * (sm.t1 - sm.t0)) / (sm.slider.width - 16);
  check(k && Math.abs(k[3][0] - wantT4) < 2e-3 && k[3][1] === 1, `dragging its mark 20 px left moves point 4 to t = ${k && k[3][0]} (≈ ${wantT4.toFixed(3)}), its position kept`);
  sm = await marks();
  check(Math.abs(sm.marks.find((m) => m.knot === 3).x - xOf(k[3][0])) < 1, 'and the mark follows it');
  await page.screenshot({ path: join(outDir, '6-slider-marks.png') });

  // A velocity trajectory (-state dpos): its values are velocities, drawn
  // as arrows from where its body is at each point's time, at the scale of
  // the velocity arrows, the curve through their tips; the core moves the
  // body with those velocities; dragging a tip changes the velocity.
  count = await page.evaluate(() => window.asgard.stateCount);
  await page.locator('.viewer[data-viewer="0"] .cm-content').click();
  await page.keyboard.press('Control+End');
  await page.keyboard.insertText('\nbody pusher -shape ball -init_pos {0 3 0}\ntrajectory push -points {{0 1 0 0} {1 0 2 0} {2 -1 0 0}} -body pusher -state dpos\n');
  await page.click('.viewer[data-viewer="0"] button.update');
  check(await waitFor(() => page.evaluate((n) => window.asgard.stateCount > n && window.asgard.graphical.bodyNames().includes('pusher') &&
    window.asgard.graphical.handleList().filter((h) => h.element === 'push').length === 3, count), 'the velocity trajectory'),
  'after Update, the dpos trajectory push has three control-point handles');
  const arrows = () => page.evaluate(() => {
    const g = window.asgard.graphical, ix = g.bodies.get('pusher').index, times = g.poses.times;
    const frameAt = (t) => times.findIndex((x) => Math.abs(x - t) < 1e-9);
    const knots = g.handleList().filter((h) => h.element === 'push').map((h) => {
      const raw = g.handles.find((x) => x.id === h.id);
      const f = frameAt(raw.t), at = g.bodyPosition('pusher', f), vel = g.poses.velocities[f].slice(6 * ix, 6 * ix + 3);
      const want = at.map((x, c) => x + raw.value[c] * g.scales.velocity);
      // Pixels per world unit along the screen's x at the tip.
      const tip = raw.mesh.position, right = tip.clone().set(1, 0, 0).applyQuaternion(g.camera.quaternion).add(tip);
      const a = g.toScreen(tip.clone()), b = g.toScreen(right);
      return { t: raw.t, value: raw.value, frame: f, arrow: h.arrow, off: Math.max(...h.world.map((x, c) => Math.abs(x - want[c]))),
        vel, pxPerUnit: Math.hypot(b.x - a.x, b.y - a.y) };
    });
    const path = g.trajectoryPaths().push;
    const first = knots[0], last = knots[knots.length - 1];
    const end = (k) => g.bodyPosition('pusher', k.frame).map((x, c) => x + k.value[c] * g.scales.velocity);
    const pathOff = Math.max(...[[path[0], end(first)], [path[path.length - 1], end(last)]].flatMap(([a, b]) => a.map((x, c) => Math.abs(x - b[c]))));
    return { knots, pathOff, n: path.length, scale: g.scales.velocity };
  });
  let ar = await arrows();
  check(ar.knots.every((k) => k.frame >= 0 && k.arrow && k.off < 1e-6),
    `each point is the tip of an arrow from where pusher is at its time, value × ${ar.scale.toFixed(3)} long (worst ${Math.max(...ar.knots.map((k) => k.off)).toExponential(1)})`);
  check(ar.n === 2 * 24 + 1 && ar.pathOff < 1e-6, `the curve (${ar.n} points) runs through the arrows' tips`);
  const velOff = (a) => Math.max(...a.knots.flatMap((k) => k.vel.map((v, c) => Math.abs(v - k.value[c]))));
  check(velOff(ar) < 1e-3, `the core moves pusher at those velocities at the points' times (worst ${velOff(ar).toExponential(1)})`);
  await page.screenshot({ path: join(outDir, '7-velocity-trajectory.png') });
  const mid = ar.knots[1];
  count = await page.evaluate(() => window.asgard.stateCount);
  await dragHandle(page, 'push.points#1', 60, 0);
  await waitFor(() => page.evaluate((n) => window.asgard.stateCount > n, count), 'the re-simulation after the tip drag');
  const pushKnots = (t) => {
    const m = /trajectory push -points \{(.*)\} -body/.exec(t);
    return m ? [...m[1].matchAll(/\{([^{}]*)\}/g)].map((g) => g[1].trim().split(/\s+/).map(Number)) : null;
  };
  k = pushKnots(await text(page));
  ar = await arrows();
  // The tip moved 60 px in the screen plane: 60 / pxPerUnit world units,
  // so the velocity by that over the arrows' scale (values are rounded to
  // 1e-3 per component).
  const tipMoved = k ? Math.hypot(k[1][1] - mid.value[0], k[1][2] - mid.value[1], k[1][3] - mid.value[2]) : 0;
  const want = 60 / mid.pxPerUnit / ar.scale;
  check(k && k[1][0] === 1 && Math.abs(tipMoved - want) < 0.03 * want + 2e-3 && k[0].join(' ') === '0 1 0 0' && k[2].join(' ') === '2 -1 0 0',
    `dragging the middle tip 60 px changes its velocity in the text by ${tipMoved.toFixed(3)} (≈ ${want.toFixed(3)}): {${k && k[1].join(' ')}}, was {1 ${mid.value.join(' ')}}; its time and the others kept`);
  check(await waitFor(async () => velOff(await arrows()) < 1e-3, 'the re-simulated pusher'), 'and the re-simulated pusher has the new velocity at t = 1');

  // "Add at click" (seed 4.1.4): at the shown time t = 1.7, a click in the
  // viewer puts a point where the click meets the plane through the
  // curve's place at t facing the camera — for path the point itself, for
  // push (drawn as arrows) the velocity whose arrow's tip is there.
  const clickAdd = async (element, knotsIn) => {
    await page.selectOption('#trajectory-editor select', element);
    const target = await page.evaluate((el) => {
      const g = window.asgard.graphical;
      g.seek(1.7);
      const line = g.paths.children.find((l) => l.userData.element === el);
      const through = line.userData.place(1.7, g.trajectoryValue(el, 1.7));
      const right = through.clone().set(1, 0, 0).applyQuaternion(g.camera.quaternion);
      const up = through.clone().set(0, 1, 0).applyQuaternion(g.camera.quaternion);
      const w = through.clone().addScaledVector(right, 0.8).addScaledVector(up, 0.5);
      const s = g.toScreen(w.clone()), s1 = g.toScreen(w.clone().add(right));  // one unit to the right
      return { x: s.x, y: s.y, want: line.userData.unplace(1.7, w), perPixel: 1 / Math.hypot(s1.x - s.x, s1.y - s.y) };
    }, element);
    const before = await page.evaluate(() => window.asgard.stateCount);
    await page.click('#trajectory-editor .add-click');
    await page.mouse.click(target.x, target.y);
    await waitFor(() => page.evaluate((n) => window.asgard.stateCount > n, before), `the state after the point added to ${element}`);
    const k = knotsIn(await text(page));
    return { k, added: k && k.find((q) => q[0] === 1.7), ...target };
  };
  const pathAdd = await clickAdd('path', knotsOf);
  const off = (r) => (r.added ? Math.max(...r.added.slice(1).map((v, c) => Math.abs(v - r.want[c]))) : Infinity);
  check(pathAdd.added && off(pathAdd) < pathAdd.perPixel + 1e-3,
    `a click puts path's new point at t = 1.7 where it meets the plane: {${pathAdd.added && pathAdd.added.join(' ')}}, want {${pathAdd.want.map((v) => v.toFixed(3)).join(' ')}} (a pixel is ${pathAdd.perPixel.toFixed(4)})`);
  const pushAdd = await clickAdd('push', pushKnots);
  const scaleNow = await page.evaluate(() => window.asgard.graphical.scales.velocity);
  check(pushAdd.added && pushAdd.k.length === 4 && off(pushAdd) < pushAdd.perPixel / scaleNow + 1e-3,
    `and push's velocity at t = 1.7 is the one whose arrow ends at the click: {${pushAdd.added && pushAdd.added.join(' ')}}, want {${pushAdd.want.map((v) => v.toFixed(3)).join(' ')}}`);
  await page.screenshot({ path: join(outDir, '8-added-by-click.png') });
  check(errors.length === 0, `no script errors in the page ${errors.join('; ')}`);
});
