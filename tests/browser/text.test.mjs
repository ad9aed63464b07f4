// Browser test of "text that fits": every plot reports the boxes
// of the text it drew (titles, tick labels, axis descriptions, the key) in
// the page's status (`text_boxes`, measured by the canvas's measureText).
// At 390x844 (a touch phone), 1366x768 and 1920x1080, on the default page,
// on the Fig. 9 preset (small multiples with panel titles) and at a load
// of 900 000 N m (tick labels like "-100000.0"), no two
// boxes of one canvas overlap and none leaves its canvas. Screenshots of
// the plots go to tests/browser/screenshots/ for a human to look at.
import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import path from 'node:path';
import { start, open, status, nextStatus, SHOTS } from './harness.mjs';

const SIZES = [
  { name: 'phone-390x844', context: { viewport: { width: 390, height: 844 }, hasTouch: true, isMobile: true } },
  { name: '1366x768', context: { viewport: { width: 1366, height: 768 } } },
  { name: '1920x1080', context: { viewport: { width: 1920, height: 1080 } } },
];

// The job each view draws (its slot in `last_draw_ms` is its place here).
const VIEW_JOBS = [
  ['fr', 'fr'],
  ['bif', 'bif'],
  ['phase', 'omega_job'],
  ['poincare', 'omega_job'],
  ['time', 'omega_job'],
  ['spectrum', 'omega_job'],
  ['map', 'map'],
  ['lyap', 'lyap'],
];

/**
 * Whether the jobs of `views` have ended (finished or failed), the family
 * members' too, and each of those views was drawn after its job's end.
 */
function settled(s, views = VIEW_JOBS.map(([v]) => v)) {
  const ended = (j) => !j || j.id === 0 || j.finished_ms != null || j.error != null;
  const rows = VIEW_JOBS.map((row, slot) => [...row, slot]).filter(([v]) => views.includes(v));
  if (rows.some(([, job]) => !ended(s[job]))) return false;
  if (rows.some(([, job]) => job === 'omega_job') && s.omega_result?.preview) return false;
  const members = s.family?.members ?? [];
  return rows.every(([, job, slot]) => {
    const own = members.map((m) => m[job]).filter(Boolean);
    if (!own.every(ended)) return false;
    const end = Math.max(s[job].finished_ms ?? 0, ...own.map((j) => j.finished_ms ?? 0));
    return s[job].id === 0 || (s.last_draw_ms[slot] ?? 0) >= end;
  });
}

/**
 * Waits for `pred` as `waitStatus` does, checking the text boxes of every
 * status read on the way (captions while computing included); returns the
 * last status and the faults seen.
 */
async function watch(page, pred, what, seen) {
  const t0 = Date.now();
  let s = await status(page);
  for (;;) {
    for (const f of faults(s)) seen.add(f);
    if (pred(s)) return s;
    const left = 300000 - (Date.now() - t0);
    // The next status is read at the page's next change of state.
    const next = left > 0 ? await nextStatus(page, s, left) : null;
    if (next === null) {
      const open = VIEW_JOBS.filter(([v]) => !settled(s, [v])).map(([v]) => v);
      throw new Error(`timed out waiting for ${what}; not settled: ${open}`);
    }
    s = next;
  }
}

/** Every overlap and every box outside its canvas, as readable lines. */
function faults(s) {
  const out = [];
  for (const [view, { size, boxes }] of Object.entries(s.text_boxes)) {
    const [w, h] = size;
    if (!w || !h) continue;
    for (const b of boxes) {
      const [l, t, r, bo] = b.edges;
      if (l < 0 || t < 0 || r > w || bo > h) out.push(`${view}: "${b.text}" [${b.edges}] leaves the ${w}x${h} canvas`);
    }
    for (let i = 0; i < boxes.length; i++) {
      for (let j = i + 1; j < boxes.length; j++) {
        const [a, b] = [boxes[i].edges, boxes[j].edges];
        if (Math.max(a[0], b[0]) < Math.min(a[2], b[2]) && Math.max(a[1], b[1]) < Math.min(a[3], b[3])) {
          out.push(`${view}: "${boxes[i].text}" [${a}] overlaps "${boxes[j].text}" [${b}]`);
        }
      }
    }
  }
  return out;
}

/** A screenshot of one view's figure (its heading, plot and exports). */
async function viewShot(page, view, name) {
  const fig = page.locator(`#view-${view}`);
  await fig.scrollIntoViewIfNeeded();
  await fig.screenshot({ path: path.join(SHOTS, `${name}.png`) });
}

// Smaller grids than the defaults (the layout of text does not depend on
// them): the three sizes' runs fit the suite's time on a shared machine.
const QUICK = 'bif_points=24&transient_periods=120&record_periods=40&map_omega_points=10&map_value_points=5&lyap_points=8&fr_points=60';
const FIG9_VIEWS = ['phase', 'poincare', 'time', 'spectrum'];

for (const size of SIZES) {
  test(`at ${size.name} no plot's text overlaps other text or leaves its canvas (default page, Fig. 9, 900 000 N m)`, async () => {
    const h = await start(size.context);
    try {
      const { page, errors } = await open(h.browser, h.url, QUICK);
      const seen = new Set();
      const s = await watch(page, (x) => settled(x), 'every view computed and drawn', seen);
      // Every view drew text: the boxes are reported, not merely absent.
      for (const [v, job] of VIEW_JOBS) {
        if (s[job].id !== 0) assert.ok(s.text_boxes[v].boxes.length > 3, `${v}: ${JSON.stringify(s.text_boxes[v])}`);
      }
      for (const v of ['fr', 'bif', 'poincare']) await viewShot(page, v, `text-${size.name}-${v}`);
      // The frequency response uses the width of its screen and its key
      // leaves the data room.
      const fr = await page.evaluate(() => {
        const c = document.getElementById('canvas-fr');
        const r = c.getBoundingClientRect();
        return { css: [r.width, r.height], drawn: [c.width, c.height] };
      });
      const frame = (await status(page)).fr_frame;
      const dataCssHeight = ((frame[3] - frame[1]) * fr.css[1]) / fr.drawn[1];
      if (!size.name.startsWith('phone')) {
        const main = await page.evaluate(() => document.querySelector('main').getBoundingClientRect().width);
        assert.ok(fr.css[0] >= main - 40, `the frequency response ${fr.css.map(Math.round)} in a ${Math.round(main)} px column`);
        // At 1920 its key under the chart left it 170 px of data when drawn
        // in one of two columns; across both, drawn wider, about 400.
        const least = size.name === '1920x1080' ? 350 : 200;
        assert.ok(dataCssHeight >= least, `the frequency response's data ${Math.round(dataCssHeight)} px high`);
      }
      await page.selectOption('#preset', 'fig9');
      await watch(page, (x) => x.family?.values?.length === 3 && x.family.members.length === 2 && settled(x, FIG9_VIEWS), 'the Fig. 9 orbits drawn', seen);
      await viewShot(page, 'phase', `text-${size.name}-fig9-phase`);
      // A load far outside the model's validity: ticks like "-100000.0"
      // are whole and clear of the axis descriptions.
      const big = await open(h.browser, h.url, `${QUICK}&torque_s1_nm=900000`);
      await watch(big.page, (x) => settled(x), 'the 900 000 N m views computed and drawn', seen);
      for (const v of ['fr', 'time']) await viewShot(big.page, v, `text-${size.name}-900000-${v}`);
      errors.push(...big.errors);
      const found = [...seen];
      assert.deepEqual(found, [], `text boxes that overlap or leave their canvas at ${size.name}:\n${found.join('\n')}`);
      assert.deepEqual(errors, []);
    } finally {
      await h.close();
    }
  });
}
