// The calculation worker: loads the wasm core once and runs calls by name.
// Protocol: {id, fn, args, progress} in; {id, result} | {id, error} |
// {id, progress: [fraction, message]} out; {ready: version} | {initError} once.
import init, * as wasm from './pkg/mtmotion.js';

const ready = init({ module_or_path: new URL('./pkg/mtmotion_bg.wasm', import.meta.url) }).then(
  () => self.postMessage({ ready: wasm.version() }),
  (e) => self.postMessage({ initError: String((e && e.message) || e) }),
);

// Float64Array buffers in a result are transferred, not copied.
function transferables(value, out = [], depth = 0) {
  if (value && typeof value === 'object' && depth < 4) {
    if (ArrayBuffer.isView(value)) out.push(value.buffer);
    else for (const v of Array.isArray(value) ? value : Object.values(value)) transferables(v, out, depth + 1);
  }
  return out;
}

self.onmessage = async ({ data: { id, fn, args = [], progress } }) => {
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
