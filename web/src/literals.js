// The language viewer's view of the session's parameters (seed 4.2, 4.2.1):
// the literals a graphical viewer edits are highlighted (a colour per kind),
// read-only ones are underlined and say why on hover, and long point lists
// of trajectories and shapes are elided to a widget that expands on click
// (and folds again from the ⊟ at the end of the expanded text).
import { StateEffect, StateField } from '@codemirror/state';
import { Decoration, EditorView, WidgetType, hoverTooltip } from '@codemirror/view';
import { columnIndex } from './echo.js';

// Parameters with a handle or a control-panel field, by element kind.
const GRAPHICAL = {
  body: ['init_pos', 'init_rot', 'init_dpos', 'init_drot'],
  force: ['x', 'y', 'z', 'offset'],
  link: ['offset1', 'offset2', 'x', 'y', 'z'],
  torque: ['x', 'y', 'z', 'offset'],
  lightsource: ['pos', 'dir'],
  view: ['pos', 'rot', 'center'],
  trajectory: ['points'],
  simulator: ['start', 'finish', 'rtol'],
};
const ELIDABLE = { trajectory: ['points'], shape_set: ['desc'] };
export const ELIDE_AT = 40;  // characters: about half a line (seed 4.2.1)

export const isGraphical = (p) => (GRAPHICAL[p.kind] || []).includes(p.param);

// A 1-based line and byte column of the text → an offset into the document.
function offsetOf(doc, line, column) {
  if (!(line >= 1 && line <= doc.lines)) return -1;
  const l = doc.line(line);
  const i = columnIndex(l.text, column);
  return i < 0 ? -1 : l.from + i;
}

// The parameter's word in the document, or null when its span is unknown.
function rangeOf(doc, p) {
  const from = offsetOf(doc, p.line, p.column), to = offsetOf(doc, p.end_line, p.end_column);
  return from >= 0 && to > from ? { from, to } : null;
}

class Elided extends WidgetType {
  constructor(key, summary, viewer) { super(); this.key = key; this.summary = summary; this.viewer = viewer; }
  eq(o) { return o.key === this.key && o.summary === this.summary; }
  toDOM() {
    const b = document.createElement('span');
    b.className = 'cm-elided';
    b.dataset.key = this.key;
    b.textContent = `{⋯ ${this.summary}}`;
    b.title = 'Click to show the full text';
    b.onmousedown = (ev) => { ev.preventDefault(); this.viewer.toggleElided(this.key); };
    return b;
  }
  ignoreEvent() { return false; }
}

class Fold extends WidgetType {
  constructor(key, viewer) { super(); this.key = key; this.viewer = viewer; }
  eq(o) { return o.key === this.key; }
  toDOM() {
    const b = document.createElement('span');
    b.className = 'cm-fold-again';
    b.dataset.key = this.key;
    b.textContent = '⊟';
    b.title = 'Elide this list again';
    b.onmousedown = (ev) => { ev.preventDefault(); this.viewer.toggleElided(this.key); };
    return b;
  }
  ignoreEvent() { return false; }
}

function summary(p, text) {
  const count = (text.match(/-?\d*\.?\d+(?:e[-+]?\d+)?/gi) || []).length;
  if (p.kind === 'trajectory') return `${Math.floor(count / 4)} points`;
  const pieces = (text.match(/-(sub|face)\b/g) || []).length;
  return pieces ? `${pieces} pieces` : `${count} numbers`;
}

export const setLiterals = StateEffect.define();

// {marks, elided}: decorations built from the parameters, mapped through
// edits until the next state arrives.
export function literalsField(viewer) {
  const build = (doc, parameters) => {
    const marks = [], elided = [];
    const seen = new Set();
    for (const p of parameters) {
      const r = rangeOf(doc, p);
      if (!r) continue;
      const key = `${p.element}.${p.param}`;
      if ((ELIDABLE[p.kind] || []).includes(p.param) && r.to - r.from > ELIDE_AT && !seen.has(`e${r.from}`)) {
        seen.add(`e${r.from}`);
        if (viewer.expanded.has(key)) {
          marks.push(Decoration.mark({ class: 'cm-expanded', attributes: { 'data-key': key } }).range(r.from, r.to));
          marks.push(Decoration.widget({ widget: new Fold(key, viewer), side: 1 }).range(r.to));
        } else {
          elided.push(Decoration.replace({ widget: new Elided(key, summary(p, doc.sliceString(r.from, r.to)), viewer) }).range(r.from, r.to));
        }
        continue;
      }
      if (!isGraphical(p) || seen.has(`m${r.from}`)) continue;
      seen.add(`m${r.from}`);
      const what = `${p.element} -${p.param}`;
      const info = p.editable ? `${what}: graphically editable` : `${what} is read-only: ${p.reason}`;
      marks.push(Decoration.mark({
        class: p.editable ? `cm-literal cm-literal-${p.kind}` : 'cm-literal-readonly',
        attributes: { 'data-param': `${p.element}.${p.param}` },
        info,
      }).range(r.from, r.to));
    }
    return { marks: Decoration.set(marks, true), elided: Decoration.set(elided, true) };
  };
  return StateField.define({
    create: () => ({ marks: Decoration.none, elided: Decoration.none }),
    update(v, tr) {
      for (const e of tr.effects) if (e.is(setLiterals)) return build(tr.state.doc, e.value);
      return tr.docChanged ? { marks: v.marks.map(tr.changes), elided: v.elided.map(tr.changes) } : v;
    },
    provide: (f) => [
      EditorView.decorations.from(f, (v) => v.marks),
      EditorView.decorations.from(f, (v) => v.elided),
      EditorView.atomicRanges.of((view) => view.state.field(f).elided),
    ],
  });
}

// The reason (or the editability) of the literal under the pointer.
export function literalTooltips(field) {
  return hoverTooltip((view, pos) => {
    let found = null;
    view.state.field(field).marks.between(pos, pos, (from, to, d) => {
      if (d.spec.info && from <= pos && pos <= to) found = { from, to, info: d.spec.info };
    });
    if (!found) return null;
    return {
      pos: found.from, end: found.to, above: true,
      create: () => {
        const dom = document.createElement('div');
        dom.className = 'cm-literal-tip';
        dom.textContent = found.info;
        return { dom };
      },
    };
  }, { hoverTime: 200 });
}
