// Calls the page adds on top of the core's functions, served where the
// core runs (the worker: lib/worker-core.js; or in-page: lib/api.js), so
// that a result made for drawing crosses to the page as transferred typed
// arrays. Each one is a core call plus drawing preparation, no model.
import { programPieces } from './pieces.js';

/** name → (wasm module, ...args) → result */
export const derived = {
  /**
   * parseNc(text, options), its segments as drawing pieces (lib/pieces.js).
   * @param {typeof import('../pkg/mtmotion.js')} wasm
   * @param {string} text
   * @param {import('../pkg/mtmotion.js').NcParseOptions} [options]
   */
  programPieces: (wasm, text, options) => programPieces(wasm.parseNc(text, options).segments),
};
