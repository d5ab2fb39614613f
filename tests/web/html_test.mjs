// The HTML export plays in WebGL (issue 13): `dochost convert memo.ens -o
// memo.html` embeds the bodies' meshes and poses and the player; in headless
// Chromium the WebGL canvas draws the bodies where the pre-rendered frames
// have them (the same camera), a body's pixels move between two times, a
// drag turns the view, play advances the time, and a browser without WebGL
// plays the frames; on samples/two-animations.ens the links and the force are
// drawn; a view whose -pos is an expression of time moves the WebGL camera
// as it moves the pre-rendered frames'.  Prints the sizes of the three
// --html modes.
// Usage: node html_test.mjs DOCHOST OUT/memo.ens OUT
import { spawnSync } from 'node:child_process';
import { statSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { fileURLToPath, pathToFileURL } from 'node:url';
import { checker, launchBrowser, sleep, waitFor } from './common.mjs';

const [dochost, doc, outDir] = process.argv.slice(2);
const { check, failures } = checker();

const sizes = {};
for (const mode of ['webgl', 'webgl-poster', 'frames']) {
  const out = join(outDir, `memo-${mode}.html`);
  const r = spawnSync(dochost, ['convert', doc, '-o', out, '--html', mode, '--quiet'], { encoding: 'utf8' });
  check(r.status === 0, `dochost convert --html ${mode} exits 0 ${r.stderr || ''}`);
  sizes[mode] = r.status === 0 ? statSync(out).size : 0;
}
console.log(`     sizes: webgl (with frames) ${sizes.webgl} B, webgl-poster ${sizes['webgl-poster']} B, ` +
  `frames (pre-rendered) ${sizes.frames} B: webgl-poster is ${(100 * sizes['webgl-poster'] / sizes.frames).toFixed(1)} %`);
check(sizes['webgl-poster'] > 0 && sizes['webgl-poster'] < sizes.frames / 4, 'the WebGL page with only its poster is under a quarter of the pre-rendered one');

// The centroid and count of the pixels of a canvas (the WebGL one, or a
// pre-rendered frame given as a data URL) whose colour is near `rgb`.
async function colourBlob(page, { frame = null, rgb }) {
  return page.evaluate(async ({ frame, rgb }) => {
    const fig = document.querySelector('#anim-1');
    let source = fig.querySelector('canvas.asgard-webgl');
    if (frame !== null) {
      const data = JSON.parse(document.getElementById('asgard-frames').textContent)['anim-1'];
      source = new Image();
      source.src = data.frames[frame];
      await source.decode();
    }
    const w = fig.querySelector('canvas').width, h = fig.querySelector('canvas').height;
    const c = document.createElement('canvas');
    c.width = w; c.height = h;
    const ctx = c.getContext('2d');
    ctx.drawImage(source, 0, 0, w, h);
    const d = ctx.getImageData(0, 0, w, h).data;
    let n = 0, sx = 0, sy = 0;
    for (let y = 0; y < h; ++y)
      for (let x = 0; x < w; ++x) {
        const i = 4 * (y * w + x);
        // Same hue: the colour's channels in the same order with the same
        // spread (shading scales them).
        const [r, g, b] = [d[i], d[i + 1], d[i + 2]];
        const m = Math.max(r, g, b);
        if (m < 40) continue;
        const e = Math.abs(r / m - rgb[0] / Math.max(...rgb)) + Math.abs(g / m - rgb[1] / Math.max(...rgb)) + Math.abs(b / m - rgb[2] / Math.max(...rgb));
        if (e < 0.25) { ++n; sx += x; sy += y; }
      }
    return n ? { n, x: sx / n, y: sy / n } : { n: 0 };
  }, { frame, rgb });
}

const { context, close } = await launchBrowser();
try {
  const page = context.pages()[0] ?? await context.newPage();
  const errors = [];
  page.on('pageerror', (e) => errors.push(String(e)));
  await page.goto(pathToFileURL(join(outDir, 'memo-webgl.html')).href);
  await waitFor(() => page.evaluate(() => document.querySelector('#anim-1')?.dataset.state === 'paused'), 'the page is set up');
  const info = await page.evaluate(() => {
    const fig = document.querySelector('#anim-1');
    const gl = fig.querySelector('canvas.asgard-webgl');
    const data = JSON.parse(document.getElementById('asgard-frames').textContent)['anim-1'];
    return { renderer: fig.dataset.renderer, glShown: !!gl && gl.offsetWidth > 0, fallbackHidden: fig.querySelector('canvas:not(.asgard-webgl)').offsetWidth === 0,
      colours: Object.fromEntries(data.player.bodies.map((b) => [b.name, b.pieces[0].color])), times: data.times, moving: data.player.bodies.map((b) => b.track !== undefined) };
  });
  check(info.renderer === 'webgl' && info.glShown && info.fallbackHidden, 'the animation plays in WebGL (the frames canvas hidden)');
  check(info.moving.every((m) => m), 'both bodies move, so both have a track of poses');
  const orange = info.colours.b3, blue = info.colours.b2;
  const fig = page.locator('figure#anim-1');
  const shot = async (name) => writeFileSync(join(outDir, name), await fig.screenshot());

  // At two times: b3's pixels are where the player projects its centre, and
  // where the pre-rendered frame of that time has them (the same camera).
  const at = {};
  for (const t of [1.0, 2.5]) {
    const k = info.times.findIndex((x) => Math.abs(x - t) < 1e-6);
    const p = await page.evaluate((t) => { const f = document.querySelector('#anim-1'); f.asgard.showTime(t); return f.asgard.webgl.project('b3', t); }, t);
    const gl = await colourBlob(page, { rgb: orange });
    const frame = await colourBlob(page, { frame: k, rgb: orange });
    const b2 = await colourBlob(page, { rgb: blue });
    const p2 = await page.evaluate((t) => document.querySelector('#anim-1').asgard.webgl.project('b2', t), t);
    await shot(`webgl-t${t}.png`);
    at[t] = { p, gl };
    check(gl.n > 200 && Math.hypot(gl.x - p[0], gl.y - p[1]) < 2,
      `t = ${t}: b3's ${gl.n} orange pixels centre at (${gl.x?.toFixed(1)}, ${gl.y?.toFixed(1)}), its projected centre (${p[0].toFixed(1)}, ${p[1].toFixed(1)})`);
    check(k >= 0 && frame.n > 200 && Math.hypot(frame.x - gl.x, frame.y - gl.y) < 3 && Math.abs(frame.n / gl.n - 1) < 0.2,
      `t = ${t}: the pre-rendered frame has b3 at (${frame.x?.toFixed(1)}, ${frame.y?.toFixed(1)}), ${frame.n} pixels`);
    check(b2.n > 200 && Math.hypot(b2.x - p2[0], b2.y - p2[1]) < 2, `t = ${t}: b2 (blue) is drawn at its projected centre`);
  }
  const moved = Math.hypot(at[2.5].gl.x - at[1.0].gl.x, at[2.5].gl.y - at[1.0].gl.y);
  check(moved > 20, `b3's pixels move by ${moved.toFixed(1)} px from t = 1 to t = 2.5 (b3 rises 1.5 m)`);
  check(at[2.5].gl.y < at[1.0].gl.y, 'b3 rises on the screen');

  // A drag turns the view: b3 is drawn elsewhere, where the player projects it.
  const box = await page.locator('canvas.asgard-webgl').boundingBox();
  await page.mouse.move(box.x + box.width / 2, box.y + box.height / 2);
  await page.mouse.down();
  for (let i = 1; i <= 5; ++i) { await page.mouse.move(box.x + box.width / 2 + 12 * i, box.y + box.height / 2 + 12 * i); await sleep(20); }
  await page.mouse.up();
  const turned = await page.evaluate(() => document.querySelector('#anim-1').asgard.webgl.project('b3'));
  const glTurned = await colourBlob(page, { rgb: orange });
  await shot('webgl-turned.png');
  check(Math.hypot(turned[0] - at[2.5].p[0], turned[1] - at[2.5].p[1]) > 10 && Math.hypot(glTurned.x - turned[0], glTurned.y - turned[1]) < 2,
    `a diagonal drag of 85 px turns the view: b3 now at (${glTurned.x?.toFixed(1)}, ${glTurned.y?.toFixed(1)}), projected (${turned[0].toFixed(1)}, ${turned[1].toFixed(1)})`);

  // Play advances the time smoothly (any time, not only frame times).
  await page.evaluate(() => document.querySelector('#anim-1').asgard.showTime(0));
  await fig.locator('button.play').click();
  await sleep(600);
  const playing = await page.evaluate(() => ({ state: document.querySelector('#anim-1').dataset.state, t: Number(document.querySelector('#anim-1').dataset.time) }));
  await fig.locator('button.play').click();
  check(playing.state === 'playing' && playing.t > 0.2 && playing.t < 3, `playing for 0.6 s reaches t = ${playing.t.toFixed(3)}`);
  check(errors.length === 0, `no script errors ${errors.join('; ')}`);

  // Without WebGL the same page plays its pre-rendered frames.
  const plain = await context.newPage();
  await plain.addInitScript(() => {
    const get = HTMLCanvasElement.prototype.getContext;
    HTMLCanvasElement.prototype.getContext = function (kind, ...rest) { return /webgl/.test(kind) ? null : get.call(this, kind, ...rest); };
  });
  await plain.goto(pathToFileURL(join(outDir, 'memo-webgl.html')).href);
  await waitFor(() => plain.evaluate(() => document.querySelector('#anim-1')?.dataset.state === 'paused'), 'the page without WebGL is set up');
  await sleep(300);
  const fallback = await plain.evaluate(() => {
    const fig = document.querySelector('#anim-1');
    const c = fig.querySelector('canvas');
    const d = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;
    const colours = new Set();
    for (let i = 0; i < d.length; i += 4 * 7) colours.add((d[i] >> 4) << 8 | (d[i + 1] >> 4) << 4 | d[i + 2] >> 4);
    return { renderer: fig.dataset.renderer || '', webgl: !!fig.querySelector('canvas.asgard-webgl'), shown: c.offsetWidth > 0, colours: colours.size };
  });
  writeFileSync(join(outDir, 'fallback.png'), await plain.locator('figure#anim-1').screenshot());
  check(!fallback.webgl && fallback.renderer !== 'webgl' && fallback.shown && fallback.colours > 10,
    `without WebGL the frames canvas shows the poster (${fallback.colours} colours)`);
  await plain.locator('#anim-1 button.play').click();
  await sleep(500);
  const frameNow = await plain.evaluate(() => Number(document.querySelector('#anim-1').dataset.frame));
  check(frameNow > 3, `without WebGL play shows the frames (frame ${frameNow})`);

  // Links and forces (samples/two-animations.ens): the dumbbell's force is
  // an arrow, the three balls' links are lines to the points above them.
  // Along each, the canvas has the overlay's own colour (asgard render's:
  // link rgb(26, 140, 51), force rgb(204, 26, 26), drawn flat), and 8 px to
  // the side it has not.
  const two = join(outDir, 'two-animations.html');
  const sample = fileURLToPath(new URL('../../samples/two-animations.ens', import.meta.url));
  const r = spawnSync(dochost, ['convert', sample,
    '-o', two, '--html', 'webgl-poster', '--quiet'], { encoding: 'utf8' });
  check(r.status === 0, `dochost convert two-animations.ens exits 0 ${r.stderr || ''}`);
  const page2 = await context.newPage();
  page2.on('pageerror', (e) => errors.push(String(e)));
  await page2.goto(pathToFileURL(two).href);
  await waitFor(() => page2.evaluate(() => ['#anim-1', '#anim-2'].every((id) => document.querySelector(id)?.dataset.state === 'paused')),
    'the two animations are set up');
  for (const [id, kind, rgb, count] of [['anim-1', 'arrows', [204, 26, 26], 1], ['anim-2', 'links', [26, 140, 51], 3]]) {
    const seen = await page2.evaluate(({ id, kind, rgb }) => {
      const fig = document.getElementById(id);
      fig.asgard.showTime(0.1);
      const segments = fig.asgard.webgl.overlays()[kind];
      const gl = fig.querySelector('canvas.asgard-webgl');
      const c = document.createElement('canvas');
      c.width = gl.width; c.height = gl.height;
      const ctx = c.getContext('2d');
      ctx.drawImage(gl, 0, 0);
      const k = gl.width / gl.offsetWidth;  // CSS to device pixels
      // Whether a pixel within 1 of (x, y) CSS px has the colour.
      const near = (x, y) => {
        const d = ctx.getImageData(Math.round(x * k) - 1, Math.round(y * k) - 1, 3, 3).data;
        for (let i = 0; i < d.length; i += 4)
          if (Math.abs(d[i] - rgb[0]) <= 20 && Math.abs(d[i + 1] - rgb[1]) <= 20 && Math.abs(d[i + 2] - rgb[2]) <= 20) return true;
        return false;
      };
      return segments.map(([ax, ay, bx, by]) => {
        const len = Math.hypot(bx - ax, by - ay), nx = -(by - ay) / len, ny = (bx - ax) / len;
        let on = 0, off = 0;
        for (let i = 1; i <= 9; ++i) {
          const x = ax + (bx - ax) * (0.1 + 0.08 * i), y = ay + (by - ay) * (0.1 + 0.08 * i);
          if (near(x, y)) ++on;
          if (near(x + 8 * nx, y + 8 * ny) || near(x - 8 * nx, y - 8 * ny)) ++off;
        }
        return { len, on, off, down: by - ay };
      });
    }, { id, kind, rgb });
    writeFileSync(join(outDir, `two-${id}.png`), await page2.locator(`figure#${id}`).screenshot());
    check(seen.length === count && seen.every((x) => x.len > 15 && x.on === 9 && x.off === 0),
      `${id}: ${count} ${kind} drawn along their projected ends: ${seen.map((x) => `${x.len.toFixed(0)} px long, ${x.on}/9 on, ${x.off}/9 beside`).join('; ')}`);
    if (kind === 'arrows') check(seen[0]?.down > 0, 'the dumbbell\'s force (down) points down the screen');
  }
  check(errors.length === 0, `no script errors on the page with links and forces ${errors.join('; ')}`);

  // A moving view (its -pos an expression of time): a ball at rest moves
  // across the picture, in WebGL where the pre-rendered frames (drawn by the
  // slave at each frame's time) have it.
  const panDoc = join(outDir, 'pan.ens'), pan = join(outDir, 'pan.html');
  writeFileSync(panDoc, ['DOCUMENT ARTICLE', '<ARTICLE>', '<TITLE>{A moving view}</TITLE>', '<BODY>',
    '<PARAGRAPH><DOCUMENT>', 'DOCUMENT ANIMATION', '<ANIMATION>', '<ASGARD>{',
    'simulator -finish 2 -frames 24 -collisions 0',
    'shape_set ball -desc \\{-sub \\{-sphere 0.5\\}\\}',
    'body b -shape ball -init_pos \\{0 0 0\\} -color #ff8c00',
    'body c -shape ball -init_pos \\{0 2 0\\} -color #4682b4',
    'view pan -pos \\{\\{-t\\} 0 0\\}',
    '}</ASGARD>', '</ANIMATION>', '</DOCUMENT></PARAGRAPH>', '</BODY>', '</ARTICLE>', ''].join('\n'));
  const rp = spawnSync(dochost, ['convert', panDoc, '-o', pan, '--quiet'], { encoding: 'utf8' });
  check(rp.status === 0, `dochost convert of a moving view exits 0 ${rp.stderr || ''}`);
  const page3 = await context.newPage();
  page3.on('pageerror', (e) => errors.push(String(e)));
  await page3.goto(pathToFileURL(pan).href);
  await waitFor(() => page3.evaluate(() => document.querySelector('#anim-1')?.dataset.state === 'paused'), 'the moving view is set up');
  const panInfo = await page3.evaluate(() => {
    const data = JSON.parse(document.getElementById('asgard-frames').textContent)['anim-1'];
    return { cameras: typeof data.player.cameras === 'string', times: data.times,
      colour: data.player.bodies.find((b) => b.name === 'b').pieces[0].color };
  });
  check(panInfo.cameras, 'the player data carries a camera per frame');
  const seenAt = [];
  for (const t of [0.5, 1.5]) {
    const k = panInfo.times.findIndex((x) => Math.abs(x - t) < 1e-6);
    await page3.evaluate((t) => document.querySelector('#anim-1').asgard.showTime(t), t);
    const gl = await colourBlob(page3, { rgb: panInfo.colour });
    const frame = await colourBlob(page3, { frame: k, rgb: panInfo.colour });
    writeFileSync(join(outDir, `pan-t${t}.png`), await page3.locator('figure#anim-1').screenshot());
    seenAt.push(gl);
    check(k >= 0 && gl.n > 100 && frame.n > 100 && Math.hypot(frame.x - gl.x, frame.y - gl.y) < 3,
      `t = ${t}: the ball at rest is at (${gl.x?.toFixed(1)}, ${gl.y?.toFixed(1)}) in WebGL and at (${frame.x?.toFixed(1)}, ${frame.y?.toFixed(1)}) in the frame`);
  }
  check(seenAt.length === 2 && seenAt[0].x - seenAt[1].x > 20,
    `the view pans: the ball at rest moves left by ${(seenAt[0].x - seenAt[1].x).toFixed(1)} px from t = 0.5 to 1.5`);
  check(errors.length === 0, `no script errors on the moving view's page ${errors.join('; ')}`);
} catch (e) {
  check(false, `unexpected: ${e.stack || e}`);
} finally {
  await close();
}
if (failures.length) { console.log(`${failures.length} failure(s)`); process.exit(1); }
console.log('all html checks passed');
