// Entry of dist/vendor/three.js (scripts/vendor.mjs): three.js and its
// OrbitControls for the 3D path view (www/lib/path3d.js), in one local file.
export * from 'three';
export { OrbitControls } from 'three/examples/jsm/controls/OrbitControls.js';
