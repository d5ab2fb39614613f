// The Asgard editor end to end in headless Chromium (issue 13): the seed
// pendulum in two tabs (the first with two language viewers); dragging b3's
// position handle changes `-init_pos` in every language viewer while
// dragging and re-simulates on release; a new body line, Update, shows the
// body in both tabs; an error is marked at its line while the old scene stays
// shown; Undo restores the text.  Ctrl+Z in a language viewer undoes its
// unsent typing, then is the session's Undo (text and picture), Ctrl+Shift+Z
// its Redo.  Screenshots go to OUT_DIR.
import { readFileSync } from 'node:fs';
import { join } from 'node:path';
import { browserTest, sleep, waitFor } from './common.mjs';
import { formatNumber } from '../../web/src/echo.js';

const [asgard, scene, outDir] = process.argv.slice(2);

const b3Pos = (text) => (/body b3 [^\n]*-init_pos \{([^}]*)\}/.exec(text) || [])[1];
const viewerTexts = (page) => page.evaluate(() => window.asgard.languageViewers.map((v) => v.text()));

await browserTest(asgard, scene, 'editor', async ({ check, url, context }) => {
  const a = context.pages()[0] ?? await context.newPage();
  const b = await context.newPage();
  const errors = [];
  for (const p of [a, b]) p.on('pageerror', (e) => errors.push(String(e)));
  await a.goto(`${url}?viewers=2`);
  await b.goto(url);
  for (const [p, name] of [[a, 'first'], [b, 'second']])
    check(await waitFor(() => p.evaluate(() => window.asgard.ready && window.asgard.graphical.bodyNames().includes('b3'))),
      `the ${name} tab shows the pendulum's bodies`);
  await a.screenshot({ path: join(outDir, '1-open.png') });

  // The pose stream's overlays (what the document view's WebGL player draws):
  // each link's ends on its bodies as the poses place them (rods centred on
  // their centres of mass, so `-offset1 {5 0 0}` is p + q·(5 0 0)), and each
  // force's arrow at its body's centre, (0, -10·mass, 0) = (0, -100, 0).
  const stream = await a.evaluate(() => {
    const p = window.asgard.graphical.poses;
    return { names: p.bodies, poses: p.poses, links: p.links, arrows: p.arrows, length: p.arrow_length, n: p.times.length };
  });
  const rotate = (q, v) => {  // q = [x y z w]
    const u = q.slice(0, 3), c = (a, b) => [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
    const t = c(u, v).map((x) => 2 * x), ut = c(u, t);
    return v.map((x, k) => x + q[3] * t[k] + ut[k]);
  };
  const bodyPoint = (f, name, offset) => {
    const k = stream.names.indexOf(name), pose = stream.poses[f].slice(7 * k, 7 * k + 7);
    return rotate(pose.slice(3), offset).map((x, i) => x + pose[i]);
  };
  let worst = 0;
  const far = (u, v) => { worst = Math.max(worst, ...u.map((x, i) => Math.abs(x - v[i]))); };
  for (const f of [0, Math.floor(stream.n / 2), stream.n - 1]) {
    const [l1, l2] = [stream.links[f].slice(0, 6), stream.links[f].slice(6, 12)];
    far(l1.slice(0, 3), bodyPoint(f, 'b1', [5, 0, 0]));
    far(l1.slice(3), [0, 0, 0]);
    far(l2.slice(0, 3), bodyPoint(f, 'b2', [5, 0, 0]));
    far(l2.slice(3), bodyPoint(f, 'b1', [-5, 0, 0]));
    far(stream.arrows[f].slice(0, 3), bodyPoint(f, 'b1', [0, 0, 0]));
    far(stream.arrows[f].slice(3, 6), [0, -100, 0]);
    far(stream.arrows[f].slice(9), [0, -100, 0]);
  }
  check(stream.links.length === stream.n && stream.links.every((l) => l.length === 12) && stream.arrows.every((l) => l.length === 12) &&
    stream.length > 0 && worst < 1e-4,
  `the pose stream has both links' ends and both forces' arrows in every frame, where the poses put them (worst ${worst.toExponential(1)})`);
  const original = b3Pos((await viewerTexts(a))[0]);
  check(original === '10.1 -17 0', `b3 starts at -init_pos {${original}}`);
  const startPos = await a.evaluate(() => window.asgard.graphical.bodyPosition('b3'));

  // Drag b3's handle 120 px to the right, in steps.
  const h = await a.evaluate(() => window.asgard.graphical.handleScreenPos('b3'));
  check(h !== null, 'b3 has a position handle');
  await a.mouse.move(h.x, h.y);
  await a.mouse.down();
  for (let i = 1; i <= 6; ++i) { await a.mouse.move(h.x + 10 * i, h.y - 3 * i); await sleep(40); }
  const moving = await waitFor(async () => {
    const ta = await viewerTexts(a), tb = await viewerTexts(b);
    return [...ta, ...tb].every((t) => b3Pos(t) && b3Pos(t) !== original);
  }, 'the dragged value in every language viewer');
  const during = [...await viewerTexts(a), ...await viewerTexts(b)].map(b3Pos);
  check(moving, `while dragging, -init_pos changed in all three language viewers: ${during.join(' | ')}`);
  check(new Set(during).size === 1, 'every language viewer shows the same value');
  await a.screenshot({ path: join(outDir, '2-dragging.png') });
  for (let i = 7; i <= 12; ++i) { await a.mouse.move(h.x + 10 * i, h.y - 3 * i); await sleep(30); }
  await a.mouse.up();
  const released = await waitFor(async () => {
    const pa = await a.evaluate(() => window.asgard.graphical.bodyPosition('b3'));
    const pb = await b.evaluate(() => window.asgard.graphical.bodyPosition('b3'));
    return Math.abs(pa[0] - startPos[0]) > 0.5 && Math.abs(pb[0] - startPos[0]) > 0.5;
  }, 'the re-simulated motion');
  const after = b3Pos((await viewerTexts(b))[0]);
  check(released, `on release the motion is re-simulated and shown in both tabs (b3 now starts at {${after}})`);
  await a.evaluate(() => window.asgard.graphical.seek(1.5));
  await a.screenshot({ path: join(outDir, '3-after-drag.png') });

  // One history: typing not yet sent is undone in its viewer alone (Ctrl+Z,
  // no session change); the next Ctrl+Z is the session's Undo — the drag's
  // value leaves every language viewer and b3 starts where it did in both
  // tabs' pictures — and Ctrl+Shift+Z (Redo) brings the drag back.
  const dragged = b3Pos((await viewerTexts(b))[0]);
  const startOf = (p) => p.evaluate(() => { window.asgard.graphical.seek(0); return window.asgard.graphical.bodyPosition('b3'); });
  const startsAt = async (want) => {
    for (const p of [a, b]) {
      const q = await startOf(p);
      if (Math.hypot(q[0] - want[0], q[1] - want[1], q[2] - want[2]) > 1e-6) return false;
    }
    return true;
  };
  const everyB3 = async (want) => [...await viewerTexts(a), ...await viewerTexts(b)].every((t) => b3Pos(t) === want);
  const draggedStart = await startOf(a);
  const inB = b.locator('.viewer[data-viewer="0"] .cm-content');
  await inB.click();
  await b.keyboard.press('Control+End');
  const statesBefore = await b.evaluate(() => window.asgard.stateCount);
  await b.keyboard.insertText('# a note, not sent\n');
  await b.keyboard.press('Control+z');
  const local = await waitFor(async () => !(await viewerTexts(b))[0].includes('a note'), 'the typing undone');
  check(local && await everyB3(dragged) && (await b.evaluate(() => window.asgard.stateCount)) === statesBefore,
    'Ctrl+Z first undoes typing not yet sent, in its viewer alone (the session is untouched)');
  await b.keyboard.press('Control+z');
  check(await waitFor(() => everyB3(original), 'the session undo'),
    `the next Ctrl+Z is the session's Undo: -init_pos {${original}} again in all three language viewers`);
  check(await waitFor(() => startsAt(startPos), 'b3 back in the pictures'), `and b3 starts at (${startPos}) again in both tabs' pictures`);
  await a.screenshot({ path: join(outDir, '3b-undone-by-ctrl-z.png') });
  await b.keyboard.press('Control+Shift+KeyZ');
  check(await waitFor(() => everyB3(dragged), 'the session redo'), `Ctrl+Shift+Z redoes the drag: {${dragged}} in every viewer`);
  check(await waitFor(() => startsAt(draggedStart), 'b3 dragged in the pictures'), `and b3 starts where it was dragged to (${draggedStart})`);

  // The drag's local echo (web/src/echo.js): with tab a's messages held
  // back for 1.5 s before they leave, a's language viewers show the dragged
  // value at once while b's (which only the session's text reaches) still
  // show the old one; then the session writes the same characters, and on
  // release every viewer of both tabs has the session's text.
  const cases = [[0, '0'], [1e6, '1e+06'], [123456, '123456'], [0.001, '0.001'], [1e-4, '1e-04'], [1.5e-5, '1.5e-05'],
    [100, '100'], [1e5, '1e+05'], [-2.5, '-2.5'], [1e21, '1e+21'], [1.2345e-7, '1.2345e-07'], [0.1, '0.1'], [123.456, '123.456'],
    [-1e-4, '-1e-04'], [5e-324, '5e-324'], [1.7976931348623157e308, '1.7976931348623157e+308'],
    [12345678901234567890, '12345678901234567168'], [0.30000000000000004, '0.30000000000000004'], [1e15, '1e+15'],
    [1234567, '1234567'], [12345600, '12345600'], [-10.125, '-10.125']];
  const misformatted = cases.filter(([v, want]) => formatNumber(v) !== want).map(([v, want]) => `${v}: ${formatNumber(v)}, not ${want}`);
  check(misformatted.length === 0, `the echo writes numbers as the session does (std::to_chars): ${misformatted.join('; ') || 'all 22 cases'}`);
  await a.evaluate(() => {
    const ws = window.asgard.conn.ws, send = ws.send.bind(ws);
    window.sendUnheld = send;
    ws.send = (d) => setTimeout(() => send(d), 1500);  // in order: equal delays
  });
  const hEcho = await a.evaluate(() => window.asgard.graphical.handleScreenPos('b3'));
  const statesA = await a.evaluate(() => window.asgard.stateCount);
  await a.mouse.move(hEcho.x, hEcho.y);
  await a.mouse.down();
  await a.mouse.move(hEcho.x + 25, hEcho.y + 10);
  const echoed = (await viewerTexts(a)).map(b3Pos), stillB = (await viewerTexts(b)).map(b3Pos);
  check(echoed.every((v) => v && v !== dragged && v === echoed[0]) && stillB.every((v) => v === dragged),
    `while the edit is held back, tab a's viewers show the dragged value at once ({${echoed.join('} {')}}) and tab b's still {${stillB.join('} {')}}`);
  const reached = await waitFor(async () => (await viewerTexts(b)).every((t) => b3Pos(t) !== dragged), 'the held edit in tab b', 10000);
  const inB2 = (await viewerTexts(b)).map(b3Pos);
  check(reached && inB2.every((v) => v === echoed[0]), `the session wrote the same characters: {${inB2.join('} {')}} in tab b`);
  await a.mouse.up();
  const settled = await waitFor(async () => (await a.evaluate(() => window.asgard.stateCount)) > statesA, 'the re-simulation after the echoed drag');
  const sessionText = await a.evaluate(() => window.asgard.text);
  const all = [...await viewerTexts(a), ...await viewerTexts(b)];
  check(settled && all.every((t) => t === sessionText) && !(await a.evaluate(() => window.asgard.echo)),
    'after release every language viewer of both tabs has the session\'s text, and the echo is over');
  await a.evaluate(() => { window.asgard.conn.ws.send = window.sendUnheld; });

  // Type a new body, Update in the second language viewer of the first tab.
  const editor = a.locator('.viewer[data-viewer="1"] .cm-content');
  await editor.click();
  await a.keyboard.press('Control+End');
  await a.keyboard.insertText('\nbody b4 -shape ss1 -init_pos {0 8 0} -init_dpos {0 0 0} -ct 1\n');
  await a.locator('.viewer[data-viewer="1"] button.update').click();
  const added = await waitFor(async () =>
    (await a.evaluate(() => window.asgard.graphical.bodyNames().includes('b4'))) &&
    (await b.evaluate(() => window.asgard.graphical.bodyNames().includes('b4'))), 'b4 in both tabs');
  check(added, 'after Update the new body b4 is shown in the graphical viewers of both tabs');
  check((await viewerTexts(b))[0].includes('body b4 '), 'the other tab\'s language viewer has the new line');
  await a.evaluate(() => window.asgard.graphical.seek(0));
  await a.screenshot({ path: join(outDir, '4-new-body.png') });

  // An error: marked at its line, the last good scene stays.
  await editor.click();
  await a.keyboard.press('Control+End');
  await a.keyboard.insertText('body b5 -shape no_such_shape -init_pos {0 0 0}\n');
  const errorLine = (await viewerTexts(a))[1].split('\n').findIndex((l) => l.startsWith('body b5')) + 1;
  await a.locator('.viewer[data-viewer="1"] button.update').click();
  const marked = await waitFor(() => a.evaluate((line) =>
    [...document.querySelectorAll('.viewer .cm-error-line')].some((e) => e.dataset.errorLine === String(line)), errorLine),
    'the error line mark');
  const messages = await a.locator('.viewer[data-viewer="0"] .errors').textContent();
  check(marked, `the error is marked at line ${errorLine}: ${messages}`);
  const bodies = await a.evaluate(() => window.asgard.graphical.bodyNames());
  check(bodies.includes('b4') && !bodies.includes('b5'), `the last good scene stays shown (${bodies.join(' ')})`);
  const markedB = await waitFor(() => b.evaluate(() => document.querySelectorAll('.cm-error-line').length > 0), 'error in tab 2');
  check(markedB, 'the error is marked in the other tab too');
  await a.screenshot({ path: join(outDir, '5-error.png') });

  // Undo: the text without the faulty line, errors gone.
  await a.locator('#undo').click();
  const undone = await waitFor(async () => [...await viewerTexts(a), ...await viewerTexts(b)]
    .every((t) => !t.includes('no_such_shape') && t.includes('body b4 ')), 'undo in every viewer');
  check(undone, 'Undo restores the text in every language viewer');
  check(await waitFor(() => a.evaluate(() => document.querySelectorAll('.cm-error-line').length === 0), 'marks cleared'),
    'and the error mark is gone');
  await a.screenshot({ path: join(outDir, '6-undo.png') });

  // Save writes the session's text to the scene file; Revert drops local typing.
  await b.locator('.viewer[data-viewer="0"] button.save').click();
  const saved = await waitFor(() => {
    const t = readFileSync(scene, 'utf8');
    return t.includes('body b4 ') && !t.includes('no_such_shape') && b3Pos(t) !== original;
  }, 'the saved file');
  check(saved, 'Save writes the edited scene to the file');
  await editor.click();
  await a.keyboard.press('Control+End');
  await a.keyboard.insertText('# typed, then reverted\n');
  await a.locator('.viewer[data-viewer="1"] button.revert').click();
  check(!(await viewerTexts(a))[1].includes('then reverted'), 'Revert restores the session\'s text');
  check(errors.length === 0, `no script errors in the pages ${errors.join('; ')}`);
});
