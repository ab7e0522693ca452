// What the three.js pages here and in bench/peer/ share: a local HTTP server
// (ES modules do not load from file://) and headless Chromium on SwiftShader.
// Never part of the product build.
import { spawn } from 'node:child_process';
import { createReadStream, existsSync, statSync } from 'node:fs';
import { createServer } from 'node:http';
import path from 'node:path';
import { fileURLToPath } from 'node:url';

export const here = path.dirname(fileURLToPath(import.meta.url));

const types = { '.html': 'text/html', '.js': 'text/javascript', '.mjs': 'text/javascript', '.glb': 'model/gltf-binary',
                '.gltf': 'model/gltf+json', '.bin': 'application/octet-stream', '.png': 'image/png', '.jpg': 'image/jpeg' };

// Serves /node_modules/ from this folder (npm install here), /shared/ from
// this folder too (the pages' common module, lit_scene.js), /files/ from
// filesDir (the model's folder) and everything else from pageDir. A POST to
// /result calls onResult with the request body (the page's report).
export async function startServer({ pageDir, filesDir, onResult = () => {} }) {
  const server = createServer((req, res) => {
    const url = decodeURIComponent(new URL(req.url, 'http://x').pathname);
    if (req.method === 'POST' && url === '/result') {
      let body = '';
      req.on('data', (chunk) => { body += chunk; });
      req.on('end', () => { res.writeHead(204); res.end(); onResult(body); });
      return;
    }
    const file = url.startsWith('/files/') ? path.join(filesDir, url.slice(7))
        : url.startsWith('/node_modules/') ? path.join(here, url)
        : url.startsWith('/shared/') ? path.join(here, url.slice(8)) : path.join(pageDir, url);
    if (!existsSync(file) || !statSync(file).isFile()) { res.writeHead(404); res.end(); return; }
    res.writeHead(200, { 'Content-Type': types[path.extname(file)] || 'application/octet-stream' });
    createReadStream(file).pipe(res);
  });
  await new Promise((resolve) => server.listen(0, '127.0.0.1', resolve));
  return server;
}

// Headless Chromium with WebGL on SwiftShader (the CPU rasteriser: the same
// kind of device as lavapipe). Returns the child process.
export function launchChromium(url, size, extraArgs = []) {
  return spawn('chromium', ['--headless=new', '--no-sandbox', '--disable-gpu-sandbox', '--use-angle=swiftshader',
                            '--enable-unsafe-swiftshader', '--hide-scrollbars', `--window-size=${size},${size}`,
                            ...extraArgs, url],
               { stdio: ['ignore', 'inherit', 'inherit'] });
}

export function requireThree() {
  if (!existsSync(path.join(here, 'node_modules/three'))) {
    console.error('run npm install in ' + here);
    process.exit(1);
  }
}
