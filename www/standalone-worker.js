// Worker of the single-file page: receives the wasm bytes in its first
// message (it cannot fetch from file://), then answers calls.
import * as wasm from './pkg/mtmotion.js';
import { serveCalls } from './lib/worker-core.js';

let markReady;
const ready = new Promise((r) => (markReady = r));
self.addEventListener('message', ({ data }) => {
  if (!data || !data.wasmBytes) return;
  try {
    wasm.initSync({ module: data.wasmBytes });
    self.postMessage({ ready: wasm.version() });
    markReady();
  } catch (e) {
    self.postMessage({ initError: String((e && e.message) || e) });
  }
});
serveCalls(wasm, ready);
