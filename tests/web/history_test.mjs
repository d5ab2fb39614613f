// The session's undo history survives a slave's death (issue 13), under
// `asgard studio`: a drag of b3 (three steps of one parameter, one undo
// step), an Update, a second drag, one Undo; then the slave is killed
// before each of Undo, Redo, Redo: the restarted slave's session has the
// whole history (the server loads each text it knows in turn and undoes
// back to the current one), so each answers as it would have without the
// crash, and Undo goes back to the opened text and no further.  Node only.
import { checker, coreChildren, startStudio, sleep, waitFor, wsView } from './common.mjs';

const [asgard, scene] = process.argv.slice(2);
const { check, failures } = checker();
const { port, proc } = await startStudio(asgard, scene);
const b3 = (text) => (/body b3 [^\n]*-init_pos \{([^}]*)\}/.exec(text) || [])[1];

async function kill() {
  const [slave] = coreChildren(proc.pid);
  if (!slave) return false;
  process.kill(slave, 'SIGKILL');
  return waitFor(() => !coreChildren(proc.pid).includes(slave), 'the killed slave gone');
}

try {
  const v = await wsView(port);
  const opened = await v.call('open');
  const t0 = opened.result.state.text;
  check(b3(t0) === '10.1 -17 0', 'the pendulum opens');
  for (const x of [11, 12, 13]) await v.call('set_parameter', { element: 'b3', param: 'init_pos', values: [x, -17, 0] });
  await v.call('simulate');
  const t1 = (await v.call('open')).result.state.text;
  const t2 = `${t1}# a comment from an Update\n`;
  const updated = await v.call('update', { text: t2 });
  check(updated.result && updated.result.state.text === t2, 'an Update');
  await v.call('set_parameter', { element: 'b3', param: 'init_pos', values: [14, -17, 0] });
  await v.call('simulate');
  const t3 = (await v.call('open')).result.state.text;
  check(b3(t1) === '13 -17 0' && b3(t3) === '14 -17 0' && t3.endsWith('# a comment from an Update\n'), 'a second drag');
  const u1 = await v.call('undo');
  check(u1.result && u1.result.done && u1.result.state.text === t2, 'Undo goes back to the Update');

  const texts = { t0, t1, t2, t3 };
  const name = (t) => Object.keys(texts).find((k) => texts[k] === t) || JSON.stringify(b3(t));
  for (const [method, want] of [['undo', 't1'], ['redo', 't2'], ['redo', 't3']]) {
    check(await kill(), `the slave killed before ${method}`);
    const r = await v.call(method);
    const got = r.result ? name(r.result.state.text) : r.error.message;
    check(r.result && r.result.done && got === want, `after the restart ${method} still gives ${want} (${got})`);
  }
  const none = await v.call('redo');
  check(none.result && !none.result.done && none.result.state.text === t3, 'nothing more to redo');
  check(await kill(), 'the slave killed again');
  const back = [];
  for (let k = 0; k < 4; ++k) {
    const r = await v.call('undo');
    back.push(r.result && r.result.done ? name(r.result.state.text) : 'not done');
  }
  check(back.join(' ') === 't2 t1 t0 not done', `Undo after the restart walks the whole history back to the opened text: ${back.join(' ')}`);
  check(coreChildren(proc.pid).length === 1, 'one asgard-core');
  check(!v.events.some((e) => e.event === 'error'), 'no error reaches the views');
  v.ws.close();
} finally {
  proc.kill('SIGTERM');
  await sleep(100);
}
if (failures.length) { console.log(`${failures.length} failure(s)`); process.exit(1); }
console.log('all history checks passed');
