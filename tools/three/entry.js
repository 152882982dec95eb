// The parts of three.js the kit page's 3-D viewer uses, bundled by tools/three/build.sh into
// one classic script (kit pages open from file://, where Chromium refuses ES module imports)
// that sets window.WeaveCutThree.
export {
  WebGLRenderer, Scene, PerspectiveCamera, HemisphereLight, DirectionalLight, Box3, Vector3,
  Color, SRGBColorSpace,
} from 'three';
export { OrbitControls } from 'three/examples/jsm/controls/OrbitControls.js';
export { GLTFLoader } from 'three/examples/jsm/loaders/GLTFLoader.js';
