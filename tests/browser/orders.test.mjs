// Browser test of the mesh force by order (view 12): the page reports the
// plotted mesh's force spectrum in orders of the mesh frequency with its
// labelled peaks, and the planets' sum with the orders the phasing
// cancels; each is checked against what `gearshock simulate` prints for
// the same settings, as are the planets' peak mesh forces (the load
// sharing of view 11). Five sequential planets whose suns and ring have
// teeth alike modulo 5 (36, 46, 84) cancel mesh orders 1 to 4 in the sum.
// Every wait is for the page's reported state, never for a time.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import path from 'node:path';
import { execFileSync } from 'node:child_process';
import { start, open, waitStatus, waitText, ROOT, SHOTS } from './harness.mjs';

const RUN = { transient: 120, record: 40 };
const QUICK = `bif_points=24&transient_periods=${RUN.transient}&record_periods=${RUN.record}&map_omega_points=10&map_value_points=5&lyap_points=8&fr_points=60`;

/** `gearshock simulate` at the page's selected Ω with the page's run
 * lengths and `sets` (KEY=VALUE), through cargo (built if stale). */
function simulate(omega, sets) {
  const args = ['run', '-q', '--release', '-p', 'cli', '--', 'simulate', '--omega', String(omega), '--mesh', 's1a1',
    '--transient-periods', String(RUN.transient), '--record-periods', String(RUN.record)];
  for (const s of sets) args.push('--set', s);
  return JSON.parse(execFileSync('cargo', args, { cwd: ROOT, encoding: 'utf8', maxBuffer: 1 << 26 }));
}

function close(what, got, want, rel, scale = Math.abs(want)) {
  assert.ok(Math.abs(got - want) <= rel * scale, `${what}: page ${got}, gearshock simulate ${want}`);
}

/** The full run at the selected Ω with its force by order and sharing. */
const settled = (s) => s.orders && !s.orders.preview && s.omega_result && !s.omega_result.preview
  && s.dynamic?.load_sharing?.length > 0;

async function check(page, sets) {
  const s = await waitStatus(page, settled, 180000, 'the selected state and its force by order');
  const o = s.orders;
  assert.equal(o.mesh, 's1a1');
  assert.equal(o.record_periods, RUN.record);
  const cli = simulate(o.omega, sets);
  const f = cli.force_by_order;
  // The same labelled peaks, at the same orders, with the same amplitudes.
  assert.deepEqual(o.peaks.map((p) => p.label), f.peaks.map((p) => p.label));
  const largest = Math.max(...f.peaks.map((p) => p.amplitude_n));
  o.peaks.forEach((p, i) => {
    close(`order ${p.label}`, p.order, f.peaks[i].order, 1e-12);
    close(`amplitude at ${p.label}`, p.amplitude_n, f.peaks[i].amplitude_n, 1e-6, largest);
  });
  close('mean force', o.mean_force_n, f.amplitude_n[0], 1e-6);
  // The planets' sum per planet is the CLI's sum over the planets.
  const n = o.planet_sum.planets;
  assert.equal(n, f.planet_sum.meshes.length);
  assert.deepEqual(o.planet_sum.cancelled_orders, f.planet_sum.cancelled_orders);
  o.planet_sum.per_planet_n.forEach((a, i) => close(`sum at ${o.order[i]}`, a * n, f.planet_sum.amplitude_n[i + 1], 1e-6, largest * n));
  // Each planet's peak mesh force, kind by kind.
  for (const k of s.dynamic.load_sharing) {
    const want = cli.load_sharing[k.kind].peak_force_n;
    assert.equal(k.peak_force_n.length, want.length);
    k.peak_force_n.forEach((x, i) => close(`${k.kind} planet ${i + 1}`, x, want[i], 1e-6));
  }
  await waitText(page, '#canvas-orders', /^Mesh force by order: amplitude \(N\) against the order of the mesh frequency/, { attr: 'aria-label' });
  await waitText(page, '#note-orders', new RegExp(`^Mesh s1a1 at Ω ${o.omega.toFixed(3)}`));
  return s;
}

test('the mesh force by order and the planets\' forces agree with gearshock simulate', async () => {
  const h = await start({ viewport: { width: 1366, height: 768 } });
  try {
    // Three in-phase planets: whole orders only, the sum three times one mesh.
    let { page, errors } = await open(h.browser, h.url, `${QUICK}&omega=0.35`);
    await waitStatus(page, (s) => s.workers_ready > 0, 60000, 'workers');
    const s0 = await check(page, []);
    assert.ok(s0.orders.peaks.length >= 2 && s0.orders.peaks.every((p) => p.whole), JSON.stringify(s0.orders.peaks));
    assert.equal(s0.orders.peaks[0].label, '1×');
    assert.deepEqual(s0.orders.planet_sum.cancelled_orders, []);
    await waitText(page, '#note-orders', /the phasing cancels no mesh order/);
    // Over speed (view 11), in-phase planets share exactly at every steady state.
    const s0b = await waitStatus(page, (s) => s.dynamic?.sharing_over_speed?.length >= 6, 240000, 'six steady states of the sweep');
    for (const p of s0b.dynamic.sharing_over_speed) close(`sharing at Ω ${p.omega}`, p.worst, 1, 1e-9);
    await page.locator('#view-orders').scrollIntoViewIfNeeded();
    await page.locator('#view-orders').screenshot({ path: path.join(SHOTS, 'orders-1366x768.png') });
    assert.deepEqual(errors, []);
    await page.close();
    // Five sequential planets, teeth alike modulo 5: orders 1 to 4 cancel
    // in the sum, and no line of the sum is labelled there.
    const sets = ['planets=5', 'phasing=sequential', 'teeth_s2=46'];
    ({ page, errors } = await open(h.browser, h.url, `${QUICK}&omega=0.35&${sets.join('&')}`));
    const s1 = await check(page, sets);
    const cancelled = s1.orders.planet_sum.cancelled_orders;
    assert.deepEqual(cancelled.filter((k) => k <= 6), [1, 2, 3, 4, 6]);
    assert.ok(!s1.orders.planet_sum.peaks.some((p) => p.whole && cancelled.includes(Math.round(p.order))),
      JSON.stringify(s1.orders.planet_sum.peaks));
    await waitText(page, '#note-orders', /cancels mesh orders 1×, 2×, 3×, 4×, 6×/);
    await page.locator('#view-orders').scrollIntoViewIfNeeded();
    await page.locator('#view-orders').screenshot({ path: path.join(SHOTS, 'orders-sequential-1366x768.png') });
    // The Campbell diagram adds the planet-pass orders.
    await waitText(page, '#note-campbell', /Planet-pass orders \(5 planets passing the ring/);
    await page.locator('#view-campbell').scrollIntoViewIfNeeded();
    await page.locator('#view-campbell').screenshot({ path: path.join(SHOTS, 'campbell-planet-pass-1366x768.png') });
    // Unequal sharing over speed (view 11), drawn once a few states are in.
    const s2 = await waitStatus(page, (s) => s.dynamic?.sharing_over_speed?.length >= 6 && s.dynamic_frame, 240000, 'six steady states of the sweep');
    assert.ok(s2.dynamic.sharing_over_speed.some((p) => p.worst > 1.001), JSON.stringify(s2.dynamic.sharing_over_speed));
    await waitText(page, '#note-dynamic', /Over the \d+ steady states the largest factor of any kind runs from/);
    await page.locator('#view-dynamic').scrollIntoViewIfNeeded();
    await page.locator('#view-dynamic').screenshot({ path: path.join(SHOTS, 'dynamic-sequential-1366x768.png') });
    assert.deepEqual(errors, []);
  } finally {
    await h.close();
  }
});
