// Placeholders that scripts/bundle.mjs replaces when it inlines the wasm
// and the worker into the single-file page (www/standalone.js).
declare const __MTMOTION_WASM_BASE64__: string;
declare const __MTMOTION_WORKER_SOURCE__: string;
