// Entry of dist/vendor/three.js (scripts/vendor.mjs): the parts of three.js
// and its OrbitControls that the 3D path view (www/lib/path3d.js) uses,
// named so that esbuild leaves the rest of the library out.
export {
  WebGLRenderer, Scene, OrthographicCamera, BufferGeometry, BufferAttribute, LineSegments, Line, LineBasicMaterial,
  Points, PointsMaterial, Vector3, ColorManagement, LinearSRGBColorSpace,
} from 'three';
export { OrbitControls } from 'three/examples/jsm/controls/OrbitControls.js';
