// The Asgard editor in the browser (seed chapter 4): a graphical viewer
// (three.js) with the initial-position handles of bodies, and language
// viewers (CodeMirror 6) with Update, Save and Revert.  Every view talks to
// the server over one WebSocket; the server's asgard-core session is the one
// state, and its events keep all views of the animation — in every tab — in
// step.
import { Connection } from './connection.js';
import { GraphicalViewer } from './graphical.js';
import { LanguageViewer } from './language.js';

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

function applyState(state) {
  app.state = state;
  app.text = state.text;
  for (const v of app.languageViewers) v.showSession(state.text, state.diagnostics);
  app.graphical.setParameters(state.parameters);
  const errors = state.diagnostics.filter((d) => d.severity === 'error');
  app.setStatus(errors.length ? `${errors.length} error(s): the last good scene is shown` : '');
}

function addLanguageViewer() {
  const v = new LanguageViewer(document.getElementById('language'), app.languageViewers.length, {
    update: (text) => run('update', { text }),
    save: async (text) => {
      if (text !== app.text) await run('update', { text });
      await run('save', {});
      app.setStatus('saved');
    },
  });
  if (app.state) v.showSession(app.state.text, app.state.diagnostics);
  app.languageViewers.push(v);
  return v;
}

async function run(method, params) {
  try {
    const r = await conn.call(method, params);
    if (r && r.state) applyState(r.state);
    if (r && r.simulated && !r.simulated.ok && r.simulated.error) app.setStatus(r.simulated.error);
    return r;
  } catch (e) {
    app.setStatus(String(e.message || e));
    throw e;
  }
}

async function main() {
  app.graphical = new GraphicalViewer(document.getElementById('canvas'), {
    label: document.getElementById('label'),
    slider: document.getElementById('time'),
    clock: document.getElementById('clock'),
    play: document.getElementById('play'),
    // While dragging: the literal changes in every language viewer.
    drag: (element, param, values) => conn.call('set_parameter', { element, param, values }),
    // Drag end: re-simulate and show the new motion everywhere.
    dragEnd: () => run('simulate', {}),
  });
  const count = Math.max(1, Math.min(4, Number(params.get('viewers') || 1)));
  for (let i = 0; i < count; ++i) addLanguageViewer();

  conn.on('text', (e) => {
    app.text = e.text;
    for (const v of app.languageViewers) v.showSession(e.text, null);
    app.graphical.parameterEdited(e.element, e.param, e.values);
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
  document.getElementById('undo').onclick = () => run('undo', {});
  document.getElementById('redo').onclick = () => run('redo', {});
  document.getElementById('add-viewer').onclick = () => addLanguageViewer();

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
