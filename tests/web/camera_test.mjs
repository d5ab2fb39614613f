// The graphical viewer's camera and lights in headless Chromium (issue 13,
// seed 4.1.3, 4.1.7) on tests/web/views.al: the virtual sphere (a drag
// across the middle turns the scene about the view's up axis by
// asin(dx / r); a drag around the rim turns it about the line of sight),
// translation (the centre follows the pointer pixel for pixel), zoom, a
// centre of rotation set by double-clicking a body (that point then stays
// put while the scene turns); the scene's views (one following the ball,
// whose centre the core computes from the motion, one from the side) and
// its red point light; torque handles; the Create menu's torque, light,
// view (of the camera as it is) and trajectory, and Delete; the handles of
// a view's -center, -pos, -rot and -scale, and 'z'/'x' pushing a dragged
// handle in depth; a view whose -pos and -scale are expressions of state
// and time (seed 4.1.7): its camera where the expressions put it at each
// frame, moving while playing, its handles read-only.  Screenshots go to
// OUT_DIR.
import { join } from 'node:path';
import { browserTest, dragHandle, openEditor, sleep, waitFor } from './common.mjs';

const [asgard, scene, outDir] = process.argv.slice(2);

// Camera state: position, direction, up, centre, the centre on the screen.
const cameraState = (page) => page.evaluate(() => {
  const g = window.asgard.graphical, c = g.camera;
  const dir = c.getWorldDirection(c.position.clone());
  const up = c.position.clone().set(0, 1, 0).applyQuaternion(c.quaternion);
  return { pos: c.position.toArray(), dir: dir.toArray(), up: up.toArray(), target: g.controls.target.toArray(),
    targetScreen: g.toScreen(g.controls.target.clone()), fov: c.fov, aspect: c.aspect };
});
const dot = (a, b) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
const dist = (a, b) => Math.hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]);
const angle = (a, b) => Math.acos(Math.max(-1, Math.min(1, dot(a, b) / Math.sqrt(dot(a, a) * dot(b, b)))));

async function drag(page, points, button = 'left') {
  await page.mouse.move(points[0][0], points[0][1]);
  await page.mouse.down({ button });
  for (const [x, y] of points.slice(1)) await page.mouse.move(x, y);
  await page.mouse.up({ button });
}

await browserTest(asgard, scene, 'camera', async ({ check, url, context }) => {
  const { page, errors, ok } = await openEditor(context, url, 'runner');
  check(ok, 'the editor shows the scene');
  // Handles hidden, so that presses turn the view.
  for (const kind of ['handles', 'velocities', 'lights']) await page.uncheck(`#toggles input[data-kind=${kind}]`);
  await page.click('#fit');
  const box = await page.evaluate(() => { const r = window.asgard.graphical.canvas.getBoundingClientRect(); return { x: r.left, y: r.top, w: r.width, h: r.height }; });
  const cx = box.x + box.w / 2, cy = box.y + box.h / 2, r = 0.45 * Math.min(box.w, box.h);

  // Virtual sphere, across the middle: a turn about the up axis.
  const s0 = await cameraState(page);
  check(Math.hypot(s0.targetScreen.x - cx, s0.targetScreen.y - cy) < 0.5, 'after Fit the centre of rotation is in the middle');
  const dx = 120;
  await drag(page, Array.from({ length: 7 }, (_, i) => [cx + (dx * i) / 6, cy]));
  const s1 = await cameraState(page);
  const want = Math.asin(dx / r);
  check(Math.abs(angle(s0.dir, s1.dir) - want) < 2e-3, `a ${dx}-pixel drag across the middle turns the view by ${angle(s0.dir, s1.dir).toFixed(4)} rad, asin(dx/r) = ${want.toFixed(4)}`);
  check(angle(s0.up, s1.up) < 1e-6, 'about the up axis (up unchanged)');
  check(Math.abs(dist(s0.pos, s0.target) - dist(s1.pos, s1.target)) < 1e-9 * dist(s0.pos, s0.target), 'at the same distance from the centre');
  check(Math.hypot(s1.targetScreen.x - cx, s1.targetScreen.y - cy) < 0.5, 'the centre stays in the middle');

  // Around the rim: a quarter turn about the line of sight.
  const rim = 0.48 * Math.min(box.w, box.h);
  const arc = Array.from({ length: 13 }, (_, i) => { const a = Math.PI / 2 - (Math.PI / 2) * (i / 12); return [cx + rim * Math.cos(a), cy - rim * Math.sin(a)]; });
  await drag(page, arc);
  const s2 = await cameraState(page);
  check(angle(s1.dir, s2.dir) < 1e-6, 'a drag around the rim keeps the line of sight');
  check(Math.abs(angle(s1.up, s2.up) - Math.PI / 2) < 0.02, `and turns the picture a quarter turn (${(angle(s1.up, s2.up) * 180 / Math.PI).toFixed(2)}°)`);

  // Translate (right button): the scene at the centre's depth follows the
  // pointer, and the centre moves along (it stays in the middle).
  await drag(page, [[cx - 100, cy + 50], [cx - 80, cy + 40], [cx - 60, cy + 20]], 'right');
  const s3 = await cameraState(page);
  const moved = await page.evaluate((p) => window.asgard.graphical.toScreen(window.asgard.graphical.controls.target.clone().set(...p)), s2.target);
  check(Math.abs(moved.x - (s2.targetScreen.x + 40)) < 0.5 && Math.abs(moved.y - (s2.targetScreen.y - 30)) < 0.5,
    `a right drag by (40, −30) moves the scene at the centre on the screen by (${(moved.x - s2.targetScreen.x).toFixed(2)}, ${(moved.y - s2.targetScreen.y).toFixed(2)})`);
  check(Math.hypot(s3.targetScreen.x - cx, s3.targetScreen.y - cy) < 0.5 && angle(s2.dir, s3.dir) < 1e-9, 'without turning; the centre moves along');

  // Zoom: the wheel moves the camera toward the centre.
  await page.mouse.move(cx, cy);
  await page.mouse.wheel(0, 100);
  await waitFor(async () => (await cameraState(page)).pos[0] !== s3.pos[0], 'the zoom');
  const s4 = await cameraState(page);
  const ratio = dist(s4.pos, s4.target) / dist(s3.pos, s3.target);
  check(Math.abs(ratio - 1.0015 ** 100) < 1e-9, `a wheel notch of 100 scales the distance by ${ratio.toFixed(6)} (1.0015^100 = ${(1.0015 ** 100).toFixed(6)})`);

  // Centre of rotation: double-click the brick; the point clicked stays put while the scene turns.
  await page.click('#fit');
  const brick = await page.evaluate(() => window.asgard.graphical.bodyScreenPos('brick', [0.6, 0.2, 0.5]));
  await page.mouse.dblclick(brick.x, brick.y);
  await sleep(100);
  const s5 = await cameraState(page);
  const local = [s5.target[0], s5.target[1] + 2, s5.target[2]];
  check(Math.abs(local[2] - 0.5) < 1e-3 && Math.abs(local[0]) <= 1 && Math.abs(local[1]) <= 0.5,
    `double-clicking the brick makes the clicked point of its front face the centre (${local.map((v) => v.toFixed(3)).join(', ')} from the brick's centre)`);
  const runner0 = await page.evaluate(() => window.asgard.graphical.bodyScreenPos('runner'));
  await drag(page, Array.from({ length: 6 }, (_, i) => [cx - 50 + 20 * i, cy + 10 * i]));
  const s6 = await cameraState(page);
  const runner1 = await page.evaluate(() => window.asgard.graphical.bodyScreenPos('runner'));
  check(Math.hypot(s6.targetScreen.x - s5.targetScreen.x, s6.targetScreen.y - s5.targetScreen.y) < 0.5 && angle(s5.dir, s6.dir) > 0.1,
    `the scene turns (${angle(s5.dir, s6.dir).toFixed(3)} rad) about that point, which stays on the screen at (${s6.targetScreen.x.toFixed(1)}, ${s6.targetScreen.y.toFixed(1)})`);
  check(Math.hypot(runner1.x - runner0.x, runner1.y - runner0.y) > 20, 'while the ball moves on the screen');
  await page.screenshot({ path: join(outDir, '1-turned.png') });

  // Views: the menu lists the scene's; "chase" follows the ball (the core's
  // camera centre is the ball at each frame); "side" looks along x.
  const options = await page.evaluate(() => [...document.querySelectorAll('#camera-view option')].map((o) => o.value));
  check(options.join(',') === ',chase,crane,side', `the camera menu: ${options.map((o) => o || 'Free camera').join(', ')}`);
  await page.selectOption('#camera-view', 'chase');
  const centred = [];
  for (const t of [0, 0.5, 1.0, 1.73]) {
    await page.evaluate((tt) => window.asgard.graphical.seek(tt), t);
    const p = await page.evaluate(() => window.asgard.graphical.bodyScreenPos('runner'));
    centred.push(Math.hypot(p.x - cx, p.y - cy));
  }
  check(centred.every((d) => d < 1), `the chase view keeps the ball in the middle (off by ${centred.map((d) => d.toFixed(2)).join(', ')} px at t = 0, 0.5, 1, 1.73)`);
  const view = await page.evaluate(() => window.asgard.graphical.views.find((v) => v.name === 'chase'));
  const s7 = await cameraState(page);
  const wantFov = (2 * Math.atan(Math.tan(view.fov_y / 2) / Math.min(1, s7.aspect)) * 180) / Math.PI;
  check(Math.abs(s7.fov - wantFov) < 1e-9, `with the core's field of view (${s7.fov.toFixed(3)}°)`);
  await page.screenshot({ path: join(outDir, '2-chase.png') });
  // "crane": -pos {{-runner.x} 1 {-t}} and -scale {2 + t}, expressions the
  // core evaluates at every frame: it looks at (runner.x, −1, t) = (−3 + 3t,
  // −1, t) from 4 framing radii / (2 + t) along +z, so the ball stays in the
  // middle across and the camera closes in.
  await page.selectOption('#camera-view', 'crane');
  const framing = await page.evaluate(() => window.asgard.graphical.poses.framing);
  const craneAt = [];
  for (const t of [0, 0.5, 1.0, 1.5]) {
    await page.evaluate((tt) => window.asgard.graphical.seek(tt), t);
    const s = await cameraState(page), p = await page.evaluate(() => window.asgard.graphical.bodyScreenPos('runner'));
    craneAt.push({ t, target: dist(s.target, [-3 + 3 * t, -1, t]), distance: dist(s.pos, s.target) / (framing.eye_distance * framing.radius / (2 + t)) - 1, x: p.x - cx, y: p.y - cy });
  }
  check(craneAt.every((c) => c.target < 1e-5 && Math.abs(c.distance) < 1e-5),
    `the crane view looks at (−3 + 3t, −1, t) from 4 radii / (2 + t) (off by ${craneAt.map((c) => `${c.target.toExponential(1)}, ${c.distance.toExponential(1)}`).join('; ')} at t = 0, 0.5, 1, 1.5)`);
  check(craneAt.every((c) => Math.abs(c.x) < 1) && craneAt.every((c, i) => i === 0 || c.y < craneAt[i - 1].y - 2),
    `the ball stays in the middle across (${craneAt.map((c) => c.x.toFixed(2)).join(', ')} px) and rises on the screen as the view zooms (${craneAt.map((c) => c.y.toFixed(1)).join(', ')} px)`);
  // Playing: the camera moves with the motion (no server round trip).
  await page.evaluate(() => window.asgard.graphical.seek(0));
  await page.click('#play');
  const playing = [];
  for (let i = 0; i < 3; ++i) {
    await sleep(200);
    playing.push(await page.evaluate(() => { const g = window.asgard.graphical; return { t: g.t, target: g.controls.target.toArray(), playing: g.playing }; }));
  }
  await page.screenshot({ path: join(outDir, '3-crane-playing.png') });
  await page.click('#play');
  const advanced = playing.every((p, i) => i === 0 || (p.t > playing[i - 1].t && p.target[0] > playing[i - 1].target[0] + 0.1));
  const onTrack = playing.every((p) => dist(p.target, [-3 + 3 * p.t, -1, p.t]) < 1e-3);
  check(playing.every((p) => p.playing) && advanced && onTrack,
    `while playing, the crane camera moves along (−3 + 3t, −1, t): t = ${playing.map((p) => p.t.toFixed(3)).join(', ')}, target x = ${playing.map((p) => p.target[0].toFixed(3)).join(', ')}`);
  await page.selectOption('#camera-view', '');
  const free = [];
  for (const t of [0, 1]) {
    await page.evaluate((tt) => window.asgard.graphical.seek(tt), t);
    free.push(await page.evaluate(() => window.asgard.graphical.bodyScreenPos('runner')));
  }
  check(Math.abs(free[1].x - free[0].x) > 30, `in the free camera the ball crosses the picture (${(free[1].x - free[0].x).toFixed(1)} px)`);
  await page.selectOption('#camera-view', 'side');
  const side = [];
  for (const t of [0, 1]) {
    await page.evaluate((tt) => window.asgard.graphical.seek(tt), t);
    side.push(await page.evaluate(() => window.asgard.graphical.bodyScreenPos('runner')));
  }
  check(Math.abs(side[0].x - cx) < 1 && Math.abs(side[1].x - cx) < 1,
    `the side view (-rot {0 π/2 0}) sees the ball's path end on: x = ${side.map((p) => (p.x - cx).toFixed(2)).join(', ')} px from the middle`);
  check(Math.abs(side[1].y - cy) < Math.abs(side[0].y - cy),
    `the ball moving along +x goes away from the eye (${Math.abs(side[0].y - cy).toFixed(1)} → ${Math.abs(side[1].y - cy).toFixed(1)} px from the middle)`);
  await page.screenshot({ path: join(outDir, '4-side.png') });
  // Turning the view by hand leaves the scene's view for the free camera.
  await drag(page, [[cx, cy], [cx + 20, cy], [cx + 40, cy]]);
  check(await page.evaluate(() => document.getElementById('camera-view').value === '' && window.asgard.graphical.viewName === ''),
    'dragging in a view switches to the free camera');

  // Torque handles (`torque`, `force -torque 1`) like the force handles:
  // an arrow along the torque from the centre of mass, its tip dragged.
  await page.evaluate(() => window.asgard.graphical.seek(0));
  const torques = await page.evaluate(() => window.asgard.graphical.handleList().filter((h) => h.kind === 'torque'));
  check(torques.map((h) => `${h.element}:${h.editable ? h.value.join(' ') : 'read-only'}`).join(', ') === 'torque#0:0 0 2, torque#1:1 0 0, torque#2:read-only',
    `three torque handles: ${torques.map((h) => `${h.element} ${h.editable ? `{${h.value}}` : `(${h.reason})`}`).join(', ')}`);
  const tip = await page.evaluate(() => {
    const g = window.asgard.graphical, h = g.handles.find((x) => x.element === 'torque#0');
    const c = g.bodies.get('brick').group.position.clone();
    return { off: h.mesh.position.clone().sub(c).sub(c.clone().set(0, 0, 2 * h.scale)).length(), shown: h.arrow.visible };
  });
  check(tip.off < 1e-9 && tip.shown, 'the torque\'s arrow starts at the brick\'s centre and ends at centre + scale × {0 0 2}');
  // The read-only torque (-z 0.5 sin(t) × mass) shows the core's value at
  // the frame shown: at t = 1, centre + scale × {0 0 0.5 sin(1) × 2}.
  const ro = await page.evaluate(() => {
    const g = window.asgard.graphical;
    g.seek(1);
    const h = g.handles.find((x) => x.element === 'torque#2'), c = g.bodies.get('brick').group.position.clone();
    const want = 0.5 * Math.sin(g.poses.times[g.frame]) * 2;  // the brick: a 2 × 1 × 1 hull at density 1, mass 2
    const off = h.mesh.position.clone().sub(c).sub(c.clone().set(0, 0, want * h.scale)).length();
    g.seek(0);
    return { off, want, scale: h.scale };
  });
  check(ro.off < 1e-3 * ro.scale,
    `the read-only torque's arrow is its evaluated value at the frame shown (z = ${ro.want.toFixed(4)}; off by ${ro.off.toExponential(1)})`);
  const spin = () => page.evaluate(() => { const g = window.asgard.graphical; return g.bodyQuaternion('brick', g.poses.times.length - 1); });
  const spinBefore = await spin();
  const t0 = torques.find((h) => h.element === 'torque#0');
  await dragHandle(page, 'torque#0.vector', 60, -40);
  const torqueLine = await page.evaluate(() => window.asgard.languageViewers[0].text().split('\n').find((l) => l.startsWith('torque -body brick -x') && !l.includes('mass')));
  const words = /-x (\S+) -y (\S+) -z (\S+)/.exec(torqueLine || '');
  const after = await page.evaluate(() => window.asgard.graphical.handleList().find((h) => h.element === 'torque#0'));
  check(words && words.slice(1).map(Number).every((v, k) => Math.abs(v - after.value[k]) < 1e-9) && Math.hypot(after.x - t0.x - 60, after.y - t0.y + 40) < 2,
    `dragging its tip rewrites the torque: "${torqueLine}", the tip under the pointer`);
  const spinAfter = await spin();
  check(spinAfter.some((v, k) => Math.abs(v - spinBefore[k]) > 1e-3), 'and the brick turns differently after the re-simulation');
  await page.screenshot({ path: join(outDir, '4-torque.png') });

  // The red point light: the lit ball is red; without the light source
  // (Update) the default white lights show its own colour.  At t = 1 the
  // ball is over the brick, in the clear: at t = 0 it sits at the left edge,
  // where a wider control panel (fonts differ between machines) covers it.
  await page.click('#fit');
  await page.evaluate(() => window.asgard.graphical.seek(1));
  const colour = () => page.evaluate(() => {
    const g = window.asgard.graphical;
    g.draw();
    const p = g.bodyScreenPos('runner'), r = g.canvas.getBoundingClientRect();
    const c = document.createElement('canvas');
    c.width = g.canvas.width; c.height = g.canvas.height;
    const x = c.getContext('2d');
    x.drawImage(g.canvas, 0, 0);
    const k = g.canvas.width / r.width;
    const d = x.getImageData(Math.round((p.x - r.left) * k) - 2, Math.round((p.y - r.top) * k) - 2, 5, 5).data;
    const sum = [0, 0, 0];
    for (let i = 0; i < d.length; i += 4) for (let j = 0; j < 3; ++j) sum[j] += d[i + j];
    return sum.map((v) => v / 25);
  });
  // A new set of lights means new shader programs, which Chromium may still
  // be compiling at the first draw (the canvas then reads as the white
  // background, or, under load, as the picture under the old lights): read
  // again until the ball is there and, given the colour under the old
  // lights, until it has changed, for at most 5 s.
  const drawnColour = async (before) => {
    const stale = (c) => c.every((v) => v > 250) || (before && c.every((v, j) => v === before[j]));
    let c = await colour();
    for (let i = 0; i < 50 && stale(c); ++i) {
      await new Promise((res) => setTimeout(res, 100));
      c = await colour();
    }
    return c;
  };
  const lit = await drawnColour();
  const lights = await page.evaluate(() => window.asgard.graphical.sceneLights.children.map((l) => l.type));
  check(lights.join(',') === 'AmbientLight,PointLight', `the scene's light source lights the picture (${lights.join(', ')})`);
  await page.screenshot({ path: join(outDir, '5-red-light.png') });
  const text = await page.evaluate(() => window.asgard.text);
  await page.evaluate((t) => window.asgard.conn.call('update', { text: t }), text.replace(/^lightsource.*$/m, ''));
  check(await waitFor(() => page.evaluate(() => window.asgard.graphical.defaultLights.visible), 'the default lights'), 'without a light source the default lights are on');
  await page.evaluate(() => window.asgard.graphical.seek(1));
  const plain = await drawnColour(lit);
  const redness = (c) => c[0] / Math.max(1, (c[1] + c[2]) / 2);
  check(redness(lit) > 1.6 * redness(plain), `the ball is redder under the red light: rgb(${lit.map(Math.round)}) vs rgb(${plain.map(Math.round)})`);
  await page.screenshot({ path: join(outDir, '6-default-light.png') });

  // The Create menu: a torque on the selected body, a light, a view of the
  // camera as it is, a trajectory; Delete removes a picked element.
  const lines = async () => (await page.evaluate(() => window.asgard.languageViewers[0].text())).split('\n');
  const created = async (re) => { let l; await waitFor(async () => (l = (await lines()).find((x) => re.test(x))), `${re}`); return l; };
  const brickAt = await page.evaluate(() => window.asgard.graphical.bodyScreenPos('brick', [0.5, 0, 0.5]));
  await page.mouse.click(brickAt.x, brickAt.y);
  await waitFor(() => page.evaluate(() => window.asgard.graphical.selected === 'brick'), 'brick selected');
  await page.click('#create-torque');
  check(!!(await created(/^torque -body brick -x 0 -y 0 -z 1$/)), 'Torque makes "torque -body brick -x 0 -y 0 -z 1"');
  check(await waitFor(() => page.evaluate(() => window.asgard.graphical.handleList().some((h) => h.element === 'torque#3' && h.kind === 'torque')), 'handle'),
    'and the new torque has a handle');
  // Light: a click places it, in the plane through the view's centre
  // facing the camera; Sun: a directional light along the view.
  await page.click('#create-light');
  check(await page.evaluate(() => document.getElementById('prompt').textContent.startsWith('Light: click')), 'Light asks for a click');
  const lightAt = { x: cx + 40, y: cy - 30 };
  const wantLight = await page.evaluate(({ x, y }) => {
    const g = window.asgard.graphical, r = g.canvas.getBoundingClientRect();
    const c = g.controls.target.clone(), d = g.camera.getWorldDirection(c.clone());
    // The pixel's ray (unprojected at the near and far planes) met with the plane.
    const onPlane = (px, py) => {
      const ndc = (z) => c.clone().set(((px - r.left) / r.width) * 2 - 1, -((py - r.top) / r.height) * 2 + 1, z).unproject(g.camera);
      const a = ndc(-1), dir = ndc(1).sub(a);
      return a.addScaledVector(dir, c.clone().sub(a).dot(d) / dir.dot(d));
    };
    const p = onPlane(x, y);
    return { p: p.toArray(), pixel: onPlane(x + 1, y).distanceTo(p) };
  }, lightAt);
  await page.mouse.click(lightAt.x, lightAt.y);
  const light = await created(/^lightsource -type point -pos \{[^}]*\}$/);
  const lightPos = light ? /-pos \{([^}]*)\}/.exec(light)[1].split(' ').map(Number) : [NaN, NaN, NaN];
  const lightOff = Math.max(...lightPos.map((v, c) => Math.abs(v - wantLight.p[c])));
  check(!!light && lightOff < 2e-3 + wantLight.pixel && await waitFor(() => page.evaluate(() => window.asgard.graphical.sceneLights.children.some((l) => l.type === 'PointLight')), 'light'),
    `Light makes "${light}" where the click meets the plane (${wantLight.p.map((v) => v.toFixed(3)).join(' ')}), which lights the picture`);
  const viewDir = await page.evaluate(() => { const c = window.asgard.graphical.camera; return c.getWorldDirection(c.position.clone()).toArray(); });
  await page.click('#create-sun');
  const sun = await created(/^lightsource -type directional -pos \{[^}]*\} -dir \{[^}]*\}$/);
  const sunDir = sun ? /-dir \{([^}]*)\}/.exec(sun)[1].split(' ').map(Number) : [NaN, NaN, NaN];
  check(sunDir.every((v, c) => Math.abs(v - viewDir[c]) < 6e-4), `Sun makes "${sun}": along the view (${viewDir.map((v) => v.toFixed(3)).join(' ')})`);
  await page.click('#undo');
  check(await waitFor(async () => !(await lines()).some((l) => l.includes('-type directional')), 'the sun undone'), 'and Undo takes the sun away again');
  await page.click('#create-trajectory');
  const traj = await created(/^trajectory trajectory1 -points /);
  check(/^trajectory trajectory1 -points \{\{0 0 -2 0\} \{2 [\d.]+ -2 0\}\}$/.test(traj || ''), `Trajectory makes "${traj}" from the brick's start over the simulated time`);
  // View: the free camera as a view element; choosing it shows the same picture.
  await page.evaluate(() => window.asgard.graphical.seek(0));
  await drag(page, [[cx, cy], [cx + 30, cy + 20], [cx + 60, cy + 30]]);
  const seen = await page.evaluate(() => ['runner', 'brick'].map((b) => window.asgard.graphical.bodyScreenPos(b)));
  await page.click('#create-view');
  const viewLine = await created(/^view view1 /);
  check(!!viewLine, `View makes "${viewLine}"`);
  check(await waitFor(() => page.evaluate(() => [...document.querySelectorAll('#camera-view option')].some((o) => o.value === 'view1')), 'view1 offered'), 'and offers it in the camera menu');
  await page.selectOption('#camera-view', 'view1');
  const inView = await page.evaluate(() => ['runner', 'brick'].map((b) => window.asgard.graphical.bodyScreenPos(b)));
  const off = Math.max(...inView.map((p, i) => Math.hypot(p.x - seen[i].x, p.y - seen[i].y)));
  check(off < 0.03 * box.w, `seen through view1 the bodies are where the free camera showed them (within ${off.toFixed(1)} px)`);
  await page.screenshot({ path: join(outDir, '7-created.png') });
  // Delete: pick the new light's handle, then Delete.
  await page.selectOption('#camera-view', '');
  await page.check('#toggles input[data-kind=lights]');
  const lh = await page.evaluate(() => window.asgard.graphical.handleList().find((h) => h.kind === 'light'));
  await page.mouse.click(lh.x, lh.y);
  check(await waitFor(() => page.evaluate(() => document.getElementById('selection').textContent === 'selected: lightsource#0'), 'selection'),
    'clicking its handle selects the light');
  const n = await page.evaluate(() => window.asgard.stateCount);
  await page.click('#delete-element');
  await waitFor(() => page.evaluate((k) => window.asgard.stateCount > k, n), 'the state after Delete');
  check(!(await lines()).some((l) => l.startsWith('lightsource')) &&
    await waitFor(() => page.evaluate(() => window.asgard.graphical.defaultLights.visible), 'default lights'), 'Delete removes its command, and the default lights are back');

  // View handles (seed 4.1.7): `view side`'s -center, -pos and -rot dragged
  // in the viewer; the core's camera for the view then agrees with them.
  await page.check('#toggles input[data-kind=views]');
  await page.click('#fit');
  const vh = (id) => page.evaluate((i) => window.asgard.graphical.handleList().find((h) => h.id === i), id);
  const sideCamera = () => page.evaluate(() => window.asgard.graphical.poses.views.find((v) => v.name === 'side').cameras[0]);
  const sideLine = async () => (await lines()).find((l) => l.startsWith('view side '));
  const chase = await vh('chase.center');
  check(!!chase && !chase.editable && /-follow runner moves it/.test(chase.reason), `chase's -center is read-only: "${chase && chase.reason}"`);
  const spokeLength = await page.evaluate(() => window.asgard.graphical.radius * 0.3);
  let [eye, target, up] = await sideCamera();
  let [hc, hp, hr] = await Promise.all(['side.center', 'side.pos', 'side.rot'].map(vh));
  const sub = (a, b) => a.map((v, k) => v - b[k]);
  check(dist(hc.world, target) < 1e-6, "side's -center ball is at the point its camera looks at (-pos is zero)");
  check(angle(sub(hr.world, target), sub(eye, target)) < 1e-6 && Math.abs(dist(hr.world, target) - spokeLength) < 1e-6, 'its -rot knob is on the line toward its eye');
  check(angle(sub(hp.world, target), up) < 1e-6, 'its -pos knob above that point along its up');
  const viewLiterals = await page.evaluate(() => [...document.querySelectorAll('.cm-literal-view')].map((e) => e.textContent));
  check(viewLiterals.includes('{0 1.5707963267948966 0}'), `the language viewer highlights the views' literals (${viewLiterals.join(', ')})`);
  await page.screenshot({ path: join(outDir, '8-view-handles.png') });

  // -center: dragged, with 'z' pushing it away three times and 'x' pulling
  // it back once, while the pointer stays.
  const step = await page.evaluate(() => window.asgard.graphical.depthStep());
  await page.mouse.move(hc.x, hc.y);
  await page.mouse.down();
  for (let i = 1; i <= 4; ++i) { await page.mouse.move(hc.x + 10 * i, hc.y); await sleep(30); }
  const c1 = (await vh('side.center')).value;
  const sight = (await cameraState(page)).dir;
  for (const key of ['z', 'z', 'z']) { await page.keyboard.press(key); await sleep(30); }
  const c3 = (await vh('side.center')).value, at3 = await vh('side.center');
  await page.keyboard.press('x');
  const c2 = (await vh('side.center')).value;
  const n0 = await page.evaluate(() => window.asgard.stateCount);
  await page.mouse.up();
  await waitFor(() => page.evaluate((k) => window.asgard.stateCount > k, n0), 'the state after the drag');
  check(Math.abs(dot(sub(c3, c1), sight) - 3 * step) < 3e-3, `'z' three times pushes -center ${dot(sub(c3, c1), sight).toFixed(3)} deeper (3 × ${step.toFixed(3)})`);
  check(Math.hypot(at3.x - (hc.x + 40), at3.y - hc.y) < 1, 'and the ball stays under the pointer');
  check(Math.abs(dot(sub(c3, c2), sight) - step) < 3e-3, "'x' pulls it one step back");
  const centerText = /-center \{([^}]*)\}/.exec((await sideLine()) || '');
  check(!!centerText && centerText[1].split(' ').map(Number).every((v, k) => Math.abs(v - c2[k]) < 1e-9), `the text says -center {${centerText && centerText[1]}}`);
  check(await waitFor(async () => { [eye, target, up] = await sideCamera(); return dist(target, c2) < 1e-6; }, 'the core camera at the new centre'),
    'the core\'s camera for side now looks at the new centre');

  // -rot: the knob dragged up; the core's eye is then along the new spoke.
  hr = await vh('side.rot');
  await dragHandle(page, 'side.rot', 0, -50);
  hr = await vh('side.rot');
  const rotText = /-rot \{([^}]*)\}/.exec((await sideLine()) || '');
  check(!!rotText && rotText[1] !== '0 1.5707963267948966 0', `the drag rewrites -rot {${rotText && rotText[1]}}`);
  check(await waitFor(async () => { [eye, target, up] = await sideCamera(); return angle(sub(hr.world, target), sub(eye, target)) < 2e-3; }, 'the core eye along the knob'),
    `the core's eye is along the dragged knob (${angle(sub(hr.world, target), sub(eye, target)).toExponential(2)} rad)`);

  // -pos: the knob dragged sideways; the core looks at the point under it.
  hp = await vh('side.pos');
  await dragHandle(page, 'side.pos', -40, 0);
  hp = await vh('side.pos');
  const posText = /-pos \{([^}]*)\}/.exec((await sideLine()) || '');
  check(!!posText, `the drag appends -pos {${posText && posText[1]}}`);
  check(await waitFor(async () => { [eye, target, up] = await sideCamera(); return dist(hp.world, target.map((v, k) => v + spokeLength * up[k])) < 2e-3; }, 'the core target under the knob'),
    'the core\'s camera looks at the point below the dragged -pos knob');

  // -scale: side writes none; its knob, on a spoke along the view's right
  // 0.3 radius × the scale long, dragged outward appends -scale, the label
  // saying the value; the core's eye is then 4 radii / scale away.
  const scaleKnob = () => page.evaluate(() => {
    const g = window.asgard.graphical, h = g.handles.find((x) => x.id === 'side.scale');
    const a = g.toScreen(h.anchor()), b = g.toScreen(h.mesh.position);
    return { value: h.value, editable: h.editable, dx: b.x - a.x, dy: b.y - a.y };
  });
  const k0 = await scaleKnob();
  check(k0.editable && Math.abs(k0.value[0] - 1) < 1e-3, `side's -scale knob starts at the core's scale (${k0.value})`);
  const along = Math.hypot(k0.dx, k0.dy);
  let label = '';
  await dragHandle(page, 'side.scale', (40 * k0.dx) / along, (40 * k0.dy) / along,
    { during: async () => { label = await page.evaluate(() => document.getElementById('label').textContent); } });
  const k1 = await scaleKnob();
  const scaleText = /-scale (\S+)/.exec((await sideLine()) || '');
  check(!!scaleText && Number(scaleText[1]) === k1.value[0] && k1.value[0] > 1.05,
    `dragging the knob outward appends -scale ${scaleText && scaleText[1]}`);
  check(label === `side -scale ${k1.value[0]}`, `the label shows the value while dragging ("${label}")`);
  check(await waitFor(async () => { [eye, target, up] = await sideCamera(); return Math.abs(dist(eye, target) * k1.value[0] / (framing.eye_distance * framing.radius) - 1) < 1e-5; }, 'the core eye distance'),
    `the core's eye for side is then 4 radii / ${k1.value[0]} from what it looks at`);
  await page.screenshot({ path: join(outDir, '9-view-dragged.png') });

  // crane's -pos and -scale are expressions: read-only handles (the reason
  // on a click) that the core's camera places at the frame shown; its
  // literal -rot keeps a live knob.
  await page.evaluate(() => window.asgard.graphical.seek(1));
  const [cp, cs, cr] = await Promise.all(['crane.pos', 'crane.scale', 'crane.rot'].map(vh));
  check(!cp.editable && !cs.editable && /expression of time or state/.test(cp.reason) && /expression of time or state/.test(cs.reason) && cr.editable,
    `crane's -pos and -scale are read-only ("${cp.reason}"), its -rot is not`);
  check(dist(cp.world, [0, -1 + spokeLength, 1]) < 1e-5 && dist(cs.world, [3 * spokeLength, -1, 1]) < 1e-5,
    'at t = 1 its -pos knob is above (0, −1, 1), where it looks, and its -scale knob 3 × 0.3 radius to the right');
  await page.mouse.click(cp.x, cp.y);
  const hover = await page.evaluate(() => document.getElementById('label').textContent);
  check(hover === 'crane -pos is read-only: an expression of time or state (the view moves)', `clicking it says why: "${hover}"`);
  const craneLine = (await lines()).find((l) => l.startsWith('view crane'));
  check(craneLine === 'view crane -center {0 0 0} -rot {0 0 0} -pos {{-runner.x} 1 {-t}} -scale {2 + t}', `and its text is unchanged ("${craneLine}")`);
  await page.screenshot({ path: join(outDir, '10-crane-handles.png') });
  check(errors.length === 0, `no page errors ${errors.join('; ')}`);
});
