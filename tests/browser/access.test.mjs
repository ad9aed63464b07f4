// Browser tests of the page on phones and for every reader: touch (a
// vertical swipe on a plot scrolls and never selects, a tap selects, a
// sideways drag scrubs, and the jump to the motion), every export button
// of every view gives its file, reduced motion starts the animation
// paused, and axe-core finds no accessibility violation. Every wait is
// for a state the page reports (its status, an attribute), never a time.
import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import fs from 'node:fs';
import path from 'node:path';
import { start, open, status, waitStatus, recordOffers, ROOT } from './harness.mjs';

const QUICK = 'bif_points=16&transient_periods=120&record_periods=40&map_omega_points=8&map_value_points=4&lyap_points=8';
const allDone = (s) => ['fr', 'bif', 'map', 'lyap', 'omega_job'].every((k) => s[k].finished_ms);

let h;
before(async () => {
  h = await start();
});
after(async () => {
  await h?.close();
});

/** The centre of the frequency response's plotting area, in page CSS pixels. */
async function plotPoint(page, fx) {
  return page.evaluate((fx) => {
    const c = document.getElementById('canvas-fr');
    const r = c.getBoundingClientRect();
    const f = JSON.parse(window.gearshockStatus()).fr_frame;
    const sx = r.width / c.width;
    const x = r.left + (f[0] + fx * (f[2] - f[0])) * sx;
    const y = r.top + ((f[1] + f[3]) / 2) * (r.height / c.height);
    return { x, y };
  }, fx);
}

test('on a phone a swipe over a plot scrolls and never selects; a tap selects, a drag scrubs, and a jump leads to the motion', async () => {
  const phone = await start({ viewport: { width: 390, height: 844 }, hasTouch: true, isMobile: true });
  try {
    const page = await phone.browser.newPage();
    const errors = [];
    page.on('pageerror', (e) => errors.push(String(e)));
    await page.goto(`${phone.url}?${QUICK}`);
    await page.waitForFunction(() => typeof window.gearshockStatus === 'function');
    await waitStatus(page, (s) => s.fr_frame && s.bif_frame && s.fr.finished_ms, 120000, 'the frequency response drawn');
    await page.locator('#canvas-fr').scrollIntoViewIfNeeded();
    const s0 = await status(page);
    const omega0 = s0.omega;
    // A real touch swipe upwards that starts on the plot: the browser
    // scrolls the page and cancels the pointer.
    const cdp = await page.context().newCDPSession(page);
    const touch = (type, x, y) => cdp.send('Input.dispatchTouchEvent', {
      type, touchPoints: type === 'touchEnd' ? [] : [{ x: Math.round(x), y: Math.round(y) }],
    });
    const p = await plotPoint(page, 0.2);
    const y0 = await page.evaluate(() => window.scrollY);
    await touch('touchStart', p.x, p.y);
    for (let k = 1; k <= 10; k++) await touch('touchMove', p.x + k, p.y - 25 * k);
    await touch('touchEnd', p.x + 10, p.y - 250);
    const s1 = await waitStatus(page, (s) => s.gesture.n > s0.gesture.n, 30000, 'the swipe to end');
    assert.ok(['scroll', 'cancel'].includes(s1.gesture.last), JSON.stringify(s1.gesture));
    assert.ok((await page.evaluate(() => window.scrollY)) > y0, 'the page scrolled');
    // The selection is the one before the swipe (a selection would be applied in the frame after it).
    await page.evaluate(() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r))));
    assert.equal((await status(page)).omega, omega0, 'a swipe changed the selected Ω');
    // A tap selects where it lands.
    await page.locator('#canvas-fr').scrollIntoViewIfNeeded();
    const t = await plotPoint(page, 0.25);
    await page.touchscreen.tap(t.x, t.y);
    const s2 = await waitStatus(page, (s) => s.omega !== omega0, 30000, 'the tap to select');
    assert.equal(s2.gesture.last, 'tap');
    // The bifurcation diagram shares the frequency response's Ω range.
    const range = [s2.bif_frame[4], s2.bif_frame[5]];
    assert.ok(Math.abs(s2.omega - (range[0] + 0.25 * (range[1] - range[0]))) < 0.05, `tap at a quarter picked ${s2.omega}`);
    // A drag sideways scrubs: the selection follows the finger.
    const a = await plotPoint(page, 0.3);
    const b = await plotPoint(page, 0.7);
    await touch('touchStart', a.x, a.y);
    for (let k = 1; k <= 8; k++) await touch('touchMove', a.x + ((b.x - a.x) * k) / 8, a.y);
    await touch('touchEnd', b.x, a.y);
    const s3 = await waitStatus(page, (s) => s.gesture.n > s2.gesture.n, 30000, 'the drag to end');
    assert.equal(s3.gesture.last, 'scrub');
    const s4 = await waitStatus(page, (s) => s.omega > s2.omega + 0.3, 30000, 'the scrub to move Ω');
    // On a phone the selection offers a jump to the motion, one tap away.
    assert.equal(s4.see_orbit, true);
    const jump = page.locator('#see-orbit');
    await jump.waitFor({ state: 'visible', timeout: 60000 });
    assert.match(await jump.textContent(), /See the motion at Ω = \d/);
    // A click, not a touch tap: the button acts on click, and the click a
    // tap makes is the browser's guess from the touch's duration, which a
    // busy machine stretches into a long press (CI once waited 10 s for a
    // click that never came). The taps above, on the plots, are pointer
    // events the page reads itself.
    await jump.click();
    await jump.waitFor({ state: 'hidden', timeout: 60000 });
    await page.waitForFunction(() => {
      const r = document.getElementById('view-phase').getBoundingClientRect();
      return r.top < window.innerHeight && r.bottom > 0;
    });
    assert.deepEqual(errors, []);
    await page.close();
  } finally {
    await phone.close();
  }
});

test('on a phone every button, field, drop-down, slider and disclosure is at least 24 px square', async () => {
  const phone = await start({ viewport: { width: 390, height: 844 }, hasTouch: true, isMobile: true });
  try {
    const { page, errors } = await open(phone.browser, phone.url, QUICK);
    await waitStatus(page, (s) => s.workers_ready > 0, 60000, 'workers');
    // The drawer open and every disclosure open, so every control shows.
    await page.evaluate(() => document.querySelectorAll('details').forEach((d) => { d.open = true; }));
    const small = await page.evaluate(() => {
      const controls = [...document.querySelectorAll('button, select, input, summary, [tabindex="0"]')];
      return controls
        .filter((e) => e.offsetParent !== null || e.tagName === 'SUMMARY')
        .map((e) => {
          const r = e.getBoundingClientRect();
          return { what: `${e.tagName.toLowerCase()}#${e.id || e.textContent.trim().slice(0, 30)}`, w: r.width, h: r.height };
        })
        .filter((c) => c.w > 0 && c.h > 0 && (c.w < 23.5 || c.h < 23.5));
    });
    const total = await page.evaluate(() => document.querySelectorAll('button, select, input, summary').length);
    assert.ok(total > 100, `${total} controls`);
    assert.deepEqual(small.map((c) => `${c.what} ${Math.round(c.w)}x${Math.round(c.h)}`), []);
    assert.deepEqual(errors, []);
  } finally {
    await phone.close();
  }
});

test('printed, the page shows the settings and the plots, not the buttons', async () => {
  const { page, errors } = await open(h.browser, h.url, `${QUICK}&backlash_um=60`);
  await waitStatus(page, allDone, 120000, 'all jobs');
  await page.emulateMedia({ media: 'print' });
  for (const id of ['copy-link', 'tour-start', 'reset', 'family-apply']) {
    assert.equal(await page.isVisible(`#${id}`), false, `${id} prints`);
  }
  assert.equal(await page.locator('#exports-fr button').first().isVisible(), false, 'export buttons print');
  // The settings print as their values.
  assert.equal(await page.isVisible('#num-backlash_um'), true);
  assert.equal(await page.inputValue('#num-backlash_um'), '60');
  assert.equal(await page.isVisible('#slider-backlash_um'), false);
  for (const v of ['fr', 'map', 'bif', 'phase']) assert.equal(await page.isVisible(`#canvas-${v}`), true, v);
  await page.screenshot({ path: path.join(ROOT, 'tests/browser/screenshots/print-1500.png'), fullPage: false });
  await page.emulateMedia({ media: 'screen' });
  assert.deepEqual(errors, []);
  await page.close();
});

test('every export button of every view gives its file', async () => {
  const { page, errors } = await open(h.browser, h.url, QUICK);
  await waitStatus(page, allDone, 120000, 'all jobs');
  const bars = await page.$$eval('[id^="exports-"]', (xs) => xs.map((x) => x.id));
  // Every view but the gear set's animation.
  assert.equal(bars.length, 11, bars.join());
  // Each file the page offers is recorded as it is offered (the anchor with
  // a download name it clicks), and read back from its object URL. Chromium
  // may hold back a download that arrives without a fresh user gesture (a
  // PNG encoded asynchronously, a command-line JSON the worker answers
  // late), which is the browser's policy, not the page's: the first export
  // is also checked as a real download.
  await recordOffers(page);
  let n = 0;
  const pngWidth = {};
  for (const bar of bars) {
    const labels = await page.$$eval(`#${bar} button`, (bs) => bs.map((b) => b.textContent));
    assert.ok(labels.length >= 4, `${bar}: ${labels}`);
    for (const [i, label] of labels.entries()) {
      // The file, or the message the page gives instead (then the test says which).
      const issues = (await status(page)).issues.length;
      const offered = await page.evaluate(() => window.offers.length);
      const real = n === 0 ? page.waitForEvent('download', { timeout: 120000 }) : null;
      await page.locator(`#${bar} button`).nth(i).click();
      const issuesNow = () => JSON.parse(window.gearshockStatus()).issues.length;
      await page
        .waitForFunction(
          ([k, m]) => window.offers.length > k || JSON.parse(window.gearshockStatus()).issues.length > m,
          [offered, issues],
          { timeout: 120000, polling: 100 },
        )
        .catch((e) => {
          throw new Error(`${bar} ${label}: ${e.message}`);
        });
      const after = await page.evaluate(issuesNow);
      const st = await status(page);
      assert.ok(after === issues, `${bar} ${label}: no file but ${JSON.stringify(st.issues)}`);
      const offer = await page.evaluate(async (k) => {
        const o = window.offers[k];
        const bytes = new Uint8Array(await (await fetch(o.href)).arrayBuffer());
        return { name: o.name, length: bytes.length, head: Array.from(bytes.subarray(0, 24)) };
      }, offered);
      const name = offer.name;
      const head = Buffer.from(offer.head);
      if (real) {
        const dl = await real;
        assert.equal(dl.suggestedFilename(), name, 'the real download is the offered file');
        assert.equal(fs.readFileSync(await dl.path()).length, offer.length);
      }
      const ext = { PNG: '.png', SVG: '.svg', CSV: '.csv', JSON: '.json', 'CLI JSON': '.json' }[label];
      assert.ok(name.endsWith(ext), `${bar} ${label}: ${name}`);
      assert.ok(offer.length > 100, `${bar} ${label}: ${offer.length} bytes`);
      if (label === 'PNG') {
        assert.equal(head.subarray(1, 4).toString(), 'PNG', `${bar}: not a PNG`);
        pngWidth[bar] = head.readUInt32BE(16);
      }
      if (label === 'SVG') {
        // The PNG is this picture at twice its size (the view's own size,
        // the same on every screen: a wide screen draws the frequency
        // response wider on the page, not in the files).
        const svgWidth = await page.evaluate(async (k) => {
          const t = await (await fetch(window.offers[k].href)).text();
          return Number(/<svg[^>]*\swidth="(\d+)"/.exec(t)?.[1]);
        }, offered);
        assert.equal(pngWidth[bar], 2 * svgWidth, `${bar}: PNG width`);
      }
      n++;
    }
  }
  // Four per view, and the command-line JSON of the sweep and of the five
  // views of the motion (the four and the mesh force by order).
  assert.equal(n, 11 * 4 + 6, `${n} exports`);
  assert.deepEqual(errors, []);
  await page.close();
});

test('reduced motion starts the gear set paused', async () => {
  const still = await start({ reducedMotion: 'reduce' });
  try {
    const { page, errors } = await open(still.browser, still.url, QUICK);
    const s = await waitStatus(page, (x) => x.anim && x.anim.frames >= 1, 120000, 'the gear set drawn');
    assert.equal(s.anim.playing, false);
    assert.equal(await page.textContent('#anim-play'), 'Play');
    await page.click('#anim-play');
    await waitStatus(page, (x) => x.anim.playing === true, 60000, 'Play to start it');
    assert.deepEqual(errors, []);
    await page.close();
  } finally {
    await still.close();
  }
});

test('axe-core finds no accessibility violation', async () => {
  const { page, errors } = await open(h.browser, h.url, QUICK);
  await waitStatus(page, allDone, 120000, 'all jobs');
  await page.addScriptTag({ path: path.join(ROOT, 'node_modules/axe-core/axe.min.js') });
  const violations = await page.evaluate(async () => {
    const r = await window.axe.run(document);
    return r.violations.map((v) => `${v.id}: ${v.nodes.length} (${v.nodes.slice(0, 3).map((n) => n.target.join(' ')).join(', ')})`);
  });
  assert.deepEqual(violations, []);
  // The plots' keyboard selection is announced and visible.
  for (const k of ['fr', 'bif', 'lyap']) {
    const hint = await page.$eval(`#canvas-${k}`, (c) => document.getElementById(c.getAttribute('aria-describedby'))?.textContent ?? '');
    assert.match(hint, /arrow keys/);
  }
  assert.deepEqual(errors, []);
  await page.close();
});
