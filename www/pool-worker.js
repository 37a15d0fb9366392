// One worker of the study pool (www/lib/pool.js): loads the wasm core and
// answers { id, fn, args } with { id, result } or { id, error }.
import init, * as wasm from './pkg/mtmotion.js';

const ready = init({ module_or_path: new URL('./pkg/mtmotion_bg.wasm', import.meta.url) });
self.onmessage = async ({ data: { id, fn, args } }) => {
  try {
    await ready;
    const f = wasm[fn];
    if (typeof f !== 'function' || fn === 'default' || fn.startsWith('init')) throw new Error(`unknown function '${fn}'`);
    self.postMessage({ id, result: f(...args) });
  } catch (e) {
    self.postMessage({ id, error: (e && e.message) || String(e) });
  }
};
