// Browser tests of present mode: one view on the whole screen for a
// projector. A link opens straight into it; the view is drawn again for
// the screen (the canvas has the stage's device pixels, the drawing at
// most 900 pixels wide, so the words grow with the screen); the keys move
// through the views, step Ω and leave; the link carries the mode; axe-core
// finds no violation; and it works on a phone. Every wait is for a state
// the page reports, never a time. Screenshots: present-*.png.
import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import path from 'node:path';
import { start, open, status, waitStatus, waitText, canvasStats, shot, ROOT } from './harness.mjs';

const QUICK = 'bif_points=16&transient_periods=120&record_periods=40&map_omega_points=8&map_value_points=4&lyap_points=8';

/** The stage's box (CSS pixels) and its canvas's pixels. */
const stage = (page) =>
  page.evaluate(() => {
    const c = document.getElementById('canvas-present');
    const r = c.getBoundingClientRect();
    return { css: [r.width, r.height], px: [c.width, c.height], top: r.top, bottom: r.bottom, vh: innerHeight, vw: innerWidth };
  });

const search = (page) => page.evaluate(() => location.search);

let h;
before(async () => {
  h = await start({ viewport: { width: 1920, height: 1080 } });
});
after(async () => {
  await h?.close();
});

test('a link opens a view on the whole projector screen, drawn for it, and the keys move, step Ω and leave', async () => {
  const { page, errors } = await open(h.browser, h.url, `${QUICK}&present=fr`);
  let s = await waitStatus(page, (x) => x.fr.finished_ms && x.present.draws > 0 && x.omega_job.finished_ms, 120000, 'the frequency response presented');
  assert.equal(s.present.shown, 'fr');
  assert.deepEqual(s.issues, []);
  assert.equal(await page.isVisible('#present'), true);
  assert.equal(await page.isVisible('header'), false, 'the rest of the page is out of the way');
  await waitText(page, '#present-title', /^1\. Frequency response$/);
  await waitText(page, '#present-omega', /^Ω = \d\.\d{3}$/);
  await waitText(page, '#present-caption', /\w+.*\.$/);
  // Drawn for the screen: the canvas has every pixel of the stage, the
  // plot a drawing of 900 pixels scaled up by the context (sharp words
  // of 13 × 1920/900 ≈ 28 pixels).
  s = await waitStatus(page, (x) => x.present.canvas && x.text_boxes.fr.size[0] === 900, 60000, 'the presented drawing');
  const st = await stage(page);
  assert.deepEqual(st.px, st.css.map(Math.round), JSON.stringify(st));
  assert.deepEqual(s.present.canvas, st.px);
  assert.equal(s.present.drawing[0], 900);
  assert.ok(st.css[1] > 0.7 * st.vh, `the plot fills the screen: ${JSON.stringify(st)}`);
  assert.ok(st.bottom <= st.vh, 'the stage ends on the screen');
  const ink = await canvasStats(page, 'canvas-present');
  assert.ok(ink.ink > 0.02 * ink.total, `drawn: ${JSON.stringify(ink)}`);
  assert.match(await page.getAttribute('#canvas-present', 'aria-label'), /frequency response/i);
  assert.match(await search(page), /present=fr/);
  await shot(page, 'present-1920x1080-fr');
  // axe-core on the presented page.
  await page.addScriptTag({ path: path.join(ROOT, 'node_modules/axe-core/axe.min.js') });
  const violations = await page.evaluate(async () => {
    const r = await window.axe.run(document);
    return r.violations.map((v) => `${v.id}: ${v.nodes.length} (${v.nodes.slice(0, 3).map((n) => n.target.join(' ')).join(', ')})`);
  });
  assert.deepEqual(violations, []);
  // n: the next view in page order, in the link too.
  const draws = s.present.draws;
  await page.keyboard.press('n');
  s = await waitStatus(page, (x) => x.present.shown === 'map' && x.present.draws > draws, 60000, 'the map presented');
  await waitText(page, '#present-title', /^2\. Impact-regime map$/);
  assert.match(await search(page), /present=map/);
  // The right arrow steps Ω, as on the page's plots.
  const omega = s.omega;
  await page.keyboard.press('ArrowRight');
  s = await waitStatus(page, (x) => x.omega > omega, 60000, 'a higher Ω');
  await waitText(page, '#present-omega', new RegExp(`^Ω = ${s.omega.toFixed(3)}$`));
  // p twice: back past the first view to the last (the mesh force by
  // order), then to the dynamic factor, the Campbell diagram and the
  // spectrum.
  await page.keyboard.press('p');
  await page.keyboard.press('p');
  await waitStatus(page, (x) => x.present.shown === 'orders', 60000, 'the mesh force by order presented');
  await waitText(page, '#present-title', /^12\. Mesh force by order$/);
  await page.keyboard.press('p');
  await waitStatus(page, (x) => x.present.shown === 'dynamic', 60000, 'the dynamic factor presented');
  await waitText(page, '#present-title', /^11\. Dynamic factor$/);
  await page.keyboard.press('p');
  await waitStatus(page, (x) => x.present.shown === 'campbell', 60000, 'the Campbell diagram presented');
  await waitText(page, '#present-title', /^10\. Campbell diagram$/);
  await page.keyboard.press('p');
  await waitStatus(page, (x) => x.present.shown === 'spectrum', 60000, 'the spectrum presented');
  await waitText(page, '#present-title', /^9\. Spectrum$/);
  // Escape leaves: the page is back, the link without the mode, the
  // focus on the button that presents the view.
  await page.keyboard.press('Escape');
  await waitStatus(page, (x) => x.present.shown === null, 60000, 'present mode left');
  assert.equal(await page.isVisible('#present'), false);
  assert.equal(await page.isVisible('header'), true);
  assert.doesNotMatch(await search(page), /present=/);
  assert.equal(await page.evaluate(() => document.activeElement?.id), 'present-spectrum');
  // The page's canvas is drawn at the page's size again.
  const back = await waitStatus(page, (x) => x.text_boxes.spectrum.size[0] !== 900, 60000, 'the spectrum drawn on the page');
  assert.equal(back.text_boxes.spectrum.size[0], await page.$eval('#canvas-spectrum', (c) => c.width));
  assert.deepEqual(errors, []);
  await page.close();
});

test('at 1366 x 768 a view presented from its button fills the screen, and its way out is visible', async () => {
  const small = await start({ viewport: { width: 1366, height: 768 } });
  try {
    const { page, errors } = await open(small.browser, small.url, `${QUICK}&omega=0.84`);
    await waitStatus(page, (x) => x.omega_job.finished_ms && x.draws[2] > 0, 120000, 'the phase portrait drawn');
    await page.click('#present-phase');
    const s = await waitStatus(page, (x) => x.present.shown === 'phase' && x.present.draws > 0, 60000, 'the phase portrait presented');
    assert.equal(await page.evaluate(() => document.activeElement?.id), 'present-leave');
    await waitText(page, '#present-title', /^5\. Phase portrait$/);
    await waitText(page, '#present-omega', /^Ω = 0\.840$/);
    const st = await stage(page);
    assert.deepEqual(s.present.canvas, st.px);
    assert.ok(s.present.drawing[0] < st.px[0], `scaled up: ${JSON.stringify(s.present)}`);
    assert.ok(await page.isVisible('#present-leave'));
    const leave = await page.$eval('#present-leave', (b) => b.getBoundingClientRect().bottom);
    assert.ok(leave <= st.vh, 'the way out is on the screen');
    await shot(page, 'present-1366x768-phase');
    await page.click('#present-next');
    await waitStatus(page, (x) => x.present.shown === 'poincare', 60000, 'the Poincaré section presented');
    await page.click('#present-leave');
    await waitStatus(page, (x) => x.present.shown === null, 60000, 'present mode left');
    assert.deepEqual(errors, []);
    await page.close();
  } finally {
    await small.close();
  }
});

test('on a phone the gear set in motion is presented from a link and left by its button', async () => {
  const phone = await start({ viewport: { width: 390, height: 844 }, hasTouch: true, isMobile: true });
  try {
    const { page, errors } = await open(phone.browser, phone.url, `${QUICK}&present=anim`);
    const s0 = await waitStatus(page, (x) => x.anim && x.anim.frames >= 1 && x.present.draws > 0, 120000, 'the gear set presented');
    assert.equal(s0.present.shown, 'anim');
    await waitText(page, '#present-title', /^8\. The gear set in motion$/);
    // It runs: the stage is drawn again as the animation plays.
    await waitStatus(page, (x) => x.present.draws > s0.present.draws + 2, 60000, 'the animation running on the stage');
    const st = await stage(page);
    assert.ok(st.css[0] > 340 && st.css[1] > 300, JSON.stringify(st));
    const ink = await canvasStats(page, 'canvas-present');
    assert.ok(ink.ink > 0.05 * ink.total, `drawn: ${JSON.stringify(ink)}`);
    for (const id of ['present-leave', 'present-next', 'present-back', 'present-omega-up']) {
      const r = await page.$eval(`#${id}`, (b) => { const q = b.getBoundingClientRect(); return [q.width, q.height, q.bottom]; });
      assert.ok(r[0] >= 24 && r[1] >= 24 && r[2] <= 844, `${id}: ${r}`);
    }
    await shot(page, 'present-phone-390x844-anim');
    await page.tap('#present-omega-up');
    await waitStatus(page, (x) => x.omega > s0.omega, 60000, 'a higher Ω');
    await page.tap('#present-leave');
    await waitStatus(page, (x) => x.present.shown === null, 60000, 'present mode left');
    assert.equal(await page.isVisible('header'), true);
    assert.deepEqual(errors, []);
    await page.close();
  } finally {
    await phone.close();
  }
});
