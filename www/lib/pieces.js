// The programmed path as straight pieces for drawing (typed arrays), made
// where the core runs (lib/derived.js: in the worker, next to parseNc), so
// the page receives a few transferred arrays instead of one object per
// segment: cameo's 35k segments as objects took 0.3 s to receive on the
// page's thread. Drawing only: the segments are the core's parseNc reading.

/**
 * The programmed path as straight pieces for drawing: lines and rapids as
 * they are, arcs (any plane, helical too) as chords of at most 5°. Dwells
 * draw nothing.
 * @param {import('../pkg/mtmotion.js').NcSegment[]} segments the core's parseNc segments
 * @returns {ProgramPieces}
 */
export function programPieces(segments) {
  let n = 0;
  const chords = segments.map((g) => {
    const m = g.motion;
    const k = m.type === 'arc' ? Math.min(720, Math.max(1, Math.ceil(Math.abs(m.sweep) / (Math.PI / 36)))) : m.type === 'dwell' ? 0 : 1;
    n += k;
    return k;
  });
  const pos = new Float64Array(n * 6);
  const seg = new Int32Array(n);
  const line = new Int32Array(segments.length);
  const rapid = new Uint8Array(segments.length);
  const feed = new Float64Array(segments.length);
  const first = new Int32Array(segments.length + 1);
  const plane = { XY: [0, 1, 2], ZX: [2, 0, 1], YZ: [1, 2, 0] };
  let p = 0;
  segments.forEach((g, i) => {
    line[i] = g.line;
    rapid[i] = g.motion.type === 'rapid' ? 1 : 0;
    feed[i] = g.feed;
    first[i] = p;
    const a = [g.start.x, g.start.y, g.start.z];
    const b = [g.end.x, g.end.y, g.end.z];
    const m = g.motion;
    const k = chords[i];
    if (m.type === 'arc') {
      const [u, v, w] = plane[m.plane];
      const c = m.center;
      const r0 = Math.hypot(a[u] - c[u], a[v] - c[v]);
      const th0 = Math.atan2(a[v] - c[v], a[u] - c[u]);
      let prev = a;
      for (let j = 1; j <= k; j++) {
        const f = j / k;
        let q;
        if (j === k) q = b;
        else {
          q = [0, 0, 0];
          const th = th0 + m.sweep * f;
          q[u] = c[u] + r0 * Math.cos(th);
          q[v] = c[v] + r0 * Math.sin(th);
          q[w] = a[w] + (b[w] - a[w]) * f;
        }
        pos.set(prev, p * 6);
        pos.set(q, p * 6 + 3);
        seg[p++] = i;
        prev = q;
      }
    } else if (k) {
      pos.set(a, p * 6);
      pos.set(b, p * 6 + 3);
      seg[p++] = i;
    }
  });
  first[segments.length] = p;
  return { pos, seg, line, rapid, feed, first };
}

/**
 * @typedef {object} ProgramPieces the programmed path as straight pieces
 * @property {Float64Array} pos x0 y0 z0 x1 y1 z1 per piece, mm
 * @property {Int32Array} seg the segment of each piece
 * @property {Int32Array} line source line per segment
 * @property {Uint8Array} rapid 1 for a rapid, per segment
 * @property {Float64Array} feed programmed feed per segment, mm/min
 * @property {Int32Array} first first piece of each segment (and the count at the end)
 */
