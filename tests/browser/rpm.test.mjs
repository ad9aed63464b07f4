// Browser test of the speed axes in rpm: the Speed axes control switches
// every speed axis, field and readout to the input member's rpm; a
// critical speed read off the Campbell diagram (its rpm from the page's
// status) and clicked is selected as that whole rpm, which the summary,
// the readout and the selected-speed field then state, its Omega the rpm
// converted back; the copied link restores the rpm axes in a fresh page.
// On a narrow range (3 000 to 3 020 rpm) a click selects the speed it
// points at to 0.01 rpm (a thousandth of the range at most), not a whole
// rpm, and the link restores it exactly; the tour keeps the rpm axes and
// gives its speeds in rpm.
// Every wait is for the page's reported state, never for a time.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import path from 'node:path';
import { start, open, waitStatus, waitText, pagePoint, SHOTS } from './harness.mjs';

const QUICK = 'bif_points=24&transient_periods=120&record_periods=40&map_omega_points=10&map_value_points=5&lyap_points=8&fr_points=60';

test('the speed axes in rpm: a critical speed clicked is selected in rpm, and the link keeps the axes', async () => {
  const h = await start({ viewport: { width: 1366, height: 768 } });
  try {
    await h.browser.grantPermissions(['clipboard-read', 'clipboard-write'], { origin: new URL(h.url).origin });
    const { page, errors } = await open(h.browser, h.url, QUICK);
    await waitStatus(page, (s) => s.workers_ready > 0, 60000, 'workers');
    const s0 = await waitStatus(page, (s) => s.speed?.axis === 'omega' && s.speed.rpm > 0, 60000, 'the speed axes in Omega');
    assert.ok(!s0.query.includes('axis='), s0.query);
    // The control, labelled, switches the axes to rpm.
    assert.match(await page.textContent('label[for="sel-axis"]'), /Speed axes/);
    assert.match(await page.textContent('#sel-axis option[value="rpm"]'), /^sun s1 speed, rpm$/);
    await page.selectOption('#sel-axis', 'rpm');
    const s1 = await waitStatus(page, (s) => s.speed.axis === 'rpm' && s.query.includes('axis=rpm'), 60000, 'the axes in rpm');
    // The range fields show rpm, their labels say so, nothing else changed.
    assert.match(await page.textContent('#label-omega_to'), /sun s1 \(rpm\)/);
    const perOmega = s1.speed.rpm / s1.speed.omega;
    const toRpm = Number(await page.inputValue('#num-omega_to'));
    const omegaTo = Number(new URLSearchParams(s1.query).get('omega_to'));
    assert.ok(Math.abs(toRpm - omegaTo * perOmega) <= 1e-6 * toRpm, `${toRpm} vs ${omegaTo * perOmega}`);
    await waitText(page, '#axes-speed-fr', /^sun s1 speed \(rpm\)$/);
    await waitText(page, '#speed-readout', /rpm, mesh frequency [\d\u00a0]+ Hz/);

    // A critical speed read off the Campbell diagram (its frame is rpm
    // across whatever the axes show, so its crossings keep their pixels).
    await waitText(page, '#axes-speed-campbell', /^sun s1 speed \(rpm\)$/);
    const s2 = await waitStatus(page, (s) => s.campbell_frame && s.campbell?.crossings?.some((c) => c.px), 60000, 'the Campbell diagram drawn');
    const c = s2.campbell.crossings.find((x) => x.order === 1 && x.mode === 1);
    assert.ok(c && c.excited && c.rpm > 0, JSON.stringify(s2.campbell.crossings));
    const cv = page.locator('#canvas-campbell');
    await cv.scrollIntoViewIfNeeded();
    const box = await cv.boundingBox();
    const width = await page.evaluate(() => document.getElementById('canvas-campbell').width);
    const scale = box.width / width;
    await page.mouse.click(box.x + c.px[0] * scale, box.y + c.px[1] * scale);
    // Selected as the whole rpm nearest the crossing; its Omega is that
    // rpm converted back, by the crossing's own ratio of Omega to rpm
    // (the solver's modal route, not the page's conversion).
    const rpm = Math.round(c.rpm);
    const want = (rpm * c.omega) / c.rpm;
    const s3 = await waitStatus(page, (s) => Math.abs(s.omega - want) <= 1e-12 * want && s.omega_result?.omega === s.omega && !s.omega_result.preview, 120000, 'the critical speed selected and computed');
    assert.ok(Math.abs(s3.speed.rpm - rpm) <= 1e-9 * rpm, `${s3.speed.rpm} vs ${rpm}`);
    assert.equal(await page.inputValue('#num-omega'), String(rpm));
    await waitText(page, '#summary', new RegExp(`sun s1 at ${fmt(rpm)} rpm \\(Ω [\\d.]+\\): a mesh frequency of \\d+ Hz`));
    await waitText(page, '#speed-readout', new RegExp(`^Selected speed: Ω ${s3.omega.toFixed(4)}, sun s1 at ${fmt(rpm)} rpm, mesh frequency`));
    // The views of the selected speed are at it: the diagram's key says it.
    await waitText(page, '#canvas-campbell', /order 1 meets/, { attr: 'aria-label' });

    // The frequency response with its rpm axis, to look at.
    await waitStatus(page, (s) => s.fr_frame && s.fr.finished_ms, 120000, 'the frequency response drawn');
    const fr = page.locator('#view-fr');
    await fr.scrollIntoViewIfNeeded();
    await fr.screenshot({ path: path.join(SHOTS, 'rpm-fr-1366x768.png') });

    // The copied link opens on the rpm axes and the selected speed.
    await page.click('#copy-link');
    const link = await page.evaluate(() => navigator.clipboard.readText());
    assert.ok(link.includes('axis=rpm'), link);
    const query = new URL(link).search.slice(1);
    const fresh = await open(h.browser, h.url, query);
    const s4 = await waitStatus(fresh.page, (s) => s.speed?.axis === 'rpm' && s.omega === s3.omega, 60000, 'the link restored');
    assert.ok(Math.abs(s4.speed.rpm - rpm) <= 1e-9 * rpm);
    assert.equal(await fresh.page.inputValue('#sel-axis'), 'rpm');
    assert.equal(await fresh.page.inputValue('#num-omega'), String(rpm));
    await waitText(fresh.page, '#axes-speed-fr', /rpm/);
    assert.deepEqual(fresh.errors, []);
    assert.deepEqual(errors, []);
  } finally {
    await h.close();
  }
});

test('a malformed speed axis in a link is named and the Omega axes kept', async () => {
  const h = await start({ viewport: { width: 1366, height: 768 } });
  try {
    const { page, errors } = await open(h.browser, h.url, `${QUICK}&axis=rmp&omega=0.9`);
    const s = await waitStatus(page, (s) => s.speed?.axis === 'omega' && s.issues?.length > 0, 60000, 'the link read');
    assert.ok(s.issues.some((i) => /Speed axes must be one of .*rpm.*\(not rmp\)/.test(i)), JSON.stringify(s.issues));
    assert.equal(s.omega, 0.9);
    await waitText(page, '#messages', /Speed axes must be one of/);
    assert.deepEqual(errors, []);
  } finally {
    await h.close();
  }
});

test('on a narrow rpm range a click selects the rpm it points at, the link keeps it, the tour keeps the axes', async () => {
  const h = await start({ viewport: { width: 1366, height: 768 } });
  try {
    await h.browser.grantPermissions(['clipboard-read', 'clipboard-write'], { origin: new URL(h.url).origin });
    const { page, errors } = await open(h.browser, h.url, `${QUICK}&axis=rpm&branches=off`);
    await waitStatus(page, (s) => s.workers_ready > 0, 60000, 'workers');
    const s0 = await waitStatus(page, (s) => s.speed?.axis === 'rpm' && s.speed.rpm > 0, 60000, 'the rpm axes');
    const perOmega = s0.speed.rpm / s0.speed.omega;
    await page.fill('#num-omega_from', '3000');
    await page.press('#num-omega_from', 'Enter');
    await page.fill('#num-omega_to', '3020');
    await page.press('#num-omega_to', 'Enter');
    const near = (a, b) => Math.abs(a - b) <= 1;
    const s1 = await waitStatus(page, (s) => s.bif_frame && near(s.bif_frame[4] * perOmega, 3000) && near(s.bif_frame[5] * perOmega, 3020),
      120000, 'the bifurcation diagram over 3 000 to 3 020 rpm');
    // A click where 3 004.3712 rpm is drawn.
    const target = 3004.3712;
    const f = s1.bif_frame;
    const [x, y] = await pagePoint(page, 'canvas-bif', f, target / perOmega, 0.5 * (f[6] + f[7]));
    await page.mouse.click(x, y);
    // A pixel is 20 rpm over some 650 pixels: the click lands within 0.05
    // rpm of the target, and the speed is rounded to 0.01 rpm, not 1.
    const s2 = await waitStatus(page, (s) => Math.abs(s.speed.rpm - target) < 0.05, 60000, 'the clicked speed selected');
    const rpm = s2.speed.rpm;
    const cents = Math.round(rpm * 100);
    assert.ok(Math.abs(rpm * 100 - cents) < 1e-6 && cents % 100 !== 0, `${rpm}`);
    const text = String(cents / 100);
    assert.equal(await page.inputValue('#num-omega'), text);
    await waitText(page, '#speed-readout', new RegExp(`sun s1 at 3\u00a0${text.slice(1)} rpm`));
    await page.locator('#view-bif').scrollIntoViewIfNeeded();
    await page.locator('#view-bif').screenshot({ path: path.join(SHOTS, 'rpm-narrow-bif-1366x768.png') });
    // The link restores that speed bit for bit, and its field.
    await page.click('#copy-link');
    const link = await page.evaluate(() => navigator.clipboard.readText());
    const fresh = await open(h.browser, h.url, new URL(link).search.slice(1));
    const s3 = await waitStatus(fresh.page, (s) => s.speed?.axis === 'rpm' && s.omega === s2.omega, 60000, 'the link restored');
    assert.equal(s3.omega, s2.omega);
    assert.equal(await fresh.page.inputValue('#num-omega'), text);
    // The tour keeps the rpm axes and says its speeds in rpm.
    await fresh.page.click('#tour-start');
    await fresh.page.waitForFunction(() => document.getElementById('tour')?.dataset.step === '1');
    await waitText(fresh.page, '#tour-text', /opens at [\d\u00a0]+ rpm \(Ω 0\.35\)/);
    for (const n of [2, 3]) {
      await fresh.page.click('#tour-next');
      await fresh.page.waitForFunction((k) => document.getElementById('tour')?.dataset.step === String(k), n);
    }
    const s4 = await waitStatus(fresh.page, (s) => s.query.includes('tour=3') && Math.abs(s.omega - 1.4) < 1e-12, 60000, 'tour step 3');
    assert.equal(s4.speed.axis, 'rpm');
    assert.ok(s4.query.includes('axis=rpm'), s4.query);
    await waitText(fresh.page, '#tour-text', new RegExp(`backlash 20 µm and ${fmt(1.4 * perOmega)} rpm \\(Ω 1\\.4\\)`));
    await waitText(fresh.page, '#axes-speed-map', /^sun s1 speed \(rpm\)$/);
    await fresh.page.screenshot({ path: path.join(SHOTS, 'rpm-tour-step-3-1366x768.png') });
    assert.deepEqual(fresh.errors, []);
    assert.deepEqual(errors, []);
  } finally {
    await h.close();
  }
});

/** A whole number with its thousands set apart as the page writes it. */
function fmt(x) {
  return String(Math.round(x)).replace(/\B(?=(\d{3})+(?!\d))/g, '\u00a0');
}
