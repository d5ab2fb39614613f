// The editor's latency benchmark (issue 13), run in headless Chromium
// (software WebGL, SwiftShader) against `asgard studio`; it prints numbers,
// asserts nothing, and writes them with the machine and the WebGL renderer
// to a CSV file that bench/report.py puts in docs/benchmarks.md.
//
//   node scripts/editor-latency.mjs [BUILD_DIR] [CSV]
//        (defaults: build, bench/results/latency.csv; CSV '-' writes none)
//
// 1. drag → text: b3's position handle on the seed pendulum dragged in 60
//    steps; per step, the time from the pointer event reaching the canvas
//    to the language viewer of the dragging tab showing the new -init_pos
//    (its local echo written, web/src/echo.js, and the next animation frame
//    done), and to the session's `text` event applied (what every other
//    view waits for: the round trip).  Each step waits for the session's
//    text before the next move.
// 2. drag end → motion: 10 drags; the time from releasing the handle to the
//    re-simulated motion being shown (the `scene` event applied and the
//    next animation frame, which draws it, done); with where it goes: the
//    `simulate` request leaving, the `scene` message's arrival, its parse,
//    setScene, the frame.  Step 1 likewise: the edit leaving, the `text`
//    event's arrival, applied.
// 3. playback of 100 bodies: a 10 × 10 grid of boxes thrown up, spinning,
//    under gravity; 3 s of Play; the frame rate (requestAnimationFrame) and
//    the main thread's time per frame in the viewer (seek: interpolation,
//    handles; and the draw).
import { mkdirSync, mkdtempSync, rmSync, writeFileSync } from 'node:fs';
import { cpus, loadavg, tmpdir } from 'node:os';
import { dirname, join, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';

const source = resolve(dirname(fileURLToPath(import.meta.url)), '..');
const build = resolve(process.argv[2] || join(source, 'build'));
process.env.ASGARD_WEB_ROOT ||= join(build, 'web');
process.env.ASGARD_WEB_MODULES ||= join(source, 'web', 'node_modules');
const { startStudio, launchBrowser, openEditor, sleep, waitFor } = await import(join(source, 'tests/web/common.mjs'));
const asgard = join(build, 'core/app/asgard');
const csvPath = process.argv[3] === '-' ? null : resolve(process.argv[3] || join(source, 'bench/results/latency.csv'));

const pct = (xs, p) => { const s = [...xs].sort((a, b) => a - b); return s[Math.min(s.length - 1, Math.floor((p / 100) * s.length))]; };
const summary = (xs) => `median ${pct(xs, 50).toFixed(1)} ms, 95th percentile ${pct(xs, 95).toFixed(1)} ms, max ${Math.max(...xs).toFixed(1)} ms (n = ${xs.length})`;

const dir = mkdtempSync(join(tmpdir(), 'asgard-latency-'));
const lines = ['simulator -finish 10 -collisions 0', 'shape_set box -desc {-box {0.6 0.4 0.3}}'];
for (let i = 0; i < 100; ++i) {
  const x = (i % 10) - 4.5, z = Math.floor(i / 10) - 4.5;
  lines.push(`body b${i} -shape box -init_pos {${x} 0 ${z}} -init_dpos {0 ${5 + (i % 7)} 0} -init_drot {${(i % 3) - 1} 2 ${(i % 5) - 2}}`);
  lines.push(`force -body b${i} -gravitational 1 -x 0 -y -9.8 -z 0`);
}
writeFileSync(join(dir, 'hundred.al'), `${lines.join('\n')}\n`);
writeFileSync(join(dir, 'pendulum.al'), (await import('node:fs')).readFileSync(join(source, 'samples/pendulum.al')));

const { context, close } = await launchBrowser();
const servers = [];
const rows = [];  // [measure, samples, target, how the target reads]
let renderer = '?';
const load = loadavg()[0];
try {
  // 1 and 2 on the pendulum.
  let s = await startStudio(asgard, join(dir, 'pendulum.al'));
  servers.push(s.proc);
  let { page } = await openEditor(context, s.url, 'b3');
  await page.evaluate(() => {
    const app = window.asgard, conn = app.conn, g = app.graphical;
    app.bench = { moves: [], texts: [], scenes: [], parts: [], steps: [], shown: [], echoing: [] };
    const preview = g.ui.preview;
    g.ui.preview = (...a) => { const t = performance.now(); preview(...a); app.bench.echoing.push(performance.now() - t); };
    const viewer = app.languageViewers[0];
    g.canvas.addEventListener('pointermove', () => {
      app.bench.moves.push(performance.now());
      app.bench.before = viewer.text();
    }, true);
    // After the viewer's own handler: whether the text changed in it (the
    // echo), and the frame that shows it.
    g.canvas.addEventListener('pointermove', () => {
      const b = app.bench, move = b.moves[b.moves.length - 1], changed = viewer.text() !== b.before;
      requestAnimationFrame(() => b.shown.push({ move, changed, latency: performance.now() - move }));
    });
    g.canvas.addEventListener('pointerup', () => { app.bench.released = performance.now(); app.bench.part = {}; }, true);
    const text = conn.handlers.get('text'), scene = conn.handlers.get('scene');
    conn.handlers.set('text', (m) => {
      const b = app.bench, move = b.moves[b.moves.length - 1];
      text(m);
      const now = performance.now();
      b.texts.push(now);
      b.steps.push({ sent: b.editSent - move, arrived: b.textIn - move, applied: now - move });
    });
    // Where a drag end's time goes: the WebSocket message in, parsed, applied, drawn.
    const ws = conn.ws, onmessage = ws.onmessage;
    ws.onmessage = (m) => {
      const part = app.bench.part;
      if (typeof m.data === 'string' && m.data.includes('"event":"text"')) app.bench.textIn = performance.now();
      if (part && typeof m.data === 'string' && m.data.startsWith('{"event":"scene"')) {
        part.arrived = performance.now();
        part.bytes = m.data.length;
      }
      onmessage(m);
    };
    const send = ws.send.bind(ws);
    ws.send = (data) => {
      if (app.bench.part && data.includes('"method":"simulate"')) app.bench.part.sent = performance.now();
      if (data.includes('"method":"set_parameter"')) app.bench.editSent = performance.now();
      send(data);
    };
    conn.handlers.set('scene', (m) => {
      const part = app.bench.part || {};
      part.parsed = performance.now();
      scene(m);
      part.applied = performance.now();
      // Shown: the animation frame that draws it (the viewer draws in it first).
      requestAnimationFrame(() => {
        const now = performance.now();
        app.bench.scenes.push(now);
        if (app.bench.part) {
          const r = app.bench.released;
          app.bench.parts.push({ sent: part.sent - r, arrived: part.arrived - r, parsed: part.parsed - r, applied: part.applied - r, shown: now - r, bytes: part.bytes });
          app.bench.part = null;
        }
      });
    });
  });
  const dragText = [], dragEcho = [], dragEnd = [];
  for (let round = 0; round < 10; ++round) {
    const at = await page.evaluate(() => window.asgard.graphical.handleList().find((x) => x.id === 'b3.init_pos'));
    await page.mouse.move(at.x, at.y);
    await page.mouse.down();
    const steps = round === 0 ? 60 : 6;
    for (let i = 1; i <= steps; ++i) {
      const n = await page.evaluate(() => window.asgard.bench.texts.length);
      await page.mouse.move(at.x + (round % 2 ? -1 : 1) * i * 2, at.y + i);
      if (!(await waitFor(() => page.evaluate((k) => window.asgard.bench.texts.length > k, n), 'the text of a drag step', 5000))) continue;
      dragText.push(await page.evaluate(() => { const b = window.asgard.bench; return b.texts[b.texts.length - 1] - b.moves[b.moves.length - 1]; }));
      const shown = await page.evaluate(() => { const b = window.asgard.bench, m = b.moves[b.moves.length - 1]; return b.shown.find((x) => x.move === m); });
      if (shown && shown.changed) dragEcho.push(shown.latency);
    }
    const n = await page.evaluate(() => window.asgard.bench.scenes.length);
    await page.mouse.up();
    if (await waitFor(() => page.evaluate((k) => window.asgard.bench.scenes.length > k, n), 'the new motion', 10000))
      dragEnd.push(await page.evaluate(() => { const b = window.asgard.bench; return b.scenes[b.scenes.length - 1] - b.released; }));
    await sleep(100);
  }
  console.log(`drag → number in this tab's text (echo, frame drawn): ${dragEcho.length ? summary(dragEcho) : 'never echoed'}`);
  console.log(`  writing the echo into the viewer: ${summary(await page.evaluate(() => window.asgard.bench.echoing))}`);
  console.log(`drag → the session's text (every other view):        ${summary(dragText)}`);
  const steps = await page.evaluate(() => window.asgard.bench.steps.filter((x) => x.sent >= 0));
  const step = (key) => pct(steps.map((x) => x[key]), 50);
  console.log(`  from the pointer event (medians): edit sent ${step('sent').toFixed(1)} ms, text event in ${step('arrived').toFixed(1)} ms, ` +
    `applied ${step('applied').toFixed(1)} ms`);
  console.log(`drag end → new motion shown: ${summary(dragEnd)}`);
  const parts = await page.evaluate(() => window.asgard.bench.parts);
  const med = (key) => pct(parts.map((x) => x[key]), 50);
  console.log(`  from the release (medians): simulate sent ${med('sent').toFixed(1)} ms, scene message in ${med('arrived').toFixed(1)} ms ` +
    `(${Math.round(med('bytes') / 1024)} KiB), parsed ${med('parsed').toFixed(1)} ms, applied ${med('applied').toFixed(1)} ms, drawn ${med('shown').toFixed(1)} ms`);
  if (dragEcho.length) rows.push(['drag_to_text', dragEcho, 16, 'ms, 95th percentile below']);
  rows.push(['drag_to_session_text', dragText, null, 'ms']);
  rows.push(['drag_end_to_motion', dragEnd, 100, 'ms, 95th percentile below']);
  renderer = await page.evaluate(() => {
    const gl = window.asgard.graphical.renderer.getContext();
    const info = gl.getExtension('WEBGL_debug_renderer_info');
    return info ? gl.getParameter(info.UNMASKED_RENDERER_WEBGL) : gl.getParameter(gl.RENDERER);
  });
  s.proc.kill('SIGTERM');

  // 3: 100 bodies.
  s = await startStudio(asgard, join(dir, 'hundred.al'));
  servers.push(s.proc);
  ({ page } = await openEditor(context, s.url, 'b99'));
  const r = await page.evaluate(async () => {
    const g = window.asgard.graphical;
    const seek = g.seek.bind(g);  // seek draws too
    const spent = [];
    let inFrame = 0;
    g.seek = (t, frame) => { const a = performance.now(); seek(t, frame); inFrame += performance.now() - a; };
    const stamps = [];
    await new Promise((done) => {
      const tick = (now) => {
        stamps.push(now);
        spent.push(inFrame);
        inFrame = 0;
        if (now - stamps[0] < 3000) requestAnimationFrame(tick); else done();
      };
      g.play();
      requestAnimationFrame(tick);
    });
    g.play();
    const intervals = stamps.slice(1).map((t, i) => t - stamps[i]);
    return { frames: intervals.length, seconds: (stamps[stamps.length - 1] - stamps[0]) / 1000, intervals, spent: spent.slice(2) };
  });
  console.log(`playback, 100 bodies:        ${(r.frames / r.seconds).toFixed(1)} frames/s over ${r.seconds.toFixed(1)} s; ` +
    `frame interval ${summary(r.intervals)}`);
  console.log(`  main thread per frame (interpolation, handles, draw): ${summary(r.spent)}`);
  rows.push(['playback_100_fps', [r.frames / r.seconds], 60, 'frames/s, at least']);
  rows.push(['playback_100_frame_interval', r.intervals, null, 'ms']);
  rows.push(['playback_100_main_thread', r.spent, null, 'ms per frame']);
  if (csvPath) {
    const machine = `${cpus().length} × ${cpus()[0].model.trim()}, load ${load.toFixed(2)}`;
    const when = new Date().toISOString().slice(0, 16).replace('T', ' ');
    const q = (x) => `"${String(x).replace(/"/g, '""')}"`;
    const lines = ['measure,median,p95,max,n,target,target_reads,renderer,machine,date'];
    for (const [measure, xs, target, reads] of rows)
      lines.push([measure, pct(xs, 50).toFixed(2), pct(xs, 95).toFixed(2), Math.max(...xs).toFixed(2), xs.length,
        target ?? '', q(reads), q(renderer), q(machine), when].join(','));
    mkdirSync(dirname(csvPath), { recursive: true });
    writeFileSync(csvPath, `${lines.join('\n')}\n`);
    console.log(`written: ${csvPath} (renderer ${renderer})`);
  }
} finally {
  await close();
  for (const p of servers) p.kill('SIGTERM');
  rmSync(dir, { recursive: true, force: true });
}
