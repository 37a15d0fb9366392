// Entry of the single-file page (dist/mtmotion-standalone.html), which works
// from file://. The wasm bytes and the worker's code are inlined by
// scripts/bundle.mjs; panels are imported statically because
// browsers block module fetches from file://. The core runs in a worker made
// from a blob URL; where the browser refuses that, it runs in-page.
/* global __MTMOTION_WASM_BASE64__, __MTMOTION_WORKER_SOURCE__ */
import * as wasm from './pkg/mtmotion.js';
import { boot } from './lib/boot.js';
import { workerApi, inPageApi } from './lib/api.js';
import * as servo from './panels/servo.js';
import * as toolpath from './panels/toolpath.js';
import * as ballbar from './panels/ballbar.js';
import * as kinematics from './panels/kinematics.js';

const panels = { servo, toolpath, ballbar, kinematics };
const wasmBytes = () => Uint8Array.from(atob(__MTMOTION_WASM_BASE64__), (c) => c.charCodeAt(0));

async function makeApi() {
  try {
    const url = URL.createObjectURL(new Blob([__MTMOTION_WORKER_SOURCE__], { type: 'text/javascript' }));
    return await workerApi(url, { initMessage: { wasmBytes: wasmBytes() }, timeoutMs: 15_000, type: 'classic' });
  } catch (e) {
    console.warn(`mtmotion: no worker (${e.message}); calculations run in the page`);
    wasm.initSync({ module: wasmBytes() });
    return inPageApi(wasm);
  }
}

boot({ makeApi, loadPanel: async (name) => panels[name] });
