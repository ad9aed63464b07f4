// Browser test of "a tour that shows": each step sets the state
// it talks about (the backlash moved, an Ω selected: the link says so) and
// its card sits beside the plot it points at, never over that plot's data
// area (the plot frame the page reports, scaled to the canvas on screen),
// at 390x844 (a touch phone), 1366x768 and 1920x1080. A screenshot of each
// step at each size goes to tests/browser/screenshots/.
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

// The steps that point at a plot: what each must set (in the link) and
// the plot's canvas, status frame and job.
const STEPS = [
  { n: 2, sets: ['backlash_um=150'], canvas: 'canvas-fr', frame: 'fr_frame', job: 'fr' },
  { n: 3, sets: ['backlash_um=20', 'omega=1.4&'], canvas: 'canvas-map', frame: 'map_frame', job: 'map' },
  // Back to the default backlash, 100 µm: the link leaves a default out.
  { n: 4, sets: ['omega=1.2&'], unset: 'backlash_um=', canvas: 'canvas-bif', frame: 'bif_frame', job: 'bif' },
];

/** The card's box and the plot's data area on screen (CSS px). */
async function boxes(page, canvasId, frame) {
  return page.evaluate(({ canvasId, frame }) => {
    const card = document.getElementById('tour').getBoundingClientRect();
    const c = document.getElementById(canvasId);
    const r = c.getBoundingClientRect();
    const [l, t, rr, b] = frame;
    const sx = r.width / c.width;
    const sy = r.height / c.height;
    return {
      card: [card.left, card.top, card.right, card.bottom],
      data: [r.left + l * sx, r.top + t * sy, r.left + rr * sx, r.top + b * sy],
    };
  }, { canvasId, frame });
}

const overlap = (a, b) => Math.max(a[0], b[0]) < Math.min(a[2], b[2]) && Math.max(a[1], b[1]) < Math.min(a[3], b[3]);

for (const size of SIZES) {
  test(`at ${size.name} each tour step sets its state and its card sits beside the plot's data, never over it`, async () => {
    const h = await start(size.context);
    try {
      const { page, errors } = await open(h.browser, h.url, QUICK);
      await waitStatus(page, (s) => s.workers_ready > 0, 60000, 'workers');
      await page.click('#tour-start');
      for (const step of STEPS) {
        await page.click('#tour-next');
        await page.waitForFunction((n) => document.getElementById('tour')?.dataset.step === String(n), step.n);
        const s = await waitStatus(
          page,
          (x) => step.sets.every((kv) => `${x.query}&`.includes(kv)) && !(step.unset && x.query.includes(step.unset))
            && x.query.includes(`tour=${step.n}`)
            && x[step.job].finished_ms != null && x[step.frame],
          240000,
          `step ${step.n}: its state computed`,
        );
        // The page places the card in the frame after a drawing: wait until
        // the view was drawn after its job ended, then one more frame.
        const slot = { fr: 0, bif: 1, map: 6 }[step.job];
        const s2 = await waitStatus(page, (x) => x.last_draw_ms[slot] >= x[step.job].finished_ms, 60000, 'the view drawn');
        await page.evaluate(() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r))));
        const b = await boxes(page, step.canvas, s2[step.frame] ?? s[step.frame]);
        await page.screenshot({ path: path.join(SHOTS, `tour-${size.name}-step-${step.n}.png`) });
        assert.ok(!overlap(b.card, b.data), `step ${step.n}: card ${b.card.map(Math.round)} over data ${b.data.map(Math.round)}`);
        // The card is on screen, and so is some of the data.
        const vh = size.context.viewport.height;
        assert.ok(b.card[1] < vh && b.card[3] > 0, `step ${step.n}: card ${b.card.map(Math.round)} off screen`);
        assert.ok(b.data[1] < vh && b.data[3] > 0, `step ${step.n}: data ${b.data.map(Math.round)} off screen`);
      }
      assert.deepEqual(errors, []);
    } finally {
      await h.close();
    }
  });
}
