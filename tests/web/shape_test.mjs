// The shape editor (issue 13, seed Figure 4.3) in headless Chromium on
// tests/web/shape.al: the cube's eight corners are handles on its hull; Add
// vertex and a click outside the cube adds a ninth point, which the hull now
// has, the text's -desc has, and the core's mesh of the body has; dragging it
// into the cube makes it an inside point (drawn so) and the hull a cube
// again; a sphere's surface handle sets its radius; snapping rounds to the
// grid; Delete vertex removes the chosen point; the text follows a drag
// while it lasts, in a second tab's shape editor too; one Undo per change
// (a whole drag); the cube's position handle moves the whole piece.
import { join } from 'node:path';
import { browserTest, openEditor, sleep, waitFor } from './common.mjs';

const [asgard, scene, outDir] = process.argv.slice(2);

await browserTest(asgard, scene, 'shape', async ({ check, url, context }) => {
  const { page, errors, ok } = await openEditor(context, url, 'g');
  check(ok, 'the editor shows the scene');
  await page.click('#shapes-open');
  const list = () => page.evaluate(() => window.asgard.shapes.handleList());
  const desc = () => page.evaluate(() => /shape_set gem -desc \{(.*)\}$/m.exec(window.asgard.languageViewers[0].text())?.[1] ?? '');
  const coreHull = () => page.evaluate(() => {
    const b = window.asgard.graphical.bodies.get('g');
    const m = b && b.meshes.find((x) => !x.userData.sphere);
    if (!m) return null;
    const p = m.geometry.getAttribute('position'), seen = new Set();
    for (let i = 0; i < p.count; ++i) seen.add([p.getX(i), p.getY(i), p.getZ(i)].map((v) => (v + b.centroid.getComponent(0) * 0).toFixed(3)).join(' '));
    return [...seen];
  });
  const stateAfter = async (action) => {
    const n = await page.evaluate(() => window.asgard.stateCount);
    await action();
    return waitFor(() => page.evaluate((k) => window.asgard.stateCount > k, n), 'the state after the change');
  };
  let h = await list();
  const corners = h.filter((x) => x.piece === 0 && typeof x.index === 'number');
  check(corners.length === 8 && corners.every((x) => !x.inside), 'the cube\'s eight corners are handles, all on the hull');
  check(h.some((x) => x.piece === 1 && x.index === 'centre') && h.some((x) => x.piece === 1 && x.index === 'surface'), 'the ball has a centre and a surface handle');
  await page.locator('#shape-editor canvas').screenshot({ path: join(outDir, '1-cube.png') });

  // Add vertex: a click to the right of the cube's right face, in the plane
  // through its centre facing the viewer.
  const right = corners.reduce((a, x) => (x.x > a.x ? x : a));
  const centre = await page.evaluate(() => { const r = window.asgard.shapes.canvas.getBoundingClientRect(); return { x: r.left + r.width / 2, y: r.top + r.height / 2 }; });
  await page.click('#shape-editor .add');
  check(await stateAfter(() => page.mouse.click(right.x + 40, centre.y)), 'a click adds the vertex and updates the scene');
  h = await list();
  const added = h.find((x) => x.piece === 0 && x.index === 8);
  check(!!added && !added.inside, `the ninth point (${added && added.world.map((v) => v.toFixed(2)).join(' ')}) is on the new hull`);
  const text1 = await desc();
  const p9 = added.world.map((v) => Math.round(v * 1e4) / 1e4);
  check(text1.includes(`{${p9.join(' ')}}`) && (text1.match(/\{-?[\d.]+ -?[\d.]+ -?[\d.]+\}/g) || []).length === 9 + 2,
    `the -desc literal has nine vertices (the new one {${p9.join(' ')}}) and the ball's -pos`);
  const hasNinth = async () => { const hull = await coreHull(); return !!hull && hull.length === 9; };
  check(await waitFor(hasNinth, 'the core mesh with nine vertices'), 'the core\'s mesh of the body now has nine vertices');
  await page.locator('#shape-editor canvas').screenshot({ path: join(outDir, '2-added.png') });

  // Drag it into the cube: an inside point, the hull a cube again.  A
  // second tab's shape editor follows the drag as it goes.
  const other = await context.newPage();
  await other.goto(url);
  await waitFor(() => other.evaluate(() => window.asgard.ready), 'the second tab');
  await other.click('#shapes-open');
  const otherNinth = () => other.evaluate(() => window.asgard.shapes.handleList().find((x) => x.piece === 0 && x.index === 8));
  check(await waitFor(async () => !!(await otherNinth()), 'the ninth point in the second tab'), 'the second tab\'s shape editor has the ninth point');
  const before = await page.evaluate(() => window.asgard.stateCount);
  await page.mouse.move(added.x, added.y);
  await page.mouse.down();
  for (let i = 1; i <= 6; ++i) { await page.mouse.move(added.x + ((centre.x - added.x) * i) / 6, added.y + ((centre.y - added.y) * i) / 6); await sleep(20); }
  h = await list();
  check(h.find((x) => x.piece === 0 && x.index === 8).inside, 'dragged into the cube, the point is shown as inside the hull while dragging');
  const moving = h.find((x) => x.piece === 0 && x.index === 8).world.map((v) => Math.round(v * 1e4) / 1e4);
  check(await waitFor(async () => (await desc()).includes(`{${moving.join(' ')}}`), 'the text while dragging'),
    `while dragging, the language viewer's -desc already has the moved point {${moving.join(' ')}}`);
  check(await waitFor(async () => { const o = await otherNinth(); return !!o && o.inside && o.world.every((v, k) => Math.abs(v - moving[k]) < 2e-4); }, 'the second tab during the drag'),
    `while dragging, the second tab's shape editor shows the point where it is, inside the hull (${JSON.stringify((await otherNinth() || {}).world)})`);
  await page.locator('#shape-editor canvas').screenshot({ path: join(outDir, '3-inside.png') });
  await page.mouse.up();
  await waitFor(() => page.evaluate((k) => window.asgard.stateCount > k, before), 'the state after the drag');
  check(await waitFor(async () => { const hull = await coreHull(); return !!hull && hull.length === 8; }, 'the core mesh a cube again'),
    'the core\'s hull is the cube again (the point is inside)');

  // The sphere's surface handle: the radius is its distance from the centre.
  h = await list();
  const surface = h.find((x) => x.piece === 1 && x.index === 'surface');
  await page.check('#shape-editor input.snap');
  await stateAfter(async () => {
    await page.mouse.move(surface.x, surface.y);
    await page.mouse.down();
    for (let i = 1; i <= 4; ++i) { await page.mouse.move(surface.x + 6 * i, surface.y); await sleep(20); }
    await page.mouse.up();
  });
  const radius = /-pos \{0 2 0\} -sphere ([\d.]+)/.exec(await desc());
  const r = radius ? Number(radius[1]) : NaN;
  const snappedOk = h.find((x) => x.piece === 1 && x.index === 'centre') && radius && r > 0.5;
  check(!!snappedOk, `dragging the surface point outward sets -sphere ${radius && radius[1]} (> 0.5)`);
  const after = await list();
  const sphereSurface = after.find((x) => x.piece === 1 && x.index === 'surface').world;
  check(Math.abs(Math.hypot(sphereSurface[0], sphereSurface[1] - 2, sphereSurface[2]) - r) < 1e-3, 'the surface handle is on the new sphere');
  check(await waitFor(() => page.evaluate((rr) => { const b = window.asgard.graphical.bodies.get('g'); const m = b && b.meshes.find((x) => x.userData.sphere); return !!m && Math.abs(m.userData.sphere.radius - rr) < 1e-6; }, r), 'core sphere'),
    'the core\'s sphere has that radius');
  // Snapping: the dragged surface point was rounded to the 0.1 grid (to
  // the 1e-4 the radius is written with).
  check(sphereSurface.every((v) => Math.abs(v * 10 - Math.round(v * 10)) < 1e-3), `with Snap the surface point {${sphereSurface.map((v) => v.toFixed(4)).join(' ')}} is on the 0.1 grid`);

  // Delete vertex: the ninth (chosen by a press) goes.
  h = await list();
  const ninth = h.find((x) => x.piece === 0 && x.index === 8);
  await page.mouse.click(ninth.x, ninth.y);
  await sleep(100);
  check(await stateAfter(() => page.click('#shape-editor .delete')), 'Delete vertex updates the scene');
  const vertices = async () => (await list()).filter((x) => x.piece === 0 && typeof x.index === 'number').length;
  check((await vertices()) === 8 && !(await desc()).includes(`{${p9.join(' ')}}`), 'the point is gone from the editor and the text');

  // Undo: the vertex back, then the radius, then inside/outside moves.
  // Each is waited for in the text itself before the next click: the state
  // count can move for a message of the step before (the deletion's
  // re-simulation), which under a slow build arrives after the click.
  const undone = async (what, ok) => {
    await page.click('#undo');
    const seen = await waitFor(async () => ok(await desc()), what);
    return seen || console.log(`     -desc is {${await desc()}}`) || false;
  };
  check(await undone('the vertex back', async () => (await vertices()) === 9), 'Undo brings the deleted vertex back');
  check(await undone('the radius', (d) => /-pos \{0 2 0\} -sphere 0.5\}/.test(d)), 'the next Undo the radius (the whole drag)');
  check(await undone('the drag into the cube', (d) => d === text1), 'and the next the drag into the cube, in one step');
  await page.locator('#shape-editor canvas').screenshot({ path: join(outDir, '4-undone.png') });

  // The cube's position handle moves the whole piece: -pos changes, the
  // vertices (relative to it) stay, every corner moves by the same amount.
  h = await list();
  const pos = h.find((x) => x.piece === 0 && x.index === 'pos');
  check(!!pos && pos.world.every((v) => Math.abs(v) < 1e-9), 'the cube has a position handle at its -pos {0 0 0}');
  const cornersBefore = h.filter((x) => x.piece === 0 && typeof x.index === 'number').map((x) => x.world);
  const vertexList = (t) => /-pos \{[^}]*\} (-vertices .*?\}\})/.exec(t)?.[1];
  const listBefore = vertexList(await desc());
  await page.uncheck('#shape-editor input.snap');
  check(await stateAfter(async () => {
    await page.mouse.move(pos.x + 30, pos.y + 30);  // off every vertex, then onto the position alone
    const free = await page.evaluate(([x, y]) => {
      const list = window.asgard.shapes.handleList();
      return list.filter((k) => Math.hypot(k.x - x, k.y - y) < 8).map((k) => k.index);
    }, [pos.x, pos.y]);
    check(free.length === 1 && free[0] === 'pos', `only the position handle is under the pointer (${JSON.stringify(free)})`);
    await page.mouse.move(pos.x, pos.y);
    await page.mouse.down();
    for (let i = 1; i <= 4; ++i) { await page.mouse.move(pos.x + 10 * i, pos.y); await sleep(20); }
    await page.mouse.up();
  }), 'dragging the position updates the scene');
  h = await list();
  const moved = h.find((x) => x.piece === 0 && x.index === 'pos').world;
  const cornersAfter = h.filter((x) => x.piece === 0 && typeof x.index === 'number').map((x) => x.world);
  const text2 = await desc();
  check(Math.hypot(...moved) > 0.05 && text2.includes(`-pos {${moved.map((v) => Math.round(v * 1e4) / 1e4).join(' ')}}`),
    `the cube's -pos is the dragged position {${moved.map((v) => v.toFixed(4)).join(' ')}}`);
  check(vertexList(text2) === listBefore, 'its vertices are written as before (relative to -pos)');
  check(cornersAfter.length === cornersBefore.length && cornersAfter.every((c, i) => c.every((v, k) => Math.abs(v - cornersBefore[i][k] - moved[k]) < 1e-6)),
    'every corner moved by the position\'s displacement');
  check(errors.length === 0, `no page errors ${errors.join('; ')}`);
});
