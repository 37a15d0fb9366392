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

/**
 * A large program file read into the core's NcStream chunk by chunk
 * (File.stream()), never as one string: the stream, told the file's size.
 * `onProgress(fraction, 'reading')` at each whole per cent read. A chunk
 * the core refuses (over a budget, not a text file) ends the reading: the
 * stream keeps the refusal, which its checkNc reports and its simulation
 * throws.
 * @param {typeof import('../pkg/mtmotion.js')} wasm
 * @param {Blob} file
 * @param {Function} [onProgress]
 */
async function streamFile(wasm, file, onProgress) {
  const stream = new wasm.NcStream(file.size);
  const reader = file.stream().getReader();
  let read = 0;
  let shown = -1;
  try {
    for (;;) {
      const { done, value } = await reader.read();
      if (done) break;
      try {
        stream.push(value);
      } catch {
        // refused: the stream keeps the core's refusal
        await reader.cancel();
        break;
      }
      read += value.length;
      const percent = Math.floor((100 * read) / Math.max(1, file.size));
      if (onProgress && percent !== shown) onProgress((shown = percent) / 100, 'reading');
    }
  } catch (e) {
    // the file could not be read (removed, unreadable)
    stream.free();
    throw e;
  }
  return stream;
}

/** name → (wasm module, ...args) → result */
export const derived = {
  /**
   * checkNc of a program file read streamed (NcStream: the whole text is
   * never one string in the page, the worker or wasm memory).
   * @param {typeof import('../pkg/mtmotion.js')} wasm
   * @param {Blob} file
   * @param {import('../pkg/mtmotion.js').NcStreamParseOptions} [options]
   * @param {Function} [onProgress]
   */
  checkNcFile: async (wasm, file, options, onProgress) => {
    const stream = await streamFile(wasm, file, onProgress);
    try {
      return stream.checkNc(options);
    } finally {
      stream.free();
    }
  },
  /**
   * simulateToolPathPacked of a program file read streamed (NcStream's
   * simulateToolPathColumns): progress 'reading', then 'simulating'.
   * @param {typeof import('../pkg/mtmotion.js')} wasm
   * @param {Blob} file
   * @param {import('../pkg/mtmotion.js').NcStreamToolPathConfig} config
   * @param {Function} [onProgress]
   */
  simulateNcFilePacked: async (wasm, file, config, onProgress) => {
    const stream = await streamFile(wasm, file, onProgress);
    try {
      return stream.simulateToolPathColumns(config, onProgress);
    } finally {
      stream.free();
    }
  },
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
