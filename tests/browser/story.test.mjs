// Browser tests of one story: the page's words about a
// steady state come from its one classification. The Fig. 2 preset (no
// backlash, a linear system) at the page's defaults is period 1, found
// exactly, in its panel titles and its summary, which says nothing of
// impacts; the page opens on the periodic state the tour's first step
// explains, with the method note and the full key behind "details".
import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import { start, open, status, waitStatus, waitText, shot, recordOffers } from './harness.mjs';

let h;
before(async () => {
  h = await start();
});
after(async () => {
  await h?.close();
});

const omegaDone = (s) => s.omega_result && !s.omega_result.preview && s.omega_job.finished_ms;

test('the Fig. 2 preset at the page defaults is period 1 (exact) in its panel titles and summary', async () => {
  const { page, errors } = await open(h.browser, h.url);
  await waitStatus(page, (s) => s.workers_ready === 2, 30000, 'the workers');
  await page.selectOption('#preset', 'fig2');
  const s = await waitStatus(
    page,
    (x) => x.family && x.family.values.length === 6 && omegaDone(x) && x.family.members.every((m) => m.motion),
    120000,
    'every member\'s steady state',
  );
  assert.equal(s.omega_result.motion, 'period 1 (exact)');
  for (const m of s.family.members) assert.equal(m.motion, 'period 1 (exact)', JSON.stringify(m));
  assert.equal(s.family.omega_titles.length, 6);
  for (const t of s.family.omega_titles) assert.match(t, /^\([a-f]\) TE \d+ µm: period 1 \(exact\)$/);
  const summary = await waitText(page, '#summary', /repeats exactly every mesh period/);
  assert.match(summary, /no backlash/);
  assert.doesNotMatch(summary, /does not repeat|not periodic|cross the whole backlash|impact/);
  const label = await waitText(page, '#canvas-phase', /period 1 \(exact\)/, { attr: 'aria-label' });
  assert.doesNotMatch(label, /not periodic|impact/);
  await page.locator('#view-phase').scrollIntoViewIfNeeded();
  await shot(page.locator('#view-phase'), '40-fig2-phase-period1-exact');
  assert.deepEqual(errors, []);
  await page.close();
});

test('the page opens on a periodic state the first tour step explains, the method and full key behind details', async () => {
  const { page, errors } = await open(h.browser, h.url);
  const s = await waitStatus(page, (x) => omegaDone(x) && x.fr.finished_ms, 120000, 'the default steady state and branch');
  assert.equal(s.omega, 0.35);
  assert.equal(s.omega_result.motion, 'period 1 (exact)');
  assert.equal(s.omega_result.impact, 'none');
  const summary = await waitText(page, '#summary', /repeats exactly every mesh period/);
  assert.match(summary, /stay in contact/);
  // The method note and the full key are folded; their text is there.
  assert.equal(await page.locator('#note-fr').isVisible(), false);
  assert.equal(await page.locator('#key-fr').isVisible(), false);
  await waitText(page, '#note-fr', /Method: harmonic balance/);
  const key = await waitText(page, '#key-fr', /\S/);
  assert.ok(key.split('\n').length >= 3, key);
  await page.locator('#view-fr').scrollIntoViewIfNeeded();
  await shot(page.locator('#view-fr'), '41-default-fr-short-key');
  // The first tour step sets the state it explains.
  await page.click('#tour-start');
  await waitText(page, '#tour-text', /The page opens at Ω 0\.35, a calm motion/);
  assert.deepEqual(errors, []);
  await page.close();
});

test('the bifurcation diagram draws the shooting branches, stable solid and unstable thin, each bifurcation explained', async () => {
  // The branches are on by default. The gear pair's are short (its
  // period-1 branch turns back at a fold near Ω 0.32), so the
  // continuation finishes quickly.
  const { page, errors } = await open(h.browser, h.url, 'model=gear-pair&bif_points=40&lyap_points=0&map_omega_points=2&map_value_points=1');
  const s = await waitStatus(
    page,
    (x) => x.bif_branches && x.bif_branches.job.finished_ms && x.bif.finished_ms,
    240000,
    'the shooting branches',
  );
  const b = s.bif_branches;
  assert.ok(b.points > 3, JSON.stringify(b));
  assert.ok(b.stable_lines + b.unstable_lines >= 1, JSON.stringify(b));
  const label = await waitText(page, '#canvas-bif', /branches of periodic motion found by shooting/, { attr: 'aria-label' });
  assert.match(label, /stable and \d+ unstable stretches/);
  await page.locator('#view-bif').scrollIntoViewIfNeeded();
  await shot(page.locator('#view-bif'), '42-bif-shooting-branches');
  // One choice hides them.
  await page.selectOption('#sel-branches', 'off');
  await waitStatus(page, (x) => x.bif_branches.stable_lines + x.bif_branches.unstable_lines === 0, 60000, 'no branches');
  assert.deepEqual(errors, []);
  await page.close();
});

test('on the default compound set the shooting branches are on and draw as they come, and exports do not wait for them', async () => {
  // The default model and Omega range: the continuation takes the better
  // part of a minute here. It is sliced like every job and runs after the
  // other views' jobs, so every view (the Lyapunov curve and the map
  // included, which once waited behind it), the phase view's exports and
  // the sweep's command-line JSON (which the workers assemble) arrive
  // while it is still running.
  const { page, errors } = await open(h.browser, h.url, 'transient_periods=120&record_periods=40&map_omega_points=8&map_value_points=4&lyap_points=8');
  await waitStatus(
    page,
    (x) => omegaDone(x) && ['fr', 'bif', 'map', 'lyap'].every((k) => x[k].finished_ms) && x.bif_branches.points > 0 && !x.bif_branches.job.finished_ms,
    240000,
    'the first shooting branch points drawn while the continuation runs',
  );
  await recordOffers(page);
  const exports = [['exports-phase', 'JSON'], ['exports-phase', 'CLI JSON'], ['exports-bif', 'CLI JSON']];
  for (const [bar, label] of exports) {
    await page.locator(`#${bar} button`, { hasText: new RegExp(`^${label}$`) }).click();
  }
  await page.waitForFunction(
    (n) => window.offers.length >= n || JSON.parse(window.gearshockStatus()).issues.length > 0,
    exports.length,
    { timeout: 120000, polling: 100 },
  );
  const s = await status(page);
  assert.deepEqual(s.issues, []);
  const names = await page.evaluate(() => window.offers.map((o) => o.name));
  assert.deepEqual(names, ['gearshock-phase-s1a1-omega0.35.json', 'gearshock-phase-simulate-s1a1-omega0.35.json', 'gearshock-bif-bifurcation-s1a1.json'], names.join());
  assert.ok(!s.bif_branches.job.finished_ms, 'the continuation had finished before the exports arrived: the test shows nothing');
  assert.ok(s.bif_branches.stable_lines + s.bif_branches.unstable_lines >= 1, JSON.stringify(s.bif_branches));
  const texts = await page.evaluate(async () => Promise.all(window.offers.map(async (o) => (await fetch(o.href)).text())));
  for (const t of texts) JSON.parse(t);
  assert.equal(JSON.parse(texts[2]).points.length, 200);
  await page.locator('#view-bif').scrollIntoViewIfNeeded();
  await shot(page.locator('#view-bif'), '43-bif-branches-while-computing');
  assert.deepEqual(errors, []);
  await page.close();
});

test('a selected state whose recorded window still settles is confirmed by shooting from the window\'s end', async () => {
  // The gear pair at Omega 0.84 with a 4-period transient budget, below
  // the first checkpoint: integration alone says "still settling towards
  // period 2" (crates/solver/tests/pipeline.rs); the page's run shoots
  // from the end of its recorded window and shows the exact orbit.
  const { page, errors } = await open(
    h.browser,
    h.url,
    'model=gear-pair&omega=0.84&transient_periods=4&bif_points=6&lyap_points=0&map_omega_points=2&map_value_points=1',
  );
  const s = await waitStatus(page, omegaDone, 120000, 'the selected steady state');
  assert.equal(s.omega, 0.84);
  assert.equal(s.omega_result.motion, 'period 2 (exact)');
  const label = await waitText(page, '#canvas-phase', /period 2 \(exact\)/, { attr: 'aria-label' });
  assert.doesNotMatch(label, /still settling|not periodic/);
  assert.deepEqual(errors, []);
  await page.close();
});
