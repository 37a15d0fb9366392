// www/embed.js imports the embed module as ./pkg/mtmotion_embed.js
// (scripts/build copies pkg-embed/ to dist/pkg/); its types are the
// generated pkg-embed/mtmotion_embed.d.ts.
export * from '../../pkg-embed/mtmotion_embed.js';
export { default } from '../../pkg-embed/mtmotion_embed.js';
