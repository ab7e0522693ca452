// Times the three.js peer page (page.html here) in headless Chromium and
// prints one line ending fps=<median-based fps>, like `facial bench frames`:
//   node peer.mjs MODEL.glb --target X,Y,Z --distance D [--size PX] [--frames N] [--warmup N]
// Uses tools/threejs-compare (its npm install of three, its server and
// Chromium launch). Never part of the product build.
import { existsSync } from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';

import { launchChromium, requireThree, startServer } from '../../tools/threejs-compare/serve.mjs';

const args = process.argv.slice(2);
const positional = [], options = {};
for (let i = 0; i < args.length; ++i) {
  if (args[i].startsWith('--')) options[args[i].slice(2)] = args[++i];
  else positional.push(args[i]);
}
if (positional.length !== 1 || !options.target || !options.distance) {
  console.error('usage: node peer.mjs MODEL.glb --target X,Y,Z --distance D [--size PX] [--frames N] [--warmup N]');
  process.exit(2);
}
const model = path.resolve(positional[0]);
if (!existsSync(model)) { console.error(`${model}: not found`); process.exit(1); }
requireThree();
const size = Number(options.size || 512);

let resolveResult;
const result = new Promise((resolve) => { resolveResult = resolve; });
const server = await startServer({ pageDir: path.dirname(fileURLToPath(import.meta.url)), filesDir: path.dirname(model),
                                   onResult: (body) => resolveResult(JSON.parse(body)) });
const query = new URLSearchParams({ model: '/files/' + path.basename(model), size: String(size),
                                    frames: options.frames || '100', warmup: options.warmup || '10',
                                    target: options.target, distance: options.distance });
const chromium = launchChromium(`http://127.0.0.1:${server.address().port}/page.html?${query}`, size);
const exited = new Promise((resolve) => chromium.on('close', (code) => resolve({ error: `chromium exited (${code})` })));
const timeout = new Promise((resolve) => setTimeout(() => resolve({ error: 'no report within 600 s' }), 600000));
const report = await Promise.race([result, exited, timeout]);
chromium.kill();
server.closeAllConnections();
server.close();
if (report.error) { console.error(`peer: ${model}: ${report.error}`); process.exit(1); }
const fps = report.median_ms > 0 ? 1000 / report.median_ms : 0;
console.log(`peer three.js r${report.revision} ${path.basename(model)} ${size}x${size} msaa=${report.samples} ` +
            `targets=${report.targets} renderer="${report.renderer}" cpu_median_ms=${report.median_ms.toFixed(3)} ` +
            `cpu_p95_ms=${report.p95_ms.toFixed(3)} fps=${fps.toFixed(2)}`);
process.exit(0);  // do not wait for Chromium's helpers to wind down
