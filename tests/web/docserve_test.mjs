// `dochost serve` on the memo (issue 13): the editor's requests and the
// document view's renditions go to one asgard-core per animation — the
// medium plugin's node.  An edit through the editor's WebSocket, then a
// recompute, changes the picture the document view gets from GET /frame;
// a second view (the document page's socket) hears the new motion; through
// it all dochost runs exactly one asgard-core, and after that slave is
// killed the next action starts one new slave that has the edited text.
// Node (its WebSocket, Node 20's --experimental-websocket); then, where
// Chromium is, the document view's toolbar in the browser.
import { createHash } from 'node:crypto';
import { existsSync, readFileSync, readdirSync } from 'node:fs';
import { join } from 'node:path';
import { checker, launchBrowser, startStudio, sleep, waitFor } from './common.mjs';

const [dochost, doc, outDir] = process.argv.slice(2);
const { check, failures } = checker();
const { url, port, proc } = await startStudio(dochost, doc, 'serve');

// The live asgard-core children of the server.
function slaves() {
  const out = [];
  for (const name of readdirSync('/proc')) {
    if (!/^\d+$/.test(name)) continue;
    let stat;
    try { stat = readFileSync(`/proc/${name}/stat`, 'latin1'); } catch { continue; }
    const close = stat.lastIndexOf(')');
    const comm = stat.slice(stat.indexOf('(') + 1, close);
    const [state, ppid] = stat.slice(close + 2).split(' ');
    if (comm === 'asgard-core' && Number(ppid) === proc.pid && state !== 'Z') out.push(Number(name));
  }
  return out;
}

async function frame(t, handles = 0) {
  const r = await fetch(`${url}frame?a=0&t=${t}&handles=${handles}`);
  return { status: r.status, live: r.headers.get('x-asgard-live'), caption: r.headers.get('x-asgard-status'),
    interval: r.headers.get('x-asgard-interval'), type: r.headers.get('content-type'),
    bytes: Buffer.from(await r.arrayBuffer()) };
}

// One WebSocket view of animation 0: call(method, params) → the answer;
// `events` collects what the server broadcasts.
async function view() {
  const ws = new WebSocket(`ws://127.0.0.1:${port}/ws?a=0`);
  await new Promise((resolve, reject) => { ws.onopen = resolve; ws.onerror = reject; });
  const pending = new Map(), events = [];
  let id = 0;
  ws.onmessage = (m) => {
    const d = JSON.parse(m.data);
    if (d.id && pending.has(d.id)) { pending.get(d.id)(d); pending.delete(d.id); } else events.push(d);
  };
  const call = (method, params = {}) => new Promise((resolve) => {
    const n = ++id; pending.set(n, resolve); ws.send(JSON.stringify({ id: n, method, params }));
  });
  return { ws, call, events };
}

try {
  const page = await (await fetch(url)).text();
  check(page.includes('<figure class="rendition" data-a="0">') && page.includes('class="recompute"'),
    'the document view shows the animation as a rendition with the host\'s toolbar');
  const first = await frame(1);
  check(first.status === 200 && first.type === 'image/png' && first.live === '1',
    `GET /frame draws a live PNG (${first.status}, ${first.type}, live ${first.live}: ${first.caption})`);
  check(first.interval === '0 3', `the rendition says its interval (${first.interval})`);
  check((await fetch(`${url}frame?a=0&t=abc`)).status === 400, 'a frame at a time that is not a number is refused (400)');
  check((await fetch(`${url}frame?a=7&t=0`)).status === 404, 'a frame of an animation the document does not have is 404');
  const before = slaves();
  check(before.length === 1, `one asgard-core for the document view (${before.length})`);

  const editor = await view(), documentView = await view();
  const opened = await editor.call('open');
  check(opened.result && opened.result.state.text.includes('-init_pos {1 0 0}'),
    'the editor opens the animation\'s scene');
  const edit = await editor.call('set_parameter', { element: 'b3', param: 'init_pos', values: [1, -1, 0] });
  check(edit.result && edit.result.text.includes('-init_pos {1 -1 0}'), 'an edit through the editor changes the text');
  const recompute = await documentView.call('simulate');
  check(recompute.result && recompute.result.ok, `recompute from the document view (${JSON.stringify(recompute.error || recompute.result.error || 'ok')})`);
  check(await waitFor(() => editor.events.some((e) => e.event === 'scene'), 'the scene event'),
    'the editor hears the recomputed motion');
  const after = await frame(1);
  check(after.live === '1' && after.status === 200, `the rendition is live after the edit (${after.caption})`);
  check(!after.bytes.equals(first.bytes), 'the rendition draws the edited scene (the picture changed)');
  const same = slaves();
  check(same.length === 1 && same[0] === before[0], `still the one asgard-core (${before} → ${same})`);

  // The slave dies: the views hear it, the next action starts one new
  // slave, which has the edited text (the node's text followed the edit).
  process.kill(same[0], 'SIGKILL');
  await sleep(200);
  const failed = await editor.call('simulate');
  check(!!failed.error || (failed.result && !failed.result.ok), 'the action that finds the slave dead fails with a reason');
  const reopened = await editor.call('open');
  check(reopened.result && reopened.result.state.text.includes('-init_pos {1 -1 0}'),
    'the next action restarts the slave with the edited text');
  const restarted = slaves();
  check(restarted.length === 1 && restarted[0] !== same[0], `one new asgard-core (${same} → ${restarted})`);
  const again = await frame(1);
  check(again.live === '1' && again.bytes.equals(after.bytes), `the restarted slave draws the edited scene (${again.caption})`);

  // The document view in Chromium (when there is one): the picture is the
  // rendition's, the slider draws another time, and an edit made in another
  // view redraws it (the page hears the `scene` event); Recompute and
  // Handles redraw through the same slave.
  if (existsSync('/usr/bin/chromium') && process.env.ASGARD_WEB_MODULES &&
      existsSync(join(process.env.ASGARD_WEB_MODULES, 'playwright-core/package.json'))) {
    const { context, close } = await launchBrowser();
    try {
      const page = context.pages()[0] ?? await context.newPage();
      const errors = [];
      page.on('pageerror', (e) => errors.push(String(e)));
      await page.goto(url);
      const drawn = () => page.evaluate(() => Number(document.querySelector('figure.rendition').dataset.drawn || 0));
      // The PNG bytes the page shows, as hex of a SHA-256, and the node side's.
      const shown = () => page.evaluate(async () => {
        const b = await (await fetch(document.querySelector('figure.rendition img').src)).arrayBuffer();
        return [...new Uint8Array(await crypto.subtle.digest('SHA-256', b))].map((x) => x.toString(16).padStart(2, '0')).join('');
      });
      const digest = (bytes) => createHash('sha256').update(bytes).digest('hex');
      check(await waitFor(async () => (await drawn()) >= 1, 'the first picture'), 'the document view draws the animation');
      check(await shown() === digest((await frame(0)).bytes), 'its picture is the rendition at t = 0');
      await page.screenshot({ path: join(outDir, '1-document-view.png') });
      let n = await drawn();
      await page.locator('figure.rendition .time').fill('1000');
      check(await waitFor(async () => (await drawn()) > n, 'the slider'), 'moving the slider draws again');
      const atEnd = digest((await frame(3)).bytes);
      check(await waitFor(async () => (await shown()) === atEnd, 'the picture at t = 3'), 'the picture at the slider\'s end is the rendition at t = 3');
      check((await page.textContent('figure.rendition .t')) === 't = 3.00 s', 'the time is shown');
      n = await drawn();
      const other = await view();
      await other.call('set_parameter', { element: 'b3', param: 'init_pos', values: [1, -2, 0] });
      await other.call('simulate');
      check(await waitFor(async () => (await drawn()) > n, 'the scene event'), 'an edit simulated in another view redraws the page');
      const edited = digest((await frame(3)).bytes);
      check(await waitFor(async () => (await shown()) === edited, 'the edited picture'), 'and the page shows the edited rendition');
      await page.screenshot({ path: join(outDir, '2-edited-elsewhere.png') });
      n = await drawn();
      await page.click('figure.rendition .recompute');
      check(await waitFor(async () => (await drawn()) > n, 'recompute'), 'Recompute redraws');
      check((await page.textContent('figure.rendition .status')).startsWith('2 bodies'), `the status after Recompute: ${await page.textContent('figure.rendition .status')}`);
      n = await drawn();
      await page.check('figure.rendition .handles');
      check(await waitFor(async () => (await drawn()) > n, 'handles'), 'Handles redraws');
      const withHandles = digest((await frame(3, 1)).bytes);
      check(withHandles !== edited && await waitFor(async () => (await shown()) === withHandles, 'handles drawn'),
        'with the position handles drawn (the rendition with handles)');
      await page.screenshot({ path: join(outDir, '3-handles.png') });
      check(errors.length === 0, `no page errors (${errors.join('; ')})`);
      other.ws.close();
    } finally {
      await close();
    }
  } else {
    console.log('SKIP the document view in Chromium: /usr/bin/chromium or playwright-core is missing');
  }
  editor.ws.close(); documentView.ws.close();
} finally {
  proc.kill('SIGTERM');
  await sleep(100);
}
if (failures.length) { console.log(`${failures.length} failure(s)`); process.exit(1); }
console.log('all docserve checks passed');
