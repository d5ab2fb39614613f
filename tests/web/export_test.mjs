// The control panel's exports in headless Chromium (issue 13, seed Figure
// 4.1) on the seed pendulum: Image downloads the viewer's picture as a PNG
// (the same pixels as the canvas), glTF the bodies at the shown time (a glTF
// 2.0 JSON whose embedded buffer decodes to the meshes, with each body's
// node at its pose), Movie an MP4 made by the server with asgard render (a
// frame per pose frame, the canvas's size, seen as the viewer shows it).
// Screenshots and the downloads go to OUT_DIR.
import { execFileSync } from 'node:child_process';
import { readFileSync } from 'node:fs';
import { join } from 'node:path';
import { browserTest, openEditor, waitFor } from './common.mjs';

const [asgard, scene, outDir] = process.argv.slice(2);

// Picture statistics in the page: the centroid (as fractions of the size)
// and count of the pixels that are not the background (the top left
// corner's colour) of an image given by URL, or of the canvas.
const bodyCentroid = (page, url) => page.evaluate(async (src) => {
  let source = window.asgard.graphical.canvas;
  if (src) {
    source = new Image();
    source.src = src;
    await source.decode();
  }
  const w = source.width, h = source.height;
  const c = document.createElement('canvas');
  c.width = w; c.height = h;
  const g = c.getContext('2d');
  g.drawImage(source, 0, 0);
  const d = g.getImageData(0, 0, w, h).data;
  let n = 0, sx = 0, sy = 0;
  for (let y = 0; y < h; ++y)
    for (let x = 0; x < w; ++x) {
      const k = 4 * (y * w + x);
      if (Math.abs(d[k] - d[0]) + Math.abs(d[k + 1] - d[1]) + Math.abs(d[k + 2] - d[2]) > 90) { ++n; sx += x; sy += y; }
    }
  return { n, x: sx / n / w, y: sy / n / h, w, h };
}, url);

async function saveDownload(page, button, name) {
  const [d] = await Promise.all([page.waitForEvent('download', { timeout: 20000 }), page.click(button)]);
  const path = join(outDir, name);
  await d.saveAs(path);
  return { path, suggested: d.suggestedFilename() };
}

await browserTest(asgard, scene, 'export', async ({ check, url, context }) => {
  const { page, errors, ok } = await openEditor(context, url, 'b3');
  check(ok, 'the editor shows the pendulum');
  // Turn the view a little so that the movie's camera is not the default one.
  const box = await page.evaluate(() => { const r = window.asgard.graphical.canvas.getBoundingClientRect(); return { x: r.left, y: r.top, w: r.width, h: r.height }; });
  await page.mouse.move(box.x + box.w / 2, box.y + box.h / 2);
  await page.mouse.down();
  await page.mouse.move(box.x + box.w / 2 + 60, box.y + box.h / 2 + 25, { steps: 5 });
  await page.mouse.up();
  await page.evaluate(() => window.asgard.graphical.seek(1.5));

  // Image: the PNG holds the canvas's pixels.
  const img = await saveDownload(page, '#export-image', 'scene.png');
  const png = readFileSync(img.path);
  check(png.subarray(1, 4).toString() === 'PNG', `Image downloads a PNG (${img.suggested}, ${png.length} bytes)`);
  const size = { w: png.readUInt32BE(16), h: png.readUInt32BE(20) };
  const canvas = await page.evaluate(() => ({ w: window.asgard.graphical.canvas.width, h: window.asgard.graphical.canvas.height }));
  check(size.w === canvas.w && size.h === canvas.h, `of the canvas's size ${size.w}×${size.h}`);
  const same = await page.evaluate(async (src) => {
    const im = new Image();
    im.src = src;
    await im.decode();
    const read = (s) => { const c = document.createElement('canvas'); c.width = s.width; c.height = s.height; const g = c.getContext('2d'); g.drawImage(s, 0, 0); return g.getImageData(0, 0, s.width, s.height).data; };
    const a = read(im), b = read(window.asgard.graphical.canvas);
    let differ = 0, dark = 0;
    for (let k = 0; k < a.length; k += 4) {
      if (a[k] !== b[k] || a[k + 1] !== b[k + 1] || a[k + 2] !== b[k + 2]) ++differ;
      if (a[k] < 60) ++dark;
    }
    return { differ, dark };
  }, `data:image/png;base64,${png.toString('base64')}`);
  check(same.differ === 0 && same.dark > 500, `its pixels are the canvas's (${same.differ} differ, ${same.dark} dark)`);

  // glTF: a valid 2.0 JSON, one node per body at its shown pose, meshes
  // decoded from the embedded buffer.
  const gl = await saveDownload(page, '#export-gltf', 'scene.gltf');
  const gltf = JSON.parse(readFileSync(gl.path, 'utf8'));
  check(gltf.asset && gltf.asset.version === '2.0', `glTF downloads glTF ${gltf.asset && gltf.asset.version} (${gl.suggested})`);
  const buffers = gltf.buffers.map((b) => {
    const m = /^data:application\/octet-stream;base64,(.*)$/.exec(b.uri);
    return m ? Buffer.from(m[1], 'base64') : null;
  });
  check(buffers.length === 1 && buffers[0] && buffers[0].length === gltf.buffers[0].byteLength,
    `one embedded buffer of ${gltf.buffers[0].byteLength} bytes`);
  const t = await page.evaluate(() => window.asgard.graphical.t);
  const shown = await page.evaluate(() => Object.fromEntries([...window.asgard.graphical.bodies].map(([n, b]) => [n, [...b.group.position.toArray(), ...b.group.quaternion.toArray()]])));
  for (const name of ['b1', 'b2', 'b3']) {
    const node = gltf.nodes.find((n) => n.name === name);
    const want = shown[name];
    const got = node ? [...(node.translation || [0, 0, 0]), ...(node.rotation || [0, 0, 0, 1])] : null;
    check(got && got.every((v, k) => Math.abs(v - want[k]) < 1e-5),
      `node ${name} at its pose at t = ${t}: (${got && got.slice(0, 3).map((v) => v.toFixed(3)).join(', ')})`);
  }
  // Every POSITION accessor lies in its buffer view and its min/max are the
  // decoded vertices' bounds.
  let vertices = 0, boundsOk = true, inside = true;
  for (const mesh of gltf.meshes)
    for (const prim of mesh.primitives) {
      const acc = gltf.accessors[prim.attributes.POSITION];
      const view = gltf.bufferViews[acc.bufferView];
      const offset = (view.byteOffset || 0) + (acc.byteOffset || 0);
      inside &&= acc.componentType === 5126 && acc.type === 'VEC3' && offset + acc.count * (view.byteStride || 12) <= buffers[0].length;
      const lo = [Infinity, Infinity, Infinity], hi = [-Infinity, -Infinity, -Infinity];
      for (let i = 0; i < acc.count; ++i)
        for (let c = 0; c < 3; ++c) {
          const v = buffers[0].readFloatLE(offset + i * (view.byteStride || 12) + 4 * c);
          lo[c] = Math.min(lo[c], v); hi[c] = Math.max(hi[c], v);
        }
      boundsOk &&= lo.every((v, c) => Math.abs(v - acc.min[c]) < 1e-6) && hi.every((v, c) => Math.abs(v - acc.max[c]) < 1e-6);
      vertices += acc.count;
    }
  check(inside && boundsOk && vertices > 0, `${gltf.meshes.length} meshes, ${vertices} vertices decoded inside the buffer, bounds as declared`);
  // The rod (10 × 1.1 × 1.1) keeps its size.
  const rod = gltf.nodes.find((n) => n.name === 'b1');
  const rodAcc = gltf.accessors[gltf.meshes[gltf.nodes[rod.children[0]].mesh].primitives[0].attributes.POSITION];
  const extent = rodAcc.max.map((v, c) => v - rodAcc.min[c]);
  check(Math.abs(extent[0] - 10) < 1e-5 && Math.abs(extent[1] - 1.1) < 1e-5 && Math.abs(extent[2] - 1.1) < 1e-5,
    `b1's mesh is 10 × 1.1 × 1.1 (${extent.map((v) => v.toFixed(4)).join(' × ')})`);

  // Movie: made by the server, every pose frame, the canvas's size (even).
  // (The editor's handles are hidden to compare the pictures.)
  for (const kind of ['handles', 'velocities', 'links', 'forces', 'lights']) await page.uncheck(`#toggles input[data-kind=${kind}]`);
  await page.evaluate(() => window.asgard.graphical.seek(0));
  const mv = await saveDownload(page, '#export-movie', 'scene.mp4');
  const probe = execFileSync('ffprobe', ['-v', 'error', '-count_frames', '-select_streams', 'v:0',
    '-show_entries', 'stream=codec_name,width,height,nb_read_frames', '-of', 'json', mv.path]).toString();
  const stream = JSON.parse(probe).streams[0];
  const frames = await page.evaluate(() => window.asgard.graphical.poses.times.length);
  const css = await page.evaluate(() => ({ w: window.asgard.graphical.canvas.clientWidth, h: window.asgard.graphical.canvas.clientHeight }));
  check(stream.codec_name === 'h264' && Number(stream.nb_read_frames) === frames,
    `Movie downloads ${mv.suggested}: ${stream.codec_name}, ${stream.nb_read_frames} frames (the motion has ${frames})`);
  check(stream.width === Math.floor(css.w / 2) * 2 && stream.height === Math.floor(css.h / 2) * 2,
    `${stream.width}×${stream.height}, the viewer's size`);
  // Seen as the viewer shows it: the dark bodies' centroid in the first
  // frame is where it is in the canvas at t = 0 (within 1.5 % of the picture; the
  // renderers' perspective and shading differ).
  const first = join(outDir, 'movie-first.png');
  execFileSync('ffmpeg', ['-v', 'error', '-y', '-i', mv.path, '-frames:v', '1', first]);
  const inMovie = await bodyCentroid(page, `data:image/png;base64,${readFileSync(first).toString('base64')}`);
  const inCanvas = await bodyCentroid(page, null);
  check(Math.abs(inMovie.x - inCanvas.x) < 0.015 && Math.abs(inMovie.y - inCanvas.y) < 0.015,
    `the movie's first frame frames the bodies as the viewer: their centroid (${inMovie.x.toFixed(3)}, ${inMovie.y.toFixed(3)}) vs (${inCanvas.x.toFixed(3)}, ${inCanvas.y.toFixed(3)})`);
  const ratio = inMovie.n / (inMovie.w * inMovie.h) / (inCanvas.n / (inCanvas.w * inCanvas.h));
  check(ratio > 0.85 && ratio < 1.15, `at the same size: area ratio ${ratio.toFixed(2)}`);
  const status = await page.evaluate(() => document.getElementById('status').textContent);
  check(/^movie: \d+ KiB$/.test(status), `the status says "${status}"`);

  // A bad request is refused with a message, and the server keeps serving.
  const bad = await page.evaluate(() => window.asgard.conn.call('movie', { width: 5 }).then(() => 'made', (e) => e.message));
  check(/width must be/.test(bad), `a 5-pixel movie is refused: "${bad}"`);
  await page.screenshot({ path: join(outDir, '1-exports.png') });
  check(errors.length === 0, `no page errors ${errors.join('; ')}`);
});
