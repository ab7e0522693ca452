// Renders a glTF (or an FBX, through three.js's FBXLoader) with three.js in headless Chromium to a PNG, framed and
// posed like `facial render` / the skinning goldens, for a side-by-side check.
// Never part of the product build.
//
//   cd tools/threejs-compare && npm install
//   node render.mjs MODEL.glb OUT.png [--clip NAME|N|all] [--time S] [--weights NAME=V,...] [--yaw DEG] [--pitch DEG] [--size PX]
//
// Needs Debian's `chromium` (apt-get install chromium). The page is served
// by serve.mjs (shared with bench/peer/); the model's folder is under /files/.
import { existsSync } from 'node:fs';
import path from 'node:path';

import { here, launchChromium, requireThree, startServer } from './serve.mjs';

const args = process.argv.slice(2);
const positional = [], options = {};
for (let i = 0; i < args.length; ++i) {
  if (args[i].startsWith('--')) options[args[i].slice(2)] = args[++i];
  else positional.push(args[i]);
}
if (positional.length !== 2) {
  console.error('usage: node render.mjs MODEL.glb OUT.png [--clip NAME|N|all] [--time S] [--weights NAME=V,...] [--yaw DEG] [--pitch DEG] [--size PX]');
  process.exit(2);
}
const model = path.resolve(positional[0]);
const out = path.resolve(positional[1]);
if (!existsSync(model)) { console.error(`${model}: not found`); process.exit(1); }
requireThree();
const size = Number(options.size || 256);

const server = await startServer({ pageDir: here, filesDir: path.dirname(model) });
const query = new URLSearchParams({ model: '/files/' + path.basename(model), size: String(size),
                                    yaw: options.yaw || '0', pitch: options.pitch || '0',
                                    clip: options.clip || '', time: options.time || '0',
                                    weights: options.weights || '' });
const url = `http://127.0.0.1:${server.address().port}/page.html?${query}`;
const chromium = launchChromium(url, size, ['--virtual-time-budget=20000', `--screenshot=${out}`]);
const code = await new Promise((resolve) => chromium.on('close', resolve));
server.close();
if (code !== 0 || !existsSync(out)) { console.error(`chromium failed (${code})`); process.exit(1); }
console.log(`wrote ${out}`);
