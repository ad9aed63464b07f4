// Browser test of the regime map's boundaries, traced in
// a worker and drawn over the map, each kind named in the key; a click on
// a curve marks it and its point on the map, says what it is beside the
// map and selects its point; the progress bar stays until the trace ends
// (the compound set's runs a minute past its cells); the cells that disagree
// with the side of a curve they lie on are counted and outlined. The gear
// pair traces its boundaries in seconds; the compound set's default map
// (the second test) in about a minute.
import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import { start, open, waitStatus, waitText, shot, pagePoint } from './harness.mjs';

const QUERY = [
  'model=gear-pair',
  'boundaries=on',
  'bif_points=8',
  'transient_periods=120',
  'record_periods=40',
  'lyap_points=0',
  'map_omega_points=30',
  'map_value_points=12',
  'map_transient_periods=200',
  'map_record_periods=30',
].join('&');

let h;
before(async () => {
  h = await start();
});
after(async () => {
  await h?.close();
});

/**
 * Waits for the whole trace, the whole map and a drawing of both (curves
 * arrive one by one; the drawn marks are the disagreeing cells counted)
 * and logs what was traced under `label`; returns that status.
 */
async function boundariesDrawn(page, timeoutMs, label) {
  const s = await waitStatus(
    page,
    (x) =>
      x.map_boundaries.finished &&
      x.map.finished_ms &&
      x.map_frame &&
      x.map_drawn &&
      x.map_drawn.curve_paths > 0 &&
      x.map_drawn.marks === x.map_boundaries.disagree,
    timeoutMs,
    `the boundaries drawn over the finished map (${label})`,
  );
  const b = s.map_boundaries;
  console.log(`# ${label}: ${b.curves} curves (${JSON.stringify(b.kinds)}) traced in ${Math.round(b.job.finished_ms - b.job.started_ms)} ms; ${b.judged} cells judged, ${b.disagree} disagree`);
  return s;
}

/**
 * Clicks the middle point of the longest curve of the finished status `s`
 * and checks what the page says and selects: the sentence, Omega and the
 * key's value within a few pixels of the curve's point, and the curves
 * kept (they depend on everything but the key). Screenshots before and
 * after, named `before` and `after`.
 */
async function clickACurve(page, s, before, after) {
  const b = s.map_boundaries;
  await page.locator('#view-map').scrollIntoViewIfNeeded();
  await shot(page.locator('#view-map'), before);
  // A click on the longest curve's middle point picks it.
  const p = b.sample;
  const [x, y] = await pagePoint(page, 'canvas-map', s.map_frame, p.omega, p.value);
  await page.mouse.click(x, y);
  const s2 = await waitStatus(page, (x) => x.map_boundaries.picked, 30000, 'the picked boundary');
  assert.match(s2.map_boundaries.picked, /^Here .*: Ω \d\.\d{3}, backlash \d+\.\d µm\.$/);
  // Its point is selected: Omega within a pixel or two of the curve's, the backlash likewise.
  const [l, , r, , x0, x1, y0, y1] = s.map_frame;
  const [, t2, , b2] = s.map_frame;
  const perPxOmega = (x1 - x0) / (r - l);
  const perPxValue = (y1 - y0) / (b2 - t2);
  const set = s2.query.match(/backlash_um=([\d.]+)/);
  assert.ok(set, s2.query);
  assert.ok(Math.abs(s2.omega - p.omega) <= 3 * perPxOmega, `${s2.omega} vs ${p.omega}`);
  assert.ok(Math.abs(Number(set[1]) - p.value) <= 3 * perPxValue, `${set[1]} vs ${p.value}`);
  // Its sentence beside the map, and the curve marked on it.
  await waitText(page, '#map-picked', /^◯ Here .* µm\.$/);
  assert.ok(await page.isVisible('#map-picked'));
  await waitStatus(page, (x) => x.map_drawn?.picked === true, 30000, 'the picked curve marked');
  assert.doesNotMatch(await page.textContent('#note-map'), /Here /);
  // The curves depend on everything but the backlash: they are kept.
  assert.equal(s2.map_boundaries.job.id, b.job.id);
  await shot(page.locator('#view-map'), after);
}

test('the map draws its traced boundaries, a click on one says what it is and selects it, disagreeing cells are outlined', async () => {
  const { page, errors } = await open(h.browser, h.url, QUERY);
  const s = await boundariesDrawn(page, 300000, 'boundaries');
  const b = s.map_boundaries;
  assert.ok(b.shown >= 2, JSON.stringify(b));
  // The gear pair's jump and its contact changes over backlash.
  assert.ok(b.kinds.fold >= 1, JSON.stringify(b.kinds));
  assert.ok(b.kinds['drive-flanks-part'] >= 1 || b.kinds['back-flanks-touch'] >= 1, JSON.stringify(b.kinds));
  assert.ok(b.judged > 0, 'cells near the curves are judged');
  assert.ok(Number.isInteger(b.disagree) && b.disagree <= b.judged);
  const note = await waitText(page, '#note-map', /Boundaries: \d+ curves traced\./);
  if (b.disagree > 0) {
    assert.match(note, /outlined in yellow lie on the wrong side of a curve: the periodic branch is not what the gears do here/);
  }
  await clickACurve(page, s, '50-map-boundaries', '51-map-boundary-picked');
  assert.deepEqual(errors, []);
  await page.close();
});

// The compound set's default map (backlash 0 to 200 µm, mesh s1a1) with
// its boundaries on, and the shooting branches on as by default: the two
// long jobs run on different workers, so the trace (about a minute on its
// own) does not wait for the branches. A smaller bifurcation diagram and
// no Lyapunov curve keep the rest short.
test('the default map draws its traced boundaries and a click on one selects it', async () => {
  const { page, errors } = await open(h.browser, h.url, 'boundaries=on&bif_points=8&lyap_points=0');
  // The map's cells end long before its boundaries: the progress bar and
  // the status line stay until the trace ends.
  await waitStatus(page, (x) => x.map.finished_ms != null && !x.map_boundaries.finished, 900000, 'the cells done, the trace running');
  await waitText(page, '#progress-map-label', /^tracing the regime boundaries: \d+%$/);
  assert.ok(await page.isVisible('#progress-map'), 'the progress bar shows while the trace runs');
  assert.match(await page.textContent('#status'), /Computing/);
  const s = await boundariesDrawn(page, 900000, 'default map');
  await page.waitForFunction(() => document.getElementById('progress-map').hidden, null, { timeout: 60000 });
  const b = s.map_boundaries;
  assert.equal(b.job.error, null);
  assert.ok(b.shown >= 2, JSON.stringify(b));
  // Mesh s1a1's contact changes over backlash are among them.
  assert.ok(b.kinds['drive-flanks-part'] >= 1 || b.kinds['back-flanks-touch'] >= 1, JSON.stringify(b.kinds));
  await waitText(page, '#note-map', /Boundaries: \d+ curves traced\./);
  await clickACurve(page, s, '52-default-map-boundaries', '53-default-map-boundary-picked');
  assert.deepEqual(errors, []);
  await page.close();
});
