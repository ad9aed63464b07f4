// Browser tests of parameter families: the frequency response
// overlaid in colour per value, a figure preset's small multiples (Fig. 5:
// three phase portraits and three Poincaré sections), the family link's
// round trip and bad family input. Small grids keep the suite quick.
import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import { start, open, waitStatus, waitText, canvasStats, shot } from './harness.mjs';

const QUICK = 'bif_points=6&transient_periods=120&record_periods=30&fr_points=120&lyap_points=0&map_omega_points=2&map_value_points=1&bif_dir=up';

let h;
before(async () => {
  h = await start();
});
after(async () => {
  await h?.close();
});

const allBranches = (s) => s.family && s.fr.finished_ms && s.family.members.every((m) => m.fr.finished_ms);

test('a family typed on the page overlays one coloured curve per value on the frequency response, and its link restores it', async () => {
  const { page, errors } = await open(h.browser, h.url, `${QUICK}&backlash_um=200`);
  await waitStatus(page, (s) => s.workers_ready === 2, 30000, 'the workers');
  await page.selectOption('#family-key', 'te_um');
  await page.fill('#family-values', '0, 20, 30');
  await page.click('#family-apply');
  const s = await waitStatus(page, allBranches, 120000, 'the three branches');
  assert.deepEqual(s.family.labels, ['TE 0 µm', 'TE 20 µm', 'TE 30 µm']);
  assert.deepEqual(s.family.values, [0, 20, 30]);
  assert.ok(s.fr_branch_points > 20, `${s.fr_branch_points}`);
  for (const m of s.family.members) assert.ok(m.fr_branch_points > 20, JSON.stringify(m));
  assert.match(s.query, /&family=te_um%3A0%2C20%2C30$/);
  assert.match(s.query, /te_um=0/);
  await page.waitForFunction(() => /Showing TE 0 µm, TE 20 µm, TE 30 µm/.test(document.querySelector('#family-status')?.textContent ?? ''));
  await page.locator('#family-clear').waitFor({ state: 'visible', timeout: 60000 });
  await page.locator('#view-fr').scrollIntoViewIfNeeded();
  await shot(page.locator('#view-fr'), '30-family-fr');
  assert.ok((await canvasStats(page, 'canvas-fr')).ink > 5000);
  // The bifurcation diagram: one panel per value, side by side.
  const sb = await waitStatus(page, (x) => x.bif.finished_ms && x.family.members.every((m) => m.bif.finished_ms), 120000, 'the three sweeps');
  for (const m of sb.family.members) assert.equal(m.bif_points, 6, JSON.stringify(m));
  await page.locator('#view-bif').scrollIntoViewIfNeeded();
  await shot(page.locator('#view-bif'), '34-family-bif');

  // Bad input: a plain message naming the value and the range; the last good state stays.
  await page.fill('#family-values', '0, 20, 5000');
  await page.click('#family-apply');
  await page.waitForFunction(() => /TE 5000/.test(document.querySelector('#family-error')?.textContent ?? ''));
  const err = await page.textContent('#family-error');
  assert.match(err, /-1000 to 1000 µm/);
  const kept = await waitStatus(page, (x) => x.family, 60000, 'the family kept');
  assert.equal(kept.query, s.query);
  await page.fill('#family-values', '1, 2, 3, 4, 5, 6, 7');
  await page.press('#family-values', 'Enter');
  await page.waitForFunction(() => /2 to 6 values/.test(document.querySelector('#family-error')?.textContent ?? ''));

  // The link restores the family exactly, and computes it again.
  const again = await open(h.browser, h.url, s.query);
  const s2 = await waitStatus(again.page, allBranches, 120000, 'the restored family');
  assert.equal(s2.query, s.query);
  assert.deepEqual(s2.family.values, [0, 20, 30]);
  assert.deepEqual(s2.issues, []);
  assert.equal(await again.page.inputValue('#family-key'), 'te_um');
  assert.equal(await again.page.inputValue('#family-values'), '0, 20, 30');
  // One value only: the link no longer carries the family.
  await again.page.click('#family-clear');
  await again.page.waitForFunction(() => !location.search.includes('family='));
  assert.deepEqual(again.errors, []);
  await again.page.close();
  assert.deepEqual(errors, []);
  await page.close();
});

test('the Fig. 5 preset shows three phase portraits and three Poincaré sections side by side', async () => {
  const { page, errors } = await open(h.browser, h.url, QUICK);
  await page.selectOption('#preset', 'fig5');
  const s = await waitStatus(
    page,
    (s) => s.family && s.family.key === 'te_um' && s.omega_job.finished_ms && !s.omega_result?.preview
      && s.omega_result?.omega === 0.5 && s.family.members.length === 2
      && s.family.members.every((m) => m.omega_job.finished_ms),
    180000,
    'the three orbits at Omega 0.5',
  );
  assert.deepEqual(s.family.labels, ['TE 0 µm', 'TE 20 µm', 'TE 30 µm']);
  assert.match(s.query, /family=te_um%3A0%2C20%2C30/);
  assert.match(s.query, /omega=0\.5/);
  for (const m of s.family.members) assert.equal(m.omega_job.error, null, JSON.stringify(m));
  // The preset's note does not say that only the first member is shown.
  await waitText(page, '#preset-note', /first curve or panel/, { not: true });
  for (const v of ['phase', 'poincare']) {
    await page.locator(`#view-${v}`).scrollIntoViewIfNeeded();
    assert.ok((await canvasStats(page, `canvas-${v}`)).ink > 3000, v);
  }
  await shot(page.locator('#view-phase'), '31-fig5-phase-panels');
  await shot(page.locator('#view-poincare'), '32-fig5-poincare-panels');
  // The claims section lists every claim of docs/paper.md; a claim's figure
  // button loads that figure's whole family.
  await page.locator('#claims summary').click();
  assert.equal(await page.locator('#claims-rows tr').count(), 16);
  assert.match(await page.textContent('#claim-8'), /chaos starts at Ω 0\.50 for every backlash/);
  assert.match(await page.textContent('#claim-8'), /gearshock lyapunov/);
  await shot(page.locator('#claims'), '33-claims');
  await page.locator('#claim-8 button').click();
  const s8 = await waitStatus(page, (x) => x.family && x.family.key === 'backlash_um', 60000, 'the Fig. 8 family');
  assert.deepEqual(s8.family.values, [50, 100, 200]);
  assert.deepEqual(errors, []);
  await page.close();
});

test('the Fig. 2 preset link shows its four mesh panels at once, every TE curve in each', async () => {
  // The preset's own link (as the menu makes it), then the same link with
  // fewer harmonics and points so six branches finish quickly.
  const first = await open(h.browser, h.url, QUICK);
  await first.page.selectOption('#preset', 'fig2');
  const p = await waitStatus(first.page, (s) => s.family && s.family.values.length === 6 && s.fr_panels, 60000, 'the Fig. 2 family');
  assert.deepEqual(p.fr_panels, ['s1a1', 's2b1', 'a1b1', 'rb1']);
  assert.match(p.query, /&panels=s1a1%2Cs2b1%2Ca1b1%2Crb1/);
  await first.page.close();
  // Each setting replaced in the preset's link (a key given twice is
  // named as an issue).
  const q = new URLSearchParams(p.query);
  for (const [k, v] of new URLSearchParams(`harmonics=3&fr_points=40&${QUICK}`)) q.set(k, v);
  const { page, errors } = await open(h.browser, h.url, q.toString());
  const s = await waitStatus(page, allBranches, 240000, 'the six branches');
  assert.deepEqual(s.fr_panels, ['s1a1', 's2b1', 'a1b1', 'rb1']);
  assert.deepEqual(s.family.labels, ['TE 5 µm', 'TE 10 µm', 'TE 15 µm', 'TE 20 µm', 'TE 25 µm', 'TE 30 µm']);
  assert.deepEqual(s.issues, []);
  // Drawn after the last branch arrived: the text alternative names the
  // four meshes in words, each with its highest peak.
  await page.waitForFunction(() => {
    const l = document.querySelector('#canvas-fr')?.getAttribute('aria-label') ?? '';
    return /4 meshes side by side/.test(l) && !/computing/.test(l);
  }, null, { timeout: 60000 });
  const label = await page.getAttribute('#canvas-fr', 'aria-label');
  for (const m of ['s1a1 (small sun – short planet a1)', 's2b1 (large sun – long planet b1)', 'a1b1 (short planet a1 – long planet b1)', 'rb1 (ring – long planet b1)']) {
    assert.ok(label.includes(m), `${m} in ${label}`);
  }
  assert.equal(await page.getAttribute('#canvas-fr', 'height'), '680');
  await waitText(page, '#note-fr', /one panel per mesh/);
  assert.ok((await canvasStats(page, 'canvas-fr')).ink > 8000);
  await page.locator('#view-fr').scrollIntoViewIfNeeded();
  await shot(page.locator('#view-fr'), '35-fig2-fr-panels');
  // Choosing a mesh shows it alone, and the link drops the panels.
  await page.selectOption('#sel-mesh', 's2b1');
  await page.waitForFunction(() => !location.search.includes('panels='));
  // One mesh's plot again, not the panels' 680: 400 pixels high or a
  // little more as its key needs (480 on a wide screen, this one's 1500
  // pixels, where it is drawn wider too).
  await page.waitForFunction(() => document.getElementById('canvas-fr').height < 680, null, { timeout: 60000 });
  const single = Number(await page.getAttribute('#canvas-fr', 'height'));
  assert.ok(single >= 400 && single <= 520, `height ${single}`);
  assert.deepEqual(errors, []);
  await page.close();
});
