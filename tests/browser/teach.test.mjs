// Browser tests of "a page that teaches": the truth by default
// (time-integration dots on the frequency response with no setting
// changed), plain words, phones, text alternatives of the canvases and the
// Copy link confirmation. Screenshots at 1366x768, 1920x1080 and 390x844
// go to tests/browser/screenshots/ for a human to look at.
import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import fs from 'node:fs';
import path from 'node:path';
import { start, open, status, waitStatus, shot, canvasStats, SHOTS } from './harness.mjs';

/** A screenshot of what the window shows (not the whole page). */
const screen = (page, name) => page.screenshot({ path: path.join(SHOTS, `${name}.png`) });

const QUICK = 'bif_points=16&transient_periods=120&record_periods=40&map_omega_points=8&map_value_points=4&lyap_points=8';
const KEY_NAMES = ['backlash_um', 'fr_ti_points', '..=', 'model.md', 'the seed'];

let h;
before(async () => {
  h = await start();
});
after(async () => {
  await h?.close();
});

/** The canvases a screen reader meets: every canvas not hidden from it. */
async function canvasLabels(page) {
  return page.evaluate(() =>
    // The page's canvases; present mode's stage (hidden until a view is
    // presented) is tested in present.test.mjs.
    [...document.querySelectorAll('canvas')]
      .filter((c) => c.getAttribute('aria-hidden') !== 'true' && !c.closest('[hidden]'))
      .map((c) => ({ id: c.id, role: c.getAttribute('role'), label: c.getAttribute('aria-label') ?? '' })),
  );
}

/** The page's visible text (closed disclosures and hidden elements excluded). */
// The page's visible words, less command lines (<code>, <pre>): those are
// the command line's own syntax, which may name keys (as links and JSON do).
async function visibleText(page) {
  return page.evaluate(() => {
    const code = [...document.querySelectorAll('code, pre')].map((e) => [e, e.style.display]);
    code.forEach(([e]) => { e.style.display = 'none'; });
    const text = document.body.innerText;
    code.forEach(([e, d]) => { e.style.display = d; });
    return text;
  });
}

/**
 * The words a user reads in attributes: tooltips (title), the names a
 * screen reader says (aria-label), alternative text and placeholders.
 * Command lines (<code>, <pre>) may name keys, as links and JSON do.
 */
async function attributeWords(page) {
  return page.evaluate(() => {
    const out = [];
    for (const e of document.querySelectorAll('[title], [aria-label], [alt], [placeholder]')) {
      if (e.closest('code, pre')) continue;
      for (const a of ['title', 'aria-label', 'alt', 'placeholder']) {
        const v = e.getAttribute(a);
        if (v) out.push({ el: e.id || e.tagName.toLowerCase(), attr: a, v });
      }
    }
    return out;
  });
}

/** A key name (a word with an underscore between letters) or a Rust range. */
const CODE = /\b[a-z][a-z0-9]*_[a-z0-9_]+\b|\.\.=/i;

/** Asserts that no attribute a user reads names a key or uses code syntax. */
async function assertPlainAttributes(page) {
  const words = await attributeWords(page);
  assert.ok(words.filter((w) => w.attr === 'title').length >= 20, `${words.length} attributes`);
  const bad = words.filter((w) => KEY_NAMES.some((k) => w.v.includes(k)) || CODE.test(w.v));
  assert.deepEqual(bad, [], 'attributes with key names or code syntax');
}

test('at the Table 1 defaults the frequency response shows time-integration dots and says where no periodic motion is stable', async () => {
  const { page, errors } = await open(h.browser, h.url, '');
  await page.setViewportSize({ width: 1366, height: 768 });
  // No setting changed: the dots come from the bifurcation sweep's steady states.
  const s = await waitStatus(page, (x) => x.fr.finished_ms && x.fr_dots >= 10, 240000, 'the branch and ten dots');
  assert.equal(s.fr_overlay.id, 0, 'no overlay job of its own at the defaults');
  assert.match(s.query, /^model=ravigneaux&omega=/, 'the defaults');
  // The plot catches up with the dots (it redraws at each tenth of the sweep).
  await waitStatus(page, (x) => x.draws[0] > s.draws[0], 120000, 'a redraw with the dots');
  // The branch is unstable over a range at the defaults: the plot says so in words.
  const sentence = s.fr_sentence ?? '';
  assert.match(sentence, /^No stable orbit on the branch between Ω [\d.]+ and [\d.]+( and between [\d.]+ and [\d.]+)*: the dots are the actual response\.$/);
  // The finding: no periodic motion is stable over Ω 1.0-1.6 at the defaults.
  const ranges = [...sentence.matchAll(/([\d.]+) and ([\d.]+)/g)].map((m) => [Number(m[1]), Number(m[2])]);
  assert.ok(ranges.some(([a, b]) => a <= 1.0 && b >= 1.6), sentence);
  // The canvas's text alternative says the same, from the same data.
  await page.waitForFunction(
    () => /Frequency response of s1a1: peak \d+ µm at Ω [\d.]+.*No stable orbit on the branch between Ω/.test(document.getElementById('canvas-fr').getAttribute('aria-label') ?? ''),
    null,
    { timeout: 60000 },
  );
  await page.waitForFunction(() => /the dots are the actual response/.test(document.getElementById('note-fr').textContent) || /Hollow dots: the actual response/.test(document.getElementById('note-fr').textContent), null, { timeout: 60000 });
  await shot(page.locator('#view-fr'), 'teach-01-fr-defaults-dots');
  await shot(page, 'teach-02-page-1366x768');
  await page.evaluate(() => window.scrollTo(0, 0));
  await screen(page, 'teach-02b-first-screen-1366x768');
  const text = await visibleText(page);
  for (const k of KEY_NAMES) assert.ok(!text.includes(k), `visible text contains ${k}`);
  await assertPlainAttributes(page);
  // The student summary: two sentences, the dynamic factor explained; the figures behind a disclosure.
  await waitStatus(page, (x) => x.omega_job.finished_ms, 120000, 'the selected-Ω run');
  await page.waitForFunction(() => /The largest tooth force is [\d.]+ times .* \(dynamic factor [\d.]+\)/.test(document.getElementById('summary').textContent), null, { timeout: 60000 });
  assert.equal(await page.locator('#summary-expert').isVisible(), false, 'the expert figures start folded');
  assert.deepEqual(errors, []);
  await page.close();
});

test('no visible text uses key names or code syntax, in the controls, a comparison and a bad link', async () => {
  const bad = `backlash_um=5000&${QUICK}`;
  const { page, errors } = await open(h.browser, h.url, bad);
  await page.setViewportSize({ width: 1920, height: 1080 });
  await page.locator('#messages').waitFor({ state: 'visible' });
  assert.match(await page.textContent('#messages'), /Backlash must be between 0 and 1000 µm \(not 5000\)/);
  // Every group of controls open, then the comparison A/B.
  await page.evaluate(() => document.querySelectorAll('details').forEach((d) => { if (!d.classList.contains('howto')) d.open = true; }));
  await page.click('#pin-a');
  await waitStatus(page, (x) => x.pinned, 60000, 'A pinned');
  const fr0 = (await status(page)).fr.id;
  await page.fill('#num-backlash_um', '160');
  await page.press('#num-backlash_um', 'Enter');
  // B's own runs: the frequency response restarted after the change (the
  // finished flags before it were A's).
  const s = await waitStatus(
    page,
    (x) => x.pinned && x.query.includes('backlash_um=160') && x.fr.id > fr0 && x.fr.finished_ms && x.bif.finished_ms && x.omega_job.finished_ms,
    120000,
    'the comparison',
  );
  assert.deepEqual(s.ab_labels, ['backlash 100 µm', 'backlash 160 µm']);
  const text = await visibleText(page);
  for (const k of KEY_NAMES) assert.ok(!text.includes(k), `visible text contains ${k}: …${text.slice(Math.max(0, text.indexOf(k) - 80), text.indexOf(k) + 40)}…`);
  assert.ok(!/\d um\b/.test(text), 'a unit written as um');
  // Tooltips, names and placeholders too, every group of controls open.
  await assertPlainAttributes(page);
  await shot(page, 'teach-03-page-1920x1080-comparison');
  await page.evaluate(() => window.scrollTo(0, 0));
  await screen(page, 'teach-03b-first-screen-1920x1080');
  assert.deepEqual(errors, []);
  await page.close();
});

test('every canvas is an image with a text alternative that follows the data', async () => {
  const { page, errors } = await open(h.browser, h.url, QUICK);
  await waitStatus(page, (x) => x.fr.finished_ms && x.bif.finished_ms && x.omega_job.finished_ms && x.map.finished_ms, 180000, 'all views');
  await page.waitForFunction(() => !document.getElementById('canvas-map').getAttribute('aria-label').includes('waiting'), null, { timeout: 60000 });
  const before = await canvasLabels(page);
  assert.ok(before.length >= 9, `${before.length} canvases`);
  for (const c of before) {
    assert.equal(c.role, 'img', `${c.id} has no role=img`);
    assert.ok(c.label.length > 20 && c.label !== 'Loading…', `${c.id}: "${c.label}"`);
  }
  // New data, new words: a larger backlash changes the response.
  const id0 = (await status(page)).fr.id;
  await page.fill('#num-backlash_um', '40');
  await page.press('#num-backlash_um', 'Enter');
  await waitStatus(page, (x) => x.fr.id > id0 && x.fr.finished_ms && x.bif.finished_ms && x.omega_job.finished_ms && x.map.finished_ms, 180000, 'the new state');
  const changed = ['canvas-fr', 'canvas-bif', 'canvas-phase', 'canvas-time'];
  await page.waitForFunction(
    ({ ids, old }) => ids.every((id) => document.getElementById(id).getAttribute('aria-label') !== old[id]),
    { ids: changed, old: Object.fromEntries(before.map((c) => [c.id, c.label])) },
    { timeout: 60000 },
  );
  // Export buttons say what they export, after their visible text (axe's label-content-name-mismatch).
  const names = await page.evaluate(() => [...document.querySelectorAll('.exports button')].map((b) => [b.textContent, b.getAttribute('aria-label')]));
  assert.ok(names.some(([, n]) => n === 'CSV: Export the frequency response as CSV'), names.join(' | '));
  assert.ok(names.every(([t, n]) => n && n.startsWith(`${t}: Export the `)), names.join(' | '));
  assert.deepEqual(errors, []);
  await page.close();
});

test('on a phone (390x844) nothing scrolls sideways, the settings are a closed drawer and a skip link leads to the plots', async () => {
  const page = await h.browser.newPage();
  await page.setViewportSize({ width: 390, height: 844 });
  await page.goto(`${h.url}?${QUICK}`);
  await page.waitForFunction(() => typeof window.gearshockStatus === 'function');
  await waitStatus(page, (x) => x.fr.finished_ms && x.omega_job.finished_ms, 120000, 'the first views');
  const w = await page.evaluate(() => ({ scroll: document.documentElement.scrollWidth, body: document.body.scrollWidth, view: window.innerWidth }));
  assert.ok(w.scroll <= 390 && w.body <= 390, JSON.stringify(w));
  assert.equal(await page.evaluate(() => document.getElementById('drawer').open), false);
  const skip = page.locator('a.skip-link').first();
  assert.equal(await skip.getAttribute('href'), '#views');
  assert.equal(await page.locator('a.skip-link').nth(1).getAttribute('href'), '#drawer');
  // The skip link is the first Tab stop and takes the focus to the plots.
  await page.keyboard.press('Tab');
  assert.equal(await page.evaluate(() => document.activeElement.className), 'skip-link');
  await page.keyboard.press('Enter');
  await page.waitForFunction(() => location.hash === '#views');
  await page.evaluate(() => window.scrollTo(0, 0));
  await shot(page, 'teach-04-phone-390x844');
  await screen(page, 'teach-05-phone-first-screen');
  await page.close();
});

test('Copy link confirms for about two seconds', async () => {
  await h.browser.grantPermissions(['clipboard-read', 'clipboard-write']);
  const { page, errors } = await open(h.browser, h.url, QUICK);
  // When the page hides the confirmation, noted in the page as it happens
  // (a check from here could come late on a busy machine).
  await page.evaluate(() => {
    const e = document.getElementById('copy-done');
    new MutationObserver(() => {
      if (e.hidden && e.dataset.shown) window.__hiddenAfter = Date.now() - Number(e.dataset.shown);
    }).observe(e, { attributes: true, attributeFilter: ['hidden'] });
  });
  await page.click('#copy-link');
  const toast = page.locator('#copy-done');
  await toast.waitFor({ state: 'visible', timeout: 60000 });
  await shot(page.locator('header'), 'teach-06-copy-link');
  assert.match(await toast.textContent(), /Link copied/);
  // Then it goes, two seconds after it was shown (not within a second).
  await toast.waitFor({ state: 'hidden', timeout: 60000 });
  const shownMs = await page.evaluate(() => window.__hiddenAfter);
  assert.ok(shownMs >= 1900, `the confirmation was shown for ${shownMs} ms`);
  assert.deepEqual(errors, []);
  await page.close();
});

test('the Start here tour runs through all its steps, each pointing at its view, and its step is in the link', async () => {
  const { page, errors } = await open(h.browser, h.url, QUICK);
  await page.setViewportSize({ width: 1366, height: 768 });
  await page.click('#tour-start');
  const expected = [
    { target: 'schematic', title: /gear set and its meshes/ },
    { target: 'view-fr', title: /Backlash and the frequency response/ },
    { target: 'view-map', title: /double-sided/ },
    { target: 'view-bif', title: /periodic to chaotic/ },
    { target: 'copy-link', title: /Share/ },
  ];
  for (const [i, step] of expected.entries()) {
    await page.waitForFunction((n) => document.getElementById('tour')?.dataset.step === String(n), i + 1);
    assert.match(await page.textContent('#tour-title'), step.title);
    assert.equal(await page.textContent('#tour-count'), `Step ${i + 1} of ${expected.length}`);
    // The step's view is highlighted and on screen.
    const target = await page.evaluate(() => [...document.querySelectorAll('.tour-target')].map((e) => e.id));
    assert.deepEqual(target, [step.target]);
    await page.waitForFunction((id) => {
      const r = document.getElementById(id).getBoundingClientRect();
      return r.bottom > 0 && r.top < window.innerHeight;
    }, step.target);
    await page.waitForFunction((n) => location.search.includes(`tour=${n}`), i + 1);
    if (i === 3) {
      // This step sets its state: the motion at Ω 1.2.
      await waitStatus(page, (x) => x.omega === 1.2, 60000, 'Ω 1.2');
      await shot(page, 'teach-07-tour-step-4');
    }
    await page.click('#tour-next');
  }
  // Finished: the panel is gone and the link no longer carries a step.
  await page.locator('#tour').waitFor({ state: 'hidden' });
  await page.waitForFunction(() => !location.search.includes('tour='));
  // A link with a step opens the tour there; Skip ends it; Start restarts it.
  const again = await open(h.browser, h.url, `${QUICK}&tour=3`);
  await again.page.locator('#tour').waitFor({ state: 'visible' });
  assert.match(await again.page.textContent('#tour-title'), /double-sided/);
  await again.page.click('#tour-skip');
  await again.page.locator('#tour').waitFor({ state: 'hidden' });
  await again.page.click('#tour-start');
  await again.page.waitForFunction(() => document.getElementById('tour')?.dataset.step === '1');
  assert.deepEqual(again.errors, []);
  await again.page.close();
  assert.deepEqual(errors, []);
  await page.close();
});

test('PNG exports are twice the canvas size and SVG exports are the same drawing', async () => {
  const { page, errors } = await open(h.browser, h.url, QUICK);
  await waitStatus(page, (x) => x.fr.finished_ms, 120000, 'the frequency response');
  const [png] = await Promise.all([
    page.waitForEvent('download'),
    page.click('#exports-fr button[aria-label="PNG: Export the frequency response as a PNG image at twice the size"]'),
  ]);
  const buf = await fs.promises.readFile(await png.path());
  // PNG header: width and height, big-endian, at bytes 16 and 20.
  assert.equal(buf.readUInt32BE(16), 1520);
  assert.equal(buf.readUInt32BE(20), 800);
  const [svg] = await Promise.all([
    page.waitForEvent('download'),
    page.click('#exports-fr button[aria-label="SVG: Export the frequency response as an SVG picture"]'),
  ]);
  assert.match(svg.suggestedFilename(), /^gearshock-fr-s1a1\.svg$/);
  const text = await fs.promises.readFile(await svg.path(), 'utf8');
  assert.ok(text.startsWith('<svg') && text.includes('Frequency response'), text.slice(0, 200));
  assert.deepEqual(errors, []);
  await page.close();
});

/** The pixels of a PNG (a screenshot) that are not white, counted in the page. */
async function pngInk(page, png) {
  return page.evaluate(async (b64) => {
    const img = new Image();
    img.src = `data:image/png;base64,${b64}`;
    await img.decode();
    const c = document.createElement('canvas');
    c.width = img.width;
    c.height = img.height;
    const ctx = c.getContext('2d');
    ctx.drawImage(img, 0, 0);
    const d = ctx.getImageData(0, 0, c.width, c.height).data;
    let ink = 0;
    for (let i = 0; i < d.length; i += 4) if (d[i] < 240 || d[i + 1] < 240 || d[i + 2] < 240) ink++;
    return { ink, total: d.length / 4 };
  }, png.toString('base64'));
}

test('the gear set\'s canvas always holds a drawn frame: before the motion, out of view, after a change and in a full-page screenshot', async () => {
  const { page, errors } = await open(h.browser, h.url, QUICK);
  await page.setViewportSize({ width: 1366, height: 768 });
  const outOfView = () => page.evaluate(() => {
    const r = document.getElementById('canvas-anim').getBoundingClientRect();
    return r.top >= window.innerHeight || r.bottom <= 0;
  });
  assert.equal(await outOfView(), true, 'the gear set starts below the first screen');
  // Drawn before any motion is computed (a frame and a line of words) ...
  await page.waitForFunction(() => {
    const c = document.getElementById('canvas-anim');
    const d = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;
    for (let i = 0; i < d.length; i += 4) if (d[i] < 200) return true;
    return false;
  }, null, { timeout: 60000 });
  // ... then the gear set, though out of view.
  const s = await waitStatus(page, (x) => x.omega_job.finished_ms && x.anim?.frames >= 1, 120000, 'a frame of the gear set');
  assert.equal(await outOfView(), true);
  const first = await canvasStats(page, 'canvas-anim');
  assert.ok(first.ink > 0.05 * first.total, `${first.ink} of ${first.total} pixels drawn`);
  // A new state out of view is drawn at once.
  await page.fill('#num-omega', '1.2');
  await page.press('#num-omega', 'Enter');
  await waitStatus(page, (x) => x.omega_job.finished_ms && x.omega_result?.omega === 1.2 && x.anim?.omega === 1.2, 120000, 'the gear set at Ω 1.2');
  assert.equal(await outOfView(), true);
  const second = await canvasStats(page, 'canvas-anim');
  assert.notEqual(second.hash, first.hash, 'the new state is drawn');
  // A full-page screenshot shows it: its region of the page is not blank.
  const box = await page.evaluate(() => {
    const r = document.getElementById('canvas-anim').getBoundingClientRect();
    return { x: r.left + window.scrollX, y: r.top + window.scrollY, width: r.width, height: r.height };
  });
  const full = await page.screenshot({ fullPage: true, path: path.join(SHOTS, 'teach-08-full-page-1366.png') });
  assert.ok(full.length > 0);
  const region = await page.screenshot({ fullPage: true, clip: box });
  const ink = await pngInk(page, region);
  assert.ok(ink.ink > 0.05 * ink.total, `the gear set in the full-page screenshot: ${ink.ink} of ${ink.total} pixels`);
  // And the canvas still holds its frame afterwards.
  const after = await canvasStats(page, 'canvas-anim');
  assert.ok(after.ink > 0.05 * after.total, `${after.ink} of ${after.total} pixels after the screenshot`);
  assert.deepEqual(errors, []);
  await page.close();
});

test('on a phone (touch, 390x844) a tap or a sideways drag on the frequency response and a tap on the bifurcation diagram select Ω, on larger plots', async () => {
  const phone = await start({ viewport: { width: 390, height: 844 }, hasTouch: true, isMobile: true });
  try {
    const { page, errors } = await open(phone.browser, phone.url, QUICK);
    const s0 = await waitStatus(page, (x) => x.fr.finished_ms && x.bif.finished_ms && x.omega_job.finished_ms && x.fr_frame && x.bif_frame, 180000, 'the first views');
    // Larger plots: drawn on 480 pixels across the screen's width, taller
    // for their width, so the 13-pixel words read at 9 CSS pixels or more.
    const sizes = await page.evaluate(() => Object.fromEntries([...document.querySelectorAll('canvas[role=img]')]
      .filter((c) => !c.closest('[hidden]'))
      .map((c) => [c.id, { w: c.width, h: c.height, css: c.getBoundingClientRect().width }])));
    assert.deepEqual([sizes['canvas-fr'].w, sizes['canvas-fr'].h], [480, 640]);
    for (const [id, c] of Object.entries(sizes)) {
      if (id === 'canvas-anim') continue;
      assert.equal(c.w, 480, id);
      assert.ok(c.css >= 340 && c.css <= 390, `${id}: ${c.css} CSS pixels wide`);
      assert.ok((13 * c.css) / c.w >= 9, `${id}: words at ${(13 * c.css) / c.w} px`);
    }
    // Where a finger lands on a canvas for a fraction `f` across its plotting area.
    const at = async (id, frame, f) => {
      const loc = page.locator(`#${id}`);
      await loc.scrollIntoViewIfNeeded();
      const box = await loc.boundingBox();
      const k = box.width / 480;
      return { x: box.x + (frame[0] + f * (frame[2] - frame[0])) * k, y: box.y + 0.5 * (frame[1] + frame[3]) * k };
    };
    const omegaAt = (f) => 0.1 + f * (2 - 0.1);
    const near = (x, want) => Math.abs(x.omega - want) < 0.02;
    // A tap on the frequency response: Ω changes and the orbit views redraw.
    let p = await at('canvas-fr', s0.fr_frame, 0.75);
    await page.touchscreen.tap(p.x, p.y);
    await waitStatus(page, (x) => near(x, omegaAt(0.75)), 60000, 'the tapped Ω');
    const s1 = await waitStatus(page, (x) => x.omega_job.finished_ms && x.omega_result && near(x.omega_result, omegaAt(0.75))
      && x.draws[2] > s0.draws[2] && x.draws[4] > s0.draws[4], 120000, 'the orbit views at the tapped Ω');
    await shot(page.locator('#view-fr'), 'teach-09-phone-touch-fr');
    // A sideways drag (touch events through the DevTools protocol).
    const cdp = await page.context().newCDPSession(page);
    p = await at('canvas-fr', s1.fr_frame, 0.3);
    const q = await at('canvas-fr', s1.fr_frame, 0.5);
    const touch = (type, x, y) => cdp.send('Input.dispatchTouchEvent', { type, touchPoints: type === 'touchEnd' ? [] : [{ x, y }] });
    await touch('touchStart', p.x, p.y);
    for (let k = 1; k <= 8; k++) await touch('touchMove', p.x + ((q.x - p.x) * k) / 8, p.y);
    await touch('touchEnd');
    await waitStatus(page, (x) => near(x, omegaAt(0.5)), 60000, 'the Ω where the drag ended');
    // A tap on the bifurcation diagram.
    p = await at('canvas-bif', s1.bif_frame, 0.25);
    await page.touchscreen.tap(p.x, p.y);
    await waitStatus(page, (x) => near(x, omegaAt(0.25)), 60000, 'the Ω tapped on the bifurcation diagram');
    await waitStatus(page, (x) => x.omega_job.finished_ms && x.omega_result && near(x.omega_result, omegaAt(0.25)), 120000, 'the orbit views');
    const w = await page.evaluate(() => ({ scroll: document.documentElement.scrollWidth, body: document.body.scrollWidth }));
    assert.ok(w.scroll <= 390 && w.body <= 390, JSON.stringify(w));
    await shot(page.locator('#view-bif'), 'teach-10-phone-bif');
    await shot(page.locator('#view-phase'), 'teach-11-phone-phase');
    assert.deepEqual(errors, []);
    await page.close();
  } finally {
    await phone.close();
  }
});
