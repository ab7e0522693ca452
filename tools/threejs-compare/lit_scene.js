// What both three.js pages (page.html here, bench/peer/page.html) draw with:
// a square WebGL canvas on the studio grey and the model under the comparison
// lights (a hemisphere fill and one key). Served at /shared/lit_scene.js.
import * as THREE from 'three';
import { GLTFLoader } from 'three/addons/loaders/GLTFLoader.js';

export function createRenderer(size, options = {}) {
  const renderer = new THREE.WebGLRenderer({ antialias: true, ...options });
  renderer.setPixelRatio(1);
  renderer.setSize(size, size);
  renderer.setClearColor(0x4a4c50);
  document.body.appendChild(renderer.domElement);
  return renderer;
}

// The glTF at modelUrl in a scene with the lights; returns { gltf, scene }.
export async function loadLitScene(modelUrl) {
  const gltf = await new GLTFLoader().loadAsync(modelUrl);
  const scene = new THREE.Scene();
  scene.add(gltf.scene);
  scene.add(new THREE.HemisphereLight(0xdde4ff, 0x4a3a30, 1.2));
  const key = new THREE.DirectionalLight(0xffffff, 2.2);
  key.position.set(0.6, 0.8, 1.0);
  scene.add(key);
  return { gltf, scene };
}
