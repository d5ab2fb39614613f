// Handles of the graphical viewer in headless Chromium (issue 13, seed
// 4.1.2–4.1.8): on handles.al, every kind is drawn — read-only ones as such,
// saying why on hover — and dragging each editable one rewrites its literal
// in the language viewer through the session while a label shows the value:
// initial rotation, velocity, angular velocity, a constant force's tip, a
// link end held on its body's surface (and off it with Shift), a light's
// direction.  Screenshots go to OUT_DIR.
import { join } from 'node:path';
import { browserTest, dragHandle, handle, openEditor, sleep, waitFor } from './common.mjs';

const [asgard, scene, outDir] = process.argv.slice(2);

const text = (page) => page.evaluate(() => window.asgard.languageViewers[0].text());
// The numbers of `-option {…}` (or `-option N`) on the line of `command`.
const literal = (t, command, option) => {
  const line = t.split('\n').find((l) => l.startsWith(command));
  const m = line && new RegExp(`-${option} (\\{[^}]*\\}|\\S+)`).exec(line);
  return m ? m[1].replace(/[{}]/g, ' ').trim().split(/\s+/).map(Number) : null;
};
const label = (page) => page.evaluate(() => document.getElementById('label').textContent);

await browserTest(asgard, scene, 'handle', async ({ check, url, context }) => {
  const { page, errors, ok } = await openEditor(context, url, 'spinner');
  check(ok, 'the editor shows handles.al');
  const list = await page.evaluate(() => window.asgard.graphical.handleList());
  const byId = new Map(list.map((h) => [h.id, h]));
  const expect = [
    ['spinner.init_pos', true], ['spinner.init_rot', true], ['spinner.init_dpos', true], ['spinner.init_drot', true],
    ['anchor.init_dpos', true], ['computed.init_pos', false], ['force#0.vector', true], ['force#1.vector', false],
    ['link#0.offset1', true], ['link#0.offset2', true], ['lightsource#0.pos', true], ['lightsource#0.dir', true],
  ];
  for (const [id, editable] of expect)
    check(byId.has(id) && byId.get(id).editable === editable && byId.get(id).shown,
      `handle ${id} is drawn, ${editable ? 'editable' : 'read-only'}${byId.has(id) && byId.get(id).reason ? ` (${byId.get(id).reason})` : ''}`);
  check(byId.get('force#1.vector')?.arrow, 'the read-only force is drawn as its evaluated vector');
  await page.screenshot({ path: join(outDir, '1-handles.png') });

  // Read-only: the reason on hover, and pressing it edits nothing.
  const computed = byId.get('computed.init_pos');
  const before = await text(page);
  await page.mouse.move(computed.x, computed.y);
  await waitFor(async () => (await label(page)).includes('read-only'), 'the read-only label');
  const hover = await label(page);
  check(/computed -init_pos is read-only: .*expression/.test(hover), `hovering a read-only handle says why: "${hover}"`);
  await page.screenshot({ path: join(outDir, '2-read-only-hover.png') });
  await page.mouse.down();
  await page.mouse.move(computed.x + 40, computed.y);
  await page.mouse.up();
  await sleep(200);
  check(await text(page) === before, 'dragging a read-only handle leaves the text alone');

  // Velocity: its tip dragged to the right makes x larger.
  const lastX = () => page.evaluate(() => {
    const g = window.asgard.graphical;
    return g.bodyPosition('spinner', g.poses.times.length - 1)[0];
  });
  const x2 = await lastX();
  await dragHandle(page, 'spinner.init_dpos', 60, 0, {
    during: async () => {
      const l = await label(page);
      check(/^spinner -init_dpos \{/.test(l), `while dragging, the label shows the value: "${l}"`);
      await page.screenshot({ path: join(outDir, '3-dragging-velocity.png') });
    },
  });
  let t = await text(page);
  const dpos = literal(t, 'body spinner', 'init_dpos');
  check(dpos && dpos[0] > 1.2, `-init_dpos grew along x: {${dpos}}`);
  const x2after = await lastX();
  check(x2after > x2 + 0.2, `the re-simulated spinner goes further: x(2) = ${x2.toFixed(3)} → ${x2after.toFixed(3)}`);

  // Angular velocity: dragged up.
  await dragHandle(page, 'spinner.init_drot', 0, -50);
  t = await text(page);
  const drot = literal(t, 'body spinner', 'init_drot');
  check(drot && (Math.abs(drot[0]) > 0.05 || Math.abs(drot[1] - 0) > 0.05 || Math.abs(drot[2] - 2) > 0.05) && drot.length === 3,
    `-init_drot changed: {${drot}}`);

  // Rotation: the knob dragged around the body turns it about the view axis.
  const q0 = await page.evaluate(() => window.asgard.graphical.bodyQuaternion('spinner'));
  const pos = await handle(page, 'spinner.init_pos');
  const knob = await handle(page, 'spinner.init_rot');
  // A quarter turn on the screen: the knob to where its spoke points turned by 90°.
  const [sx, sy] = [knob.x - pos.x, knob.y - pos.y];
  await dragHandle(page, 'spinner.init_rot', pos.x + sy - knob.x, pos.y - sx - knob.y, { steps: 10 });
  t = await text(page);
  const rot = literal(t, 'body spinner', 'init_rot');
  // The re-simulated motion arrives after the drag ends (later on a slow or
  // sanitized build): wait for it, up to 10 s.
  const turnedFrom = (q) => Math.abs(q0.reduce((s, v, k) => s + v * q[k], 0));
  let q1 = q0;
  for (let i = 0; i < 100 && turnedFrom(q1) >= 0.995; ++i) {
    if (i > 0) await page.waitForTimeout(100);
    q1 = await page.evaluate(() => window.asgard.graphical.bodyQuaternion('spinner'));
  }
  const dot = turnedFrom(q1);
  check(rot && rot.length === 3 && Math.hypot(...rot) > 0.6, `-init_rot turned, still a rotation vector: {${rot}}`);
  check(dot < 0.995, `the re-simulated start is turned (|q0·q1| = ${dot.toFixed(4)})`);

  // A constant force's tip dragged down: its -y grows more negative.
  await dragHandle(page, 'force#0.vector', 0, 50);
  t = await text(page);
  const fy = literal(t, 'force -body anchor', 'y');
  check(fy && fy[0] < -2.2, `force -body anchor -y is now ${fy}`);

  // A link end dragged over its body stays on the brick's surface.
  const brick = await page.evaluate(() => window.asgard.graphical.handleList().find((h) => h.id === 'spinner.init_pos'));
  const end = await handle(page, 'link#0.offset1');
  await dragHandle(page, 'link#0.offset1', (brick.x - end.x) * 0.6, (brick.y - end.y) * 0.6 + 4, {
    during: () => page.screenshot({ path: join(outDir, '4-dragging-link-end.png') }),
  });
  t = await text(page);
  const off = literal(t, 'link -body1 spinner', 'offset1');
  const onSurface = off && Math.abs(Math.max(Math.abs(off[0]) / 1, Math.abs(off[1]) / 0.5, Math.abs(off[2]) / 0.5) - 1) < 0.01;
  check(onSurface && Math.abs(off[0] - 1) > 0.05, `the link end moved and stayed on the brick's surface: {${off}}`);
  // With Shift it leaves the surface.
  await dragHandle(page, 'link#0.offset1', 0, -70, { shift: true });
  t = await text(page);
  const free = literal(t, 'link -body1 spinner', 'offset1');
  check(free && Math.max(Math.abs(free[0]) / 1, Math.abs(free[1]) / 0.5, Math.abs(free[2]) / 0.5) > 1.2,
    `with Shift held it moves off the surface: {${free}}`);

  // A directional light's direction.
  await dragHandle(page, 'lightsource#0.dir', 40, 0);
  t = await text(page);
  const dir = literal(t, 'lightsource', 'dir');
  check(dir && dir[0] > 0.1, `the light's -dir turned towards +x: {${dir}}`);
  await page.screenshot({ path: join(outDir, '5-after-drags.png') });
  check(errors.length === 0, `no script errors in the page ${errors.join('; ')}`);
});
