// Browser test of "a step ends with one action for the student
// and notices when it is done": on the tour's second step the card asks for
// the backlash at 50 µm; the student drags the slider there and the card
// reports it done (a tick, "Done: ...", Next highlighted), waiting for the
// page's reported state (status "tour"), never for a time.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import path from 'node:path';
import { start, open, waitStatus, SHOTS } from './harness.mjs';

const QUICK = 'bif_points=24&transient_periods=120&record_periods=40&map_omega_points=10&map_value_points=5&lyap_points=8&fr_points=60';

test('the tour step asking for 50 µm backlash reports it done once the student drags the slider there', async () => {
  const h = await start({ viewport: { width: 1366, height: 768 } });
  try {
    const { page, errors } = await open(h.browser, h.url, QUICK);
    await waitStatus(page, (s) => s.workers_ready > 0, 60000, 'workers');
    await page.click('#tour-start');
    await page.click('#tour-next');
    await waitStatus(page, (s) => s.tour?.step === 1 && s.tour.done === false, 60000, 'step 2, not done');
    const action = await page.textContent('#tour-action');
    assert.match(action, /50 µm/);
    assert.equal(await page.isVisible('#tour-done'), false);
    assert.equal(await page.$eval('#tour-next', (b) => b.classList.contains('ready')), false);
    // The student drags the slider to 50 µm.
    await page.locator('#slider-backlash_um').fill('50');
    await waitStatus(page, (s) => s.tour?.step === 1 && s.tour.done === true, 60000, 'step 2 done');
    await page.waitForFunction(() => document.getElementById('tour')?.dataset.done === 'true');
    assert.equal(await page.isVisible('#tour-done'), true);
    assert.match(await page.textContent('#tour-done'), /^✓ Done: the backlash is 50 µm/);
    assert.equal(await page.$eval('#tour-next', (b) => b.classList.contains('ready')), true);
    await page.screenshot({ path: path.join(SHOTS, 'tour-action-done-1366x768.png') });
    // The next step starts not done.
    await page.click('#tour-next');
    await waitStatus(page, (s) => s.tour?.step === 2 && s.tour.done === false, 60000, 'step 3, not done');
    assert.equal(await page.isVisible('#tour-done'), false);
    assert.deepEqual(errors, []);
  } finally {
    await h.close();
  }
});
