// The Asgard editor in the browser (seed chapter 4): a graphical viewer
// (three.js) with the initial-position handles of bodies, and language
// viewers (CodeMirror 6) with Update, Save and Revert.  Every view talks to
// the server over one WebSocket; the server's asgard-core session is the one
// state, and its events keep all views of the animation — in every tab — in
// step.
import { Connection } from './connection.js';
import { DragEcho } from './echo.js';
import { download, gltfText, imageBlob, movieRequest } from './export.js';
import { GraphicalViewer } from './graphical.js';
import { LanguageViewer } from './language.js';
import { TrajectoryEditor } from './timeline.js';
import { ShapeEditor } from './shape.js';

const params = new URLSearchParams(location.search);
const animation = Number(params.get('a') || 0);
const conn = new Connection(`ws://${location.host}/ws?a=${animation}`);
const status = document.getElementById('status');

const app = {
  text: '',          // the session's text
  state: null,       // scene_state of the session
  languageViewers: [],
  graphical: null,
  setStatus(msg) { status.textContent = msg || ''; },
};
window.asgard = app;
app.conn = conn;

function applyState(state) {
  app.echo = null;  // the fresh state's text replaces a drag's echo
  app.state = state;
  app.stateCount = (app.stateCount || 0) + 1;
  app.text = state.text;
  for (const v of app.languageViewers) v.showSession(state.text, state.diagnostics, state.parameters);
  app.graphical.setParameters(state.parameters, state.elements, state.prescribed);
  showSimulatorOptions(state);
  showCreateMenu(state);
  if (app.shapes) app.shapes.refresh();
  const errors = state.diagnostics.filter((d) => d.severity === 'error');
  app.setStatus(errors.length ? `${errors.length} error(s): the last good scene is shown` : '');
}

function addLanguageViewer() {
  const v = new LanguageViewer(document.getElementById('language'), app.languageViewers.length, {
    update: (text) => run('update', { text }),
    undo: () => run('undo', {}).catch(() => {}),
    redo: () => run('redo', {}).catch(() => {}),
    save: async (text) => {
      if (text !== app.text) await run('update', { text });
      await run('save', {});
      app.setStatus('saved');
    },
  });
  if (app.state) v.showSession(app.state.text, app.state.diagnostics, app.state.parameters);
  app.languageViewers.push(v);
  return v;
}

async function run(method, params) {
  app.busy = (app.busy || 0) + 1;
  try {
    const r = await conn.call(method, params);
    if (r && r.state) applyState(r.state);
    if (r && r.simulated && !r.simulated.ok && r.simulated.error) app.setStatus(r.simulated.error);
    return r;
  } catch (e) {
    app.setStatus(String(e.message || e));
    throw e;
  } finally {
    app.busy -= 1;
  }
}

// The control panel's time range and tolerance: the `simulator` command's
// -start, -finish and -rtol, edited through the session like a handle.
const SIMULATOR = [['start', 'sim-start', '0'], ['finish', 'sim-finish', '10'], ['rtol', 'sim-rtol', '']];

function showSimulatorOptions(state) {
  const sim = state.elements.find((e) => e.element === 'simulator');
  for (const [param, id, fallback] of SIMULATOR) {
    const field = document.getElementById(id);
    const p = state.parameters.find((q) => q.element === 'simulator' && q.param === param);
    if (document.activeElement !== field) field.value = p ? p.value : fallback;
    const reason = p && !p.editable ? p.reason : sim && !sim.editable ? sim.reason : '';
    field.disabled = !!reason;
    field.title = reason ? `simulator -${param} is read-only: ${reason}` : `simulator -${param}`;
  }
}

async function editSimulator() {
  const values = {};
  for (const [param, id] of SIMULATOR) {
    const text = document.getElementById(id).value.trim();
    if (text === '') continue;
    const v = Number(text);
    if (!Number.isFinite(v)) { app.setStatus(`simulator -${param}: '${text}' is not a number`); return; }
    values[param] = v;
  }
  if (values.finish !== undefined && values.finish <= (values.start ?? 0)) {
    app.setStatus('simulator: -finish must be after -start');
    return;
  }
  if (values.rtol !== undefined && !(values.rtol > 0)) { app.setStatus('simulator -rtol must be positive'); return; }
  app.setStatus('');
  const params = app.state.parameters;
  // Options not written stay unwritten while the field shows their default.
  const changed = Object.entries(values).filter(([param, v]) => {
    const p = params.find((q) => q.element === 'simulator' && q.param === param);
    const fallback = SIMULATOR.find(([name]) => name === param)[2];
    return p ? Number(p.value) !== v : fallback === '' || Number(fallback) !== v;
  });
  if (!changed.length) return;
  try {
    if (!app.state.elements.some((e) => e.element === 'simulator')) {
      // No simulator command yet: one at the top of the text.
      const command = `simulator ${Object.entries(values).map(([k, v]) => `-${k} ${v}`).join(' ')}\n`;
      await run('update', { text: command + app.text });
      return;
    }
    for (const [param, v] of changed) await conn.call('set_parameter', { element: 'simulator', param, values: [v] });
    await run('simulate', {});
  } catch { /* run() or the status says why */ }
}

// The Create menu (seed 4.1): a body of a chosen shape set at the view's
// centre, a constant or gravitational force on the selected body (unit
// magnitude along −y, as the seed makes them), a link by clicks on two
// bodies (or a body and a point in space).  Each is one well-formatted
// command the session inserts after the last of its kind, so undo removes
// it and every view shows it.
const literal = (v) => `{${v.map((x) => Math.round(x * 1000) / 1000).join(' ')}}`;

function freshName(prefix) {
  const taken = new Set(app.state.elements.map((e) => e.element));
  let i = 1;
  while (taken.has(`${prefix}${i}`)) ++i;
  return `${prefix}${i}`;
}

function showCreateMenu(state) {
  const select = document.getElementById('create-shape');
  const shapes = state.elements.filter((e) => e.kind === 'shape_set').map((e) => e.element);
  const current = select.value;
  if ([...select.options].map((o) => o.value).join('\n') !== shapes.join('\n')) {
    select.textContent = '';
    for (const name of shapes) select.appendChild(new Option(name, name));
    if (shapes.includes(current)) select.value = current;
  }
  document.getElementById('create-body').disabled = !shapes.length;
  showSelection(app.graphical.selected, app.graphical.selectedElement);
}

function showSelection(name, element = name) {
  document.getElementById('selection').textContent = element ? `selected: ${element}` : 'no body selected';
  for (const id of ['create-force', 'create-gravity', 'create-force-trajectory', 'create-torque']) document.getElementById(id).disabled = !name;
  const known = element && app.state && app.state.elements.some((e) => e.element === element);
  document.getElementById('delete-element').disabled = !known;
  const confirmBox = document.getElementById('delete-confirm');
  if (confirmBox && confirmBox.dataset.element !== element) confirmBox.hidden = true;
}

async function create(command) {
  try {
    const r = await run('create', { command });
    const at = r && r.edits && r.edits[0];
    // The new command's line (an insertion that starts with a newline ends the line before it).
    if (at) for (const v of app.languageViewers) v.reveal(at.line + (at.text.startsWith('\n') ? 1 : 0));
  } catch { /* the status says why */ }
}

function createLink() {
  app.graphical.startPick({
    count: 2,
    point: true,
    trajectory: true,
    prompts: ['Link: click a point on the first body (Esc cancels)',
      'Link: click a point on the second body, a trajectory shown (the link follows its moving point), or off every body for a point in space'],
    done: ([a, b]) => {
      const end2 = b.name ? `-body2 ${b.name} -offset2 ${literal(b.local)}`
        : b.trajectory ? `-trajectory ${b.trajectory}`
          : `-x ${b.point[0]} -y ${b.point[1]} -z ${b.point[2]}`;
      create(`link -body1 ${a.name} -offset1 ${literal(a.local)} ${end2} -tightness 10`);
    },
  });
}

const g = () => app.graphical;

function setupCreateMenu() {
  document.getElementById('create-body').onclick = () => {
    const shape = document.getElementById('create-shape').value;
    if (!shape) return;
    create(`body ${freshName('body')} -shape ${shape} -init_pos ${literal(app.graphical.viewCentre())}`);
  };
  document.getElementById('create-force').onclick = () => {
    if (app.graphical.selected) create(`force -body ${app.graphical.selected} -x 0 -y -1 -z 0`);
  };
  document.getElementById('create-gravity').onclick = () => {
    if (app.graphical.selected) create(`force -body ${app.graphical.selected} -gravitational 1 -x 0 -y -1 -z 0`);
  };
  // A force that follows a trajectory (seed 4.1): the trajectory first (a
  // unit force along −y at the start and the end of the simulated time),
  // then the force reading it; two commands, so two undo steps.
  document.getElementById('create-force-trajectory').onclick = async () => {
    const body = g().selected;
    if (!body) return;
    const name = freshName('force_curve');
    const t0 = g().poses ? g().poses.t0 : 0, t1 = g().poses ? g().poses.t1 : 1;
    await create(`trajectory ${name} -points {{${t0} 0 -1 0} {${t1} 0 -1 0}}`);
    if (app.state.elements.some((e) => e.element === name))
      await create(`force -body ${body} -x ${name}.x -y ${name}.y -z ${name}.z`);
  };
  document.getElementById('create-link').onclick = () => createLink();
  document.getElementById('create-torque').onclick = () => {
    if (g().selected) create(`torque -body ${g().selected} -x 0 -y 0 -z 1`);
  };
  const size = () => Math.max(1, g().radius);
  // A point light placed by a click (seed 4.1), in the plane through the
  // view's centre facing the camera; a directional one along the view.
  document.getElementById('create-light').onclick = () => {
    g().startPick({
      count: 1,
      space: g().controls.target.clone(),
      prompts: ['Light: click where the point light goes, in the plane through the view\'s centre (Esc cancels)'],
      done: ([p]) => create(`lightsource -type point -pos ${literal(p.point)}`),
    });
  };
  // (Its -pos, which a directional light does not use, puts its handle
  // in sight: back from the view's centre, against the light.)
  document.getElementById('create-sun').onclick = () => {
    const d = g().camera.getWorldDirection(g().camera.position.clone());
    const at = g().controls.target.clone().addScaledVector(d, -size() / 2);
    create(`lightsource -type directional -pos ${literal(at.toArray())} -dir ${literal(d.toArray())}`);
  };
  document.getElementById('create-view').onclick = () => {
    // The free camera as asgard render's view options (export.js), the
    // rotation as a rotation vector in radians as `view -rot` takes it.
    const r = movieRequest(g(), g().canvas.clientWidth, g().canvas.clientHeight);
    if (r.view) { app.setStatus(`the camera is the view ${r.view}`); return; }
    const rot = r.rot.map((v) => (v * Math.PI) / 180);
    create(`view ${freshName('view')} -rot ${literal(rot)} -pos ${literal(r.pan)} -scale ${Math.round(r.scale * 1000) / 1000} -center ${literal(r.center)}`);
  };
  document.getElementById('create-trajectory').onclick = () => {
    const from = (g().selected && g().bodyPosition(g().selected)) || g().viewCentre();
    const t0 = g().poses ? g().poses.t0 : 0, t1 = g().poses ? g().poses.t1 : 1;
    const to = [from[0] + size() / 2, from[1], from[2]];
    const knot = (t, p) => `{${[t, ...p].map((x) => Math.round(x * 1000) / 1000).join(' ')}}`;
    create(`trajectory ${freshName('trajectory')} -points {${knot(t0, from)} ${knot(t1, to)}}`);
  };
  // A body goes with the forces, torques, links, trajectories and views
  // that name it (one undo step): the editor asks first, listing them
  // (the session's deleted_with), and the status line lists them after.
  const confirmBox = document.getElementById('delete-confirm');
  const remove = async (element) => {
    confirmBox.hidden = true;
    try {
      const r = await run('delete', { element });
      const removed = (r && r.removed) || [];
      app.setStatus(`deleted ${element}${removed.length ? ` and what named it: ${removed.join(', ')}` : ''}`);
      g().select(null);
    } catch { /* the status says why */ }
  };
  document.getElementById('delete-element').onclick = () => {
    const element = g().selectedElement;
    if (!element) return;
    const info = app.state && app.state.elements.find((e) => e.element === element);
    const also = (info && info.deleted_with) || [];
    if (!also.length) return remove(element);
    confirmBox.querySelector('.question').textContent =
      `Delete ${element} and the ${also.length === 1 ? 'element that names' : `${also.length} elements that name`} it: ${also.join(', ')}?`;
    confirmBox.querySelector('.yes').onclick = () => remove(element);
    confirmBox.querySelector('.no').onclick = () => { confirmBox.hidden = true; };
    confirmBox.dataset.element = element;
    confirmBox.hidden = false;
  };
}

// A parameter's word in the text as byte offsets [begin, end) (lines and
// columns count bytes, as the session does), with the text's bytes.
function wordBytes(p) {
  const bytes = new TextEncoder().encode(app.text);
  const offset = (line, column) => {
    let i = 0;
    for (let l = 1; l < line && i < bytes.length; ++i) if (bytes[i] === 10) ++l;
    return i + column - 1;
  };
  return { bytes, begin: offset(p.line, p.column), end: offset(p.end_line, p.end_column) };
}
const decode = (x) => new TextDecoder().decode(x);

// The scene's shape sets and their -desc words, for the shape editor.  A
// -desc the editor may rewrite is a braced word (Tcl substitutes nothing
// in it) of a command that ran once.
function shapeSets() {
  if (!app.state) return [];
  return app.state.elements.filter((e) => e.kind === 'shape_set').map((e) => {
    const p = app.state.parameters.find((x) => x.element === e.element && x.param === 'desc');
    let reason = !e.editable ? e.reason : !p ? 'it has no -desc' : p.line > 0 ? '' : 'its -desc could not be located';
    if (!reason) {
      const w = wordBytes(p);
      if (w.bytes[w.begin] !== 123) reason = 'its -desc is not a braced literal (it is built by variables or commands)';
    }
    return { element: e.element, value: p ? p.value : '', editable: !reason, reason };
  });
}

// The shape editor's -desc: the braced word replaced through the session
// (set_parameter with text), so that every language viewer shows it while
// dragging and a drag is one undo step; when `done`, re-simulated.  One
// call is in flight at a time; meanwhile only the newest word waits.
const shapeWriter = { busy: false, next: null };
async function writeShape(element, desc, done) {
  shapeWriter.next = { element, desc, done: done || (shapeWriter.next && shapeWriter.next.done) };
  if (shapeWriter.busy) return;
  shapeWriter.busy = true;
  try {
    while (shapeWriter.next) {
      const w = shapeWriter.next;
      shapeWriter.next = null;
      try { await conn.call('set_parameter', { element: w.element, param: 'desc', text: w.desc }); } catch (e) { app.setStatus(String(e.message || e)); }
      if (w.done && !shapeWriter.next) await run('simulate', {}).catch(() => {});
    }
  } finally { shapeWriter.busy = false; }
}

// Exports (control panel): downloads of the picture, the scene as glTF,
// and a movie the server renders with asgard render.
function setupExports() {
  document.getElementById('export-image').onclick = async () => {
    try { download(await imageBlob(g()), 'scene.png'); } catch (e) { app.setStatus(String(e.message || e)); }
  };
  document.getElementById('export-gltf').onclick = async () => {
    if (!g().poses) return;
    try { download(new Blob([await gltfText(g())], { type: 'model/gltf+json' }), 'scene.gltf'); } catch (e) { app.setStatus(String(e.message || e)); }
  };
  document.getElementById('export-movie').onclick = async () => {
    if (!g().poses) return;
    const button = document.getElementById('export-movie');
    button.disabled = true;
    app.setStatus('making the movie …');
    try {
      const r = await conn.call('movie', movieRequest(g(), g().canvas.clientWidth, g().canvas.clientHeight));
      app.setStatus(`movie: ${Math.round(r.bytes / 1024)} KiB`);
      download(r.url, r.name);
    } catch (e) {
      app.setStatus(String(e.message || e));
    } finally {
      button.disabled = false;
    }
  };
}

// The camera menu: the free camera or one of the scene's view elements.
function showViews(names, current) {
  const select = document.getElementById('camera-view');
  const want = ['', ...names];
  if ([...select.options].map((o) => o.value).join('\n') !== want.join('\n')) {
    select.textContent = '';
    for (const name of want) select.appendChild(new Option(name || 'Free camera', name));
  }
  select.value = current;
}

// A drag's value written into this tab's language viewers before the
// session has it (echo.js).  Only from the state's own text: spans are
// stale once the session's text has moved on without a state.
function previewDrag(element, param, values) {
  if (app.echo && app.echo.matches(element, param)) app.echo.set(values);
  else app.echo = app.text === app.state?.text ? DragEcho.start(app.state, element, param, values) : null;
  if (!app.echo) return;
  const text = app.echo.text();
  for (const v of app.languageViewers) v.showSession(text, null);
}

function endEcho() {
  if (!app.echo) return;
  app.echo = null;
  for (const v of app.languageViewers) v.showSession(app.text, null);
}

async function main() {
  app.graphical = new GraphicalViewer(document.getElementById('canvas'), {
    label: document.getElementById('label'),
    slider: document.getElementById('time'),
    clock: document.getElementById('clock'),
    play: document.getElementById('play'),
    // While dragging: the literal changes in every language viewer — in
    // this tab's at once (echo.js), in every other view when the session's
    // `text` event comes.
    preview: (element, param, values) => previewDrag(element, param, values),
    drag: (element, param, values) => conn.call('set_parameter', { element, param, values }),
    // Drag end: re-simulate and show the new motion everywhere; then the
    // session's text, whatever became of the echo.
    dragEnd: () => run('simulate', {}).finally(() => endEcho()),
    selected: (name, element) => showSelection(name, element),
    views: (names, current) => showViews(names, current),
    knots: () => app.trajectories && !app.trajectories.drag && app.trajectories.render(),
    time: () => app.trajectories && app.trajectories.placeCursor(),
    view: (name) => { document.getElementById('camera-view').value = name; },
    prompt: (text) => {
      const p = document.getElementById('prompt');
      p.textContent = text;
      p.style.display = text ? 'block' : 'none';
    },
  });
  app.trajectories = new TrajectoryEditor(document.getElementById('trajectory-editor'), app.graphical, {
    edit: (element) => app.graphical.knotsEdited(element),
    // A drag's end (values null) or a new list (a point added or deleted):
    // the list through the session, then a re-simulation.
    end: async (element, values) => {
      try {
        if (values) await conn.call('set_parameter', { element, param: 'points', values });
        else await app.graphical.flushDrag();
      } catch (e) { app.setStatus(String(e.message || e)); }
      app.graphical.panelDrag = null;
      await run('simulate', {}).catch(() => {});
    },
  });
  app.shapes = new ShapeEditor(document.getElementById('shape-editor'), {
    shapes: () => shapeSets(),
    // While dragging: the -desc word rewritten in every language viewer
    // (the newest when one is in flight); `done`: then re-simulate, which
    // also ends the undo step.
    write: (element, desc, done) => writeShape(element, desc, done),
  });
  document.getElementById('shapes-open').onclick = () => app.shapes.show(!app.shapes.shown());
  setupCreateMenu();
  setupExports();
  document.getElementById('camera-view').onchange = (ev) => app.graphical.setView(ev.target.value);
  const count = Math.max(1, Math.min(4, Number(params.get('viewers') || 1)));
  for (let i = 0; i < count; ++i) addLanguageViewer();

  conn.on('text', (e) => {
    app.text = e.text;
    const echoed = app.echo && app.echo.over(e.text);
    if (!echoed) app.echo = null;
    for (const v of app.languageViewers) v.showSession(echoed || e.text, null);
    if (Array.isArray(e.values)) app.graphical.parameterEdited(e.element, e.param, e.values);
    if (typeof e.word === 'string') app.shapes.follow(e.element, e.param, e.word);
  });
  conn.on('state', (e) => applyState(e.state));
  conn.on('scene', (e) => app.graphical.setScene(e.meshes, e.poses));
  conn.on('error', (e) => app.setStatus(e.message));
  conn.on('saved', () => app.setStatus('saved'));
  conn.on('closed', () => app.setStatus('the connection to the server is closed'));

  document.getElementById('simulate').onclick = () => run('simulate', {});
  document.getElementById('fit').onclick = () => {
    if (!app.graphical.poses) return;
    app.graphical.fit();
    app.graphical.seek(app.graphical.t);
  };
  // Undo and Redo as in a language viewer (one history): a viewer's unsent
  // typing first — the one last typed in — else the session's.
  const typedIn = () => app.languageViewers.find((v) => v.view.hasFocus) ||
    [...app.languageViewers].reverse().find((v) => v.hasLocalChanges() || v.localRedo > 0);
  document.getElementById('undo').onclick = () => { const v = typedIn(); return v ? v.undo() : run('undo', {}); };
  document.getElementById('redo').onclick = () => { const v = typedIn(); return v ? v.redo() : run('redo', {}); };
  document.getElementById('add-viewer').onclick = () => addLanguageViewer();
  for (const [, id] of SIMULATOR)
    document.getElementById(id).addEventListener('change', () => editSimulator());
  document.getElementById('style').onchange = (ev) => app.graphical.setStyle(ev.target.value);
  for (const box of document.querySelectorAll('#toggles input'))
    box.onchange = () => app.graphical.setShown(box.dataset.kind, box.checked);

  await conn.open();
  const opened = await conn.call('open', {});
  document.getElementById('title').textContent = opened.title || 'Asgard';
  document.title = `${opened.title} — Asgard editor`;
  applyState(opened.state);
  if (opened.meshes && opened.poses && opened.meshes.ok && opened.poses.ok)
    app.graphical.setScene(opened.meshes, opened.poses);
  if (opened.sim_error) app.setStatus(opened.sim_error);
  app.ready = true;
}

main().catch((e) => app.setStatus(String(e.message || e)));
