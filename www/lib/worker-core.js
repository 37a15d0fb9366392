// Message loop of the calculation worker, shared by the served worker
// (worker.js) and the single-file page's inlined worker.
// Protocol: {id, fn, args, progress} in; {id, result} | {id, error, trap?} |
// {id, progress: [fraction, message]} out. `trap` marks a failure inside the
// WebAssembly instance (a RuntimeError: unreachable, out-of-bounds access):
// the instance may be left unusable, so the page replaces this worker.
// Besides the core's functions, the page's derived calls (lib/derived.js).
import { derived } from './derived.js';

// Float64Array buffers in a result are transferred, not copied.
function transferables(value, out = [], depth = 0) {
  if (value && typeof value === 'object' && depth < 4) {
    if (ArrayBuffer.isView(value)) out.push(value.buffer);
    else for (const v of Array.isArray(value) ? value : Object.values(value)) transferables(v, out, depth + 1);
  }
  return out;
}

/** True for a failure of the wasm instance itself rather than a reported error. */
export function isTrap(e) {
  return (typeof WebAssembly !== 'undefined' && e instanceof WebAssembly.RuntimeError) || e instanceof RangeError;
}

/** Answers calls on `wasm` (an initialised module namespace) once `ready` resolves. */
export function serveCalls(wasm, ready) {
  self.onmessage = async ({ data: { id, fn, args = [], progress } }) => {
    if (id === undefined) return;
    await ready;
    try {
      // The browser test's way to prove the page recovers from a trap.
      if (fn === '__simulateTrap') throw new WebAssembly.RuntimeError('unreachable (simulated by the test)');
      const f = Object.hasOwn(derived, fn) ? (...a) => derived[fn](wasm, ...a) : wasm[fn];
      if (typeof f !== 'function' || fn === 'default' || fn.startsWith('init')) throw new Error(`unknown function '${fn}'`);
      const callArgs = progress ? [...args, (fraction, message) => self.postMessage({ id, progress: [fraction, message] })] : args;
      // a derived call may be async (a file read streamed)
      const result = await f(...callArgs);
      self.postMessage({ id, result }, { transfer: [...new Set(transferables(result))] });
    } catch (e) {
      self.postMessage({ id, error: String((e && e.message) || e), trap: isTrap(e) });
    }
  };
}
