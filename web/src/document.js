// The live document view of `dochost serve` (seed 6.2.4), bundled into
// build/web/document.js: each <figure class="rendition" data-a="N"> of the
// page is a rendition of animation N with the host's toolbar (on the
// host's own pages, `placed` over the animation's region).  It plays in
// WebGL (player.js) from the meshes and poses the editor server streams
// (the `open` answer and every `scene` event, as the editor's viewer gets
// them), so playback needs no server round trip.  Handles draws the
// editor's handles over the WebGL rendition (overlay.js), from the session's
// parameters this page's WebSocket hears (the `open` answer, `state` and
// `text` events), and a drag edits the same session as the editor's views;
// they are a second bundle (handles.js) that the page loads on first use.
// Where WebGL is missing, and while the slave is down, it shows the slave's
// picture of the rendition (GET /frame; with its position handles when
// Handles is on).  Every rendition of one animation follows one clock, so
// they stay in step.
import { Connection } from './connection.js';
import { createPlayer } from './player.js';

// The handles (overlay.js with three.js and the editor's viewer) are a
// bundle of their own, build/web/handles.js, loaded the first time a
// rendition shows them: the page opens with the player alone.
let handlesModule = null;
const loadHandles = () => (handlesModule ||= import(new URL('handles.js', import.meta.url).href));

// The editor server's meshes and poses as the player takes them (plain
// arrays for its base64 fields; a body without a track keeps its pose; the
// links and force arrows as the stream has them).  The camera is the
// scene's view as the slave's renditions draw it (its last `view`); when
// that view moves (-follow, -trajectory, or -pos, -rot, -scale expressions
// of time or state) its camera per frame, [eye target up] from the
// stream's `views`, which the player follows until the reader turns it.
export function playerData(meshes, poses) {
  const n = poses.times.length, k = poses.bodies.length;
  const flat = new Float32Array(n * k * 7);
  poses.poses.forEach((frame, i) => flat.set(frame, i * k * 7));
  // Links, force arrows and cameras: the same count of numbers in every frame.
  const frames = (list) => (list && list.length === n ? Float32Array.from(list.flat(2)) : new Float32Array(0));
  const views = poses.views || [];
  const view = views[views.length - 1];
  return {
    t0: poses.t0, t1: poses.t1, n, times: poses.times, camera: poses.camera, lights: meshes.lights,
    cameras: view && view.moves ? frames(view.cameras) : new Float32Array(0),
    poses: flat, links: frames(poses.links), arrows: frames(poses.arrows), arrow_length: poses.arrow_length,
    bodies: meshes.bodies.map((b) => {
      const track = poses.bodies.indexOf(b.name);
      return {
        name: b.name, ...(track >= 0 ? { track } : { pose: [0, 0, 0, 0, 0, 0, 1] }),
        pieces: b.pieces.map((p) => (p.sphere ? { color: p.color, sphere: [...p.center, p.radius] }
          : { color: p.color, v: p.vertices, i: p.triangles })),
      };
    }),
  };
}

// As the medium plugin words a simulated node's status.
const g = (x) => String(Number(x.toPrecision(6)));
const statusOf = (poses) => `${poses.bodies.length} ${poses.bodies.length === 1 ? 'body' : 'bodies'}, t = ${g(poses.t0)} .. ${g(poses.t1)} s`;

// One animation's time, shared by all its renditions: real-time playback
// (requestAnimationFrame, the elapsed wall time), loop or stop at the end.
class Clock {
  constructor() {
    this.t = 0; this.t0 = 0; this.t1 = 0;
    this.playing = false; this.loop = false;
    this.listeners = new Set();
  }
  setInterval(t0, t1) { this.t0 = t0; this.t1 = t1; this.seek(this.t); }
  seek(t) {
    this.t = Math.min(Math.max(t, this.t0), this.t1);
    for (const f of this.listeners) f(this);
  }
  play() {
    if (this.playing) return;
    if (this.t >= this.t1) this.t = this.t0;
    this.playing = true;
    let last = null;
    const tick = (now) => {
      if (!this.playing) return;
      const dt = last === null ? 0 : (now - last) / 1000;
      last = now;
      let t = this.t + dt;
      const span = this.t1 - this.t0;
      if (t >= this.t1) {
        if (this.loop && span > 0) t = this.t0 + ((t - this.t0) % span);
        else { this.playing = false; t = this.t1; }
      }
      this.seek(t);
      if (this.playing) requestAnimationFrame(tick);
    };
    requestAnimationFrame(tick);
    this.seek(this.t);
  }
  pause() { this.playing = false; this.seek(this.t); }
}

// One rendition: the figure's WebGL player, or the slave's picture.
class Rendition {
  constructor(figure, animation) {
    this.figure = figure;
    this.animation = animation;
    const q = (c) => figure.querySelector(c);
    this.img = q('img');
    this.range = q('.time');
    this.label = q('.t');
    this.status = q('.status');
    this.handles = q('.handles');
    this.loop = q('.loop');
    this.playButton = q('.play');
    this.player = null;
    this.overlay = null;  // the handles over the player (made when first shown)
    this.webgl = true;  // until the player cannot be made
    this.picture = false;  // showing the slave's picture instead of the player
    this.drawing = null;
    this.again = false;
    const clock = animation.clock;
    this.range.oninput = () => clock.seek(clock.t0 + (clock.t1 - clock.t0) * this.range.value / 1000);
    this.loop.onchange = () => {
      clock.loop = this.loop.checked;
      for (const r of animation.renditions) r.loop.checked = clock.loop;
    };
    this.playButton.onclick = () => (clock.playing ? clock.pause() : clock.play());
    this.handles.onchange = () => this.show(clock);
    q('.recompute').onclick = () => animation.recompute(this);
    const another = q('.another');
    if (another) another.onclick = () => animation.addRendition(figure);
  }

  setScene(data) {
    if (this.webgl && !this.player) {
      this.player = createPlayer(this.figure, this.img, data);
      if (!this.player) this.webgl = false;
    } else if (this.player) {
      this.player.setScene(data);
    }
  }

  // The handles over the player, made from the animation's scene and
  // session state once their bundle has loaded; then shown at the clock's
  // time if Handles is still on.
  async handleOverlay() {
    if (this.overlay || !this.player) return this.overlay;
    if (this.loadingHandles) return this.loadingHandles;
    this.loadingHandles = loadHandles().then(({ HandleOverlay }) => this.makeOverlay(HandleOverlay), (e) => {
      this.animation.setStatus(`⚠ the handles could not be loaded: ${e.message || e}`);
      this.loadingHandles = null;
      return null;
    });
    return this.loadingHandles;
  }

  makeOverlay(HandleOverlay) {
    const a = this.animation;
    this.overlay = new HandleOverlay(this.player, {
      drag: (element, param, values) => a.conn.call('set_parameter', { element, param, values }),
      dragStart: () => { a.clock.pause(); a.clock.seek(a.clock.t0); },
      dragEnd: () => a.recompute(),
    });
    if (a.state) this.overlay.setParameters(a.state);
    if (a.scene0) this.overlay.setScene(a.scene0.meshes, a.scene0.poses);
    this.overlay.show(false);
    this.show(a.clock);
    return this.overlay;
  }

  // The slave's picture (the fallback) while `on`, else the player.
  usePicture(on) {
    this.picture = on || !this.player;
    if (this.player) this.player.canvas.style.display = this.picture ? 'none' : '';
    if (this.overlay && this.picture) this.overlay.show(false);
    this.img.style.display = this.picture ? '' : 'none';
    this.figure.dataset.renderer = this.picture ? 'picture' : 'webgl';
  }

  show(clock) {
    if (!this.animation.started) return;  // the first scene, or why there is none
    const frac = clock.t1 > clock.t0 ? (clock.t - clock.t0) / (clock.t1 - clock.t0) : 0;
    this.range.value = String(Math.round(frac * 1000));
    this.label.textContent = `t = ${clock.t.toFixed(2)} s`;
    this.playButton.textContent = clock.playing ? 'Pause' : 'Play';
    this.figure.dataset.t = String(clock.t);
    // Handles: over the WebGL rendition; the slave's picture only without one.
    this.usePicture(this.animation.down || (this.handles.checked && !this.player));
    if (this.picture) return this.drawPicture(clock.t);
    this.player.draw(clock.t);
    if (this.handles.checked && this.overlay) {
      this.overlay.show(true);
      this.overlay.seek(clock.t);
    } else if (this.handles.checked) this.handleOverlay();
    else if (this.overlay) this.overlay.show(false);
    this.drawn();
  }

  drawn() { this.figure.dataset.drawn = String(Number(this.figure.dataset.drawn || 0) + 1); }

  // GET /frame at time t; requests made while one is under way coalesce
  // into one more, at the newest time.
  async drawPicture(t) {
    this.pictureTime = t;
    if (this.drawing) { this.again = true; return this.drawing; }
    this.drawing = (async () => {
      const a = this.animation;
      const r = await fetch(`/frame?a=${a.index}&t=${this.pictureTime}&handles=${this.handles.checked ? 1 : 0}`);
      const [s0, s1] = (r.headers.get('X-Asgard-Interval') || '0 0').split(' ').map(Number);
      if (s1 > s0 && !this.player) a.clock.setInterval(s0, s1);
      a.setStatus((r.headers.get('X-Asgard-Live') === '1' ? '' : '⚠ ') + (r.headers.get('X-Asgard-Status') || ''));
      if (r.ok) {
        const old = this.img.src;
        this.img.src = URL.createObjectURL(await r.blob());
        if (old) URL.revokeObjectURL(old);
      }
      this.drawn();
    })();
    try { await this.drawing; } finally { this.drawing = null; }
    if (this.again) { this.again = false; return this.drawPicture(this.pictureTime); }
  }
}

// One animation of the document: its WebSocket (one more view of it, so an
// edit's new motion from any editor reaches it), its clock and renditions.
class Animation {
  constructor(index) {
    this.index = index;
    this.clock = new Clock();
    this.renditions = [];
    this.data = null;
    this.scene0 = null;  // the stream's {meshes, poses} (the handles' viewer takes them as they come)
    this.state = null;  // the session's scene_state (text, parameters, elements)
    this.down = false;  // the slave died; the next action restarts it
    this.started = false;  // the `open` answer has come
    this.template = null;
    this.conn = new Connection(`ws://${location.host}/ws?a=${index}`);
    this.clock.listeners.add((c) => { for (const r of this.renditions) r.show(c); });
  }

  add(figure) {
    if (!this.template) this.template = figure.cloneNode(true);
    const r = new Rendition(figure, this);
    this.renditions.push(r);
    r.loop.checked = this.clock.loop;
    if (this.data) r.setScene(this.data);
    r.show(this.clock);
    return r;
  }

  // Another rendition of this animation after `figure`, on the same clock.
  // On the host's pages a figure lies over its region, so the new one goes
  // below the pages instead, and is scrolled into view: the reader sees
  // what the click made (the clock is shared, so its toolbar serves both).
  addRendition(figure) {
    const f = this.template.cloneNode(true);
    const more = document.getElementById('more-renditions');
    const below = f.classList.contains('placed') && more;
    if (below) {
      f.classList.remove('placed');
      f.removeAttribute('style');
      more.append(f);
    } else figure.after(f);
    const r = this.add(f);
    if (below) f.scrollIntoView({ block: 'nearest' });
    return r;
  }

  setStatus(text) { for (const r of this.renditions) r.status.textContent = text; }

  scene(meshes, poses) {
    this.down = false;
    this.data = playerData(meshes, poses);
    this.scene0 = { meshes, poses };
    for (const r of this.renditions) {
      r.setScene(this.data);
      if (r.overlay) r.overlay.setScene(meshes, poses);
    }
    this.setStatus(statusOf(poses));
    this.clock.setInterval(poses.t0, poses.t1);
  }

  async start() {
    this.conn.on('scene', (m) => this.scene(m.meshes, m.poses));
    // The session's parameters for the handles: every state, and each
    // literal a drag (in any view) rewrites.
    this.conn.on('state', (m) => {
      this.state = m.state;
      for (const r of this.renditions) if (r.overlay) r.overlay.setParameters(m.state);
    });
    this.conn.on('text', (m) => {
      if (!Array.isArray(m.values)) return;
      for (const r of this.renditions) if (r.overlay) r.overlay.parameterEdited(m.element, m.param, m.values);
    });
    this.conn.on('error', (m) => {
      this.down = true;
      this.clock.seek(this.clock.t);  // the picture: the last frame or the poster
      this.setStatus(`⚠ ${m.message}`);
    });
    try {
      await this.conn.open();
      const o = await this.conn.call('open', {});
      this.started = true;
      if (o.state) this.state = o.state;
      if (o.meshes && o.poses && o.poses.times) this.scene(o.meshes, o.poses);
      else this.clock.seek(0);  // no motion: the slave's picture says why
    } catch (e) {
      this.started = true;
      this.down = true;
      this.clock.seek(0);
    }
  }

  async recompute() {
    this.setStatus('recomputing…');
    try {
      const r = await this.conn.call('simulate', {});
      if (!r.ok) this.setStatus(`⚠ ${r.error}`);  // the `scene` event brings a new motion
    } catch (e) {
      this.setStatus(`⚠ ${e.message}`);
      this.down = true;
      this.clock.seek(this.clock.t);
    }
  }
}

// The host's pages carry their text as transparent lines over the page's
// picture (web/server/launch.cc): each is stretched to the width the host
// set it at, in whatever font the browser has, so that a selection covers
// the words the picture shows.
function fitPageText() {
  for (const line of document.querySelectorAll('.page-text span[data-w]')) {
    const natural = line.offsetWidth;  // untransformed
    if (natural > 0) line.style.transform = `scaleX(${Number(line.dataset.w) / natural})`;
  }
  document.body.dataset.pageText = 'fitted';
}
fitPageText();
document.fonts?.ready.then(fitPageText);

const animations = new Map();
for (const figure of document.querySelectorAll('figure.rendition')) {
  const a = Number(figure.dataset.a);
  if (!animations.has(a)) animations.set(a, new Animation(a));
  animations.get(a).add(figure);
}
for (const a of animations.values()) a.start();
window.asgardDocument = { animations };
