// The language viewer's literals in headless Chromium (issue 13, seed 4.2,
// 4.2.1): on handles.al the graphically editable literals are highlighted,
// a read-only one says why on hover, the long point list of a trajectory
// and the long literal of a shape are elided to a widget that expands on
// click and folds again, and the highlight follows a literal a handle
// rewrote.  Then, with two language viewers, typing not yet sent in viewer
// A survives a drag in the graphical view and an Update from viewer B of
// other lines (both merged into A's text), an overlapping change from B
// marks A as diverged while keeping its typing, Undo in A takes back only
// the typing, and "Take the session's text" ends the divergence.
// Screenshots go to OUT_DIR.
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

  // Unsent typing and session changes made elsewhere.
  const two = await context.newPage();
  const errors2 = [];
  two.on('pageerror', (err) => errors2.push(String(err)));
  await two.goto(`${url}?viewers=2`);
  check(await waitFor(() => two.evaluate(() => window.asgard.ready && window.asgard.languageViewers.length === 2), 'two viewers'),
    'the editor opens with two language viewers');
  const textOf = (i) => two.evaluate((k) => window.asgard.languageViewers[k].text(), i);
  const session = () => two.evaluate(() => window.asgard.text);
  const diverged = (i) => two.evaluate((k) => window.asgard.languageViewers[k].diverged(), i);
  const lineOf = async (i, start) => (await textOf(i)).split('\n').find((l) => l.startsWith(start));
  // Types at the end of the line that starts with `start` in viewer i, with the keyboard.
  const typeAtEnd = async (i, start, text) => {
    const n = (await textOf(i)).split('\n').findIndex((l) => l.startsWith(start));
    await two.evaluate(([k, line]) => {
      const v = window.asgard.languageViewers[k].view;
      v.focus();
      v.dispatch({ selection: { anchor: v.state.doc.line(line).to }, scrollIntoView: true });
    }, [i, n + 1]);
    await two.keyboard.type(text, { delay: 5 });
  };
  // A replacement in viewer i as typing (a CodeMirror input transaction), then its Update.
  const editAndUpdate = async (i, from, to) => {
    const before = await two.evaluate(() => window.asgard.stateCount);
    await two.evaluate(([k, a, b]) => {
      const v = window.asgard.languageViewers[k].view;
      const at = v.state.doc.toString().indexOf(a);
      v.dispatch({ changes: { from: at, to: at + a.length, insert: b }, userEvent: 'input.type' });
    }, [i, from, to]);
    await two.click(`.viewer[data-viewer="${i}"] .update`);
    await waitFor(() => two.evaluate((c) => window.asgard.stateCount > c && !window.asgard.busy, before), 'the Update');
  };
  const typed = ' ;# typed in A';
  await typeAtEnd(0, 'body anchor', typed);
  check((await lineOf(0, 'body anchor')).endsWith(typed) && !(await session()).includes(typed), 'viewer A holds typing not sent');
  const startPos = /body spinner [^\n]*-init_pos (\{[^}]*\})/.exec(await session())[1];
  await dragHandle(two, 'spinner.init_pos', 0, -40);
  const dragged = /body spinner [^\n]*-init_pos (\{[^}]*\})/.exec(await session())[1];
  const a1 = await textOf(0);
  check(dragged !== startPos && a1.includes(`-init_pos ${dragged}`) && a1.includes(typed),
    `after a drag of spinner's position (${startPos} → ${dragged}) viewer A has both the drag and its typing`);
  check((await textOf(1)) === (await session()), 'viewer B (no typing) shows the session\'s text');
  check(!(await diverged(0)), 'A has not diverged (the edits do not overlap)');
  await editAndUpdate(1, '-pos {0 4 4}', '-pos {0 5 4}');
  const a2 = await textOf(0);
  check((await session()).includes('-pos {0 5 4}') && a2.includes('-pos {0 5 4}') && a2.includes(typed) && a2.includes(`-init_pos ${dragged}`),
    'an Update from viewer B of another line reaches A, whose typing stays');
  check(a2 === (await session()).replace('-init_pos {-4 0 0}', `-init_pos {-4 0 0}${typed}`), 'A\'s text is the session\'s plus its typing, nothing else');
  await two.screenshot({ path: join(outDir, '4-merged-typing.png') });

  // The same line, different words: still merged.
  await editAndUpdate(1, '-init_pos {-4 0 0}', '-init_pos {-4 1 0}');
  check((await lineOf(0, 'body anchor')) === `body anchor -shape ball -init_pos {-4 1 0}${typed}`,
    `a change from B in A's typed line but not where A typed is merged: "${await lineOf(0, 'body anchor')}"`);
  // Overlapping: B appends where A typed.
  await editAndUpdate(1, '-init_pos {-4 1 0}', '-init_pos {-4 1 0} ;# from B');
  check((await lineOf(0, 'body anchor')).endsWith(typed) && !(await textOf(0)).includes('from B'), 'an overlapping change leaves A\'s typing as it was');
  check(await diverged(0), 'and A says it has diverged');
  const status = await two.locator('.viewer[data-viewer="0"] .diverged').textContent();
  check(await two.locator('.viewer[data-viewer="0"] .diverged').isVisible() && /diverged.*line 9/.test(status), `A's status: "${status}"`);
  const conflictMarks = () => two.evaluate(() => [...document.querySelectorAll('.viewer[data-viewer="0"] .cm-conflict-line')].map((e) => e.dataset.conflictLine));
  check((await conflictMarks()).join(',') === '9', `and A marks line 9 in its text (${(await conflictMarks()).join(',')})`);
  await editAndUpdate(1, '-finish 2', '-finish 2.5');
  check((await textOf(0)).includes('-finish 2.5') && (await diverged(0)), 'while diverged, changes elsewhere still reach A');
  await two.screenshot({ path: join(outDir, '5-diverged.png') });

  // Undo in A takes back its typing (only), then the session's text is there but for the divergence.
  await two.evaluate(() => window.asgard.languageViewers[0].view.focus());
  for (let k = 0; k < 10 && (await textOf(0)).includes(typed); ++k) await two.keyboard.press('Control+z');
  const a3 = await textOf(0);
  check(!a3.includes(typed) && a3.includes('-finish 2.5') && a3.includes(`-init_pos ${dragged}`), 'Undo in A removes its typing and keeps the session\'s changes');
  await two.click('.viewer[data-viewer="0"] .take-session');
  check((await textOf(0)) === (await session()) && !(await diverged(0)) && !(await two.locator('.viewer[data-viewer="0"] .diverged').isVisible()),
    '"Take the session\'s text" shows the session\'s text and ends the divergence');
  check((await conflictMarks()).length === 0, 'and the conflict mark is gone');
  check(errors2.length === 0, `no script errors in the two-viewer page ${errors2.join('; ')}`);
});
