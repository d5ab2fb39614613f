// A language viewer (seed 4.2): the scene text in CodeMirror 6 with Update,
// Save and Revert.  Text changes from the session (another viewer's Update, a
// handle dragged) arrive as ordinary editor transactions — the smallest
// replacement.  One history: every change the session made (a graphical
// edit, an Update, a created or deleted element) is the session's undo step,
// so the editor's undo (Mod-z) and redo (Mod-y, Mod-Shift-z) are the
// session's Undo and Redo — text and picture — except for typing not yet
// sent with Update, which they undo and redo here first (CodeMirror's own
// history holds only that typing: the session's changes are not added to it
// and each one closes its group).  A session change that arrives while this
// viewer holds unsent typing is merged into it (merge.js): where the two do
// not overlap both survive; where they do, the typing is kept and the viewer
// says it has diverged (in its status and with the conflicting lines
// marked), with a button that takes the session's text.
// Errors are marked at
// their spans and listed under the text.  Graphically editable literals are
// highlighted, read-only ones say why on hover, long point lists are elided
// (literals.js).
import { EditorView, basicSetup } from 'codemirror';
import { Annotation, ChangeSet, Prec, StateEffect, StateField, Transaction } from '@codemirror/state';
import { Decoration, keymap } from '@codemirror/view';
import { isolateHistory, redo, undo } from '@codemirror/commands';
import { setDiagnostics } from '@codemirror/lint';
import { literalTooltips, literalsField, setLiterals } from './literals.js';
import { mergeSession } from './merge.js';

// Marks the transactions that carry the session's changes (not typing).
const fromSession = Annotation.define();

// Line decorations replaced as a whole by an effect and moved with the
// text's changes: the error lines, and the lines where a diverged viewer's
// typing overlaps a change made elsewhere (the session's text differs
// under them).
function lineMarks() {
  const set = StateEffect.define();
  const field = StateField.define({
    create: () => Decoration.none,
    update(deco, tr) {
      deco = deco.map(tr.changes);
      for (const e of tr.effects) if (e.is(set)) deco = e.value;
      return deco;
    },
    provide: (f) => EditorView.decorations.from(f),
  });
  return [set, field];
}
const [setErrorLines, errorLines] = lineMarks();
const [setConflictLines, conflictLines] = lineMarks();

export class LanguageViewer {
  constructor(parent, index, actions) {
    this.session = '';
    // The session text this viewer's text is made from, and the typing
    // since (a ChangeSet base → text; see merge.js).  base differs from
    // session only while diverged.
    this.base = '';
    this.pending = ChangeSet.empty(0);
    this.parameters = [];
    this.expanded = new Set();  // element.param of elided lists shown in full
    this.literals = literalsField(this);
    const root = document.createElement('div');
    root.className = 'viewer';
    root.dataset.viewer = String(index);
    const bar = document.createElement('div');
    bar.className = 'bar';
    for (const [name, f] of [
      ['Update', () => this.send(actions.update).catch(() => {})],  // the status says why
      ['Save', () => this.send(actions.save).catch(() => {})],
      ['Revert', () => this.revert()],
    ]) {
      const b = document.createElement('button');
      b.textContent = name;
      b.className = name.toLowerCase();
      b.onclick = f;
      bar.appendChild(b);
    }
    // Diverged: the typing overlaps a change made elsewhere.
    this.divergence = document.createElement('span');
    this.divergence.className = 'diverged';
    this.divergence.style.cssText = 'display:none;color:#a40;flex-basis:100%';
    bar.style.flexWrap = 'wrap';
    const text = document.createElement('span');
    const take = document.createElement('button');
    take.className = 'take-session';
    take.textContent = "Take the session's text";
    take.onclick = () => this.revert();
    this.divergence.append(text, ' ', take);
    this.divergenceText = text;
    bar.appendChild(this.divergence);
    root.appendChild(bar);
    this.errors = document.createElement('div');
    this.errors.className = 'errors';
    parent.appendChild(root);
    this.actions = actions;
    this.localRedo = 0;  // typing undone here that redo brings back first
    const history = Prec.highest(keymap.of([
      { key: 'Mod-z', run: () => { this.undo(); return true; }, preventDefault: true },
      { key: 'Mod-y', run: () => { this.redo(); return true; }, preventDefault: true },
      { key: 'Mod-Shift-z', run: () => { this.redo(); return true; }, preventDefault: true },
    ]));
    // New typing ends what a redo could bring back.
    // Every change that is not the session's is typing (undo and redo of
    // it included): composed into `pending`.
    const typing = EditorView.updateListener.of((u) => {
      for (const tr of u.transactions) {
        if (!tr.docChanged || tr.annotation(fromSession)) continue;
        this.pending = this.pending.compose(tr.changes);
        if (tr.annotation(Transaction.addToHistory) !== false && !tr.isUserEvent('undo') && !tr.isUserEvent('redo'))
          this.localRedo = 0;
      }
      if (u.docChanged && this.text() === this.base) this.pending = ChangeSet.empty(this.base.length);
    });
    this.view = new EditorView({ doc: '', extensions: [history, basicSetup, typing, EditorView.lineWrapping, errorLines, conflictLines, this.literals, literalTooltips(this.literals)], parent: root });
    root.appendChild(this.errors);
    this.root = root;
  }

  text() { return this.view.state.doc.toString(); }

  // Typing not yet sent with Update.
  hasLocalChanges() { return this.text() !== this.session; }

  // Undo: this viewer's unsent typing first (all of it at once when
  // CodeMirror's history has none left: the session's text), else the
  // session's Undo.  Redo: typing undone here, else the session's Redo.
  undo() {
    if (!this.hasLocalChanges()) return this.actions.undo();
    if (undo(this.view)) ++this.localRedo;
    else this.revert();
    return Promise.resolve();
  }
  redo() {
    if (this.localRedo > 0 && redo(this.view)) { --this.localRedo; return Promise.resolve(); }
    this.localRedo = 0;
    return this.actions.redo();
  }

  // Sends this viewer's text (Update, Save) with `action`.  Its typing is
  // taken to be the session's from now on (a change arriving meanwhile is
  // merged against it); if the action fails, the typing is pending again.
  async send(action) {
    const text = this.text();
    const was = { base: this.base, pending: this.pending };
    this.base = text;
    this.pending = ChangeSet.empty(text.length);
    try {
      return await action(text);
    } catch (e) {
      if (this.base === text) {
        this.base = was.base;
        this.pending = was.pending.compose(this.pending);
        this.showDivergence([]);
      }
      throw e;
    }
  }

  // Adopt the session's text and, when given, its diagnostics and
  // parameters.  Without typing the session's change replaces what differs;
  // with typing it is merged in (merge.js).
  showSession(text, diagnostics, parameters) {
    const changed = text !== this.session;
    this.session = text;
    // The session's change is its own undo step, not CodeMirror's: not in
    // the local history, and no typing before or after joins its group.
    const annotations = [Transaction.addToHistory.of(false), isolateHistory.of('full'), fromSession.of(true)];
    let conflicts = [];
    if (this.text() === text) {
      // This viewer's typing, now the session's (Update), or no change.
      this.base = text;
      this.pending = ChangeSet.empty(text.length);
      if (changed) this.view.dispatch({ annotations });
    } else if (text !== this.base) {
      const m = mergeSession(this.base, this.pending, text);
      this.base = m.base;
      this.pending = m.pending;
      conflicts = m.conflicts;
      if (!m.apply.empty) this.view.dispatch({ changes: m.apply, userEvent: 'input.session', annotations });
    }
    this.showDivergence(conflicts);
    if (changed) this.localRedo = 0;
    if (diagnostics) this.mark(diagnostics);
    if (parameters) {
      this.parameters = parameters;
      this.markLiterals();
    }
  }

  // Whether this viewer's text has left out some of the session's changes
  // (they overlapped its typing).
  diverged() { return this.base !== this.session; }

  // The status of a diverged viewer: the lines where the session's text
  // differs under the typing (`conflicts` in the base's offsets, when known).
  showDivergence(conflicts) {
    const on = this.diverged();
    this.root.dataset.diverged = on ? '1' : '';
    this.divergence.style.display = on ? '' : 'none';
    if (!on) {
      if (this.view.state.field(conflictLines).size) this.view.dispatch({ effects: setConflictLines.of(Decoration.none) });
      return;
    }
    const doc = this.view.state.doc;
    const at = [...new Set(conflicts.map((c) => doc.lineAt(Math.min(this.pending.mapPos(c.from), doc.length)).number))];
    if (at.length) {
      this.conflictLines = at;
      // Marked in the text too (they move with later changes).
      const marks = at.sort((x, y) => x - y).map((n) => Decoration.line({
        class: 'cm-conflict-line',
        attributes: { 'data-conflict-line': String(n), title: 'your typing here overlaps a change made elsewhere: Update sends yours, "Take the session\'s text" drops it' },
      }).range(doc.line(n).from));
      this.view.dispatch({ effects: setConflictLines.of(Decoration.set(marks)) });
    }
    const where = this.conflictLines && this.conflictLines.length ? ` (line ${this.conflictLines.join(', ')})` : '';
    this.divergenceText.textContent = `⚠ diverged: your typing overlaps a change made elsewhere${where}; Update sends yours`;
  }

  // Highlights and elisions for the session's parameters; only while the
  // text is the session's (their spans are the session text's).
  markLiterals() {
    if (this.text() !== this.session) return;
    this.view.dispatch({ effects: setLiterals.of(this.parameters) });
  }

  toggleElided(key) {
    if (this.expanded.has(key)) this.expanded.delete(key);
    else this.expanded.add(key);
    this.markLiterals();
  }

  // Test hooks: the highlighted literals and the elided lists.
  literalMarks() {
    const out = [];
    this.view.state.field(this.literals).marks.between(0, this.view.state.doc.length, (from, to, d) => {
      if (d.spec.info) out.push({ from, to, text: this.view.state.doc.sliceString(from, to), class: d.spec.class, info: d.spec.info });
    });
    return out;
  }
  elidedRanges() {
    const out = [];
    this.view.state.field(this.literals).elided.between(0, this.view.state.doc.length, (from, to, d) => {
      out.push({ from, to, key: d.spec.widget.key });
    });
    return out;
  }

  // Scrolls the session text's line (1-based) into view (a created element).
  reveal(line) {
    const doc = this.view.state.doc;
    if (!(line >= 1)) return;
    this.view.dispatch({ effects: EditorView.scrollIntoView(doc.line(Math.min(line, doc.lines)).from, { y: 'center' }) });
  }

  // Drops the typing: the session's text, replacing what differs.
  revert() {
    this.localRedo = 0;
    this.base = this.text();
    this.pending = ChangeSet.empty(this.base.length);
    this.conflictLines = null;
    this.showSession(this.session, null);
    this.markLiterals();
  }

  mark(diagnostics) {
    const doc = this.view.state.doc;
    const at = (line, column) => {
      const l = doc.line(Math.min(Math.max(line, 1), doc.lines));
      return Math.min(l.from + Math.max(column - 1, 0), l.to);
    };
    const list = [];
    const lines = [];
    this.errors.textContent = '';
    for (const d of diagnostics) {
      if (!(d.line > 0)) continue;
      const from = at(d.line, d.column);
      let to = d.end_line > 0 ? at(d.end_line, d.end_column) : from;
      if (to <= from) to = Math.min(doc.line(Math.min(d.line, doc.lines)).to, doc.length);
      list.push({ from, to, severity: d.severity === 'error' ? 'error' : 'warning', message: d.message });
      if (d.severity === 'error') lines.push(Decoration.line({ class: 'cm-error-line', attributes: { 'data-error-line': String(d.line) } }).range(doc.line(Math.min(d.line, doc.lines)).from));
      const item = document.createElement('div');
      item.className = `diagnostic ${d.severity}`;
      item.textContent = `line ${d.line}: ${d.message}`;
      this.errors.appendChild(item);
    }
    lines.sort((x, y) => x.from - y.from);
    this.view.dispatch(setDiagnostics(this.view.state, list));
    this.view.dispatch({ effects: setErrorLines.of(Decoration.set(lines, true)) });
  }
}
