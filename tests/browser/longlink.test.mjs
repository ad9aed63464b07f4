// Long share links reach the page, which names what it ignored: the static
// server answered links over about 16 kB with HTTP 431, so the page never
// loaded to show its own message (the app reads links of up to 64 KiB).
import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import { start, open } from './harness.mjs';

const QUICK = 'bif_points=16&transient_periods=120&record_periods=40&lyap_points=0&map_omega_points=2&map_value_points=1';

let h;
before(async () => {
  h = await start();
});
after(async () => {
  await h?.close();
});

test('a 20 kB link loads the page, which names the key it does not know', async () => {
  const { page, errors } = await open(h.browser, h.url, `${QUICK}&backlash_um=120&note=${'y'.repeat(20 * 1024)}`);
  const msg = page.locator('#messages');
  await msg.waitFor({ state: 'visible' });
  await page.waitForFunction(() => /unknown parameter key `note`/.test(document.querySelector('#messages')?.textContent ?? ''));
  assert.equal(await page.inputValue('#num-backlash_um'), '120');
  assert.deepEqual(errors, []);
  await page.close();
});

test('a link over 64 KiB loads the page, which says the rest was ignored', async () => {
  const { page, errors } = await open(h.browser, h.url, `${QUICK}&backlash_um=130&note=${'z'.repeat(70 * 1024)}`);
  await page.locator('#messages').waitFor({ state: 'visible' });
  await page.waitForFunction(() =>
    /the link is longer than 65536 characters; the rest was ignored/.test(document.querySelector('#messages')?.textContent ?? ''),
  );
  // What came before the cut still applies.
  assert.equal(await page.inputValue('#num-backlash_um'), '130');
  assert.deepEqual(errors, []);
  await page.close();
});

test('a key given twice and a bad tour step are named, as text', async () => {
  const { page, errors } = await open(
    h.browser,
    h.url,
    `${QUICK}&backlash_um=120&backlash_um=140&tour=%3Cscript%3Ealert(1)%3C%2Fscript%3E`,
  );
  await page.locator('#messages').waitFor({ state: 'visible' });
  await page.waitForFunction(() => {
    const t = document.querySelector('#messages')?.textContent ?? '';
    return /`backlash_um` is given twice; its last value `140` counts, `120` was ignored/.test(t)
      && /tour = .*script.* is not a step of the tour: allowed 1 to \d+/.test(t);
  });
  // The last value counts, and the step's text stayed text.
  assert.equal(await page.inputValue('#num-backlash_um'), '140');
  assert.equal(await page.locator('#messages script').count(), 0);
  assert.deepEqual(errors, []);
  await page.close();
});
