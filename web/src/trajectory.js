// Trajectories in the viewer (seed 4.1.4, Figure 4.4): a trajectory's
// `-points {{t x y z} ...}` literal read as knots, and the curve through them
// evaluated as core/physics/trajectory.cc does — cubic Bézier segments with
// Catmull–Rom tangents (central differences, one-sided at the ends), linear
// extrapolation outside the knots — so that the path drawn while a control
// point is dragged is the path the simulation will follow.

// The knots [[t, x, y, z] ...] of a -points literal, or null when it is not
// a list of groups of four numbers with increasing times.
export function parseKnots(text) {
  if (typeof text !== 'string') return null;
  const inner = text.trim();
  const groups = inner.match(/\{[^{}]*\}/g);
  if (!groups || inner.replace(/\{[^{}]*\}/g, '').trim() !== '') {
    // The word as written, braces and all: {{t x y z} ...}.
    const m = /^\{([\s\S]*)\}$/.exec(inner);
    return m ? parseKnots(m[1]) : null;
  }
  const knots = [];
  for (const g of groups) {
    const v = g.slice(1, -1).trim().split(/\s+/).map(Number);
    if (v.length !== 4 || !v.every(Number.isFinite)) return null;
    if (knots.length && v[0] <= knots[knots.length - 1][0]) return null;
    knots.push(v);
  }
  return knots.length ? knots : null;
}

// The text of a -points word for knots (its value, without the outer braces).
export function knotsText(knots) {
  return knots.map((k) => `{${k.join(' ')}}`).join(' ');
}

// The curve of knots [[t, x, y, z] ...]: value(t) → [x, y, z].
export class TrajectoryCurve {
  constructor(knots) {
    this.times = knots.map((k) => k[0]);
    this.points = knots.map((k) => k.slice(1, 4));
    const n = knots.length;
    this.tangents = this.points.map(() => [0, 0, 0]);
    if (n < 2) return;
    for (let i = 0; i < n; ++i) {
      const lo = i === 0 ? 0 : i - 1, hi = i + 1 === n ? n - 1 : i + 1;
      const dt = this.times[hi] - this.times[lo];
      this.tangents[i] = [0, 1, 2].map((c) => (this.points[hi][c] - this.points[lo][c]) / dt);
    }
  }

  value(t) {
    const { times, points, tangents } = this;
    const n = times.length;
    if (n === 0) return [0, 0, 0];
    if (n === 1) return points[0].slice();
    if (t <= times[0] || t >= times[n - 1]) {
      const e = t <= times[0] ? 0 : n - 1;
      return [0, 1, 2].map((c) => points[e][c] + tangents[e][c] * (t - times[e]));
    }
    let i = 0;
    while (i + 1 < n && times[i + 1] <= t) ++i;
    const h = times[i + 1] - times[i], s = (t - times[i]) / h, u = 1 - s;
    return [0, 1, 2].map((c) => {
      const b0 = points[i][c], b3 = points[i + 1][c];
      const b1 = b0 + (tangents[i][c] * h) / 3, b2 = b3 - (tangents[i + 1][c] * h) / 3;
      return u * u * u * b0 + 3 * u * u * s * b1 + 3 * u * s * s * b2 + s * s * s * b3;
    });
  }

  // `count` times per segment along the knots' time span (every knot's
  // among them), and the values there.
  sampleTimes(count = 24) {
    const { times } = this;
    if (times.length < 2) return times.slice();
    const out = [];
    for (let i = 0; i + 1 < times.length; ++i)
      for (let k = 0; k < count; ++k) out.push(times[i] + ((times[i + 1] - times[i]) * k) / count);
    out.push(times[times.length - 1]);
    return out;
  }
  sample(count = 24) { return this.sampleTimes(count).map((t) => this.value(t)); }
}
