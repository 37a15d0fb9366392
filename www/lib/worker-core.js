// Message loop of the calculation worker, shared by the served worker
// (worker.js) and the single-file page's inlined worker.
// Protocol: {id, fn, args, progress} in; {id, result} | {id, error} |
// {id, progress: [fraction, message]} out.

// Float64Array buffers in a result are transferred, not copied.
function transferables(value, out = [], depth = 0) {
  if (value && typeof value === 'object' && depth < 4) {
    if (ArrayBuffer.isView(value)) out.push(value.buffer);
    else for (const v of Array.isArray(value) ? value : Object.values(value)) transferables(v, out, depth + 1);
  }
  return out;
}

/** Answers calls on `wasm` (an initialised module namespace) once `ready` resolves. */
export function serveCalls(wasm, ready) {
  self.onmessage = async ({ data: { id, fn, args = [], progress } }) => {
    if (id === undefined) return;
    await ready;
    try {
      const f = wasm[fn];
      if (typeof f !== 'function' || fn === 'default' || fn.startsWith('init')) throw new Error(`unknown function '${fn}'`);
      const callArgs = progress ? [...args, (fraction, message) => self.postMessage({ id, progress: [fraction, message] })] : args;
      const result = f(...callArgs);
      self.postMessage({ id, result }, [...new Set(transferables(result))]);
    } catch (e) {
      self.postMessage({ id, error: String((e && e.message) || e) });
    }
  };
}
