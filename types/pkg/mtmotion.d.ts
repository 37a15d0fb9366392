// www/ imports the core as ./pkg/mtmotion.js (scripts/build copies pkg/ to
// dist/pkg/); its types are the generated pkg/mtmotion.d.ts.
export * from '../../pkg/mtmotion.js';
export { default } from '../../pkg/mtmotion.js';
