// The control panel and display controls in headless Chromium (issue 13,
// seed 4.1): the time range and rtol fields edit the `simulator` command
// through the session (the text changes and the motion is simulated again
// over the new range); a bad value is refused with a message; the Lines
// style draws no faces; the element-type toggles hide bodies and handles.
// Screenshots go to OUT_DIR.
import { join } from 'node:path';
import { browserTest, openEditor, sleep, waitFor } from './common.mjs';

const [asgard, scene, outDir] = process.argv.slice(2);

const simLine = (page) => page.evaluate(() => window.asgard.languageViewers[0].text().split('\n').find((l) => l.startsWith('simulator')));
// Pixels of the canvas that are neither white nor near-white, and how many
// of those are dark (edges drawn in grey/black).
const ink = (page) => page.evaluate(() => {
  const c = document.getElementById('canvas');
  const s = document.createElement('canvas');
  s.width = c.width; s.height = c.height;
  const g = s.getContext('2d');
  g.drawImage(c, 0, 0);
  const d = g.getImageData(0, 0, s.width, s.height).data;
  let n = 0;
  for (let i = 0; i < d.length; i += 4) if (d[i] + d[i + 1] + d[i + 2] < 720) ++n;
  return n;
});

async function setField(page, id, value) {
  await page.fill(`#${id}`, value);
  await page.press(`#${id}`, 'Enter');
}

await browserTest(asgard, scene, 'control panel', async ({ check, url, context }) => {
  const { page, errors, ok } = await openEditor(context, url, 'spinner');
  check(ok, 'the editor shows handles.al');
  const fields = await page.evaluate(() => ['sim-start', 'sim-finish', 'sim-rtol'].map((id) => document.getElementById(id).value));
  check(fields[0] === '0' && fields[1] === '2' && fields[2] === '', `the fields show the simulator's options: ${JSON.stringify(fields)}`);

  // -finish 3: the text changes and the motion covers [0, 3].
  await setField(page, 'sim-finish', '3');
  const longer = await waitFor(async () => /-finish 3\b/.test(await simLine(page)) &&
    (await page.evaluate(() => window.asgard.graphical.poses.t1)) === 3, 'the longer motion');
  check(longer, `-finish 3 is written and simulated: "${await simLine(page)}"`);
  check(!/-start/.test(await simLine(page)), 'an option left at its default is not written');
  // -rtol: not written yet, so appended to the command.
  await setField(page, 'sim-rtol', '1e-4');
  const rtolOf = (line) => Number((/-rtol (\S+)/.exec(line) || [])[1]);
  const rtol = await waitFor(async () => rtolOf(await simLine(page)) === 1e-4, 'the rtol option');
  check(rtol, `-rtol is appended: "${await simLine(page)}"`);
  // A bad value: refused, the text unchanged.
  await waitFor(() => page.evaluate(() => !window.asgard.busy), 'the simulation of the new rtol');
  const before = await simLine(page);
  await setField(page, 'sim-finish', 'soon');
  await sleep(300);
  const status = await page.locator('#status').textContent();
  check(/not a number/.test(status) && (await simLine(page)) === before, `a bad value is refused: "${status}"`);
  await setField(page, 'sim-finish', '3');
  await page.screenshot({ path: join(outDir, '1-panel.png') });

  // Styles: lines draw far fewer pixels than shaded faces.
  const shaded = await ink(page);
  await page.selectOption('#style', 'lines');
  await sleep(100);
  const lines = await ink(page);
  check(lines < shaded * 0.7, `the Lines style draws edges only (${lines} inked pixels against ${shaded} shaded)`);
  await page.screenshot({ path: join(outDir, '2-lines.png') });
  await page.selectOption('#style', 'shaded');

  // Toggles: bodies off, handles off.
  await page.uncheck('#toggles input[data-kind="bodies"]');
  const bodiesHidden = await page.evaluate(() => [...window.asgard.graphical.bodies.values()].every((b) => !b.group.visible));
  await page.uncheck('#toggles input[data-kind="handles"]');
  const handles = await page.evaluate(() => window.asgard.graphical.handleList());
  const positionHidden = handles.filter((h) => h.kind === 'position').every((h) => !h.shown);
  const forcesShown = handles.filter((h) => h.kind === 'force').every((h) => h.shown);
  check(bodiesHidden, 'Bodies off hides every body');
  check(positionHidden && forcesShown, 'Handles off hides position and rotation handles and keeps force arrows');
  const empty = await ink(page);
  check(empty < shaded * 0.5, `with bodies and handles hidden little is drawn (${empty} inked pixels)`);
  await page.screenshot({ path: join(outDir, '3-toggles.png') });
  // Hidden handles cannot be picked.
  const pos = await page.evaluate(() => {
    const g = window.asgard.graphical;
    return g.toScreen(g.handles.find((h) => h.id === 'spinner.init_pos').mesh.position);
  });
  const text = await page.evaluate(() => window.asgard.languageViewers[0].text());
  await page.mouse.move(pos.x, pos.y);
  await page.mouse.down();
  await page.mouse.move(pos.x + 40, pos.y, { steps: 4 });
  await page.mouse.up();
  await sleep(300);
  check(await page.evaluate(() => window.asgard.languageViewers[0].text()) === text, 'a hidden handle cannot be dragged');
  await page.check('#toggles input[data-kind="bodies"]');
  await page.check('#toggles input[data-kind="handles"]');
  check(await page.evaluate(() => [...window.asgard.graphical.bodies.values()].every((b) => b.group.visible)), 'and they come back');
  check(errors.length === 0, `no script errors in the page ${errors.join('; ')}`);
});
