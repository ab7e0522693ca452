// What both three.js pages (page.html here, bench/peer/page.html) draw with:
// a square WebGL canvas on the studio grey and the model under the comparison
// lights (a hemisphere fill and one key). Served at /shared/lit_scene.js.
import * as THREE from 'three';
import { FBXLoader } from 'three/addons/loaders/FBXLoader.js';
import { GLTFLoader } from 'three/addons/loaders/GLTFLoader.js';

export function createRenderer(size, options = {}) {
  const renderer = new THREE.WebGLRenderer({ antialias: true, ...options });
  renderer.setPixelRatio(1);
  renderer.setSize(size, size);
  renderer.setClearColor(0x4a4c50);
  document.body.appendChild(renderer.domElement);
  return renderer;
}

// The glTF (or, by its extension, FBX) at modelUrl in a scene with the
// lights; returns { gltf, scene } (an FBX's group as gltf.scene).
export async function loadLitScene(modelUrl) {
  let gltf;
  if (modelUrl.toLowerCase().endsWith('.fbx')) {
    const group = await new FBXLoader().loadAsync(modelUrl);
    // FBXLoader decodes embedded textures after it returns: wait for them.
    const maps = [];
    group.traverse((o) => {
      for (const m of [].concat(o.material || [])) if (m.map) maps.push(m.map);
    });
    await Promise.all(maps.map((map) => new Promise((resolve) => {
      const ready = () => (map.image && (map.image.complete || map.image.width) ? resolve() : setTimeout(ready, 20));
      ready();
    })));
    for (const map of maps) map.needsUpdate = true;
    gltf = { scene: group, animations: group.animations };
  } else {
    gltf = await new GLTFLoader().loadAsync(modelUrl);
  }
  const scene = new THREE.Scene();
  scene.add(gltf.scene);
  scene.add(new THREE.HemisphereLight(0xdde4ff, 0x4a3a30, 1.2));
  const key = new THREE.DirectionalLight(0xffffff, 2.2);
  key.position.set(0.6, 0.8, 1.0);
  scene.add(key);
  return { gltf, scene };
}
