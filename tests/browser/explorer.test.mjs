// Browser tests of the explorer page: the release build in dist/, served on
// 127.0.0.1, driven in Debian's headless chromium through playwright-core.
// Run by scripts/test.sh (`node --test tests/browser/`). Screenshots go to
// tests/browser/screenshots/ (git-ignored) for a human to look at.
import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import { start, open, status, waitStatus, waitText, canvasStats, shot, watchMainThread, stopWatch, watchReport } from './harness.mjs';

// Small grids keep the suite quick; the bifurcation test uses full periods.
// The frequency response keeps its defaults (150 nominal points, H = 5):
// coarser settings make the harmonic-balance continuation fail near
// Omega = 0.21 on the default model (see the partial-branch check below).
const QUICK = 'bif_points=16&transient_periods=120&record_periods=40';
const CANVASES = ['fr', 'bif', 'phase', 'poincare', 'time', 'spectrum'];

let h;
before(async () => {
  h = await start();
});
after(async () => {
  await h?.close();
});

const allDone = (s) => s.fr.finished_ms && s.bif.finished_ms && s.omega_job.finished_ms;

test('the page loads without console errors and draws every canvas', async () => {
  const { page, errors } = await open(h.browser, h.url, QUICK);
  const s = await waitStatus(page, allDone, 90000, 'all jobs');
  assert.equal(s.workers_ready, 2);
  assert.deepEqual(s.issues, []);
  // ViewId::Fr is the harmonic-balance branch, complete (not a partial one).
  assert.equal(s.fr_method, 'harmonic balance, H = 5, exact');
  assert.equal(s.fr.error, null);
  assert.equal(s.fr_partial, null);
  assert.ok(s.fr_branch_points > 20, `${s.fr_branch_points} branch points`);
  await waitText(page, '#note-fr', /Method: harmonic balance, H = 5, exact/);
  for (const id of CANVASES) {
    const st = await canvasStats(page, `canvas-${id}`);
    assert.ok(st.ink > st.total * 0.02, `canvas-${id} looks blank (${st.ink} of ${st.total} pixels drawn)`);
  }
  // The summary names the regime and period; the schematic marks the plotted mesh.
  // Two sentences for students, the figures for experts behind a disclosure.
  const summary = await waitText(page, '#summary', /^At this speed the teeth .* The largest tooth force is [\d.]+ times .* \(dynamic factor [\d.]+\)/);
  assert.match(summary, /impact|no contact/);
  await waitText(page, '#summary-expert', /Natural frequencies in range/);
  await waitText(page, '#mesh-s1a1', /^mesh selected$/, { attr: 'class' });
  await shot(page, '01-loaded');
  assert.deepEqual(errors, []);
  await page.close();
});

test('moving the backlash slider with the keyboard changes the frequency response and the URL', async () => {
  const { page, errors } = await open(h.browser, h.url, QUICK);
  await waitStatus(page, allDone, 90000, 'all jobs');
  const before = await canvasStats(page, 'canvas-fr');
  const frId = (await status(page)).fr.id;
  await page.focus('#slider-backlash_um');
  for (let i = 0; i < 20; i++) await page.keyboard.press('ArrowRight');
  await page.waitForFunction(() => location.search.includes('backlash_um=120'));
  assert.equal(await page.inputValue('#num-backlash_um'), '120');
  const s = await waitStatus(page, (s) => s.fr.id > frId && s.fr.finished_ms, 90000, 'new frequency response');
  assert.ok(s.fr.id > frId);
  const afterStats = await canvasStats(page, 'canvas-fr');
  assert.notEqual(afterStats.hash, before.hash, 'the frequency response did not change');
  await shot(page.locator('#view-fr'), '02-backlash-120-fr');
  assert.deepEqual(errors, []);
  await page.close();
});

test('a slider change previews the selected-Omega views at once, then the full steady state replaces the preview', async () => {
  // A long transient usually keeps the worker's full run busy, but the
  // test does not count on it: it waits for the marker the page leaves
  // when it draws a preview (its time and the summary it showed) or for
  // the full run, whichever comes first, then for the full run.
  // At Ω 0.84: at the default 0.35 a mesh period takes more steps than
  // the preview's budget, and the page shows the full run only.
  const { page, errors } = await open(h.browser, h.url, 'omega=0.84&bif_points=4&transient_periods=2500&record_periods=100');
  await waitStatus(page, (s) => s.omega_job.finished_ms, 90000, 'the first Omega job');
  const before = await canvasStats(page, 'canvas-phase');
  const t0 = await page.evaluate(() => {
    const el = document.getElementById('slider-backlash_um');
    el.value = '130';
    el.dispatchEvent(new Event('input', { bubbles: true }));
    return performance.now();
  });
  // Whichever the page reports first: the preview drawn, or the full run
  // done. A worker that settles the orbit early (shooting) can finish
  // before the preview reaches the screen, and then the page rightly
  // never draws it; the preview's words are checked when it was drawn.
  const full = (s) => s.omega_job.finished_ms && s.omega_job.started_ms >= t0 && !s.omega_result.preview;
  const sp = await waitStatus(page, (s) => s.preview_drawn?.ms >= t0 || full(s), 60000, 'the preview drawn or the full run');
  assert.ok(sp.omega_job.preview_ms >= t0, 'the preview started at the slider change');
  if (sp.preview_drawn?.ms >= t0) {
    // The transient it ran is reported as run (20 periods, more where a
    // probe's window went back to the transient).
    assert.match(sp.preview_drawn.summary, /^Preview \((\d+) \+ 10 periods continued from the previous state; the full run is computing\): Ω = /);
    assert.ok(Number(/^Preview \((\d+)/.exec(sp.preview_drawn.summary)[1]) >= 20, sp.preview_drawn.summary);
    assert.ok(sp.preview_drawn.ms >= sp.omega_job.preview_ms);
    if (sp.omega_result.preview) {
      // Still the preview on screen: how it looks, for a human.
      await shot(page.locator('#view-phase'), '03a-phase-preview');
    }
  }
  const s = await waitStatus(page, full, 90000, 'the full run');
  assert.ok(s.omega_job.finished_ms > s.omega_job.preview_ms, 'the full run replaced the preview');
  await waitText(page, '#summary-expert', /^Preview/, { not: true });
  const after = await canvasStats(page, 'canvas-phase');
  assert.notEqual(after.hash, before.hash, 'the phase portrait did not change with the backlash');
  assert.deepEqual(errors, []);
  await page.close();
});

test('a saved link restores slider values, the mesh and the selected Omega', async () => {
  const link = `backlash_um=150&te_um=35.5&damping_ratio=0.045&omega=1.2345&mesh=s2b2&bif_dir=up&${QUICK}`;
  const { page, errors } = await open(h.browser, h.url, link);
  assert.equal(await page.inputValue('#num-backlash_um'), '150');
  assert.equal(await page.inputValue('#slider-backlash_um'), '150');
  assert.equal(await page.inputValue('#num-te_um'), '35.5');
  assert.equal(await page.inputValue('#num-damping_ratio'), '0.045');
  assert.equal(await page.inputValue('#num-omega'), '1.2345');
  assert.equal(await page.inputValue('#sel-mesh'), 's2b2');
  assert.equal(await page.inputValue('#sel-bif_dir'), 'up');
  const s = await waitStatus(page, (s) => s.omega_job.finished_ms, 60000, 'the Omega job');
  assert.equal(s.omega, 1.2345);
  assert.equal(s.omega_result.omega, 1.2345);
  assert.equal(s.omega_result.mesh, 's2b2');
  // The URL the page writes back carries the same values.
  const search = await page.evaluate(() => location.search);
  for (const kv of ['backlash_um=150', 'te_um=35.5', 'omega=1.2345', 'mesh=s2b2', 'damping_ratio=0.045']) {
    assert.ok(search.includes(kv), `${kv} missing from ${search}`);
  }
  // Re-opening the page's own link gives the same state.
  const again = await open(h.browser, h.url, search.slice(1));
  assert.equal((await status(again.page)).query, s.query);
  await again.page.close();
  await shot(page, '03-restored-link');
  assert.deepEqual(errors, []);
  await page.close();
});

test('clicking the frequency response moves the selected Omega', async () => {
  const { page, errors } = await open(h.browser, h.url, QUICK);
  const s0 = await waitStatus(page, (s) => s.fr.finished_ms && s.fr_frame, 90000, 'frequency response');
  const [l, t, r, b] = s0.fr_frame;
  const box = await page.locator('#canvas-fr').boundingBox();
  const width = await page.evaluate(() => document.getElementById('canvas-fr').width);
  const scale = box.width / width;
  const x = l + 0.75 * (r - l);
  await page.mouse.click(box.x + x * scale, box.y + ((t + b) / 2) * scale);
  const expected = 0.1 + 0.75 * (2.0 - 0.1);
  const s = await waitStatus(page, (s) => Math.abs(s.omega - expected) < 0.02 && s.omega_result && s.omega_result.omega === s.omega, 60000, 'the new Omega');
  assert.ok(Math.abs(s.omega - expected) < 0.02, `omega ${s.omega} vs ${expected}`);
  assert.equal(await page.inputValue('#num-omega'), String(s.omega));
  assert.ok((await page.evaluate(() => location.search)).includes(`omega=${s.omega}`));
  // Dragging moves it too.
  await page.mouse.move(box.x + (l + 0.3 * (r - l)) * scale, box.y + 100 * scale);
  await page.mouse.down();
  await page.mouse.move(box.x + (l + 0.4 * (r - l)) * scale, box.y + 100 * scale, { steps: 5 });
  await page.mouse.up();
  const s2 = await waitStatus(page, (s) => Math.abs(s.omega - (0.1 + 0.4 * 1.9)) < 0.02, 30000, 'dragged Omega');
  assert.ok(s2.omega < expected);
  await shot(page, '04-clicked-omega');
  assert.deepEqual(errors, []);
  await page.close();
});

test('a malformed link shows a message naming the key and range, and the page still works', async () => {
  const link = 'backlash_um=5000&omega=NaN&bif_points=999999999&te_um=25&%3Cimg%20src%3Dx%20onerror%3Dalert(1)%3E=1&mesh=%3Cb%3Ebold%3C%2Fb%3E&' + QUICK.replace('bif_points=16&', '');
  const { page, errors } = await open(h.browser, h.url, link);
  const msg = page.locator('#messages');
  await msg.waitFor({ state: 'visible' });
  const text = await msg.textContent();
  assert.match(text, /Backlash must be between 0 and 1000 µm \(not 5000\)/);
  assert.match(text, /Selected Ω must be between 0\.01 and 20 \(not NaN\)/);
  assert.match(text, /Bifurcation points must be a whole number between 2 and 1000/);
  assert.match(text, /<img src=x onerror=alert\(1\)>/, 'the hostile key is shown as text');
  // Nothing from the link became markup.
  assert.equal(await page.locator('#messages img, #messages b').count(), 0);
  // The valid keys applied, the bad ones kept their defaults and jobs stay capped.
  assert.equal(await page.inputValue('#num-te_um'), '25');
  assert.equal(await page.inputValue('#num-backlash_um'), '100');
  const s = await waitStatus(page, allDone, 90000, 'all jobs');
  assert.equal(s.bif.total, 200, 'default bifurcation grid (100 points, both directions)');
  await shot(page, '05-malformed-link');
  // And the page still responds to input.
  await page.fill('#num-backlash_um', '80');
  await page.press('#num-backlash_um', 'Enter');
  await page.waitForFunction(() => location.search.includes('backlash_um=80'));
  assert.deepEqual(errors, []);
  await page.close();
});

test('exports: CSV and JSON of the views, and the CLI formats of simulate and bifurcation', async () => {
  const { page, errors } = await open(h.browser, h.url, QUICK);
  await waitStatus(page, allDone, 90000, 'all jobs');
  const grab = async (view, label) => {
    const [dl] = await Promise.all([
      page.waitForEvent('download', { timeout: 60000 }),
      page.locator(`#exports-${view} button`, { hasText: new RegExp(`^${label}$`) }).click(),
    ]);
    const file = await dl.path();
    const fs = await import('node:fs');
    return { name: dl.suggestedFilename(), text: fs.readFileSync(file, 'utf8') };
  };
  const csv = await grab('fr', 'CSV');
  assert.equal(csv.name, 'gearshock-fr-s1a1.csv');
  assert.match(csv.text, /^branch,omega,x_max_um,x_min_um,stable,regime,period,bifurcation\nhbm,0\.1,/);
  const frJson = JSON.parse((await grab('fr', 'JSON')).text);
  // The branch, then the dots: at the defaults the bifurcation sweep's upward steady states.
  assert.equal(frJson.overlay_source.method, 'sweep');
  assert.equal(frJson.overlay.length, 16);
  assert.equal(csv.text.trim().split('\n').length, frJson.branches[0].points.length + frJson.overlay.length + 1);
  assert.equal(frJson.source.method, 'hbm');
  assert.equal(frJson.source.harmonics, 5);
  assert.equal(frJson.method, 'harmonic balance, H = 5, exact');
  const sim = JSON.parse((await grab('phase', 'CLI JSON')).text);
  assert.equal(sim.mesh, 's1a1');
  assert.equal(sim.omega, 0.35);
  assert.ok(Array.isArray(sim.poincare.delta_m) && sim.poincare.delta_m.length === 40);
  const bif = JSON.parse((await grab('bif', 'CLI JSON')).text);
  assert.equal(bif.spec.chains, 2);
  assert.equal(bif.spec.shard, null);
  assert.equal(bif.points.length, 32);
  assert.deepEqual(bif.points.slice(0, 3).map((p) => p.index), [0, 1, 2]);
  const png = await grab('spectrum', 'PNG');
  assert.equal(png.name, 'gearshock-spectrum-s1a1-omega0.35.png');
  assert.deepEqual(errors, []);
  await page.close();
});

test('a figure preset loads its first member and says what the paper shows', async () => {
  const { page, errors } = await open(h.browser, h.url, QUICK);
  await page.selectOption('#preset', 'fig8');
  await page.waitForFunction(() => location.search.includes('backlash_um=50'));
  const note = await waitText(page, '#preset-note', /The paper shows/);
  assert.match(note, /gearshock assumes/);
  assert.equal(await page.inputValue('#num-backlash_um'), '50');
  assert.equal(await page.inputValue('#num-te_um'), '20');
  await page.selectOption('#preset', 'pair');
  await page.waitForFunction(() => location.search.includes('model=gear-pair'));
  assert.equal(await page.inputValue('#sel-mesh'), 'pg');
  assert.ok(await page.locator('#control-planets').isHidden());
  assert.deepEqual(errors, []);
  await page.close();
});

test('the bifurcation diagram completes progressively while the main thread stays responsive', async () => {
  // 60 points up and down at the full 300 + 100 periods: 120 steady states,
  // computed anew after a TE change, with the views' other jobs small.
  // What the test checks the page records as it happens (its draws with
  // some points in, the progress labels shown), so a fast machine that
  // finishes before a status read fails nothing that held.
  const query = 'bif_points=60&fr_points=12&fr_record_periods=10&omega_from=0.3&omega_to=1.8'
    + '&branches=off&boundaries=off&map_omega_points=8&map_value_points=4&lyap_points=4';
  const { page, errors } = await open(h.browser, h.url, query, undefined, () => {
    // The bifurcation view's progress labels while shown, noted in the page.
    window.__bifProgress = [];
    document.addEventListener('DOMContentLoaded', () => {
      const box = document.getElementById('progress-bif');
      const label = document.getElementById('progress-bif-label');
      const note = () => {
        if (!box.hidden && label.textContent) window.__bifProgress.push(label.textContent);
      };
      new MutationObserver(note).observe(box, { attributes: true, attributeFilter: ['hidden'] });
      new MutationObserver(note).observe(label, { childList: true, characterData: true, subtree: true });
    });
  });
  const done = (s) => ['fr', 'omega_job', 'bif', 'map', 'lyap'].every((k) => s[k].finished_ms);
  const s0 = await waitStatus(page, done, 240000, 'the page\'s first jobs');
  await page.evaluate(() => { window.__bifProgress = []; });
  await page.fill('#num-te_um', '12');
  await page.press('#num-te_um', 'Enter');
  // Responsiveness while the sweep runs, from the frame after the change
  // on (the change's own frame, its preview and redraw of every view, is
  // the benchmark's slider-to-redraw figure; page load, with its one-time
  // wasm compilation, its first-paint figure).
  await waitStatus(page, (s) => s.draws[0] > s0.draws[0], 60000, 'the frequency response redrawn after the change');
  await watchMainThread(page);
  const fresh = (s) => s.bif.id > s0.bif.id;
  const partial = await waitStatus(page, (s) => fresh(s) && s.bif.done > 0, 240000, 'first bifurcation points');
  if (!partial.bif.finished_ms) await shot(page.locator('#view-bif'), '06-bifurcation-partial');
  const s = await waitStatus(page, (x) => fresh(x) && x.bif.finished_ms, 240000, 'the bifurcation sweep');
  const beat = await stopWatch(page);
  const partials = s.partial_draws[1] - s0.partial_draws[1];
  console.log(`# bifurcation: 120 points in ${Math.round(s.bif.finished_ms - s.bif.started_ms)} ms, first points after ${Math.round(s.bif.first_data_ms - s.bif.started_ms)} ms, ${partials} partial draws; ${watchReport(beat)}; slowest draws (ms) ${s.max_draw_ms.map(Math.round)}; longest frame ${Math.round(s.max_frame_ms)} ms, longest worker message ${Math.round(s.max_message_ms)} ms`);
  assert.equal(s.bif.done, 120);
  assert.equal(s.bif.error, null);
  // Drawn progressively: pictures with some of the points, before the end.
  assert.ok(s.bif.first_data_ms < s.bif.finished_ms);
  assert.ok(partials >= 1, `partial draws: ${partials}`);
  // A job this long shows its progress: the labels count points up.
  const seen = await page.evaluate(() => window.__bifProgress);
  assert.ok(seen.length > 0, 'no progress shown');
  for (const t of seen) assert.match(t, /^computing \d+\/120 points$/);
  // The shaded parametric-instability bands (engaged system, rho > 1): the
  // default model's 0.99-1.22 band holds Omega 1.1 (gearshock instability).
  assert.ok(s.bif_bands.some(([a, b]) => a < 1.1 && b > 1.1), JSON.stringify(s.bif_bands));
  assert.deepEqual(beat.over, [], `main-thread tasks over their limit: ${watchReport(beat)}`);
  const st = await canvasStats(page, 'canvas-bif');
  assert.ok(st.ink > st.total * 0.03);
  await shot(page.locator('#view-bif'), '07-bifurcation-complete');
  assert.deepEqual(errors, []);
  await page.close();
});

test('the frequency response is the harmonic-balance branch at the default settings, with an optional time-integration overlay', async () => {
  // Default settings: 150 nominal points, H = 5, Floquet stability; the
  // bifurcation sweep runs alongside on both workers, as on a fresh page.
  const { page, errors } = await open(h.browser, h.url, '');
  const s = await waitStatus(page, (s) => s.fr.finished_ms, 120000, 'the harmonic-balance branch');
  assert.equal(s.fr_method, 'harmonic balance, H = 5, exact');
  assert.equal(s.fr_partial, null, `the branch failed: ${s.fr_partial}`);
  const ready = s.first_draw_ms[0];
  console.log(`# harmonic balance (default: 150 points, H = 5, stability): ${s.fr_branch_points} points in ${Math.round(s.fr.finished_ms - s.fr.started_ms)} ms from page start, first points after ${Math.round(s.fr.first_data_ms - s.fr.started_ms)} ms; first FR draw at ${Math.round(ready)} ms`);
  await page.locator('#progress-fr').waitFor({ state: 'hidden', timeout: 60000 });
  const st = await canvasStats(page, 'canvas-fr');
  assert.ok(st.ink > st.total * 0.03);
  await shot(page.locator('#view-fr'), '08-fr-harmonic-balance');
  // A parameter change restarts the branch (a live update). At TE = 30 um
  // the continuation currently fails near Omega = 0.22: a failure must show
  // as a partial branch with the solver's message, never as a result.
  const id0 = s.fr.id;
  await page.fill('#num-te_um', '30');
  await page.press('#num-te_um', 'Enter');
  const s2 = await waitStatus(page, (x) => x.fr.id > id0 && x.fr.finished_ms, 120000, 'the new branch');
  console.log(`# harmonic balance after a TE change: ${s2.fr_branch_points} points in ${Math.round(s2.fr.finished_ms - s2.fr.started_ms)} ms (first points after ${Math.round(s2.fr.first_data_ms - s2.fr.started_ms)} ms); ${s2.fr_partial ? 'partial: ' + s2.fr_partial : 'complete'}`);
  if (s2.fr_partial) {
    assert.match(s2.fr.error, /harmonic-balance solver failed after Omega = [\d.]+ .*the branch shown is partial/);
    assert.ok(s2.issues.includes(s2.fr.error), 'the failure is in the messages');
    // The branch as drawn once the job ended (its caption says partial).
    await waitStatus(page, (x) => x.last_draw_ms[0] > s2.fr.finished_ms, 20000, 'the partial branch drawn');
    await shot(page.locator('#view-fr'), '10-fr-partial-branch');
  }
  await page.close();

  // The overlay: time-integration steady states as dots, with the discrepancy figure.
  const o = await open(h.browser, h.url, 'fr_ti_points=12&fr_record_periods=20&transient_periods=200&bif_points=4');
  const so = await waitStatus(o.page, (x) => x.fr.finished_ms && x.fr_overlay.finished_ms, 120000, 'branch and overlay');
  assert.equal(so.fr_overlay.done, 12);
  const d = so.fr_discrepancy;
  assert.equal(d.compared + d.off_branch, 12);
  assert.ok(d.compared > 0 && typeof d.max_um === 'number');
  console.log(`# time-integration overlay: 12 points; ${d.compared} under a stable stretch of the branch, largest distance ${d.max_um.toFixed(2)} um; ${d.off_branch} where the branch is unstable or absent`);
  await waitText(o.page, '#note-fr', /Hollow dots: the actual response, from time integration \(upward sweep\)/);
  await shot(o.page.locator('#view-fr'), '09-fr-hbm-with-time-integration');
  assert.deepEqual(errors, []);
  assert.deepEqual(o.errors, []);
  await o.page.close();
});
