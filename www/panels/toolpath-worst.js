// Where the tool leaves the path, for the tool-path panel: the worst
// segments of cutting moves (ranked by the core's per-segment maximum) and,
// apart, those of rapids; each entry links to its line. Display only: the
// segments and their errors are the core's (simulateToolPath's segments).
import { h, table, fmt } from '../lib/ui.js';

/**
 * The `n` segments of cutting moves with the largest error, and the `n`
 * rapids, largest first.
 * @param {import('../pkg/mtmotion.js').ToolPathSimulation} s
 */
export function worstSegments(s, n = 10) {
  const byError = (a, b) => b.maxErrorUm - a.maxErrorUm;
  return {
    cutting: s.segments.filter((g) => g.kind !== 'rapid' && g.samples > 0).sort(byError).slice(0, n),
    rapids: s.segments.filter((g) => g.kind === 'rapid' && g.samples > 0).sort(byError).slice(0, n),
  };
}

/**
 * Where each of `worst` is drawn: the point on the programmed path (the
 * core's nearest point) of the segment's own kept sample (the core's
 * sampleSegment) with the largest error; `spot` when that error is the
 * segment's maximum (a thinned series may not have kept it). A segment
 * with no kept sample is marked at the middle of its drawn pieces.
 * @param {import('../pkg/mtmotion.js').ToolPathSimulation} s
 * @param {import('../pkg/mtmotion.js').SegmentStats[]} worst
 * @param {import('../lib/path3d.js').ProgramPieces | null} pieces
 * @returns {import('../lib/path3d.js').Mark[]}
 */
export function marksOf(s, worst, pieces) {
  // Per segment of `worst`, its largest kept sample (-1: none; a typed
  // array, not a Map: a million samples are looked up).
  const size = worst.reduce((m, g) => Math.max(m, g.segment + 1), 0);
  const best = new Int32Array(size).fill(-2);
  for (const g of worst) best[g.segment] = -1;
  const e = s.errorUm;
  const seg = s.sampleSegment;
  for (let i = 0; i < e.length; i++) {
    const g = seg[i];
    if (g >= size) continue;
    const b = best[g];
    if (b === -1 || (b >= 0 && e[i] > e[b])) best[g] = i;
  }
  return worst.map((g, r) => {
    const i = best[g.segment];
    let at;
    if (i >= 0) at = [s.nearX[i], s.nearY[i], s.nearZ[i]];
    else if (pieces && g.segment < pieces.first.length - 1) {
      const mid = (pieces.first[g.segment] + pieces.first[g.segment + 1] - 1) >> 1;
      at = [0, 1, 2].map((a) => (pieces.pos[mid * 6 + a] + pieces.pos[mid * 6 + 3 + a]) / 2);
    } else at = [s.nearX[0], s.nearY[0], s.nearZ[0]];
    return { rank: r + 1, line: g.line, errorUm: g.maxErrorUm, at, spot: i >= 0 && e[i] === g.maxErrorUm };
  });
}

/**
 * The two lists, each line a link (`onLine(line, rank)`).
 * @param {ReturnType<typeof worstSegments>} worst
 * @param {(line: number) => void} onLine
 */
export function worstLists(worst, onLine) {
  const link = (g, rank, kind) => h('a', {
    href: '#', class: 'nc-line', 'data-line': g.line, 'data-rank': rank, 'data-kind': kind,
    onclick: (ev) => {
      ev.preventDefault();
      onLine(g.line);
    },
  }, `line ${g.line}`);
  const rows = (list, kind) => list.map((g, i) => [
    kind === 'cutting' ? `#${i + 1}` : '',
    link(g, i + 1, kind), g.kind, fmt(g.length, 4), g.radius ? fmt(g.radius, 4) : '—', fmt(g.maxErrorUm, 4), g.meanDeviation == null ? '—' : fmt(g.meanDeviation * 1e3, 3),
  ]);
  const head = ['', 'line', 'kind', 'length mm', 'radius mm', 'max error µm', 'mean deviation µm'];
  return h('div', { id: 'toolpath-worst' },
    h('h4', {}, 'Largest errors on cutting moves (marked #1… in the view; click a line to see it in the program)'),
    worst.cutting.length ? table(head, rows(worst.cutting, 'cutting')) : h('p', {}, 'No cutting moves.'),
    h('details', { id: 'toolpath-worst-rapids' },
      h('summary', {}, `Rapids (G0), apart: ${worst.rapids.length ? `largest ${fmt(worst.rapids[0].maxErrorUm, 4)} µm` : 'none'} (not in the maximum above, not on the colour scale)`),
      worst.rapids.length ? table(head, rows(worst.rapids, 'rapid')) : ''));
}
