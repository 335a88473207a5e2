// Issue 15, must-show 1: the page of `ctmap serve` in headless Chromium (playwright-core, Debian's
// Chromium) on nefertiti/astronaut. Adds a feature by clicking the mesh and then the image, drags
// the left eye's point 20 image pixels, and checks from the preview's pixels that the texture moved
// with it (the eye vertex is drawn in the image's colour at the new point, not the old); saves,
// reloads, and finds the saved features in the page and in the file.
// Usage: node editor_test.mjs CTMAP_BIN SOURCE_DIR WORK_DIR   (screenshots: WORK_DIR/editor_*.png)
import { spawn } from 'node:child_process';
import fs from 'node:fs';
import path from 'node:path';
import readline from 'node:readline';
import { checkTools, fail, launchBrowser } from './harness.mjs';

const NAME = 'editor test';
const [ctmap, source, work] = process.argv.slice(2);
if (!work) fail('usage: editor_test.mjs CTMAP_BIN SOURCE_DIR WORK_DIR', NAME);
checkTools(NAME);
const data = [process.env.CTMAP_DATA, path.join(source, 'data'), path.join(source, '..', 'shared', 'data'),
  path.join(source, '.cache', 'data')].find((d) => d && fs.existsSync(path.join(d, 'meshes', 'nefertiti.off')));
if (!data) fail('no nefertiti.off (scripts/fetch_data.sh)', NAME);
fs.rmSync(work, { recursive: true, force: true });
fs.mkdirSync(work, { recursive: true });
const featuresFile = path.join(work, 'features.json');
fs.copyFileSync(path.join(source, 'data', 'features', 'nefertiti_astronaut.json'), featuresFile);

const server = spawn(ctmap, ['serve', path.join(data, 'meshes', 'nefertiti.off'), path.join(data, 'images', 'astronaut.png'),
  featuresFile, '--port', '0'], { stdio: ['ignore', 'pipe', 'inherit'] });
const origin = await new Promise((ok) => {
  readline.createInterface({ input: server.stdout }).once('line', (l) => ok((l.match(/http:\/\/[0-9.:]+/) || [null])[0]));
});
if (!origin) fail('the server did not start', NAME);

const failures = [];
const check = (ok, what) => { if (!ok) failures.push(what); };
const dist = (a, b) => Math.hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]);
let context, profile, code = 1;
try {
  ({ context, profile } = await launchBrowser());
  const page = context.pages()[0] || await context.newPage();
  await page.setViewportSize({ width: 1400, height: 760 });
  const errors = [];
  page.on('pageerror', (e) => errors.push(String(e)));
  const open = async () => {
    await page.goto(origin + '/');
    await page.waitForFunction(() => window.ctmapEditor);
    await page.evaluate(() => window.ctmapEditor.ready);
  };
  const settle = () => page.waitForFunction(() => window.ctmapEditor.idle(), null, { timeout: 60000 });
  const features = () => page.evaluate(() => window.ctmapEditor.features());
  const status = () => page.textContent('#status');
  await open();
  const before = await features();
  check(before.length === 16, `the page shows ${before.length} features, the file has 16`);
  await page.screenshot({ path: path.join(work, 'editor_start.png') });

  // Add a feature: the mesh point halfway between the nose tip and the left eye on the screen, and
  // the image point halfway between theirs.
  const f = (name, list) => list.find((x) => x.name === name);
  const [pe, pn] = await page.evaluate(([a, b]) => [window.ctmapEditor.project(a), window.ctmapEditor.project(b)],
    [f('left_eye', before).vertex, f('nose_tip', before).vertex]);
  await page.mouse.click((pe.x + pn.x) / 2, (pe.y + pn.y) / 2);
  check((await status()).includes('picked'), `clicking the mesh picked no vertex: ${await status()}`);
  const box = await page.evaluate(() => window.ctmapEditor.imageBox());
  const toScreen = (p) => [box.left + p[0] * box.scale, box.top + p[1] * box.scale];
  const mid = [(f('left_eye', before).image[0] + f('nose_tip', before).image[0]) / 2,
    (f('left_eye', before).image[1] + f('nose_tip', before).image[1]) / 2];
  await page.mouse.click(...toScreen(mid));
  await settle();
  const added = await features();
  check(added.length === 17, `after adding: ${added.length} features (${await status()})`);
  check((await page.textContent('#figures')).includes('valid'), 'no certified map after adding');

  // Drag the left eye 20 image pixels, in the direction where the photograph's colour changes most.
  const eye = f('left_eye', added);
  const dirs = [[20, 0], [-20, 0], [0, 20], [0, -20]];
  const colours = await page.evaluate(([p, ds]) => ({
    old: window.ctmapEditor.imageColour(p[0], p[1]),
    next: ds.map((d) => window.ctmapEditor.imageColour(p[0] + d[0], p[1] + d[1])),
  }), [eye.image, dirs]);
  const k = [0, 1, 2, 3].reduce((a, b) => (dist(colours.next[a], colours.old) >= dist(colours.next[b], colours.old) ? a : b));
  const target = [eye.image[0] + dirs[k][0], eye.image[1] + dirs[k][1]];
  const drawn = () => page.evaluate((v) => {
    const p = window.ctmapEditor.project(v);
    return window.ctmapEditor.drawnColour(p.cx, p.cy);
  }, eye.vertex);
  const c0 = await drawn();
  const [sx, sy] = toScreen(eye.image), [tx, ty] = toScreen(target);
  await page.mouse.move(sx, sy);
  await page.mouse.down();
  for (let i = 1; i <= 10; i++) await page.mouse.move(sx + (tx - sx) * i / 10, sy + (ty - sy) * i / 10);
  await page.mouse.up();
  await page.waitForTimeout(200);
  await settle();
  // Where the server holds the eye (not the page's own copy of where it was dragged).
  const serverState = await (await fetch(origin + '/api/state')).json();
  const moved = f('left_eye', serverState.features.features).image;
  check(Math.hypot(moved[0] - target[0], moved[1] - target[1]) < 1.5,
    `the eye is at ${moved}, dragged to ${target} (${await status()})`);
  const c1 = await drawn();
  const i0 = colours.old, i1 = colours.next[k];
  console.log(`left eye dragged by ${dirs[k]}: image colour ${i0} -> ${i1}; drawn at the eye vertex ${c0} -> ${c1}`);
  check(dist(i0, i1) > 30, `the photograph hardly changes colour there (${i0} vs ${i1}): no test`);
  check(dist(c0, i0) < dist(c0, i1), `before the drag the eye is drawn ${c0}, nearer the new point's ${i1} than the old ${i0}`);
  check(dist(c1, i1) < dist(c1, i0), `after the drag the eye is drawn ${c1}, nearer the old point's ${i0} than the new ${i1}`);
  await page.screenshot({ path: path.join(work, 'editor_dragged.png') });
  await page.selectOption('#mode', 'checker');
  await page.check('#showuv');
  await page.screenshot({ path: path.join(work, 'editor_checker.png') });

  // Save, reload: the page and the file hold the 17 features, the eye where it was dragged.
  await page.click('#save');
  await page.waitForFunction(() => document.getElementById('status').textContent.startsWith('saved'));
  const saved = JSON.parse(fs.readFileSync(featuresFile, 'utf8')).features;
  check(saved.length === 17 && Math.hypot(f('left_eye', saved).image[0] - moved[0], f('left_eye', saved).image[1] - moved[1]) < 1e-9,
    'the saved file does not hold the page\'s features');
  await open();
  const reloaded = await features();
  check(reloaded.length === 17 && JSON.stringify(f('left_eye', reloaded).image) === JSON.stringify(moved),
    `after reload: ${reloaded.length} features, left eye at ${f('left_eye', reloaded)?.image}`);
  check(errors.length === 0, `page errors: ${errors.join('; ')}`);
  if (failures.length) console.log(`${NAME}: FAILED\n${failures.join('\n')}`);
  else {
    console.log(`${NAME}: passed`);
    code = 0;
  }
} catch (e) {
  console.log(`${NAME}: FAILED, ${e.stack || e}`);
} finally {
  if (context) await context.close();
  if (profile) fs.rmSync(profile, { recursive: true, force: true });
  server.kill('SIGTERM');
}
process.exitCode = code;
