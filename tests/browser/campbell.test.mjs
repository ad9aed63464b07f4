// Browser test of the Campbell diagram: the page lists its critical speeds
// (status "campbell", with each crossing's pixel once drawn) and names the
// first ones in words; a click on a crossing selects its Omega, which the
// summary and the Omega field then show, and the arrow keys on the
// diagram step to the next critical speed. Every wait is for the page's
// reported state, never for a time.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import path from 'node:path';
import { start, open, waitStatus, waitText, SHOTS } from './harness.mjs';

const QUICK = 'bif_points=24&transient_periods=120&record_periods=40&map_omega_points=10&map_value_points=5&lyap_points=8&fr_points=60';

test('a click on a critical speed of the Campbell diagram selects its Omega', async () => {
  const h = await start({ viewport: { width: 1366, height: 768 } });
  try {
    const { page, errors } = await open(h.browser, h.url, QUICK);
    await waitStatus(page, (s) => s.workers_ready > 0, 60000, 'workers');
    const s0 = await waitStatus(page, (s) => s.campbell_frame && s.campbell?.crossings?.some((c) => c.px), 60000, 'the Campbell diagram drawn');
    // Order 1 meets the first mode: the critical speed an engineer reads first.
    const c = s0.campbell.crossings.find((x) => x.order === 1 && x.mode === 1);
    assert.ok(c, JSON.stringify(s0.campbell.crossings));
    assert.ok(c.excited);
    assert.ok(c.omega > 0.1 && c.omega < 2, `${c.omega}`);
    // The words name it, with its frequency, speed and Omega.
    const words = `order 1 meets the first mode (${fmt(c.natural_frequency_hz)} Hz) at ${fmt(c.rpm)} rpm, Ω ${c.omega.toFixed(3)}`;
    assert.ok(s0.campbell.label.includes(words), `${s0.campbell.label} lacks ${words}`);
    await waitText(page, '#note-campbell', /Critical speeds, lowest order first: order \d+ meets the/);
    assert.ok((await page.getAttribute('#canvas-campbell', 'aria-label')).includes(words));
    // A click on the crossing's pixel.
    const cv = page.locator('#canvas-campbell');
    await cv.scrollIntoViewIfNeeded();
    const box = await cv.boundingBox();
    const width = await page.evaluate(() => document.getElementById('canvas-campbell').width);
    const scale = box.width / width;
    await page.mouse.click(box.x + c.px[0] * scale, box.y + c.px[1] * scale);
    const want = Math.round(c.omega * 1e4) / 1e4;
    const s1 = await waitStatus(page, (s) => s.omega === want && s.omega_result?.omega === want && !s.omega_result.preview, 120000, 'the crossing\'s Omega selected and computed');
    assert.equal(s1.omega, want);
    assert.equal(await page.inputValue('#num-omega'), String(want));
    await waitText(page, '#summary', /^At this speed the teeth/);
    // The diagram's selected speed follows.
    await waitText(page, '#canvas-campbell', new RegExp(`order 1 meets`), { attr: 'aria-label' });
    await page.screenshot({ path: path.join(SHOTS, 'campbell-1366x768.png') });
    // The arrow key on the diagram steps to the next critical speed.
    const next = s1.campbell.crossings.map((x) => x.omega).filter((o) => o > c.omega + 1e-9).sort((a, b) => a - b)[0];
    await cv.focus();
    await page.keyboard.press('ArrowRight');
    const want2 = Math.round(next * 1e4) / 1e4;
    await waitStatus(page, (s) => s.omega === want2, 60000, 'the next critical speed');
    assert.deepEqual(errors, []);
  } finally {
    await h.close();
  }
});

/** A whole number with its thousands set apart as the page writes it. */
function fmt(x) {
  return String(Math.round(x)).replace(/\B(?=(\d{3})+(?!\d))/g, '\u00a0');
}
