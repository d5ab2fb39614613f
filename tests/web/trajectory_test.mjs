// The trajectory editor in headless Chromium (issue 13, seed 4.1.4 and
// Figure 4.4): on trajectory.al, with Trajectories shown, each control point
// of `path` is a handle and the path is drawn as the curve the core
// evaluates; dragging the middle control point rewrites that point of the
// `-points` literal in the language viewer while dragging, the drawn path
// follows it, and after the re-simulation the ball riding the trajectory
// passes through the moved point; Undo puts the point back in one step.  A
// trajectory whose points are computed has read-only handles.  Screenshots go to OUT_DIR.
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
  await page.screenshot({ path: join(outDir, '1-trajectory.png') });

  // Drag the middle control point (t = 1, at the origin) up the screen.
  const before = knotsOf(await text(page));
  check(before && before[2].join(' ') === '1 0 0 0', `the middle point is {${before && before[2].join(' ')}}`);
  const pathBefore = paths.path;
  let during = null;
  await dragHandle(page, 'path.points#2', 0, -80, {
    during: async () => {
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
  check(errors.length === 0, `no script errors in the page ${errors.join('; ')}`);
});
