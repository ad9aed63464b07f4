// Browser test of "messages that follow the state": a refused
// value's message and red border go once the state moves on (the field
// already shows the value in force); a solver failure reads in plain words
// with what to try, never the solver's own ("Newton", "residual", "Omega =");
// a load that deflects the teeth by millimetres is warned beside the
// summary, and the warning goes with the load. Screenshots of each state go
// to tests/browser/screenshots/.
import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import path from 'node:path';
import { start, open, waitStatus, waitText, shot, SHOTS } from './harness.mjs';

const QUICK = 'bif_points=16&transient_periods=120&record_periods=40&map_omega_points=8&map_value_points=4&lyap_points=8&fr_points=40';

let h;
before(async () => {
  h = await start({ viewport: { width: 1366, height: 768 } });
});
after(async () => {
  await h?.close();
});

/** Types `value` into the number field of `key` and commits it. */
async function setField(page, key, value) {
  await page.evaluate(({ key, value }) => {
    const f = document.getElementById(`num-${key}`);
    f.value = value;
    f.dispatchEvent(new Event('change', { bubbles: true }));
  }, { key, value });
}

const invalid = (page, key) => page.evaluate((k) => document.getElementById(`control-${k}`).classList.contains('invalid'), key);

test('an empty TE is refused; a valid backlash then takes the TE message and red border away', async () => {
  const { page, errors } = await open(h.browser, h.url, QUICK);
  await waitStatus(page, (s) => s.workers_ready > 0, 60000, 'workers');
  await setField(page, 'te_um', '');
  const msg = await waitText(page, '#messages', /TE/);
  assert.ok(await invalid(page, 'te_um'), 'the TE field is marked');
  assert.equal(await page.evaluate(() => document.getElementById('num-te_um').value), '20', msg);
  await page.screenshot({ path: path.join(SHOTS, 'messages-te-refused.png') });
  await setField(page, 'backlash_um', '80');
  await waitStatus(page, (s) => s.query.includes('backlash_um=80'), 60000, 'backlash 80 in the link');
  await page.waitForFunction(() => document.getElementById('messages').hidden, null, { timeout: 60000 });
  assert.ok(!(await invalid(page, 'te_um')), 'the TE field is no longer marked');
  assert.equal(await page.evaluate(() => document.getElementById('num-te_um').value), '20');
  await page.screenshot({ path: path.join(SHOTS, 'messages-te-cleared.png') });
  assert.deepEqual(errors, []);
  await page.close();
});

test('with no torque the failures read in plain words with what to try, and go when a torque is set', async () => {
  const { page, errors } = await open(h.browser, h.url, `${QUICK}&torque_s1_nm=0`);
  const msg = await waitText(page, '#messages', /could not|stops/, { timeoutMs: 300000 });
  for (const raw of [/Newton/, /Omega =/, /residual/, /\de0\b/]) assert.doesNotMatch(msg, raw, msg);
  assert.match(msg, /Try a load torque above 0/, msg);
  await shot(page.locator('header'), 'messages-torque-0');
  await setField(page, 'torque_s1_nm', '2000');
  await waitStatus(page, (s) => s.fr.finished_ms != null || s.fr.error != null, 300000, 'the new branch');
  const after = await page.evaluate(() => document.getElementById('messages').textContent);
  assert.doesNotMatch(after, /torque above 0/, after);
  assert.deepEqual(errors, []);
  await page.close();
});

test('900 000 N m is warned as outside the model, at once and after the steady state; 2000 N m is not', async () => {
  const { page, errors } = await open(h.browser, h.url, `${QUICK}&torque_s1_nm=900000`);
  const first = await waitText(page, '#validity', /Outside the model/);
  assert.match(first, /mm\)/);
  assert.ok(await page.evaluate(() => !document.getElementById('validity').hidden));
  await waitStatus(page, (s) => s.omega_job.finished_ms != null, 300000, 'the steady state');
  const text = await waitText(page, '#validity', /not physical/);
  await shot(page.locator('main .summary'), 'messages-torque-900000');
  assert.match(text, /Lower the input torque/);
  await setField(page, 'torque_s1_nm', '2000');
  await page.waitForFunction(() => document.getElementById('validity').hidden, null, { timeout: 60000 });
  assert.deepEqual(errors, []);
  await page.close();
});
