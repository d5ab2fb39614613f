// The language viewer's literals in headless Chromium (issue 13, seed 4.2,
// 4.2.1): on handles.al the graphically editable literals are highlighted,
// a read-only one says why on hover, the long point list of a trajectory
// and the long literal of a shape are elided to a widget that expands on
// click and folds again, and the highlight follows a literal a handle
// rewrote.  Screenshots go to OUT_DIR.
import { join } from 'node:path';
import { browserTest, dragHandle, openEditor, waitFor } from './common.mjs';

const [asgard, scene, outDir] = process.argv.slice(2);

const marks = (page) => page.evaluate(() => window.asgard.languageViewers[0].literalMarks());
const elided = (page) => page.evaluate(() => window.asgard.languageViewers[0].elidedRanges());

await browserTest(asgard, scene, 'language viewer', async ({ check, url, context }) => {
  const { page, errors, ok } = await openEditor(context, url, 'spinner');
  check(ok, 'the editor shows handles.al');
  let m = await marks(page);
  const find = (list, info) => list.find((x) => x.info.startsWith(info));
  const pos = find(m, 'spinner -init_pos');
  check(pos && pos.text === '{0 0 0}' && /cm-literal-body/.test(pos.class), `spinner's -init_pos literal is highlighted: ${JSON.stringify(pos)}`);
  for (const what of ['spinner -init_rot', 'spinner -init_dpos', 'force#0 -y', 'link#0 -offset1', 'lightsource#0 -dir', 'simulator -finish'])
    check(find(m, what)?.class.startsWith('cm-literal '), `${what} is highlighted as editable`);
  const ro = find(m, 'computed -init_pos');
  check(ro && ro.class === 'cm-literal-readonly' && ro.text === '[list 4 $h 0]' && /expression/.test(ro.info),
    `the computed -init_pos is marked read-only: ${ro && ro.info}`);
  check(!find(m, 'spinner -shape') && !find(m, 'link#0 -tightness'), 'options with no handle are not highlighted');
  const shown = await page.evaluate(() => document.querySelectorAll('.viewer .cm-literal').length);
  check(shown >= 10, `the highlights are in the page (${shown} marked literals)`);

  // Hover the read-only literal: a tooltip with the reason.
  const box = await page.locator('.viewer [data-param="computed.init_pos"]').first().boundingBox();
  await page.mouse.move(box.x + box.width / 2, box.y + box.height / 2);
  const tipShown = await waitFor(() => page.evaluate(() => !!document.querySelector('.cm-literal-tip')), 'the tooltip');
  const tip = tipShown ? await page.locator('.cm-literal-tip').textContent() : '';
  check(/computed -init_pos is read-only: .*expression/.test(tip), `hovering it says why: "${tip}"`);
  await page.screenshot({ path: join(outDir, '1-highlights-and-reason.png') });

  // Elided lists: the trajectory's points and the brick's faces.
  let e = await elided(page);
  const keys = e.map((x) => x.key).sort();
  check(keys.join(',') === 'brick.desc,path.points', `the long lists are elided: ${keys.join(', ')}`);
  const widget = page.locator('.cm-elided[data-key="path.points"]');
  check((await widget.textContent()).includes('5 points'), `the trajectory's widget counts its points: "${await widget.textContent()}"`);
  const visible = () => page.evaluate(() => document.querySelector('.viewer .cm-content').innerText);
  check(!(await visible()).includes('{0.5 1 0 0}'), 'the elided points are not shown');
  check((await page.evaluate(() => window.asgard.languageViewers[0].text())).includes('{0.5 1 0 0}'), 'but they stay in the text');
  await widget.click();
  const expanded = await waitFor(async () => (await visible()).includes('{0.5 1 0 0}'), 'the expanded points');
  check(expanded && (await page.locator('.cm-expanded').count()) > 0, 'a click expands them, drawn with their own background');
  await page.screenshot({ path: join(outDir, '2-expanded.png') });
  await page.locator('.cm-fold-again[data-key="path.points"]').click();
  check(await waitFor(async () => !(await visible()).includes('{0.5 1 0 0}'), 'folded'), 'the ⊟ elides them again');

  // A handle rewrites a literal: the highlight covers the new text.
  await dragHandle(page, 'spinner.init_pos', 50, 0);
  m = await marks(page);
  const text = await page.evaluate(() => window.asgard.languageViewers[0].text());
  const now = /body spinner [^\n]*-init_pos (\{[^}]*\})/.exec(text)[1];
  const moved = find(m, 'spinner -init_pos');
  check(moved && moved.text === now && now !== '{0 0 0}', `after a drag the highlight covers the new literal ${now}`);
  e = await elided(page);
  check(e.length === 2, 'and the lists are still elided');
  await page.screenshot({ path: join(outDir, '3-after-drag.png') });
  check(errors.length === 0, `no script errors in the page ${errors.join('; ')}`);
});
