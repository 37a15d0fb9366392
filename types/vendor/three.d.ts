// The page imports three.js and OrbitControls from vendor/three.js (bundled
// by scripts/vendor.mjs from scripts/vendor/three.mjs); types from @types/three.
export * from 'three';
export { OrbitControls } from 'three/examples/jsm/controls/OrbitControls.js';
