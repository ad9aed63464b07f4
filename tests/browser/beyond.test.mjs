// Browser tests of the views beyond the paper: the impact-regime map (ViewId::Map), the
// Lyapunov curve under the bifurcation diagram, the animated gear set and
// the A/B comparison. Small grids keep the suite quick.
import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import { start, open, status, waitStatus, waitText, canvasStats, shot, watchMainThread, stopWatch, watchReport, pagePoint } from './harness.mjs';

const QUICK = 'bif_points=8&transient_periods=120&record_periods=40&fr_points=150';

let h;
before(async () => {
  h = await start();
});
after(async () => {
  await h?.close();
});

test('the impact-regime map fills in from both workers and a cell click sets backlash and Omega', async () => {
  const q = `${QUICK}&lyap_points=0&map_omega_points=10&map_value_points=5&map_from=40&map_to=200&map_transient_periods=150&map_record_periods=30`;
  const { page, errors } = await open(h.browser, h.url, q);
  // The page stays responsive while both workers compute the map (from the
  // first paint on, as for the bifurcation sweep).
  await waitStatus(page, (s) => s.first_draw_ms.every((t) => t > 0), 30000, 'the first paint');
  await watchMainThread(page);
  const s = await waitStatus(page, (s) => s.map.finished_ms && s.map_frame, 90000, 'the map');
  const beat = await stopWatch(page);
  console.log(`# map: 50 cells in ${Math.round(s.map.finished_ms - s.map.started_ms)} ms; ${watchReport(beat)}`);
  assert.deepEqual(beat.over, [], `main-thread tasks over their limit: ${watchReport(beat)}`);
  assert.equal(s.map.total, 50);
  assert.equal(s.map.done, 50);
  const [byRegime, , failed] = s.map_counts;
  assert.equal(byRegime.reduce((a, b) => a + b, 0) + failed, 50);
  const st = await canvasStats(page, 'canvas-map');
  assert.ok(st.ink > st.total * 0.3, `the map looks empty (${st.ink} of ${st.total})`);
  assert.match(await page.textContent('#note-map'), /50 of 50 cells/);
  await shot(page.locator('#view-map'), '10-map');
  // Row 3 is 40 + 3 * 40 = 160 um; column 7 is Omega = 0.1 + 7 * 1.9 / 9.
  const g = s.map_grid;
  const omega = g.omega_from + (7 * (g.omega_to - g.omega_from)) / (g.omega_points - 1);
  const [x, y] = await pagePoint(page, 'canvas-map', s.map_frame, omega + 0.03, 160 - 8);
  const mapId = s.map.id;
  await page.mouse.click(x, y);
  const want = Math.round(omega * 1e4) / 1e4;
  const s2 = await waitStatus(page, (s) => s.omega === want && s.query.includes('backlash_um=160'), 20000, 'the clicked cell');
  assert.equal(await page.inputValue('#num-backlash_um'), '160');
  assert.equal(await page.inputValue('#num-omega'), String(want));
  const search = await page.evaluate(() => location.search);
  assert.ok(search.includes('backlash_um=160') && search.includes(`omega=${want}`), search);
  // The map over backlash does not depend on the backlash: it is kept.
  assert.equal(s2.map.id, mapId);
  await shot(page.locator('#view-map'), '11-map-clicked');
  // The TE axis: the select switches the rows' key and its range.
  await page.selectOption('#sel-map_key', 'te_um');
  const s3 = await waitStatus(page, (s) => s.map_grid && s.map_grid.key === 'te_um', 20000, 'the TE map');
  assert.equal(s3.map_grid.value_to, 60);
  assert.ok(s3.query.includes('map_key=te_um'));
  assert.deepEqual(errors, []);
  await page.close();
});

test('the Lyapunov exponent is drawn under the bifurcation diagram on the same Omega axis', async () => {
  const q = `${QUICK}&lyap_points=8&lyap_transient_periods=100&lyap_periods=40&map_omega_points=2&map_value_points=1`;
  const { page, errors } = await open(h.browser, h.url, q);
  const s = await waitStatus(page, (s) => s.lyap.finished_ms && s.bif.finished_ms && s.lyap_frame, 90000, 'the Lyapunov curve');
  assert.equal(s.lyap_points, 8);
  const st = await canvasStats(page, 'canvas-lyap');
  assert.ok(st.ink > st.total * 0.02, `the Lyapunov chart looks blank (${st.ink})`);
  // The same Omega axis as the bifurcation diagram: range and pixel columns.
  assert.deepEqual(s.lyap_frame.slice(4, 6), [0.1, 2.0]);
  assert.deepEqual(s.bif_frame.slice(4, 6), [0.1, 2.0]);
  assert.ok(Math.abs(s.lyap_frame[0] - s.bif_frame[0]) <= 1, `left edges ${s.lyap_frame[0]} vs ${s.bif_frame[0]}`);
  assert.ok(Math.abs(s.lyap_frame[2] - s.bif_frame[2]) <= 1, `right edges ${s.lyap_frame[2]} vs ${s.bif_frame[2]}`);
  // The zero line sits inside the plotted range.
  assert.ok(s.lyap_frame[6] < 0 && s.lyap_frame[7] > 0);
  assert.match(await page.textContent('#note-lyap'), /flow of a forced system always has one zero exponent/);
  await shot(page.locator('#view-bif'), '12-bif-lyapunov');
  assert.deepEqual(errors, []);
  await page.close();
});

const CONTACT_RGB = { drive: [31, 119, 180], apart: [230, 120, 0], back: [200, 30, 40] };

test('the animated gear set turns, and its mesh colours are the contact states of the simulated history at that instant', async () => {
  // Double-sided impacts at this Omega and backlash, so all three states occur.
  const q = `${QUICK}&lyap_points=0&map_omega_points=2&map_value_points=1&backlash_um=20&omega=1.2&mesh=s1a1`;
  const { page, errors } = await open(h.browser, h.url, q);
  // The animation draws only while in view.
  await page.locator('#canvas-anim').scrollIntoViewIfNeeded();
  await waitStatus(page, (s) => s.omega_job.finished_ms && s.anim && s.anim.frames > 2 && s.time_frame, 60000, 'the animation');
  const a = await canvasStats(page, 'canvas-anim');
  // The next frames: drawn after that snapshot, at another instant.
  const sa = (await status(page)).anim;
  await waitStatus(page, (s) => s.anim.frames > sa.frames + 1 && s.anim.sample !== sa.sample, 20000, 'later animation frames');
  const b = await canvasStats(page, 'canvas-anim');
  assert.notEqual(a.hash, b.hash, 'the animation canvas did not change between frames');
  assert.ok(a.ink > a.total * 0.2, 'the gear set looks blank');
  await page.click('#anim-play');
  // Paused: a frame drawn after the click says so.
  await waitStatus(page, (s) => s.anim.playing === false, 20000, 'the paused animation');
  const states = new Set();
  for (let step = 0; step < 6; step++) {
    const s = await status(page);
    assert.equal(s.anim.playing, false);
    assert.equal(s.anim.markers.length, 12);
    // The plotted mesh's gauge shows the time history's own sample.
    const m0 = s.anim.markers.find((m) => m.name === 's1a1');
    assert.ok(Math.abs(m0.x_um - s.anim.plotted_x_um) < 1e-3, `${m0.x_um} vs ${s.anim.plotted_x_um}`);
    const pixels = await page.evaluate((ms) => {
      const c = document.getElementById('canvas-anim');
      const ctx = c.getContext('2d');
      return ms.map((m) => Array.from(ctx.getImageData(Math.round(m.px[0]), Math.round(m.px[1]), 1, 1).data.slice(0, 3)));
    }, s.anim.markers);
    s.anim.markers.forEach((m, i) => {
      const want = m.x_um > m.b_um ? 'drive' : m.x_um < -m.b_um ? 'back' : 'apart';
      assert.equal(m.state, want, `${m.name}: x = ${m.x_um}, b = ${m.b_um}`);
      assert.deepEqual(pixels[i], CONTACT_RGB[want], `${m.name} at sample ${s.anim.sample}: pixel ${pixels[i]} is not ${want}`);
      states.add(want);
    });
    // The time history's cursor is drawn at that instant.
    const [l, t, r, bt, x0, x1] = s.time_frame;
    const t0 = s.anim.history_sample / 64;
    const cx = Math.round(l + ((t0 - x0) / (x1 - x0)) * (r - l));
    const cursor = await page.evaluate(([x, y]) => {
      const c = document.getElementById('canvas-time-cursor');
      return Array.from(c.getContext('2d').getImageData(x, y, 1, 1).data);
    }, [cx, Math.round((t + bt) / 2)]);
    assert.ok(cursor[3] > 100 && cursor[0] > 150, `no cursor at x = ${cx}: ${cursor}`);
    // Nine samples on: wait for the frame that shows that instant.
    for (let k = 0; k < 9; k++) await page.click('#anim-fwd');
    const want = (s.anim.sample + 9) % s.anim.window_len;
    await waitStatus(page, (x) => x.anim.sample === want && x.anim.frames > s.anim.frames, 20000, `the animation at sample ${want}`);
  }
  assert.ok(states.size >= 2, `only ${[...states]} seen`);
  await shot(page.locator('#view-anim'), '13-gear-set');
  await shot(page.locator('#view-time'), '14-time-cursor');
  // A click on the time history moves the animation there.
  const s = await status(page);
  const [l, t, r, bt, x0, x1] = s.time_frame;
  const box = await page.locator('#canvas-time').boundingBox();
  const scale = box.width / 760;
  const target = x0 + 0.25 * (x1 - x0);
  await page.mouse.click(box.x + (l + 0.25 * (r - l)) * scale, box.y + ((t + bt) / 2) * scale);
  const s2 = await waitStatus(page, (s) => Math.abs(s.anim.history_sample / 64 - target) < 0.1, 60000, 'the clicked instant');
  assert.equal(s2.anim.playing, false);
  assert.deepEqual(errors, []);
  await page.close();
});

test('Pin as A draws B over A on both diagrams, and the link restores the comparison', async () => {
  const q = `${QUICK}&lyap_points=0&map_omega_points=2&map_value_points=1&bif_dir=up&backlash_um=100`;
  const { page, errors } = await open(h.browser, h.url, q);
  await waitStatus(page, (s) => s.fr.finished_ms && s.bif.finished_ms, 90000, 'the first state');
  await page.click('#pin-a');
  await waitStatus(page, (s) => s.pinned && s.query.includes('&a='), 60000, 'the pinned state');
  // The status and the button are updated by different renders: wait for the
  // button itself rather than checking it the moment the status says pinned.
  await page.locator('#clear-a').waitFor({ state: 'visible', timeout: 60000 });
  // B: a larger backlash.
  await page.fill('#num-backlash_um', '160');
  await page.press('#num-backlash_um', 'Enter');
  const s = await waitStatus(page, (s) => s.query.startsWith('model=ravigneaux&backlash_um=160') && s.fr.finished_ms && s.bif.finished_ms, 90000, 'state B');
  assert.deepEqual(s.ab_labels, ['backlash 100 µm', 'backlash 160 µm']);
  await page.waitForFunction(
    () => /Comparing A \(backlash 100 µm\) with B \(backlash 160 µm\)/.test(document.querySelector('#ab-status')?.textContent ?? ''),
    null,
    { timeout: 60000 },
  );
  await shot(page.locator('#view-fr'), '15-ab-fr');
  await shot(page.locator('#view-bif'), '16-ab-bif');
  const link = s.query;
  // The link restores both: B's values in the controls, A computed anew.
  const again = await open(h.browser, h.url, link);
  const s2 = await waitStatus(again.page, (s) => s.pinned && s.pinned.fr.finished_ms && s.pinned.bif.finished_ms && s.fr.finished_ms, 90000, 'the restored comparison');
  assert.equal(await again.page.inputValue('#num-backlash_um'), '160');
  assert.deepEqual(s2.ab_labels, ['backlash 100 µm', 'backlash 160 µm']);
  assert.equal(s2.query, link);
  assert.ok(s2.pinned.fr_branch_points > 20 && s2.pinned.bif_points === 8, JSON.stringify(s2.pinned));
  assert.deepEqual(s2.issues, []);
  await shot(again.page.locator('#view-fr'), '17-ab-restored-fr');
  // Clear A ends it, and the link no longer carries A.
  await again.page.click('#clear-a');
  await again.page.waitForFunction(() => !location.search.includes('&a='));
  await again.page.locator('#clear-a').waitFor({ state: 'hidden', timeout: 60000 });
  assert.deepEqual(again.errors, []);
  await again.page.close();
  assert.deepEqual(errors, []);
  await page.close();
});

test('the phasing preset compares in-phase (A) with sequential (B) and gives the cancelled orders in the summary', async () => {
  const { page, errors } = await open(h.browser, h.url, `${QUICK}&lyap_points=0&map_omega_points=2&map_value_points=1`);
  await page.selectOption('#preset', 'phasing5');
  const s = await waitStatus(page, (s) => s.pinned && s.omega_job.finished_ms && s.query.includes('phasing=sequential'), 60000, 'the phasing preset');
  assert.deepEqual(s.ab_labels, ['mesh phasing in-phase', 'mesh phasing sequential']);
  const summary = await waitText(page, '#summary-expert', /Planet phasing \(sequential, N = 5\)/);
  assert.match(summary, /s1a 0\.00\/0\.00\/0\.00\/0\.00\/1\.00\/0\.00/);
  assert.match(summary, /orders 1, 2, 3, 4, 6 cancel in every kind/);
  assert.match(summary, /Response of s1a1 at orders 1–4: [0-9.]+, [0-9.]+, [0-9.]+, [0-9.]+ µm/);
  // The solver's geometry warnings reach the page: five pairs clash.
  assert.match(summary, /Model warnings: .*planets = 5/);
  await waitText(page, '#preset-note', /Parker & Lin/);
  await waitStatus(page, (s) => s.fr.finished_ms && s.pinned.fr.finished_ms, 60000, 'both branches');
  await shot(page.locator('#view-fr'), '18-phasing-fr');
  await shot(page.locator('#summary'), '19-phasing-summary');
  assert.deepEqual(errors, []);
  await page.close();
});
