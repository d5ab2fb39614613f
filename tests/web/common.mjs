// Shared by the editor's tests: start `asgard studio` and find its URL.
import { spawn } from 'node:child_process';
import { readFileSync, readdirSync } from 'node:fs';

export const sleep = (ms) => new Promise((r) => setTimeout(r, ms));

export function checker() {
  const failures = [];
  const check = (ok, what) => {
    console.log(`${ok ? 'ok  ' : 'FAIL'} ${what}`);
    if (!ok) failures.push(what);
    return ok;
  };
  return { check, failures };
}

// Starts the server on a free port; resolves {url, port, proc}.  `command`
// is asgard's `studio` (a scene) or dochost's `serve` (a document).
export function startStudio(asgard, scene, command = 'studio', extra = []) {
  return new Promise((resolve, reject) => {
    const proc = spawn(asgard, [command, scene, '--port', '0', ...extra], { stdio: ['ignore', 'pipe', 'pipe'] });
    let out = '';
    const timer = setTimeout(() => reject(new Error(`no URL from asgard studio: ${out}`)), 20000);
    proc.stdout.on('data', (d) => {
      out += d;
      const m = /serving on (http:\/\/127\.0\.0\.1:(\d+)\/)/.exec(out);
      if (m) { clearTimeout(timer); resolve({ url: m[1], port: Number(m[2]), proc }); }
    });
    proc.stderr.on('data', (d) => process.stderr.write(`[studio] ${d}`));
    proc.on('exit', (code) => { clearTimeout(timer); reject(new Error(`asgard studio exited with ${code}`)); });
  });
}

export async function waitFor(f, what, ms = 15000) {
  const end = Date.now() + ms;
  for (;;) {
    try { if (await f()) return true; } catch { /* not yet */ }
    if (Date.now() > end) { console.log(`     (timed out waiting: ${what})`); return false; }
    await sleep(50);
  }
}

// Headless Chromium (playwright-core from web/node_modules, Debian's
// /usr/bin/chromium with software WebGL); resolves {context, close}.
export async function launchBrowser() {
  const { createRequire } = await import('node:module');
  const { mkdtempSync, rmSync } = await import('node:fs');
  const { tmpdir } = await import('node:os');
  const { join } = await import('node:path');
  const require = createRequire(join(process.env.ASGARD_WEB_MODULES, 'x.js'));
  const { chromium } = require('playwright-core');
  const userData = mkdtempSync(join(tmpdir(), 'asgard-chromium-'));
  const context = await chromium.launchPersistentContext(userData, {
    executablePath: '/usr/bin/chromium',
    headless: true,
    args: ['--headless', '--no-sandbox', '--disable-gpu', '--disable-background-networking',
           '--disable-component-update', '--disable-sync', '--no-first-run',
           '--use-angle=swiftshader', '--enable-unsafe-swiftshader'],
    viewport: { width: 1200, height: 800 },
  });
  const close = async () => { await context.close(); rmSync(userData, { recursive: true, force: true }); };
  return { context, close };
}

// Opens the editor in a page and waits until it shows `body`; page errors
// are collected in the returned list.
export async function openEditor(context, url, body) {
  const page = context.pages()[0] ?? await context.newPage();
  const errors = [];
  page.on('pageerror', (e) => errors.push(String(e)));
  await page.goto(url);
  const ok = await waitFor(() => page.evaluate((b) => window.asgard.ready && window.asgard.graphical.bodyNames().includes(b), body),
    'the editor shows the scene');
  return { page, errors, ok };
}

// The handle `id` of the graphical viewer ({x, y, value, editable, ...}).
export const handle = (page, id) => page.evaluate((i) => window.asgard.graphical.handleList().find((h) => h.id === i), id);

// Drags a handle by (dx, dy) pixels in steps (Shift held when `shift`), then
// waits for the re-simulation's new state to reach the page.
export async function dragHandle(page, id, dx, dy, { shift = false, steps = 8, during = null } = {}) {
  const h = await handle(page, id);
  if (!h) throw new Error(`no handle ${id}`);
  const before = await page.evaluate(() => window.asgard.stateCount);
  await page.mouse.move(h.x, h.y);
  await page.mouse.down();
  if (shift) await page.keyboard.down('Shift');
  for (let i = 1; i <= steps; ++i) { await page.mouse.move(h.x + (dx * i) / steps, h.y + (dy * i) / steps); await sleep(30); }
  if (during) await during();
  await page.mouse.up();
  if (shift) await page.keyboard.up('Shift');
  await waitFor(() => page.evaluate((n) => window.asgard.stateCount > n, before), `the state after dragging ${id}`);
  return h;
}

// One browser test: `asgard studio` on `scene`, headless Chromium, then
// body({check, url, context}); failures make the exit status 1.
export async function browserTest(asgard, scene, what, body) {
  const { check, failures } = checker();
  const { url, proc } = await startStudio(asgard, scene);
  const { context, close } = await launchBrowser();
  try {
    await body({ check, url, context });
  } catch (e) {
    check(false, `unexpected: ${e.stack || e}`);
  } finally {
    await close();
    proc.kill('SIGTERM');
  }
  if (failures.length) { console.log(`${failures.length} failure(s)`); process.exit(1); }
  console.log(`all ${what} checks passed`);
}

// The live asgard-core children of process `pid` (from /proc).
export function coreChildren(pid) {
  const out = [];
  for (const name of readdirSync('/proc')) {
    if (!/^\d+$/.test(name)) continue;
    let stat;
    try { stat = readFileSync(`/proc/${name}/stat`, 'latin1'); } catch { continue; }
    const close = stat.lastIndexOf(')');
    const comm = stat.slice(stat.indexOf('(') + 1, close);
    const [state, ppid] = stat.slice(close + 2).split(' ');
    if (comm === 'asgard-core' && Number(ppid) === pid && state !== 'Z') out.push(Number(name));
  }
  return out;
}

// One WebSocket view of animation `a` (Node's WebSocket): call(method,
// params) → the whole answer {id, result | error}; `events` collects what
// the server broadcasts.
export async function wsView(port, a = 0) {
  const ws = new WebSocket(`ws://127.0.0.1:${port}/ws?a=${a}`);
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
