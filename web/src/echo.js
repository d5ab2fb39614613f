// The local echo of a drag (seed 4.2: the number changes in the language
// viewers while you drag).  A drag's values go to the session one request at
// a time, and every view shows the session's `text` events; the tab that
// drags also writes each new value into its own language viewers at once,
// as the session will write it, so its text follows the pointer without
// waiting for the server.  The session stays the one state: every `text`
// event of the drag is shown with the newest value in place of the one it
// carries (its other characters are the session's), and when the drag's
// re-simulation brings the fresh state, its text replaces the echo — the
// same characters unless the session formatted a number differently or
// refused the edit.
//
// Only a parameter written as one word (a body's -init_pos, a link's
// -offset1, a light's -pos, a view's -center …) is echoed; a force's vector
// (-x -y -z), a trajectory's point list and an option not yet written go
// through the session alone.

// The shortest text that reads back as exactly `v`, as the session writes
// it (C++ std::to_chars without a format: fixed or scientific, whichever is
// shorter, fixed on a tie; an exponent of at least two digits; a fixed
// integer in all its exact digits).
export function formatNumber(v) {
  if (v === 0) return '0';
  if (!Number.isFinite(v)) return String(v);
  const sign = v < 0 ? '-' : '';
  const a = Math.abs(v);
  const [mantissa, exp] = a.toExponential().split('e');
  const digits = mantissa.replace('.', '');
  const e = Number(exp);
  const scientific = `${digits[0]}${digits.length > 1 ? `.${digits.slice(1)}` : ''}e${e < 0 ? '-' : '+'}${String(Math.abs(e)).padStart(2, '0')}`;
  let fixed;
  if (Number.isInteger(a)) fixed = BigInt(a).toString();
  else if (e < 0) fixed = `0.${'0'.repeat(-e - 1)}${digits}`;
  else fixed = `${digits.slice(0, e + 1)}.${digits.slice(e + 1)}`;
  return sign + (fixed.length <= scientific.length ? fixed : scientific);
}

// The word the session writes for `values` in place of `source` (the
// literal as it is in the text): its braces or quotes kept.
export function literalText(source, values) {
  const body = values.map(formatNumber).join(' ');
  if (source.startsWith('{')) return `{${body}}`;
  if (source.startsWith('"')) return `"${body}"`;
  return values.length > 1 ? `{${body}}` : body;
}

// The index in `line` (one line's text) of its 1-based byte column (the
// core counts columns in UTF-8 bytes), or -1 when no character starts there.
export function columnIndex(line, column) {
  let bytes = 1, i = 0;
  while (bytes < column && i < line.length) {
    const c = line.codePointAt(i);
    bytes += c < 0x80 ? 1 : c < 0x800 ? 2 : c < 0x10000 ? 3 : 4;
    i += c >= 0x10000 ? 2 : 1;
  }
  return bytes === column ? i : -1;
}

// A 1-based line and byte column of `text` → a string offset, or -1.
export function offsetIn(text, line, column) {
  let at = 0;
  for (let l = 1; l < line; ++l) {
    at = text.indexOf('\n', at);
    if (at < 0) return -1;
    ++at;
  }
  const end = text.indexOf('\n', at);
  const i = columnIndex(text.slice(at, end < 0 ? text.length : end), column);
  return i < 0 ? -1 : at + i;
}

export class DragEcho {
  // `state` is the session's scene_state (text and parameters with spans).
  // Returns null when the parameter cannot be echoed.
  static start(state, element, param, values) {
    if (!state || param === 'points' || param === 'vector' || param === 'desc') return null;
    const p = state.parameters.find((q) => q.element === element && q.param === param);
    if (!p || !p.editable || !(p.line > 0) || !(p.end_line > 0)) return null;
    const from = offsetIn(state.text, p.line, p.column), to = offsetIn(state.text, p.end_line, p.end_column);
    if (from < 0 || to <= from) return null;
    const echo = new DragEcho(element, param, state.text.slice(0, from), state.text.slice(to), state.text.slice(from, to));
    echo.set(values);
    return echo;
  }

  constructor(element, param, prefix, suffix, source) {
    Object.assign(this, { element, param, prefix, suffix, source });
  }

  matches(element, param) { return element === this.element && param === this.param; }

  // The newest values of the drag.
  set(values) {
    this.values = values.slice();
    this.literal = literalText(this.source, values);
  }

  text() { return this.prefix + this.literal + this.suffix; }

  // What to show for the session's `text`: the echo, when the session's
  // text is this drag's literal in the same surroundings; null when it is
  // not (another change came in: the echo is over).
  over(sessionText) {
    const n = this.prefix.length + this.suffix.length;
    if (sessionText.length <= n || !sessionText.startsWith(this.prefix) || !sessionText.endsWith(this.suffix)) return null;
    const literal = sessionText.slice(this.prefix.length, sessionText.length - this.suffix.length);
    return /[\n;[\]$]/.test(literal) ? null : this.text();
  }
}
