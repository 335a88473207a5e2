// What the browser tests share (viewer_test.mjs, morph_test.mjs): a localhost server for one page,
// three.js's modules and the files directly in DIR, and Debian's Chromium through playwright-core.
import fs from 'node:fs';
import http from 'node:http';
import os from 'node:os';
import path from 'node:path';
import { fileURLToPath } from 'node:url';

export const here = path.dirname(fileURLToPath(import.meta.url));
export const CHROMIUM = process.env.CTMAP_CHROMIUM || '/usr/bin/chromium';

/// Exits with the message (exit code 1).
export function fail(msg, name = 'browser test') {
  console.log(`${name}: ${msg}`);
  process.exit(1);
}

/// Checks that three.js and Chromium are there.
export function checkTools(name) {
  if (!fs.existsSync(path.join(here, 'node_modules', 'three'))) fail(`three.js missing: run 'npm ci' in ${here}`, name);
  if (!fs.existsSync(CHROMIUM)) fail(`no Chromium at ${CHROMIUM} (Debian package chromium, scripts/install_deps.sh)`, name);
}

/// Serves `page` (a file beside this one) at / , the files directly in `dir` under /model/ and
/// three.js under /node_modules/three/; anything else is a 404. Resolves to {server, origin}.
export async function startServer(page, dir) {
  const types = { '.html': 'text/html', '.js': 'text/javascript', '.glb': 'model/gltf-binary', '.png': 'image/png' };
  const server = http.createServer((req, res) => {
    const url = decodeURIComponent(new URL(req.url, 'http://localhost').pathname);
    let file = null;
    if (url === '/' || url === `/${page}`) file = path.join(here, page);
    else if (url.startsWith('/model/') && !url.slice(7).includes('/')) file = path.join(dir, url.slice(7));
    else if (url.startsWith('/node_modules/three/')) {
      file = path.join(here, url);
      if (!file.startsWith(path.join(here, 'node_modules', 'three') + path.sep)) file = null;
    }
    if (!file || !fs.existsSync(file) || !fs.statSync(file).isFile()) {
      res.writeHead(404);
      res.end();
      return;
    }
    res.writeHead(200, { 'Content-Type': types[path.extname(file)] || 'application/octet-stream' });
    fs.createReadStream(file).pipe(res);
  });
  await new Promise((ok) => server.listen(0, '127.0.0.1', ok));
  return { server, origin: `http://127.0.0.1:${server.address().port}` };
}

/// Headless Chromium in a fresh profile; resolves to {context, profile} (remove the profile after).
export async function launchBrowser() {
  const { chromium } = await import('playwright-core');
  const profile = fs.mkdtempSync(path.join(os.tmpdir(), 'ctmap-chromium-'));
  const context = await chromium.launchPersistentContext(profile, {
    executablePath: CHROMIUM,
    headless: true,
    args: ['--headless', '--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run',
      '--disable-background-networking', '--disable-component-update', '--disable-sync'],
    viewport: { width: 640, height: 640 },
    deviceScaleFactor: 1,
  });
  return { context, profile };
}
