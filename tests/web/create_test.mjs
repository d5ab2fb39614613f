// Creating elements from the Create menu in headless Chromium (issue 13,
// seed 4.1): on the seed pendulum in two tabs (the first with two language
// viewers), "Body" makes a box at the view's centre, "Force" a constant force
// on the selected body, "Link" a link made by clicking two bodies.  Each new
// element appears as one well-formatted command in every language viewer and
// in both graphical viewers, and the session's Undo removes them again.
// Delete of b1 asks first, listing the force and links that name it, and
// then removes them too, in one undo step.
// "Force curve" makes a force that follows a new trajectory; Link's second
// click on a trajectory links the body to its moving point.
// Screenshots go to OUT_DIR.
import { join } from 'node:path';
import { browserTest, sleep, waitFor } from './common.mjs';

const [asgard, scene, outDir] = process.argv.slice(2);

const texts = async (pages) => (await Promise.all(pages.map((p) => p.evaluate(() => window.asgard.languageViewers.map((v) => v.text()))))).flat();
const everyText = async (pages, f) => (await texts(pages)).every(f);
const nums = (s) => s.trim().split(/\s+/).map(Number);

await browserTest(asgard, scene, 'create', async ({ check, url, context }) => {
  const a = context.pages()[0] ?? await context.newPage();
  const b = await context.newPage();
  const pages = [a, b];
  const errors = [];
  for (const p of pages) p.on('pageerror', (e) => errors.push(String(e)));
  await a.goto(`${url}?viewers=2`);
  await b.goto(url);
  for (const p of pages)
    check(await waitFor(() => p.evaluate(() => window.asgard.ready && window.asgard.graphical.bodyNames().includes('b3'))), 'a tab shows the pendulum');
  const shapes = await a.evaluate(() => [...document.querySelectorAll('#create-shape option')].map((o) => o.value));
  check(shapes.join(' ') === 'ss1 box rod', `the Create menu offers the scene's shape sets: ${shapes.join(' ')}`);
  const forceDisabled = await a.evaluate(() => document.getElementById('create-force').disabled);
  check(forceDisabled, 'Force is disabled while no body is selected');

  // Body: a box at the view's centre, after the last body command.
  const centre = await a.evaluate(() => window.asgard.graphical.viewCentre());
  await a.selectOption('#create-shape', 'box');
  await a.click('#create-body');
  const bodyLine = /^body body1 -shape box -init_pos \{([^}]*)\}$/m;
  check(await waitFor(() => everyText(pages, (t) => bodyLine.test(t)), 'the new body in every language viewer'),
    'the new body is one command in all three language viewers');
  const t1 = (await texts([a]))[0];
  const pos = nums(bodyLine.exec(t1)[1]);
  check(pos.every((v, k) => Math.abs(v - centre[k]) <= 5e-4), `at the view's centre: {${pos.join(' ')}} vs (${centre.join(', ')})`);
  const lines = t1.split('\n');
  const at = lines.findIndex((l) => bodyLine.test(l));
  check(lines[at - 1].startsWith('body b3 '), 'written right after the last body command');
  check(await waitFor(async () => (await Promise.all(pages.map((p) => p.evaluate(() => window.asgard.graphical.bodyNames().includes('body1'))))).every(Boolean),
    'body1 in both graphical viewers'), 'the new body is drawn in both tabs');
  const start = await b.evaluate(() => window.asgard.graphical.bodyPosition('body1'));
  check(start.every((v, k) => Math.abs(v - pos[k]) < 1e-5), `and starts where -init_pos says (${start.map((v) => v.toFixed(3)).join(', ')})`);
  await a.screenshot({ path: join(outDir, '1-new-body.png') });

  // Select body1 (a click on it) and give it a constant force.
  const h = await a.evaluate(() => window.asgard.graphical.handleScreenPos('body1'));
  await a.mouse.click(h.x, h.y);
  check(await waitFor(() => a.evaluate(() => document.getElementById('selection').textContent === 'selected: body1'), 'selection'),
    'clicking the body selects it');
  await sleep(300);  // the press's re-simulation
  await a.click('#create-force');
  const forceLine = 'force -body body1 -x 0 -y -1 -z 0';
  check(await waitFor(() => everyText(pages, (t) => t.split('\n').includes(forceLine)), 'the force in every viewer'),
    `"${forceLine}" in every language viewer`);
  const forceLines = (await texts([a]))[0].split('\n');
  check(forceLines[forceLines.indexOf(forceLine) - 1].startsWith('force '), 'written after the last force command');
  check(await waitFor(() => b.evaluate(() => window.asgard.graphical.handleList().some((x) => x.id === 'force#2.vector' && x.editable)), 'force handle'),
    'the other tab draws the new force\'s handle');
  // A unit box has unit mass at unit density: y(1) − y(0) = −½·1·1².
  const fall = await waitFor(async () => {
    const d = await b.evaluate(() => {
      const g = window.asgard.graphical, i = g.poses.times.findIndex((t) => Math.abs(t - 1) < 1e-9);
      return i < 0 ? null : g.bodyPosition('body1', i)[1] - g.bodyPosition('body1', 0)[1];
    });
    return d !== null && Math.abs(d + 0.5) < 1e-3;
  }, 'the force in the motion');
  check(fall, 'the re-simulated box falls 0.5 in the first second under the new force');
  // Between frames the pose is the cubic Hermite interpolant of the frames'
  // poses and velocities: exact for this parabola (y0 − t²/2), where the
  // linear mix of the two frames is off by (Δt/2)²/2.
  const mid = await b.evaluate(() => {
    const g = window.asgard.graphical, times = g.poses.times, i = times.findIndex((t) => t >= 0.5);
    const t = (times[i] + times[i + 1]) / 2, y0 = g.bodyPosition('body1', 0)[1];
    const linear = (g.bodyPosition('body1', i)[1] + g.bodyPosition('body1', i + 1)[1]) / 2;
    g.seek(t);
    return { t, dt: times[i + 1] - times[i], y: g.bodies.get('body1').group.position.y, exact: y0 - (t * t) / 2, linear };
  });
  check(Math.abs(mid.y - mid.exact) < 1e-5 && Math.abs(mid.linear - mid.exact) > 0.9 * (mid.dt * mid.dt) / 8,
    `at t = ${mid.t.toFixed(4)}, between frames, the box is drawn at y = ${mid.y.toFixed(6)}, the exact ${mid.exact.toFixed(6)} (linear: ${mid.linear.toFixed(6)})`);
  await a.screenshot({ path: join(outDir, '2-new-force.png') });

  // Link: two clicks, on b3's ball and on the box (handles are not picked
  // while the link waits for its clicks).
  const linksBefore = await b.evaluate(() => window.asgard.graphical.linkLines.children.length);
  await a.click('#create-link');
  check(await a.evaluate(() => document.getElementById('prompt').textContent.includes('first body')), 'the viewer asks for the first body');
  const p3 = await a.evaluate(() => window.asgard.graphical.bodyScreenPos('b3'));
  await a.mouse.click(p3.x, p3.y);
  check(await a.evaluate(() => document.getElementById('prompt').textContent.includes('second body')), 'then for the second');
  await a.screenshot({ path: join(outDir, '3-link-second-click.png') });
  const p1 = await a.evaluate(() => window.asgard.graphical.bodyScreenPos('body1'));
  await a.mouse.click(p1.x, p1.y);
  const linkLine = /^link -body1 b3 -offset1 \{([^}]*)\} -body2 body1 -offset2 \{([^}]*)\} -tightness 10$/m;
  check(await waitFor(() => everyText(pages, (t) => linkLine.test(t)), 'the link in every viewer'),
    'the link is one command in every language viewer');
  const m = linkLine.exec((await texts([b]))[0]);
  const o1 = nums(m[1]), o2 = nums(m[2]);
  // Rounded to 1e-3 per component: within 1e-3 of the surfaces.
  check(Math.abs(Math.hypot(...o1) - 0.5) < 2e-3, `-offset1 {${o1.join(' ')}} is on b3's ball (radius 0.5)`);
  check(Math.abs(Math.max(...o2.map(Math.abs)) - 0.5) < 2e-3, `-offset2 {${o2.join(' ')}} is on the unit box`);
  check(await waitFor(() => b.evaluate((n) => window.asgard.graphical.linkLines.children.length === n + 1, linksBefore), 'link line'),
    'the other tab draws the new link');
  await a.evaluate(() => window.asgard.graphical.seek(2));
  await a.screenshot({ path: join(outDir, '4-new-link.png') });

  // Undo three times: link, force and body go from every view.
  for (const [what, gone] of [
    ['link', (t) => !linkLine.test(t)],
    ['force', (t) => !t.includes(forceLine)],
    ['body', (t) => !bodyLine.test(t)],
  ]) {
    await a.click('#undo');
    check(await waitFor(() => everyText(pages, gone), `undo ${what}`), `Undo removes the ${what} from every language viewer`);
  }
  check(await waitFor(() => b.evaluate(() => !window.asgard.graphical.bodyNames().includes('body1')), 'body gone'),
    'and the body from the other tab\'s picture');
  check((await texts(pages)).every((t) => t === (lines.filter((l) => !bodyLine.test(l)).join('\n'))), 'the text is the original again');
  await b.screenshot({ path: join(outDir, '5-undone.png') });

  // Delete b1: the force on it and both links that name it go too, in
  // every view, as one undo step.
  const original = (await texts([a]))[0];
  const namesB1 = (l) => /^body b1 |^link -body1 b1 |-body2 b1 |^force .*-body b1 /.test(l);
  check(original.split('\n').filter(namesB1).length === 4, 'the pendulum has b1, its force and two links naming it');
  const hb1 = await a.evaluate(() => window.asgard.graphical.handleScreenPos('b1'));
  await a.mouse.click(hb1.x, hb1.y);
  check(await waitFor(() => a.evaluate(() => document.getElementById('selection').textContent === 'selected: b1'), 'b1 selected'), 'clicking b1 selects it');
  await sleep(300);
  await a.click('#delete-element');
  // It asks first, naming what goes with b1; Cancel keeps everything.
  const question = () => a.evaluate(() => !document.getElementById('delete-confirm').hidden && document.querySelector('#delete-confirm .question').textContent);
  check(await waitFor(async () => (await question()) === 'Delete b1 and the 3 elements that name it: link#0, link#1, force#0?', 'the question'),
    `Delete asks first, listing what names b1 ("${await question()}")`);
  await a.click('#delete-confirm .no');
  await sleep(300);
  check((await texts([a]))[0] === original && await a.evaluate(() => document.getElementById('delete-confirm').hidden), 'Cancel deletes nothing');
  await a.click('#delete-element');
  await a.click('#delete-confirm .yes');
  const without = original.split('\n').filter((l) => !namesB1(l)).join('\n');
  check(await waitFor(() => everyText(pages, (t) => t === without), 'b1 deleted everywhere'),
    'Delete removes b1, its force and both links from every language viewer');
  const listed = await waitFor(() => a.evaluate(() => /deleted b1 and what named it: link#0, link#1, force#0/.test(document.getElementById('status').textContent)), 'the status');
  check(listed, `the status lists them: "${await a.evaluate(() => document.getElementById('status').textContent)}"`);
  check(await waitFor(() => b.evaluate(() => !window.asgard.graphical.bodyNames().includes('b1') && window.asgard.graphical.linkLines.children.length === 0), 'b1 gone'),
    'the other tab no longer draws b1 or any link');
  check(await a.evaluate(() => window.asgard.state.diagnostics.filter((d) => d.severity === 'error').length === 0), 'the scene left has no errors');
  await b.screenshot({ path: join(outDir, '6-deleted-b1.png') });
  await a.click('#undo');
  check(await waitFor(() => everyText(pages, (t) => t === original), 'undo delete'), 'one Undo brings b1, its force and links back everywhere');
  check(await waitFor(() => b.evaluate(() => window.asgard.graphical.bodyNames().includes('b1')), 'b1 back'), 'and b1 is drawn again');

  // "Force curve": a trajectory and a force on the selected body that reads
  // it (two commands), drawn with Trajectories shown as the force's arrows
  // from b3 at the points' times; the core's force on b3 is the curve's
  // value (0, −1, 0) at every frame.
  const hb3 = await a.evaluate(() => window.asgard.graphical.handleScreenPos('b3'));
  await a.mouse.click(hb3.x, hb3.y);
  check(await waitFor(() => a.evaluate(() => document.getElementById('selection').textContent === 'selected: b3'), 'b3 selected'), 'clicking b3 selects it');
  await a.click('#create-force-trajectory');
  const curveLine = /^trajectory force_curve1 -points \{\{0 0 -1 0\} \{5 0 -1 0\}\}$/m;
  const curveForce = 'force -body b3 -x force_curve1.x -y force_curve1.y -z force_curve1.z';
  check(await waitFor(() => everyText(pages, (t) => curveLine.test(t) && t.includes(curveForce)), 'the force curve everywhere'),
    `"Force curve" writes the trajectory and "${curveForce}" in every language viewer`);
  await a.check('#toggles input[data-kind="trajectories"]');
  await waitFor(() => a.evaluate(() => window.asgard.graphical.handleList().filter((h) => h.element === 'force_curve1').length === 2), 'its handles');
  const fc = await a.evaluate(() => {
    const g = window.asgard.graphical, times = g.poses.times;
    const tips = g.handleList().filter((h) => h.element === 'force_curve1').map((h) => {
      const raw = g.handles.find((x) => x.id === h.id), f = times.findIndex((x) => Math.abs(x - raw.t) < 1e-9);
      const want = g.bodyPosition('b3', f).map((x, c) => x + raw.value[c] * g.scales.force);
      return { off: f < 0 || !raw.arrow ? Infinity : Math.max(...h.world.map((x, c) => Math.abs(x - want[c]))) };
    });
    const i = window.asgard.state.parameters.filter((p) => p.kind === 'force' && p.param === 'x').findIndex((p) => p.value === 'force_curve1.x');
    const applied = g.poses.forces.map((frame) => frame[i]).filter(Boolean);
    const worst = Math.max(...applied.map((v) => Math.hypot(v[0], v[1] + 1, v[2])));
    return { tips, frames: applied.length, worst, n: times.length };
  });
  // (At the pendulum's force scale, set by its gravity of mass × 9.8, a
  // unit force's arrow is shorter than a handle: its shaft is not drawn.)
  check(fc.tips.length === 2 && fc.tips.every((t) => t.off < 1e-6),
    `its two points are the tips of force arrows from b3 at their times (worst ${Math.max(...fc.tips.map((t) => t.off)).toExponential(1)})`);
  check(fc.frames === fc.n && fc.worst < 1e-9, `the force on b3 is (0, -1, 0) at all ${fc.frames} frames (worst ${fc.worst.toExponential(1)})`);
  await a.screenshot({ path: join(outDir, '7-force-curve.png') });

  // Link to a trajectory: "Trajectory" makes one from b3's start, then
  // Link, a click on b3 and one on that trajectory's last point.
  await a.click('#create-trajectory');
  check(await waitFor(() => a.evaluate(() => window.asgard.graphical.handleList().some((h) => h.id === 'trajectory1.points#1' && h.shown)), 'trajectory1'),
    'Trajectory makes trajectory1, shown with its points');
  // b3 to the middle of the canvas (the panels cover its edges).
  await a.evaluate(() => {
    const g = window.asgard.graphical;
    g.seek(0);
    const d = g.bodies.get('b3').group.position.clone().sub(g.controls.target);
    g.camera.position.add(d);
    g.controls.target.add(d);
    g.controls.update();
    g.seek(0);
  });
  await a.click('#create-link');
  const q3 = await a.evaluate(() => window.asgard.graphical.bodyScreenPos('b3'));
  await a.mouse.click(q3.x, q3.y);
  check(await a.evaluate(() => document.getElementById('prompt').textContent.includes('a trajectory shown')), 'the second prompt offers a trajectory');
  const k1 = await a.evaluate(() => window.asgard.graphical.handleList().find((h) => h.id === 'trajectory1.points#1'));
  await a.mouse.click(k1.x, k1.y);
  const trLink = /^link -body1 b3 -offset1 \{[^}]*\} -trajectory trajectory1 -tightness 10$/m;
  check(await waitFor(() => everyText(pages, (t) => trLink.test(t)), 'the trajectory link everywhere'),
    'a click on the trajectory makes "link -body1 b3 -offset1 {…} -trajectory trajectory1 -tightness 10" in every language viewer');
  check(await waitFor(() => a.evaluate(() => window.asgard.state.diagnostics.filter((d) => d.severity === 'error').length === 0 && window.asgard.graphical.poses), 'simulated'),
    'and the scene has no errors');
  await a.screenshot({ path: join(outDir, '8-trajectory-link.png') });
  check(errors.length === 0, `no script errors in the pages ${errors.join('; ')}`);
});
