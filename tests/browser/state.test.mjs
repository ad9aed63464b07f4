// Browser test of "one state": every control shows the state
// after a change. "Backlash b (all meshes)" fills the per-mesh-kind fields;
// the gear pair's labels and subtitle name the gear pair; the torque's
// tooltip states its range from the key table; a negative torque is
// refused in words naming the value and the range, and the field goes back
// to the torque in force.
import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import { start, open, waitStatus, waitText } from './harness.mjs';

const QUICK = 'bif_points=16&transient_periods=120&record_periods=40&map_omega_points=8&map_value_points=4&lyap_points=8&fr_points=40';

let h;
before(async () => {
  h = await start();
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

const fieldValue = (page, key) => page.evaluate((key) => document.getElementById(`num-${key}`).value, key);

test('backlash on all meshes shows in the Advanced fields; a per-kind value makes it read mixed', async () => {
  const { page, errors } = await open(h.browser, h.url, QUICK);
  await waitStatus(page, (s) => s.workers_ready > 0, 60000, 'workers');
  await setField(page, 'backlash_um', '73');
  await waitStatus(page, (s) => s.query.includes('backlash_um=73'), 60000, 'backlash 73 in the link');
  for (const kind of ['s1a', 's2b', 'ab', 'rb']) {
    await page.waitForFunction((k) => document.getElementById(`num-backlash_${k}_um`).value === '73', kind, { timeout: 60000 });
  }
  await setField(page, 'backlash_ab_um', '40');
  await page.waitForFunction(() => document.getElementById('num-backlash_um').value === '', null, { timeout: 60000 });
  assert.equal(await page.getAttribute('#num-backlash_um', 'placeholder'), 'mixed');
  assert.equal(await fieldValue(page, 'backlash_s1a_um'), '73');
  assert.deepEqual(errors, []);
  await page.close();
});

test('the gear pair names itself and its one mesh; the torque tooltip states the range', async () => {
  const { page, errors } = await open(h.browser, h.url, QUICK);
  const tip = await page.getAttribute('#control-torque_s1_nm', 'title');
  assert.match(tip, /Allowed: between 0 and 1×10\^6 N m\./);
  assert.doesNotMatch(tip, /NaN|inf/);
  await page.selectOption('#sel-model', 'gear-pair');
  const sub = await waitText(page, '#model-subtitle', /gear pair/);
  assert.doesNotMatch(sub, /Ravigneaux/);
  const labels = await page.evaluate(() =>
    [...document.querySelectorAll('.control:not([hidden]) label')].map((l) => l.textContent));
  assert.ok(labels.includes('Backlash b') && labels.includes('TE amplitude'), labels.join(' | '));
  for (const l of labels) assert.doesNotMatch(l, /meshes|s1a/, l);
  assert.deepEqual(errors, []);
  await page.close();
});

test('a negative torque is refused in words with the value and the range; the last state stays', async () => {
  const { page, errors } = await open(h.browser, h.url, QUICK);
  await waitStatus(page, (s) => s.workers_ready > 0, 60000, 'workers');
  const before = await fieldValue(page, 'torque_s1_nm');
  const query = (await waitStatus(page, (s) => s.query, 60000, 'the link')).query;
  await setField(page, 'torque_s1_nm', '-5');
  const msg = await waitText(page, '#messages', /torque/i);
  assert.match(msg, /between 0 and 1×10\^6 N m \(not -5\)/);
  assert.doesNotMatch(msg, /torque_s1_nm|Newton|NaN/);
  await page.waitForFunction((v) => document.getElementById('num-torque_s1_nm').value === v, before, { timeout: 60000 });
  const s = await waitStatus(page, (x) => x.query === query, 60000, 'the link unchanged');
  assert.equal(s.query, query);
  assert.deepEqual(errors, []);
  await page.close();
});
