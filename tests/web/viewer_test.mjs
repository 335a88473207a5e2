// Issue 4 must-show 5: a ctmap map opens with its texture in a real viewer. Serves viewer.html,
// three.js and the GLB on localhost, opens them in Debian's Chromium (headless, through
// playwright-core) and checks, for every feature vertex the camera sees from the front, that the
// rendered pixel has that feature's blob colour (ctmap_viewer_fixture painted a distinct blob at
// each feature's image point; the map must put the feature's UV exactly there).
//
// Usage: node viewer_test.mjs --glb MAP.glb --expected expected.json [--screenshot OUT.png]
// Exit 0 when every visible feature shows its colour and at least MIN_CHECKED were visible.
import fs from 'node:fs';
import http from 'node:http';
import os from 'node:os';
import path from 'node:path';
import { fileURLToPath } from 'node:url';

const here = path.dirname(fileURLToPath(import.meta.url));
const TOLERANCE = 8;     // levels per channel (0-255): sRGB decode/encode and texture filtering only
const MIN_CHECKED = 5;   // visible features needed for the test to mean something
const CHROMIUM = process.env.CTMAP_CHROMIUM || '/usr/bin/chromium';

function arg(name, required = true) {
  const i = process.argv.indexOf(name);
  if (i < 0 || i + 1 >= process.argv.length) {
    if (required) fail(`missing ${name}`);
    return null;
  }
  return process.argv[i + 1];
}

function fail(msg) {
  console.log(`viewer test: ${msg}`);
  process.exit(1);
}

const glbPath = arg('--glb');
const expected = JSON.parse(fs.readFileSync(arg('--expected'), 'utf8'));
const screenshot = arg('--screenshot', false);
if (!fs.existsSync(glbPath)) fail(`no GLB at ${glbPath}`);
if (!fs.existsSync(path.join(here, 'node_modules', 'three'))) fail(`three.js missing: run 'npm ci' in ${here}`);
if (!fs.existsSync(CHROMIUM)) fail(`no Chromium at ${CHROMIUM} (Debian package chromium, scripts/install_deps.sh)`);
const { chromium } = await import('playwright-core');

// Only the page, three.js's modules and the map are served; anything else is a 404.
const types = { '.html': 'text/html', '.js': 'text/javascript', '.glb': 'model/gltf-binary' };
const server = http.createServer((req, res) => {
  const url = decodeURIComponent(new URL(req.url, 'http://localhost').pathname);
  let file = null;
  if (url === '/' || url === '/viewer.html') file = path.join(here, 'viewer.html');
  else if (url === '/map.glb') file = glbPath;
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
const origin = `http://127.0.0.1:${server.address().port}`;

const profile = fs.mkdtempSync(path.join(os.tmpdir(), 'ctmap-chromium-'));
let context = null;
let code = 1;
try {
  context = await chromium.launchPersistentContext(profile, {
    executablePath: CHROMIUM,
    headless: true,
    args: ['--headless', '--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run',
      '--disable-background-networking', '--disable-component-update', '--disable-sync'],
    viewport: { width: 640, height: 640 },
    deviceScaleFactor: 1,
  });
  const page = await context.newPage();
  const errors = [];
  page.on('pageerror', (e) => errors.push(String(e)));
  page.on('console', (m) => { if (m.type() === 'error') errors.push(m.text()); });
  await page.goto(`${origin}/viewer.html`);
  await page.waitForFunction(() => window.ctmapReady === true, null, { timeout: 30000 });
  const result = await page.evaluate((f) => window.ctmapCheck(f),
    expected.features.map(({ name, vertex }) => ({ name, vertex })));
  if (screenshot) await page.screenshot({ path: screenshot });

  console.log(`three.js r${(await import('three')).REVISION} in ${await context.browser()?.version?.() ?? 'Chromium'}, ` +
    `${result.renderer}; ${result.triangles} triangles, ${result.vertices} vertices`);
  const byName = new Map(expected.features.map((f) => [f.name, f]));
  let checked = 0, wrong = 0;
  for (const r of result.features) {
    const want = byName.get(r.name).colour;
    if (!r.visible) {
      console.log(`  ${r.name.padEnd(14)} vertex ${String(r.vertex).padStart(5)} at (${r.px}, ${r.py}): not checked, ${r.reason}`);
      continue;
    }
    ++checked;
    const diff = Math.max(...want.map((w, k) => Math.abs(w - r.rgb[k])));
    const ok = diff <= TOLERANCE;
    if (!ok) ++wrong;
    console.log(`  ${r.name.padEnd(14)} vertex ${String(r.vertex).padStart(5)} at (${r.px}, ${r.py}): ` +
      `rendered [${r.rgb}], blob [${want}], max channel difference ${diff} ${ok ? 'ok' : 'WRONG'}`);
  }
  if (errors.length) console.log(`page errors:\n  ${errors.join('\n  ')}`);
  console.log(`${checked} of ${result.features.length} features visible from the front and checked, ` +
    `${checked - wrong} show their blob colour (tolerance ${TOLERANCE} levels per channel), ${wrong} do not`);
  if (errors.length) console.log('viewer test: FAILED, the page reported errors');
  else if (checked < MIN_CHECKED) console.log(`viewer test: FAILED, only ${checked} features visible, need ${MIN_CHECKED}`);
  else if (wrong > 0) console.log('viewer test: FAILED, wrong colours');
  else code = 0;
} catch (e) {
  console.log(`viewer test: FAILED, ${e.stack || e}`);
} finally {
  if (context) await context.close();
  server.close();
  fs.rmSync(profile, { recursive: true, force: true });
}
// Not process.exit: stdout to a pipe is written asynchronously and would be cut short.
process.exitCode = code;
