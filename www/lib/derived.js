// Calls the page adds on top of the core's functions, served where the
// core runs (the worker: lib/worker-core.js; or in-page: lib/api.js), so
// that a result made for drawing crosses to the page as transferred typed
// arrays. Each one is a core call plus drawing preparation, no model.
import { programPieces } from './pieces.js';

/** SegmentColumns.kind codes (the core's toolpath::columns). */
const KINDS = ['line', 'arc', 'rapid'];

/**
 * simulateToolPath's result with its segments unpacked again into the
 * core's objects (SegmentStats[]), on the page.
 * @returns {import('../pkg/mtmotion.js').ToolPathSimulation}
 */
export function unpackSimulation(r) {
  const { segmentColumns: c, ...rest } = r;
  const segments = new Array(c.kind.length);
  for (let i = 0; i < segments.length; i++) {
    const d = c.meanDeviation[i];
    segments[i] = {
      segment: c.segment[i], line: c.line[i], kind: KINDS[c.kind[i]], length: c.length[i], radius: c.radius[i],
      maxErrorUm: c.maxErrorUm[i], meanDeviation: Number.isNaN(d) ? null : d, samples: c.samples[i],
    };
  }
  return { ...rest, segments };
}

/** name → (wasm module, ...args) → result */
export const derived = {
  /**
   * parseNc(text, options), its segments as drawing pieces (lib/pieces.js).
   * @param {typeof import('../pkg/mtmotion.js')} wasm
   * @param {string} text
   * @param {import('../pkg/mtmotion.js').NcParseOptions} [options]
   */
  programPieces: (wasm, text, options) => programPieces(wasm.parseNc(text, options).segments),
  /**
   * simulateToolPath with its per-segment statistics as columns (the
   * core's simulateToolPathColumns): cameo's 35k segment objects took
   * ~0.2 s to receive on the page's thread, and 2 M of them were seconds
   * and hundreds of MB; the page rebuilds the objects it shows with
   * unpackSimulation.
   * @param {typeof import('../pkg/mtmotion.js')} wasm
   * @param {string} text
   * @param {import('../pkg/mtmotion.js').ToolPathConfig} config
   * @param {Function} [onProgress]
   */
  simulateToolPathPacked: (wasm, text, config, onProgress) => wasm.simulateToolPathColumns(text, config, onProgress),
};
