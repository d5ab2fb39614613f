// The editor server when an animation's slave dies (issue 12/13), under
// `asgard studio` with --core pointing at a wrapper of asgard-core that
// refuses to start while a marker file exists.  An edit not yet simulated,
// then the slave killed: the next request restarts it once with the edited
// text and succeeds, no error reaching the views.  Killed again while
// restarts are refused: the request fails with the reason and the views get
// an `error` event.  Restarts allowed again: the next request starts a new
// slave that still has the edit — nothing typed is lost.  Node only.
import { chmodSync, existsSync, rmSync, writeFileSync } from 'node:fs';
import { dirname, join } from 'node:path';
import { checker, coreChildren, startStudio, sleep, waitFor, wsView } from './common.mjs';

const [asgard, scene, outDir] = process.argv.slice(2);
const { check, failures } = checker();
const core = join(dirname(asgard), 'asgard-core');
const deny = join(outDir, 'deny-restarts');
const wrapper = join(outDir, 'core.sh');
writeFileSync(wrapper, `#!/bin/sh\nif [ -e '${deny}' ]; then echo 'asgard-core: refused by the test' >&2; exit 3; fi\nexec '${core}' "$@"\n`);
chmodSync(wrapper, 0o755);
if (!existsSync(core)) { console.log(`SKIP: no ${core}`); process.exit(77); }

const { port, proc } = await startStudio(asgard, scene, 'studio', ['--core', wrapper]);
const b3 = (text) => (/body b3 [^\n]*-init_pos \{([^}]*)\}/.exec(text) || [])[1];
try {
  const v = await wsView(port);
  const opened = await v.call('open');
  check(opened.result && b3(opened.result.state.text) === '10.1 -17 0', 'the pendulum opens');
  const first = coreChildren(proc.pid);
  check(first.length === 1, `one asgard-core (${first})`);
  const edit = await v.call('set_parameter', { element: 'b3', param: 'init_pos', values: [12, -17, 0] });
  check(edit.result && b3(edit.result.text) === '12 -17 0', 'an edit, not yet simulated');

  process.kill(first[0], 'SIGKILL');
  await waitFor(() => !coreChildren(proc.pid).includes(first[0]), 'the killed slave gone');
  const sim = await v.call('simulate');
  check(sim.result && sim.result.ok, `simulate after the kill restarts the slave once and succeeds (${JSON.stringify(sim.error || sim.result)})`);
  const second = coreChildren(proc.pid);
  check(second.length === 1 && second[0] !== first[0], `one new asgard-core (${first} → ${second})`);
  const state = await v.call('open');
  check(state.result && b3(state.result.state.text) === '12 -17 0', 'the restarted slave has the edit');
  check(await waitFor(() => v.events.some((e) => e.event === 'scene'), 'the new motion'), 'the views get the new motion');
  const b3x = (poses) => poses.poses[0][7 * poses.bodies.indexOf('b3')];
  check(Math.abs(b3x(state.result.poses) - 12) < 1e-6, `and it is the edited motion (b3 starts at x = ${b3x(state.result.poses)})`);
  check(!v.events.some((e) => e.event === 'error'), 'no error reaches the views');

  // Restarts refused: the request fails with the reason, the views hear it.
  const edit2 = await v.call('set_parameter', { element: 'b3', param: 'init_pos', values: [13, -17, 0] });
  check(edit2.result && b3(edit2.result.text) === '13 -17 0', 'a second edit, not yet simulated');
  writeFileSync(deny, '');
  process.kill(second[0], 'SIGKILL');
  await waitFor(() => coreChildren(proc.pid).length === 0, 'the killed slave gone');
  const failed = await v.call('simulate');
  const reason = failed.error ? failed.error.message : failed.result && failed.result.error;
  check((!!failed.error || (failed.result && !failed.result.ok)) && !!reason,
    `with restarts refused the request fails with the reason (${reason})`);
  check(await waitFor(() => v.events.some((e) => e.event === 'error'), 'the error event'), 'and the views get an error event');

  // Restarts allowed again: nothing typed is lost.
  rmSync(deny);
  const back = await v.call('open');
  check(back.result && b3(back.result.state.text) === '13 -17 0', `the next request restarts the slave with the second edit (${back.error ? back.error.message : 'ok'})`);
  check(coreChildren(proc.pid).length === 1, 'one asgard-core again');
  v.ws.close();
} finally {
  proc.kill('SIGTERM');
  await sleep(100);
}
if (failures.length) { console.log(`${failures.length} failure(s)`); process.exit(1); }
console.log('all restart checks passed');
