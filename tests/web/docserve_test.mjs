// `dochost serve` on the memo (issue 13): the editor's requests and the
// document view's renditions go to one asgard-core per animation — the
// medium plugin's node.  An edit through the editor's WebSocket, then a
// recompute, changes the picture the document view gets from GET /frame;
// a second view (the document page's socket) hears the new motion; through
// it all dochost runs exactly one asgard-core, and after that slave is
// killed the next action starts one new slave that has the edited text.
// Node (its WebSocket, Node 20's --experimental-websocket); then, where
// Chromium is, the document view's toolbar in the browser.
import { spawnSync } from 'node:child_process';
import { existsSync, readFileSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { checker, coreChildren, launchBrowser, startStudio, sleep, waitFor, wsView } from './common.mjs';

const [dochost, doc, outDir] = process.argv.slice(2);
const { check, failures } = checker();
const { url, port, proc } = await startStudio(dochost, doc, 'serve');

const slaves = () => coreChildren(proc.pid);

async function frame(t, handles = 0) {
  const r = await fetch(`${url}frame?a=0&t=${t}&handles=${handles}`);
  return { status: r.status, live: r.headers.get('x-asgard-live'), caption: r.headers.get('x-asgard-status'),
    interval: r.headers.get('x-asgard-interval'), type: r.headers.get('content-type'),
    bytes: Buffer.from(await r.arrayBuffer()) };
}

const view = () => wsView(port);

try {
  const page = await (await fetch(url)).text();
  check(/<figure class="rendition placed" style="left:\d+px;top:\d+px" data-a="0">/.test(page) && page.includes('class="recompute"'),
    'the document view shows the animation as a rendition with the host\'s toolbar');
  // The host's own pages: as `dochost convert` lays the PDF out (its
  // --layout), each page a picture the host drew, the rendition over the
  // animation's region.
  const layoutFile = join(outDir, 'memo-layout.json');
  const converted = spawnSync(dochost, ['convert', doc, '-o', join(outDir, 'memo.pdf'), '--layout', layoutFile, '--quiet']);
  check(converted.status === 0, `dochost convert writes the PDF and its layout (${converted.status}: ${converted.stderr})`);
  const layout = JSON.parse(readFileSync(layoutFile, 'utf8'));
  const pageCount = (page.match(/<div class="page" data-page=/g) || []).length;
  check(pageCount === layout.pages.length, `the document view has the PDF's ${layout.pages.length} page(s) (${pageCount})`);
  const picture = await fetch(`${url}page?n=0`);
  check(picture.status === 200 && picture.headers.get('content-type') === 'image/png' &&
    Buffer.from(await picture.arrayBuffer()).subarray(1, 4).toString() === 'PNG', 'GET /page?n=0 is the first page\'s picture');
  check((await fetch(`${url}page?n=${layout.pages.length}`)).status === 404 && (await fetch(`${url}page?n=x`)).status === 404,
    'a page the document does not have is 404');
  const regions = layout.pages.flatMap((p, k) => p.filter((b) => b.kind === 'embedded').map((b) => ({ ...b, page: k })));
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

  // The slave dies: the action that finds it dead restarts it once (one
  // new slave, with the edited text: the node's text followed the edit) and
  // succeeds; the views hear of no error.
  process.kill(same[0], 'SIGKILL');
  await waitFor(() => !slaves().includes(same[0]), 'the killed slave gone');
  const redone = await editor.call('simulate');
  check(redone.result && redone.result.ok, `the action that finds the slave dead restarts it and succeeds (${JSON.stringify(redone.error || redone.result)})`);
  check(!editor.events.some((e) => e.event === 'error'), 'no error reaches the views');
  const reopened = await editor.call('open');
  check(reopened.result && reopened.result.state.text.includes('-init_pos {1 -1 0}'),
    'the restarted slave has the edited text');
  const restarted = slaves();
  check(restarted.length === 1 && restarted[0] !== same[0], `one new asgard-core (${same} → ${restarted})`);
  const again = await frame(1);
  check(again.live === '1' && again.bytes.equals(after.bytes), `the restarted slave draws the edited scene (${again.caption})`);

  // The document view in Chromium (when there is one): the renditions play
  // in WebGL from the pose stream (no picture fetched while playing) and
  // agree with the slave's picture on where the bodies are drawn; a second
  // rendition of the animation keeps in step on the shared clock; an edit
  // made in another view reaches both (the `scene` event); Recompute goes
  // through the same slave; Handles draws the editor's handles over the
  // WebGL rendition (no picture fetched, even while playing) and a drag of
  // one edits the session; without WebGL the page shows the slave's
  // pictures (with Handles, its handles).
  if (existsSync('/usr/bin/chromium') && process.env.ASGARD_WEB_MODULES &&
      existsSync(join(process.env.ASGARD_WEB_MODULES, 'playwright-core/package.json'))) {
    const { context, close } = await launchBrowser();
    try {
      const page = context.pages()[0] ?? await context.newPage();
      const errors = [];
      page.on('pageerror', (e) => errors.push(String(e)));
      let frameRequests = 0;
      const scripts = [];
      page.on('request', (r) => { if (r.url().includes('/frame?')) ++frameRequests; });
      page.on('response', async (r) => {
        if (/\.js$/.test(new URL(r.url()).pathname)) scripts.push({ path: new URL(r.url()).pathname, bytes: (await r.body()).length });
      });
      await page.goto(url);
      const fig = (k) => `figure.rendition >> nth=${k}`;
      const drawn = (k = 0) => page.evaluate((i) => Number(document.querySelectorAll('figure.rendition')[i].dataset.drawn || 0), k);
      const renderer = (k = 0) => page.evaluate((i) => document.querySelectorAll('figure.rendition')[i].dataset.renderer, k);
      // Where the bodies are in a picture, as fractions of its width and
      // height: the centroid and box of the pixels that differ from the
      // corner's colour (the background) by more than 24 in some channel.
      const blobOf = (k, source) => page.evaluate(async ([i, src]) => {
        const f = document.querySelectorAll('figure.rendition')[i];
        let image;
        if (src === 'canvas') image = f.querySelector('canvas');
        else {
          image = new Image();
          image.src = src === 'img' ? f.querySelector('img').src : src;
          await image.decode();
        }
        const w = image.width, h = image.height;
        const c = document.createElement('canvas');
        c.width = w; c.height = h;
        const g = c.getContext('2d');
        g.drawImage(image, 0, 0, w, h);
        const d = g.getImageData(0, 0, w, h).data;
        let n = 0, sx = 0, sy = 0, x0 = w, x1 = 0, y0 = h, y1 = 0;
        for (let y = 0; y < h; ++y)
          for (let x = 0; x < w; ++x) {
            const o = 4 * (y * w + x);
            if (Math.max(Math.abs(d[o] - d[0]), Math.abs(d[o + 1] - d[1]), Math.abs(d[o + 2] - d[2])) <= 24) continue;
            ++n; sx += x; sy += y;
            x0 = Math.min(x0, x); x1 = Math.max(x1, x); y0 = Math.min(y0, y); y1 = Math.max(y1, y);
          }
        return n ? { n: n / (w * h), cx: sx / n / w, cy: sy / n / h, box: [x0 / w, y0 / h, x1 / w, y1 / h] } : null;
      }, [k, source]);
      let fetches = 0;  // a fresh URL each time: an <img> of a URL seen before comes from the page's image cache
      const frameUrl = (t, handles = 0) => `/frame?a=0&t=${t}&handles=${handles}&n=${++fetches}`;
      // The WebGL picture and the slave's agree when their centroids are
      // within 2% of the picture (the balls are about 10% across; the
      // renderers differ in shading and edges, not in the camera).
      const agree = (webgl, slave) => !!webgl && !!slave && Math.abs(webgl.cx - slave.cx) < 0.02 &&
        Math.abs(webgl.cy - slave.cy) < 0.02 && webgl.box.every((v, i) => Math.abs(v - slave.box[i]) < 0.03);
      check(await waitFor(async () => (await renderer()) === 'webgl' && (await drawn()) >= 1, 'the WebGL rendition'),
        'the document view plays the animation in WebGL');
      const g0 = await blobOf(0, 'canvas'), s0 = await blobOf(0, frameUrl(0));
      check(agree(g0, s0), `at t = 0 the WebGL rendition draws the bodies where the slave's picture has them (${JSON.stringify(g0)} vs ${JSON.stringify(s0)})`);
      await page.screenshot({ path: join(outDir, '1-document-view.png') });
      // The figure lies on the region of the PDF's layout (points → CSS
      // pixels, 96/72), within a pixel; the page's picture has the text.
      await waitFor(() => page.evaluate(() => { const i = document.querySelector('.page-picture'); return i.complete && i.naturalWidth > 0; }), 'the page\'s picture');
      const placed = await page.evaluate(() => {
        const f = document.querySelector('figure.rendition'), p = f.closest('.page');
        const pr = p.getBoundingClientRect(), fr = f.querySelector('canvas, img').getBoundingClientRect();
        const pic = p.querySelector('.page-picture');
        const c = document.createElement('canvas');
        c.width = pic.naturalWidth; c.height = pic.naturalHeight;
        c.getContext('2d').drawImage(pic, 0, 0);
        const d = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;
        let dark = 0;  // text-coloured pixels above the figure
        const above = Math.floor((fr.top - pr.top) * c.height / pr.height);
        for (let o = 0; o < 4 * c.width * above; o += 4) if (d[o] < 96 && d[o + 1] < 96 && d[o + 2] < 96) ++dark;
        return { page: Number(p.dataset.page), x: fr.left - pr.left, y: fr.top - pr.top, w: fr.width, h: fr.height,
          scale: c.width / pr.width, dark: dark / Math.max(1, c.width * above) };
      });
      const r0 = regions[0], k = 96 / 72;
      check(!!r0 && placed.page === r0.page && [placed.x - r0.x * k, placed.y - r0.y * k, placed.w - r0.w * k, placed.h - r0.h * k].every((e) => Math.abs(e) <= 1),
        `the rendition lies on the animation's region of the PDF's page (${JSON.stringify(placed)} vs ${JSON.stringify(r0)} pt)`);
      check(placed.scale >= 1.9 && placed.dark > 0.005, `the page's picture has the text above the animation, at twice the page's pixels (${placed.dark.toFixed(4)} dark, ×${placed.scale.toFixed(2)})`);
      // The page's text lies over the picture, line by line where the host
      // set it: each line's box spans the ink of its words on the picture
      // (leftmost and rightmost dark pixels within 2 CSS pixels of its ends),
      // and a drag across a line selects its words.
      check(await waitFor(() => page.evaluate(() => document.body.dataset.pageText === 'fitted'), 'the page text'), 'the page\'s text is fitted to its lines');
      const lines = await page.evaluate(() => {
        const p = document.querySelector('.page'), pr = p.getBoundingClientRect();
        const pic = p.querySelector('.page-picture');
        const c = document.createElement('canvas');
        c.width = pic.naturalWidth; c.height = pic.naturalHeight;
        c.getContext('2d').drawImage(pic, 0, 0);
        const d = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;
        const k = c.width / pr.width;
        return [...p.querySelectorAll('.page-text span[data-w]')].map((s) => {
          const r = s.getBoundingClientRect();
          const x0 = Math.floor((r.left - pr.left - 6) * k), x1 = Math.ceil((r.right - pr.left + 6) * k);
          const y0 = Math.floor((r.top - pr.top) * k), y1 = Math.ceil((r.bottom - pr.top) * k);
          let left = Infinity, right = -Infinity;
          for (let y = y0; y < y1; ++y)
            for (let x = Math.max(0, x0); x < Math.min(c.width, x1); ++x) {
              const o = 4 * (y * c.width + x);
              if (d[o] < 128 && d[o + 1] < 128 && d[o + 2] < 128) { left = Math.min(left, x); right = Math.max(right, x); }
            }
          return { text: s.textContent, left: r.left - pr.left, right: r.right - pr.left, w: Number(s.dataset.w),
            inkLeft: left / k, inkRight: (right + 1) / k, top: r.top, middle: (r.top + r.bottom) / 2, x: r.left, x1: r.right };
        });
      });
      const layerText = lines.map((l) => l.text).join(' ');
      check(['To:', 'Whom it may concern', 'Thanks to Vance for putting this example together'].every((t) => lines.some((l) => l.text === t)),
        `the page's text layer has the memo's lines (${JSON.stringify(layerText)})`);
      const off = lines.filter((l) => !(Math.abs(l.right - l.left - l.w) <= 1 && Math.abs(l.inkLeft - l.left) <= 2 && Math.abs(l.inkRight - l.right) <= 2));
      check(lines.length >= 4 && off.length === 0, `each line of the text layer spans its words' ink on the page's picture (${JSON.stringify(off)})`);
      const thanks = lines.find((l) => l.text.startsWith('Thanks'));
      if (thanks) {
        await page.mouse.move(thanks.x + 1, thanks.middle);
        await page.mouse.down();
        await page.mouse.move(thanks.x1 - 1, thanks.middle, { steps: 5 });
        await page.mouse.up();
        const selected = await page.evaluate(() => String(window.getSelection()));
        check(selected === thanks.text, `a drag across a line of the page selects its words (${JSON.stringify(selected)})`);
        await page.evaluate(() => window.getSelection().removeAllRanges());
      }
      // Selected whole, the page's text reads as the page: a field's label
      // and its text on one line, the fields on lines of their own.
      const whole = await page.evaluate(() => {
        const r = document.createRange();
        r.selectNodeContents(document.querySelector('.page-text'));
        const sel = window.getSelection();
        sel.removeAllRanges();
        sel.addRange(r);
        const text = String(sel);
        sel.removeAllRanges();
        return text;
      });
      check(/To: Whom it may concern\s*\n\s*From: Wayne\s*\n/.test(whole), `the page's text copies line by line, each field on its line (${JSON.stringify(whole)})`);
      await page.locator(`${fig(0)} >> .time`).fill('1000');
      check(await waitFor(async () => (await page.textContent(`${fig(0)} >> .t`)) === 't = 3.00 s', 'the slider'), 'the slider at its end shows t = 3.00 s');
      const g3 = await blobOf(0, 'canvas'), s3 = await blobOf(0, frameUrl(3));
      check(agree(g3, s3) && !agree(g3, g0), `at t = 3 too, and the bodies moved (${JSON.stringify(g3)} vs ${JSON.stringify(s3)})`);

      // A second rendition of the animation on the same clock.
      await page.click(`${fig(0)} >> .another`);
      check(await waitFor(async () => (await renderer(1)) === 'webgl', 'the second rendition'), 'Another view adds a second WebGL rendition');
      const inView = await page.evaluate(() => {
        const r = document.querySelectorAll('figure.rendition')[1].getBoundingClientRect();
        return { top: r.top, bottom: r.bottom, height: innerHeight };
      });
      check(inView.top >= 0 && inView.bottom <= inView.height,
        `the new rendition, below the pages, is scrolled into view (${JSON.stringify(inView)})`);
      const times = () => page.evaluate(() => [...document.querySelectorAll('figure.rendition')].map((f) => Number(f.dataset.t)));
      check((await times()).every((t) => t === 3), `it shows the first one's time (${await times()})`);
      await page.locator(`${fig(1)} >> .time`).fill('500');
      check(await waitFor(async () => (await times()).every((t) => Math.abs(t - 1.5) < 1e-9), 'both at 1.5 s'),
        `the second's slider moves both (${await times()})`);
      // Play (from the first) runs both in real time without a picture from the server.
      const requestsBefore = frameRequests, drawnBefore = await drawn(1);
      const started = Date.now();
      await page.click(`${fig(0)} >> .play`);
      check(await waitFor(async () => (await page.textContent(`${fig(1)} >> .play`)) === 'Pause', 'pause'), 'Play shows Pause on every rendition');
      check(await waitFor(async () => (await page.textContent(`${fig(0)} >> .play`)) === 'Play', 'the end', 10000), 'playback stops at the end (Loop off)');
      const elapsed = (Date.now() - started) / 1000, frames = (await drawn(1)) - drawnBefore;
      const after = await times();
      check(after.every((t) => t === 3), `both renditions end at t = 3 (${after})`);
      check(elapsed >= 1.4 && elapsed < 6, `1.5 s of motion played in ${elapsed.toFixed(2)} s of wall time (real time)`);
      check(frames >= 10, `${frames} WebGL frames drawn while playing (${(frames / elapsed).toFixed(1)} a second)`);
      check(frameRequests === requestsBefore, `no picture fetched from the server while playing (${frameRequests - requestsBefore})`);
      await page.screenshot({ path: join(outDir, '2-two-renditions.png') });
      // Loop: set on one rendition, it is set on the other (one clock);
      // played from t = 2.5 it goes past the end to the start and plays on.
      await page.check(`${fig(0)} >> .loop`);
      check(await page.isChecked(`${fig(1)} >> .loop`), 'Loop on one rendition is on for the other');
      await page.locator(`${fig(0)} >> .time`).fill('833');
      await page.click(`${fig(0)} >> .play`);
      let late = false;
      const wrapped = await waitFor(async () => {
        const t = Number(await page.evaluate(() => document.querySelector('figure.rendition').dataset.t));
        late ||= t > 2.6;
        return late && t < 1.5 && (await page.textContent(`${fig(1)} >> .play`)) === 'Pause';
      }, 'the loop', 10000);
      check(wrapped, 'with Loop, playback goes past t = 3 back to the start and plays on');
      await page.click(`${fig(0)} >> .play`);
      await page.uncheck(`${fig(0)} >> .loop`);
      await page.locator(`${fig(0)} >> .time`).fill('1000');  // back at t = 3 for what follows
      await waitFor(async () => (await times()).every((t) => t === 3), 'the end again');

      // An edit simulated in another view reaches both renditions.
      const other = await view();
      await other.call('set_parameter', { element: 'b3', param: 'init_pos', values: [1, -2, 0] });
      await other.call('simulate');
      const edited = await blobOf(0, frameUrl(3));
      check(!agree(edited, s3), `the edit moves b3 in the slave's picture (${JSON.stringify(edited)} vs ${JSON.stringify(s3)})`);
      check(await waitFor(async () => agree(await blobOf(0, 'canvas'), edited) && agree(await blobOf(1, 'canvas'), edited), 'the edited motion'),
        'both WebGL renditions draw the edited motion');
      await page.screenshot({ path: join(outDir, '3-edited-elsewhere.png') });
      await page.click(`${fig(0)} >> .recompute`);
      check(await waitFor(async () => (await page.textContent(`${fig(0)} >> .status`)).startsWith('2 bodies'), 'recompute'),
        `the status after Recompute: ${await page.textContent(`${fig(0)} >> .status`)}`);
      // Handles: the editor's handles over the WebGL rendition (no picture
      // from the server, even while playing), draggable through the session.
      // The page opened with a small script; the handles' bundle (three.js
      // and the editor's viewer) comes when Handles is first checked.
      const documentJs = scripts.find((x) => x.path === '/document.js');
      check(documentJs && documentJs.bytes < 64 * 1024 && !scripts.some((x) => x.path === '/handles.js'),
        `the page opened with document.js alone (${JSON.stringify(scripts)}), under 64 KiB`);
      const overlay = (k = 0) => `window.asgardDocument.animations.get(0).renditions[${k}].overlay`;
      const handlesOf = (k = 0) => page.evaluate(`${overlay(k)} ? ${overlay(k)}.viewer.handleList() : []`);
      const requestsBeforeHandles = frameRequests;
      await page.check(`${fig(0)} >> .handles`);
      check(await waitFor(async () => (await handlesOf()).some((h) => h.id === 'b3.init_pos' && h.shown), 'the handles'),
        'Handles shows the handles over the rendition');
      check((await renderer()) === 'webgl', `the rendition stays WebGL with Handles on (${await renderer()})`);
      const handlesJs = scripts.filter((x) => x.path === '/handles.js');
      check(handlesJs.length === 1 && handlesJs[0].bytes > 100 * 1024, `Handles loaded the handles' bundle once (${JSON.stringify(handlesJs)})`);
      const kinds = [...new Set((await handlesOf()).filter((h) => h.shown).map((h) => h.kind))].sort();
      check(['position', 'rotation', 'velocity'].every((k) => kinds.includes(k)), `the handles' kinds: ${kinds.join(', ')}`);
      await page.locator(`${fig(0)} >> .time`).fill('0');
      const b3 = (await handlesOf()).find((h) => h.id === 'b3.init_pos');
      check(JSON.stringify(b3.value) === '[1,-2,0]', `b3's position handle holds the session's -init_pos (${JSON.stringify(b3.value)})`);
      // The handle is drawn where the player draws b3 at t = 0 (its start).
      const b3Drawn = await page.evaluate(() => {
        const r = window.asgardDocument.animations.get(0).renditions[0];
        const box = r.player.canvas.getBoundingClientRect(), p = r.player.project('b3', r.player.times.t0);
        return { x: box.left + p[0], y: box.top + p[1] };
      });
      check(Math.hypot(b3Drawn.x - b3.x, b3Drawn.y - b3.y) < 1.5,
        `b3's position handle is on b3 as the player draws it (${b3.x.toFixed(1)}, ${b3.y.toFixed(1)} vs ${b3Drawn.x.toFixed(1)}, ${b3Drawn.y.toFixed(1)})`);
      await page.screenshot({ path: join(outDir, '4-handles.png'), clip: { x: 0, y: 150, width: 640, height: 330 } });
      // Playing with the handles shown: every frame in WebGL, none fetched.
      const drawnHandles = await drawn(0);
      const playStart = Date.now();
      await page.click(`${fig(0)} >> .play`);
      check(await waitFor(async () => (await page.textContent(`${fig(0)} >> .play`)) === 'Play' && Date.now() - playStart > 500, 'the end', 10000),
        'playback with handles runs to the end');
      const handleFrames = (await drawn(0)) - drawnHandles;
      check(handleFrames >= 20, `${handleFrames} frames drawn with handles while playing`);
      check(frameRequests === requestsBeforeHandles, `no picture fetched from the server with handles shown (${frameRequests - requestsBeforeHandles})`);
      // Drag b3's position handle 40 pixels right: the session's text changes by the drag.
      await page.locator(`${fig(0)} >> .time`).fill('0');
      const h0 = (await handlesOf()).find((h) => h.id === 'b3.init_pos');
      const sceneEvents = other.events.filter((e) => e.event === 'scene').length;
      await page.mouse.move(h0.x, h0.y);
      await page.mouse.down();
      for (let i = 1; i <= 8; ++i) { await page.mouse.move(h0.x + 5 * i, h0.y); await sleep(30); }
      const during = await page.evaluate(() => {
        const r = window.asgardDocument.animations.get(0).renditions[0];
        const box = r.player.canvas.getBoundingClientRect(), p = r.player.project('b3');
        return { x: box.left + p[0], y: box.top + p[1], label: r.figure.querySelector('.handle-label').textContent };
      });
      check(Math.hypot(during.x - (h0.x + 40), during.y - h0.y) < 2, `while dragging, the player draws b3 under the pointer (${during.x.toFixed(1)}, ${during.y.toFixed(1)})`);
      check(/^b3 -init_pos \{/.test(during.label), `a label shows the value dragged: "${during.label}"`);
      await page.mouse.up();
      check(await waitFor(() => other.events.filter((e) => e.event === 'scene').length > sceneEvents, 'the re-simulation'),
        'the drag\'s end re-simulates (another view hears the new motion)');
      const textEvents = other.events.filter((e) => e.event === 'text' && e.element === 'b3' && e.param === 'init_pos');
      check(textEvents.length >= 2, `the drag sent b3's -init_pos while dragging (${textEvents.length} text events)`);
      const reread = await other.call('open');
      const moved = /body b3 [^\n]*-init_pos \\?\{([^}\\]*)\\?\}/.exec(reread.result.state.text);
      const value = moved ? moved[1].split(' ').map(Number) : null;
      const h1 = (await handlesOf()).find((h) => h.id === 'b3.init_pos');
      check(value && JSON.stringify(value) === JSON.stringify(h1.value), `the session's text has b3 -init_pos {${moved && moved[1]}} as the handle does`);
      // The value is the one drawn under the pointer 40 pixels right of
      // where the drag began (checked above, in the camera of the drag: the
      // new motion may frame the picture anew, as without handles).
      check(value && value[1] === -2 && value[0] !== 1 && during.label === `b3 -init_pos {${moved[1]}}`,
        `the value is the one dragged to (the label said "${during.label}")`);
      const b3After = await page.evaluate(() => {
        const r = window.asgardDocument.animations.get(0).renditions[0];
        const box = r.player.canvas.getBoundingClientRect(), p = r.player.project('b3', r.player.times.t0);
        return { x: box.left + p[0], y: box.top + p[1] };
      });
      // Handle and player are compared in one camera: the new motion may
      // arrive (and frame the picture anew) after h1 was read, so the
      // handle is read again with each look at the player.
      let last = null;
      check(await waitFor(async () => {
        const p = await page.evaluate(() => window.asgardDocument.animations.get(0).renditions[0].player.project('b3', 0));
        const box = await page.evaluate(() => window.asgardDocument.animations.get(0).renditions[0].player.canvas.getBoundingClientRect().toJSON());
        const h = (await handlesOf()).find((x) => x.id === 'b3.init_pos');
        last = { player: [box.left + p[0], box.top + p[1]], handle: h && [h.x, h.y] };
        return h && Math.hypot(box.left + p[0] - h.x, box.top + p[1] - h.y) < 1.5;
      }, 'the new motion'), `the new motion starts b3 at the handle (${b3After.x.toFixed(1)}, ${b3After.y.toFixed(1)}; last look ${JSON.stringify(last)})`);
      const second = (await handlesOf(1)).length;
      check(second === 0, `the second rendition (Handles off) made no handles (${second})`);
      check(frameRequests === requestsBeforeHandles, `no picture fetched from the server through the drag (${frameRequests - requestsBeforeHandles})`);
      await page.screenshot({ path: join(outDir, '5-handle-dragged.png'), clip: { x: 0, y: 150, width: 640, height: 330 } });
      await page.uncheck(`${fig(0)} >> .handles`);
      check(await waitFor(() => page.evaluate(() => document.querySelector('canvas.asgard-handles').style.display === 'none'), 'hidden'),
        'unchecking Handles hides them');

      // A view whose -pos is an expression of t (it pans 1 unit a second):
      // the renditions follow its camera per frame (the stream's views), as
      // the slave's pictures do.
      const stillView = await blobOf(0, frameUrl(3));
      const panned = `${reread.result.state.text.trimEnd()}\nview pan -pos {{-t} 0 0}\n`;
      const updated = await other.call('update', { text: panned });
      check(updated.result && updated.result.simulated && updated.result.simulated.ok,
        `a view whose -pos is an expression of t is added (${JSON.stringify(updated.error || (updated.result && updated.result.simulated))})`);
      const cameraAt = (t) => page.evaluate((time) => {
        const r = window.asgardDocument.animations.get(0).renditions[0];
        r.player.draw(time);
        return r.player.camera();
      }, t);
      check(await waitFor(async () => {
        const c0 = await cameraAt(0), c3 = await cameraAt(3);
        return Math.abs(Math.hypot(...c3.target.map((v, k) => v - c0.target[k])) - 3) < 1e-3;
      }, 'the moving view'), 'the rendition\'s camera pans with the view: its target moves 3 units from t = 0 to t = 3');
      for (const [t, slider] of [[1.5, '500'], [3, '1000']]) {
        await page.locator(`${fig(0)} >> .time`).fill(slider);
        await waitFor(async () => Number(await page.evaluate(() => document.querySelector('figure.rendition').dataset.t)) === t, 'the slider');
        const webgl = await blobOf(0, 'canvas'), slave = await blobOf(0, frameUrl(t));
        check(agree(webgl, slave), `at t = ${t} the WebGL rendition draws the bodies where the slave's picture of the moving view has them (${JSON.stringify(webgl)} vs ${JSON.stringify(slave)})`);
        // Not where the still view had them: the view moved them on the screen.
        if (t === 3) check(!agree(webgl, stillView), `the panned picture differs from the still view's (${JSON.stringify(stillView)})`);
      }
      await page.screenshot({ path: join(outDir, '6-moving-view.png'), clip: { x: 0, y: 150, width: 640, height: 330 } });
      // Handles again: the overlay shows the views' handles (the moving
      // view's, read-only) as the editor does; a click on a body selects it
      // (the box around it), a click off every body clears the selection.
      await page.check(`${fig(0)} >> .handles`);
      check(await waitFor(async () => (await handlesOf()).some((h) => h.kind === 'view' && h.element === 'pan' && h.shown && !h.editable), 'the view handles'),
        'the overlay shows the moving view\'s handles, read-only');
      await page.locator(`${fig(0)} >> .time`).fill('500');
      const target = await page.evaluate(() => {
        const r = window.asgardDocument.animations.get(0).renditions[0];
        const box = r.player.canvas.getBoundingClientRect(), p = r.player.project('b2', 1.5);
        return { x: box.left + p[0], y: box.top + p[1], right: box.right, bottom: box.bottom, left: box.left, top: box.top };
      });
      // A point of b2 (about 18 px across here) at least 8 px from every handle shown.
      const shownHandles = (await handlesOf()).filter((h) => h.shown);
      const spot = [[0, 0], [6, 0], [-6, 0], [0, 6], [0, -6]].map(([dx, dy]) => ({ x: target.x + dx, y: target.y + dy }))
        .find((q) => shownHandles.every((h) => Math.hypot(h.x - q.x, h.y - q.y) > 8));
      const selected = () => page.evaluate(() => document.querySelector('figure.rendition').dataset.selected);
      if (check(!!spot, 'a point of b2 away from the handles')) {
        await page.mouse.click(spot.x, spot.y);
        check(await waitFor(async () => (await selected()) === 'b2', 'the selection'), `a click on b2 selects it (${await selected()})`);
        check(await page.evaluate(`${overlay(0)}.viewer.selectionBox.visible`), 'the selected body has its box');
        await page.screenshot({ path: join(outDir, '7-selected.png'), clip: { x: 0, y: 150, width: 640, height: 330 } });
        await page.mouse.click(target.left + 5, target.top + 5);  // the toolbar lies over the foot
        check(await waitFor(async () => (await selected()) === '', 'no selection'), 'a click off every body clears the selection');
      }
      await page.uncheck(`${fig(0)} >> .handles`);
      check(errors.length === 0, `no page errors (${errors.join('; ')})`);

      // Without WebGL the renditions are the slave's pictures.
      const plain = await context.newPage();
      await plain.addInitScript(() => {
        const get = HTMLCanvasElement.prototype.getContext;
        HTMLCanvasElement.prototype.getContext = function (kind, ...rest) {
          return /webgl/.test(kind) ? null : get.call(this, kind, ...rest);
        };
      });
      await plain.goto(url);
      check(await waitFor(() => plain.evaluate(() => {
        const f = document.querySelector('figure.rendition');
        return f.dataset.renderer === 'picture' && Number(f.dataset.drawn) >= 1 && !f.querySelector('canvas');
      }), 'the picture fallback'), 'without WebGL the document view shows the slave\'s picture');
      await plain.screenshot({ path: join(outDir, '8-no-webgl.png') });
      // There, Handles is the slave's picture with the position handles drawn.
      const plainFrame = (await frame(3)).bytes, handlesFrame = (await frame(3, 1)).bytes;
      writeFileSync(join(outDir, 'frame-3.png'), plainFrame);
      writeFileSync(join(outDir, 'frame-3-handles.png'), handlesFrame);
      check(!plainFrame.equals(handlesFrame), 'the slave\'s picture with handles differs from the one without');
      await plain.locator('figure.rendition >> nth=0 >> .time').fill('1000');
      await plain.check('figure.rendition >> nth=0 >> .handles');
      check(await waitFor(() => plain.evaluate(async () => {
        const a = await (await fetch(document.querySelector('figure.rendition img').src)).arrayBuffer();
        const b = await (await fetch('/frame?a=0&t=3&handles=1')).arrayBuffer();
        return a.byteLength === b.byteLength && new Uint8Array(a).every((x, i) => x === new Uint8Array(b)[i]);
      }), 'handles drawn'), 'without WebGL, Handles shows the slave\'s picture with the position handles');
      await plain.screenshot({ path: join(outDir, '9-no-webgl-handles.png') });
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
