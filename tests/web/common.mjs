// Shared by the editor's tests: start `asgard studio` and find its URL.
import { spawn } from 'node:child_process';

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

// Starts the server on a free port; resolves {url, port, proc}.
export function startStudio(asgard, scene) {
  return new Promise((resolve, reject) => {
    const proc = spawn(asgard, ['studio', scene, '--port', '0'], { stdio: ['ignore', 'pipe', 'pipe'] });
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
