// Browser test of "a tour that never hides its target":
// at 390x844 (a touch phone), 1366x768 and 1920x1080, every step of the
// tour sets the state it talks about (the link says so) and its card
// covers neither the step's picture (a plot's whole canvas, the gear set's
// drawing, the Copy link button) nor what the step names (the control its
// action uses, the summary): their boxes on screen never overlap. The card
// is wholly on screen with its action, "Done" and Next; on the phone the
// tour opens the settings drawer for a step that uses a control and jumps
// to the control and back, the card never covering it. Step 5 shows
// "Done" once the link is copied. A screenshot of each step at each size
// goes to tests/browser/screenshots/.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import path from 'node:path';
import { start, open, waitStatus, SHOTS } from './harness.mjs';

const SIZES = [
  { name: 'phone-390x844', context: { viewport: { width: 390, height: 844 }, hasTouch: true, isMobile: true } },
  { name: '1366x768', context: { viewport: { width: 1366, height: 768 } } },
  { name: '1920x1080', context: { viewport: { width: 1920, height: 1080 } } },
];

const QUICK = 'bif_points=24&transient_periods=120&record_periods=40&map_omega_points=10&map_value_points=5&lyap_points=8&fr_points=60';

// Each step: what it sets (in the link), the element it highlights, what
// the card must leave in view (its picture first, as
// crates/app/src/tour.rs lists them), the control its action uses, and the
// job whose plot it points at (with the plot's slot in `last_draw_ms`).
// On the laptop and the wide screen the card leaves the highlighted
// element whole in view too (its caption and key); on the phone, whose
// docked card takes the screen's foot, its picture.
const STEPS = [
  { n: 1, sets: ['tour=1'], target: 'schematic', keep: ['schematic-svg', 'control-mesh'], control: 'control-mesh' },
  { n: 2, sets: ['backlash_um=150'], target: 'view-fr', keep: ['canvas-fr', 'control-backlash_um'], control: 'control-backlash_um', job: 'fr', slot: 0 },
  { n: 3, sets: ['backlash_um=20', 'omega=1.4&'], target: 'view-map', keep: ['canvas-map'], job: 'map', slot: 6 },
  // Back to the default backlash, 100 µm: the link leaves a default out.
  { n: 4, sets: ['omega=1.2&'], unset: 'backlash_um=', target: 'view-bif', keep: ['canvas-bif'], job: 'bif', slot: 1 },
  { n: 5, sets: ['tour=5'], target: 'copy-link', keep: ['copy-link', 'summary'] },
];

/** The boxes on screen (CSS px) of the card, its parts and `ids`. */
async function boxes(page, ids) {
  return page.evaluate((ids) => {
    const box = (e) => {
      if (!e) return null;
      const r = e.getBoundingClientRect();
      return r.width > 0 && r.height > 0 ? [r.left, r.top, r.right, r.bottom] : null;
    };
    const $ = (id) => document.getElementById(id);
    return {
      card: box($('tour')),
      next: box($('tour-next')),
      action: box($('tour-action')),
      done: $('tour-done').hidden ? null : box($('tour-done')),
      keep: Object.fromEntries(ids.map((id) => [id, box($(id))])),
      view: [window.innerWidth, window.innerHeight],
    };
  }, ids);
}

const overlap = (a, b) => Math.max(a[0], b[0]) < Math.min(a[2], b[2]) && Math.max(a[1], b[1]) < Math.min(a[3], b[3]);
const within = (r, [w, h]) => r[0] >= -0.5 && r[1] >= -0.5 && r[2] <= w + 0.5 && r[3] <= h + 0.5;
const showing = (r, [w, h]) => r[1] < h && r[3] > 0 && r[0] < w && r[2] > 0;
const round = (r) => r?.map(Math.round);

/** Two animation frames: the page's writes of the frame after an event are made. */
const frames = (page) => page.evaluate(() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r))));

/**
 * The card on screen with its action and Next (and "Done" if shown), over
 * none of `ids` that show; the first of `ids` shows. Returns the boxes.
 */
async function checkClear(page, ids, what) {
  const b = await boxes(page, ids);
  assert.ok(b.card && within(b.card, b.view), `${what}: card ${round(b.card)} not wholly on the ${b.view} screen`);
  for (const part of ['next', 'action', 'done']) {
    if (part === 'done' && !b.done) continue;
    assert.ok(b[part] && within(b[part], b.view), `${what}: ${part} ${round(b[part])} off the screen`);
  }
  const first = b.keep[ids[0]];
  assert.ok(first && showing(first, b.view), `${what}: ${ids[0]} ${round(first)} not on screen`);
  for (const id of ids) {
    const r = b.keep[id];
    if (!r || !showing(r, b.view)) continue;
    assert.ok(!overlap(b.card, r), `${what}: card ${round(b.card)} over ${id} ${round(r)}`);
  }
  return b;
}

for (const size of SIZES) {
  test(`at ${size.name} every tour step sets its state and its card covers neither its picture nor what it names`, async () => {
    const h = await start(size.context);
    const phone = size.name.startsWith('phone');
    try {
      await h.browser.grantPermissions(['clipboard-read', 'clipboard-write'], { origin: new URL(h.url).origin });
      const { page, errors } = await open(h.browser, h.url, QUICK);
      await waitStatus(page, (s) => s.workers_ready > 0, 60000, 'workers');
      await page.click('#tour-start');
      for (const step of STEPS) {
        if (step.n > 1) await page.click('#tour-next');
        await page.waitForFunction((n) => document.getElementById('tour')?.dataset.step === String(n), step.n);
        const s = await waitStatus(
          page,
          (x) => step.sets.every((kv) => `${x.query}&`.includes(kv)) && !(step.unset && x.query.includes(step.unset))
            && x.query.includes(`tour=${step.n}`)
            && (!step.job || x[step.job].finished_ms != null),
          240000,
          `step ${step.n}: its state computed`,
        );
        // The page moves the card in the frame after a drawing: wait until
        // the plot was drawn after its job ended, then one more frame.
        if (step.job) {
          await waitStatus(page, (x) => x.last_draw_ms[step.slot] >= x[step.job].finished_ms, 60000, 'the view drawn');
        }
        await frames(page);
        await page.screenshot({ path: path.join(SHOTS, `tour-${size.name}-step-${step.n}.png`) });
        await checkClear(page, phone ? step.keep : [...step.keep, step.target], `step ${step.n}`);
        assert.ok(s.tour.step === step.n - 1);
        if (step.control) {
          // The drawer is open: the control has a box.
          assert.ok(await page.evaluate(() => document.getElementById('drawer').open), `step ${step.n}: drawer closed`);
          if (phone) {
            // The card jumps to the control and back, never over it.
            await page.click('#tour-control');
            await frames(page);
            await page.screenshot({ path: path.join(SHOTS, `tour-${size.name}-step-${step.n}-control.png`) });
            await checkClear(page, [step.control], `step ${step.n}, at its control`);
            await page.click('#tour-plot');
            await frames(page);
            await checkClear(page, step.keep, `step ${step.n}, back`);
          }
        }
      }
      // Step 5 is done by copying the link: "Done" shows, on screen.
      await page.click('#copy-link');
      await page.waitForFunction(() => document.getElementById('tour').dataset.done === 'true', null, { timeout: 60000 });
      await frames(page);
      const b = await checkClear(page, phone ? STEPS[4].keep : [...STEPS[4].keep, 'views'], 'step 5, done');
      assert.ok(b.done, 'step 5: "Done" hidden');
      await page.screenshot({ path: path.join(SHOTS, `tour-${size.name}-step-5-done.png`) });
      await page.click('#tour-next');
      await page.waitForFunction(() => document.getElementById('tour').hidden, null, { timeout: 60000 });
      assert.deepEqual(errors, []);
    } finally {
      await h.close();
    }
  });
}
