// Renders a glTF with three.js in headless Chromium to a PNG, framed and
// posed like `facial render` / the skinning goldens, for a side-by-side check.
// Never part of the product build.
//
//   cd tools/threejs-compare && npm install
//   node render.mjs MODEL.glb OUT.png [--clip NAME|N|all] [--time S] [--yaw DEG] [--pitch DEG] [--size PX]
//
// Needs Debian's `chromium` (apt-get install chromium). The page is served
// from a local HTTP server (ES modules do not load from file://); the model's
// folder is served under /files/.
import { spawn } from 'node:child_process';
import { createReadStream, existsSync, statSync } from 'node:fs';
import { createServer } from 'node:http';
import path from 'node:path';
import { fileURLToPath } from 'node:url';

const here = path.dirname(fileURLToPath(import.meta.url));
const args = process.argv.slice(2);
const positional = [], options = {};
for (let i = 0; i < args.length; ++i) {
  if (args[i].startsWith('--')) options[args[i].slice(2)] = args[++i];
  else positional.push(args[i]);
}
if (positional.length !== 2) {
  console.error('usage: node render.mjs MODEL.glb OUT.png [--clip NAME|N|all] [--time S] [--yaw DEG] [--pitch DEG] [--size PX]');
  process.exit(2);
}
const model = path.resolve(positional[0]);
const out = path.resolve(positional[1]);
if (!existsSync(model)) { console.error(`${model}: not found`); process.exit(1); }
if (!existsSync(path.join(here, 'node_modules/three'))) { console.error('run npm install in ' + here); process.exit(1); }
const size = Number(options.size || 256);

const types = { '.html': 'text/html', '.js': 'text/javascript', '.mjs': 'text/javascript', '.glb': 'model/gltf-binary',
                '.gltf': 'model/gltf+json', '.bin': 'application/octet-stream', '.png': 'image/png', '.jpg': 'image/jpeg' };
const server = createServer((req, res) => {
  const url = decodeURIComponent(new URL(req.url, 'http://x').pathname);
  const file = url.startsWith('/files/') ? path.join(path.dirname(model), url.slice(7)) : path.join(here, url);
  if (!existsSync(file) || !statSync(file).isFile()) { res.writeHead(404); res.end(); return; }
  res.writeHead(200, { 'Content-Type': types[path.extname(file)] || 'application/octet-stream' });
  createReadStream(file).pipe(res);
});
await new Promise((resolve) => server.listen(0, '127.0.0.1', resolve));
const query = new URLSearchParams({ model: '/files/' + path.basename(model), size: String(size),
                                    yaw: options.yaw || '0', pitch: options.pitch || '0',
                                    clip: options.clip || '', time: options.time || '0' });
const url = `http://127.0.0.1:${server.address().port}/page.html?${query}`;
const chromium = spawn('chromium', ['--headless=new', '--no-sandbox', '--disable-gpu-sandbox', '--use-angle=swiftshader',
                                    '--enable-unsafe-swiftshader', '--hide-scrollbars', `--window-size=${size},${size}`,
                                    '--virtual-time-budget=20000', `--screenshot=${out}`, url],
                       { stdio: ['ignore', 'inherit', 'inherit'] });
const code = await new Promise((resolve) => chromium.on('close', resolve));
server.close();
if (code !== 0 || !existsSync(out)) { console.error(`chromium failed (${code})`); process.exit(1); }
console.log(`wrote ${out}`);
