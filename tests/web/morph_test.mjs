// Issue 14 must-show 3: a `ctmap morph` GLB played by three.js in headless Chromium. At weight 0
// the morph must look like the source mesh, at weight 1 like the target (one camera, face normals
// as colours); each must differ from the other shape (the control), and the GLB's animation must
// drive the weight from 0 to 1. The test fails if the morph target is missing or wrong.
//
// Usage: node morph_test.mjs DIR   (DIR holds morph.glb, source.glb and target.glb)
import fs from 'node:fs';
import path from 'node:path';
import { checkTools, fail as failWith, launchBrowser, startServer } from './harness.mjs';

const TOLERANCE = 48;   // levels per channel: face-normal colours of chords of the same surface
const SAME = 0.02;      // at most this fraction of covered pixels may differ from the matching shape
const OTHER = 0.25;     // at least this fraction must differ from the other shape

const fail = (msg) => failWith(msg, 'morph test');
if (process.argv.length !== 3) fail('usage: node morph_test.mjs DIR');
const dir = path.resolve(process.argv[2]);
for (const f of ['morph.glb', 'source.glb', 'target.glb']) if (!fs.existsSync(path.join(dir, f))) fail(`no ${f} in ${dir}`);
checkTools('morph test');
const { server, origin } = await startServer('morph.html', dir);
let context = null, profile = null, code = 1;
try {
  ({ context, profile } = await launchBrowser());
  const page = await context.newPage();
  const errors = [];
  page.on('pageerror', (e) => errors.push(String(e)));
  page.on('console', (m) => { if (m.type() === 'error') errors.push(m.text()); });
  await page.goto(`${origin}/morph.html`);
  await page.waitForFunction(() => window.ctmapReady === true, null, { timeout: 30000 });
  const r = await page.evaluate((t) => window.ctmapMorph(t), TOLERANCE);
  await page.screenshot({ path: path.join(dir, 'morph_threejs.png') });
  const pct = (x) => `${(100 * x).toFixed(2)}%`;
  console.log(`three.js r${r.revision}: morph.glb with ${r.vertices} vertices, animation of ${r.clipDuration} s`);
  console.log(`  weight 0 vs source: ${pct(r.w0_source)} of covered pixels differ (at most ${pct(SAME)})`);
  console.log(`  weight 1 vs target: ${pct(r.w1_target)} differ (at most ${pct(SAME)})`);
  console.log(`  controls: weight 0 vs target ${pct(r.w0_target)}, weight 1 vs source ${pct(r.w1_source)} (at least ${pct(OTHER)})`);
  console.log(`  animation: weight ${r.atStart} at its start, ${r.atMiddle} at its middle`);
  const failures = [...errors];
  if (r.w0_source > SAME) failures.push('at weight 0 the morph does not look like the source');
  if (r.w1_target > SAME) failures.push('at weight 1 the morph does not look like the target (morph target wrong?)');
  if (r.w0_target < OTHER || r.w1_source < OTHER) failures.push('the control failed: the two shapes look alike');
  if (Math.abs(r.atMiddle - 1) > 1e-6 || Math.abs(r.atStart) > 1e-6) failures.push('the animation does not run the weight 0 -> 1');
  if (failures.length) console.log(`morph test: FAILED\n  ${failures.join('\n  ')}`);
  else {
    console.log('morph test: passed');
    code = 0;
  }
} catch (e) {
  console.log(`morph test: FAILED, ${e.stack || e}`);
} finally {
  if (context) await context.close();
  server.close();
  if (profile) fs.rmSync(profile, { recursive: true, force: true });
}
process.exitCode = code;
