// Opens the HTML of the memo in headless Chromium without WebGL: the page
// embeds the WebGL player and its data, but falls back to its pre-rendered
// frames; the animation must move (two screenshots of its box at different
// times differ) and its controls (play/pause, seek) must work.  (The WebGL
// playing is tests/web/html_test.mjs.)  Exits 1 with a message on any failure.
import { chromium } from 'playwright-core';
import { mkdtempSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { pathToFileURL } from 'node:url';

const [html, outDir] = process.argv.slice(2);
const userData = mkdtempSync(join(tmpdir(), 'asgard-chromium-'));
const failures = [];
function check(ok, what) {
  console.log(`${ok ? 'ok  ' : 'FAIL'} ${what}`);
  if (!ok) failures.push(what);
}
const sleep = (ms) => new Promise((r) => setTimeout(r, ms));

const context = await chromium.launchPersistentContext(userData, {
  executablePath: '/usr/bin/chromium',
  headless: true,
  args: ['--headless', '--no-sandbox', '--disable-gpu', '--disable-webgl', '--disable-quic', '--no-first-run',
         '--disable-background-networking', '--disable-component-update', '--disable-sync'],
  viewport: { width: 900, height: 900 },
});
try {
  const page = context.pages()[0] ?? await context.newPage();
  const errors = [];
  page.on('pageerror', (e) => errors.push(String(e)));
  await page.goto(pathToFileURL(html).href);
  const fig = page.locator('figure#anim-1');
  const canvas = fig.locator('canvas');
  const button = fig.locator('button.play');
  const seek = fig.locator('input.seek');
  const time = fig.locator('output.time');
  await page.waitForFunction(() => document.querySelector('#anim-1')?.dataset.state === 'paused');
  await sleep(300);  // the poster frame is decoded and drawn
  const shot = async (name) => {
    const png = await canvas.screenshot();
    if (outDir) writeFileSync(join(outDir, name), png);
    return png;
  };
  const state = () => fig.getAttribute('data-state');
  const frame = async () => Number(await fig.getAttribute('data-frame'));

  check(await page.locator('text=Whom it may concern').count() === 1, 'the memo text is shown');
  const fallback = await page.evaluate(() => ({
    data: !!JSON.parse(document.getElementById('asgard-frames').textContent)['anim-1'].player,
    player: typeof window.asgardPlayer === 'function',
    webgl: document.querySelectorAll('#anim-1 canvas').length !== 1 || document.querySelector('#anim-1').dataset.renderer === 'webgl',
  }));
  check(fallback.data && fallback.player && !fallback.webgl, 'the page has the WebGL player and data, and without WebGL it plays its frames');
  const poster = await shot('poster.png');
  check(await time.textContent() === '0.00 s', 'the poster frame is at t = 0.00 s');
  const blank = await page.evaluate(() => {
    const c = document.querySelector('#anim-1 canvas');
    const d = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;
    const colours = new Set();
    for (let i = 0; i < d.length; i += 4 * 7) colours.add((d[i] >> 4) << 8 | (d[i + 1] >> 4) << 4 | d[i + 2] >> 4);
    return colours.size;
  });
  check(blank > 10, `the poster frame is drawn (${blank} colours)`);

  await button.click();
  check(await state() === 'playing' && await button.textContent() === 'Pause', 'play starts playback');
  await sleep(500);
  const a = await shot('playing-a.png');
  const frameA = await frame();
  await sleep(700);
  const b = await shot('playing-b.png');
  const frameB = await frame();
  check(!a.equals(b), `two screenshots during playback differ (frames ${frameA}, ${frameB})`);
  check(!a.equals(poster), 'playback moved away from the poster frame');

  await button.click();
  check(await state() === 'paused' && await button.textContent() === 'Play', 'pause stops playback');
  const p1 = await shot('paused-a.png');
  const f1 = await frame();
  await sleep(500);
  const p2 = await shot('paused-b.png');
  check(p1.equals(p2) && f1 === await frame(), 'while paused the picture stays still');

  const max = Number(await seek.getAttribute('max'));
  await seek.evaluate((el, v) => { el.value = String(v); el.dispatchEvent(new Event('input', { bubbles: true })); }, max);
  await sleep(200);
  check(await frame() === max && await time.textContent() === '3.00 s', `seek to the end shows t = 3.00 s (${await time.textContent()})`);
  const end = await shot('end.png');
  check(!end.equals(p1), 'the last frame differs from the paused one');
  await seek.evaluate((el) => { el.value = '0'; el.dispatchEvent(new Event('input', { bubbles: true })); });
  await sleep(200);
  check(await time.textContent() === '0.00 s' && (await shot('start.png')).equals(poster), 'seek back to the start shows the poster frame');
  check(errors.length === 0, `no script errors ${errors.join('; ')}`);
} finally {
  await context.close();
  rmSync(userData, { recursive: true, force: true });
}
if (failures.length) {
  console.error(`browser test: ${failures.length} check(s) failed`);
  process.exit(1);
}
console.log('browser test: all checks passed');
