// The calculation worker of the served page: loads the wasm core once and
// answers calls by name (protocol in lib/worker-core.js). Posts {ready: version}
// or {initError} once.
import init, * as wasm from './pkg/mtmotion.js';
import { serveCalls } from './lib/worker-core.js';

const ready = init({ module_or_path: new URL('./pkg/mtmotion_bg.wasm', import.meta.url) }).then(
  () => self.postMessage({ ready: wasm.version() }),
  (e) => self.postMessage({ initError: String((e && e.message) || e) }),
);
serveCalls(wasm, ready);
