// Browser test of the excitation's waveforms in the Advanced group: a link
// with a rectangular stiffness and a TE second harmonic restores both
// controls, and choosing the trapezoid writes it into the link.
import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import { start, open, waitStatus } from './harness.mjs';

const QUICK = 'bif_points=16&transient_periods=120&record_periods=40&map_omega_points=8&map_value_points=4&lyap_points=8&fr_points=40';

let h;
before(async () => {
  h = await start();
});
after(async () => {
  await h?.close();
});

test('a link with a waveform restores its controls, and a new waveform goes into the link', async () => {
  const link = `model=gear-pair&stiffness_wave=rectangular&contact_ratio=1.6&te_cos2_um=2.5&${QUICK}`;
  const { page, errors } = await open(h.browser, h.url, link);
  await waitStatus(page, (s) => s.workers_ready > 0, 60000, 'workers');
  assert.equal(await page.inputValue('#sel-stiffness_wave'), 'rectangular');
  assert.equal(await page.inputValue('#num-te_cos2_um'), '2.5');
  // The Advanced group is folded: choose as its select's change does.
  await page.evaluate(() => {
    const s = document.getElementById('sel-stiffness_wave');
    s.value = 'trapezoid';
    s.dispatchEvent(new Event('change', { bubbles: true }));
  });
  const s = await waitStatus(page, (st) => st.query.includes('stiffness_wave=trapezoid'), 60000, 'trapezoid in the link');
  assert.ok(s.query.includes('contact_ratio=1.6') && s.query.includes('te_cos2_um=2.5'), s.query);
  assert.deepEqual(errors, []);
  await page.close();
});
