// Merging a session change into a language viewer's unsent typing (seed
// 4.2: every view reflects every change, and nothing typed is lost).
//
// A viewer's text is `base` (the session text it was last in step with)
// followed by `pending` (a CodeMirror ChangeSet: its typing since).  When
// the session's text becomes `next`, the change base → next is split into
// hunks (a line diff, each hunk trimmed to the characters that differ);
// the hunks no typed change touches are mapped through the typing and
// applied to the viewer's text, so both survive; a hunk that touches typing
// is left out — the typing wins there — and the viewer has diverged from
// the session until its text is sent (Update) or the session's is taken.
import { ChangeSet, Text } from '@codemirror/state';

// Lines with their line feeds.
const lines = (s) => s.match(/[^\n]*\n|[^\n]+$/g) || [];

// The smallest single replacement that turns a[from, to) into b[from, bTo).
function trimmed(a, b, from, to, bFrom, bTo) {
  while (from < to && bFrom < bTo && a[from] === b[bFrom]) { ++from; ++bFrom; }
  while (to > from && bTo > bFrom && a[to - 1] === b[bTo - 1]) { --to; --bTo; }
  return { from, to, insert: b.slice(bFrom, bTo) };
}

// The changes from text a to text b as [{from, to, insert}] in a's offsets,
// in order and disjoint: one per run of differing lines (longest common
// subsequence of lines), trimmed to the characters that differ.  Beyond
// `limit` line pairs the differing middle is one replacement.
export function textDiff(a, b, limit = 4e6) {
  if (a === b) return [];
  // Common whole lines at both ends.
  const la = lines(a), lb = lines(b);
  let head = 0, offset = 0;
  while (head < la.length && head < lb.length && la[head] === lb[head]) offset += la[head++].length;
  let tail = 0;
  while (tail < la.length - head && tail < lb.length - head && la[la.length - 1 - tail] === lb[lb.length - 1 - tail]) ++tail;
  const ma = la.slice(head, la.length - tail), mb = lb.slice(head, lb.length - tail);
  const n = ma.length, m = mb.length;
  if (n === 0 || m === 0 || n * m > limit) {
    const r = trimmed(a, b, offset, a.length - tailLength(la, tail), offset, b.length - tailLength(lb, tail));
    return r.from < r.to || r.insert ? [r] : [];
  }
  // L[i][j]: the longest common subsequence of ma[i..] and mb[j..].
  const L = new Uint32Array((n + 1) * (m + 1));
  const at = (i, j) => i * (m + 1) + j;
  for (let i = n - 1; i >= 0; --i)
    for (let j = m - 1; j >= 0; --j)
      L[at(i, j)] = ma[i] === mb[j] ? L[at(i + 1, j + 1)] + 1 : Math.max(L[at(i + 1, j)], L[at(i, j + 1)]);
  const out = [];
  let i = 0, j = 0, pa = offset, pb = offset;
  let hunk = null;  // {pa, pb} where the current run of differing lines starts
  const close = () => {
    if (!hunk) return;
    const r = trimmed(a, b, hunk.pa, pa, hunk.pb, pb);
    if (r.from < r.to || r.insert) out.push(r);
    hunk = null;
  };
  while (i < n || j < m) {
    if (i < n && j < m && ma[i] === mb[j]) {
      close();
      pa += ma[i++].length; pb += mb[j++].length;
      continue;
    }
    if (!hunk) hunk = { pa, pb };
    if (j >= m || (i < n && L[at(i + 1, j)] >= L[at(i, j + 1)])) pa += ma[i++].length;
    else pb += mb[j++].length;
  }
  close();
  return out;
}

const tailLength = (list, count) => list.slice(list.length - count).reduce((s, l) => s + l.length, 0);

// Merges the session's new text into a viewer: `base` and `pending` as
// above, `next` the session's text.  Returns {apply: the ChangeSet to apply
// to the viewer's text, base: the new base, pending: the typing relative to
// it, conflicts: the hunks left out (in the new base's offsets)}.
export function mergeSession(base, pending, next) {
  const keep = [], left = [];
  for (const h of textDiff(base, next)) (pending.touchesRange(h.from, h.to) ? left : keep).push(h);
  const taken = ChangeSet.of(keep, base.length);
  const newBase = taken.apply(Text.of(base.split('\n'))).toString();
  return {
    apply: taken.map(pending),
    base: newBase,
    pending: pending.map(taken, true),
    conflicts: left.map((h) => ({ from: taken.mapPos(h.from, -1), to: taken.mapPos(h.to, 1), insert: h.insert })),
  };
}
