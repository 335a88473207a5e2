// Issue 4 must-show 5: a ctmap map opens with its texture in a real viewer. Serves viewer.html,
// three.js and the map on localhost, opens them in Debian's Chromium (headless, through
// playwright-core) and checks, for every feature the camera sees from the front, that the
// rendered pixel has that feature's blob colour (ctmap_viewer_fixture painted a distinct blob at
// each feature's image point; the map must put the feature's UV exactly there). Both files a
// user gets are opened: the GLB (GLTFLoader) and the OBJ with its MTL (OBJLoader, MTLLoader).
//
// Usage: node viewer_test.mjs DIR
// DIR holds expected.json (from ctmap_viewer_fixture), map.glb, map.obj, map.mtl and the texture;
// the screenshots are written there as viewer_glb.png and viewer_obj.png.
// Exit 0 when, in both files, every visible feature shows its colour and at least MIN_CHECKED
// features were visible.
import fs from 'node:fs';
import path from 'node:path';
import { checkTools, fail as failWith, launchBrowser, startServer } from './harness.mjs';

const TOLERANCE = 8;     // levels per channel (0-255): sRGB decode/encode and texture filtering only
const MIN_CHECKED = 5;   // visible features needed for the test to mean something

const maxDiff = (a, b) => Math.max(...a.map((v, k) => Math.abs(v - b[k])));

const fail = (msg) => failWith(msg, 'viewer test');

if (process.argv.length !== 3) fail('usage: node viewer_test.mjs DIR');
const dir = path.resolve(process.argv[2]);
const expected = JSON.parse(fs.readFileSync(path.join(dir, 'expected.json'), 'utf8'));
for (const f of ['map.glb', 'map.obj', 'map.mtl']) if (!fs.existsSync(path.join(dir, f))) fail(`no ${f} in ${dir}`);
checkTools('viewer test');
const { server, origin } = await startServer('viewer.html', dir);

let context = null;
let profile = null;
let code = 1;
try {
  ({ context, profile } = await launchBrowser());
  console.log(`Chromium ${context.browser()?.version() ?? ''}`);
  const byName = new Map(expected.features.map((f) => [f.name, f]));
  const failures = [];
  for (const model of ['glb', 'obj']) {
    const page = await context.newPage();
    const errors = [];
    page.on('pageerror', (e) => errors.push(String(e)));
    page.on('console', (m) => { if (m.type() === 'error') errors.push(m.text()); });
    await page.goto(`${origin}/viewer.html`);
    await page.waitForFunction(() => window.ctmapReady === true, null, { timeout: 30000 });
    const result = await page.evaluate(([m, f]) => window.ctmapCheck(m, f),
      [model, expected.features.map(({ name, position }) => ({ name, position }))]);
    await page.screenshot({ path: path.join(dir, `viewer_${model}.png`) });
    await page.close();

    console.log(`map.${model} in three.js r${result.revision}, ${result.renderer}: ${result.triangles} triangles in ${result.meshes} mesh(es)`);
    let checked = 0, wrong = 0, controls = 0, controlWrong = 0;
    for (const r of result.features) {
      const want = byName.get(r.name).colour;
      const where = `  ${r.name.padEnd(14)} at (${r.px}, ${r.py}):`;
      if (!r.visible) {
        console.log(`${where} not checked, ${r.reason}`);
        continue;
      }
      ++checked;
      const diff = maxDiff(want, r.rgb);
      const ok = diff <= TOLERANCE;
      if (!ok) ++wrong;
      // Control: mirrored, the pixel shows the texture at (W - x, y); outside the feature's own
      // blob (with 2 px for filtering) that is another colour.
      const x = byName.get(r.name).image[0];
      let control = 'control n/a (mirrored point inside its own blob)';
      if (Math.abs(expected.image_size[0] - 2 * x) > expected.radius_px + 2) {
        ++controls;
        const same = maxDiff(want, r.mirrored_rgb) <= TOLERANCE;
        if (same) ++controlWrong;
        control = `mirrored [${r.mirrored_rgb}] ${same ? 'STILL THE BLOB' : 'differs'}`;
      }
      console.log(`${where} rendered [${r.rgb}], blob [${want}], max channel difference ${diff} ` +
        `${ok ? 'ok' : 'WRONG'}; ${control}`);
    }
    console.log(`  ${checked} of ${result.features.length} features visible from the front and checked, ` +
      `${checked - wrong} show their blob colour (tolerance ${TOLERANCE} levels per channel), ${wrong} do not`);
    if (errors.length) failures.push(`map.${model}: the page reported errors:\n  ${errors.join('\n  ')}`);
    if (checked < MIN_CHECKED) failures.push(`map.${model}: only ${checked} features visible, need ${MIN_CHECKED}`);
    console.log(`  control: texture mirrored, ${controls - controlWrong} of ${controls} features changed colour`);
    if (wrong > 0) failures.push(`map.${model}: ${wrong} features show the wrong colour`);
    if (controls < MIN_CHECKED - 1 || controlWrong > 0)
      failures.push(`map.${model}: the mirrored control changed ${controls - controlWrong} of ${controls} colours`);
  }
  if (failures.length) console.log(`viewer test: FAILED\n${failures.join('\n')}`);
  else {
    console.log('viewer test: passed');
    code = 0;
  }
} catch (e) {
  console.log(`viewer test: FAILED, ${e.stack || e}`);
} finally {
  if (context) await context.close();
  server.close();
  if (profile) fs.rmSync(profile, { recursive: true, force: true });
}
// Not process.exit: stdout to a pipe is written asynchronously and would be cut short.
process.exitCode = code;
