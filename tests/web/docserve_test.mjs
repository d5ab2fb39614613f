// `dochost serve` on the memo (issue 13): the editor's requests and the
// document view's renditions go to one asgard-core per animation — the
// medium plugin's node.  An edit through the editor's WebSocket, then a
// recompute, changes the picture the document view gets from GET /frame;
// a second view (the document page's socket) hears the new motion; through
// it all dochost runs exactly one asgard-core, and after that slave is
// killed the next action starts one new slave that has the edited text.
// Node only (its WebSocket, Node 20's --experimental-websocket).
import { readFileSync, readdirSync } from 'node:fs';
import { checker, startStudio, sleep, waitFor } from './common.mjs';

const [dochost, doc] = process.argv.slice(2);
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

async function frame(t) {
  const r = await fetch(`${url}frame?a=0&t=${t}`);
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
  editor.ws.close(); documentView.ws.close();
} finally {
  proc.kill('SIGTERM');
  await sleep(100);
}
if (failures.length) { console.log(`${failures.length} failure(s)`); process.exit(1); }
console.log('all docserve checks passed');
