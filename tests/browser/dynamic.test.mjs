// Browser test of the dynamic factor (view 11) on the default preset: the
// page reports, for the selected mesh at the selected Ω, the model's
// dynamic factor, K_v by ISO 6336-1 method B and the planets'
// load-sharing factor; each is checked against what `gearshock simulate`
// prints for the same settings, with in-phase planets and with five
// sequential ones. A click on the plot selects Ω. Every wait is for the
// page's reported state, never for a time.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import path from 'node:path';
import { execFileSync } from 'node:child_process';
import { start, open, waitStatus, waitText, pagePoint, ROOT, SHOTS } from './harness.mjs';

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

function close(what, got, want, rel) {
  assert.ok(Math.abs(got - want) <= rel * Math.abs(want), `${what}: page ${got}, gearshock simulate ${want}`);
}

/** The page's full run at the selected Ω, its dynamic factor and sharing in. */
const settled = (s) => s.dynamic?.dynamic_factor != null && !s.dynamic.preview
  && s.omega_result && !s.omega_result.preview && s.dynamic.load_sharing.length > 0;

async function check(page, sets, phasing) {
  const s = await waitStatus(page, settled, 180000, 'the selected state and its dynamic factor');
  const d = s.dynamic;
  assert.equal(d.mesh, 's1a1');
  assert.equal(d.phasing, phasing);
  const cli = simulate(d.omega, sets);
  close('dynamic factor', d.dynamic_factor, cli.dynamic_factor, 1e-6);
  close('K_v', d.kv, cli.kv_iso6336, 1e-12);
  assert.equal(d.iso_range, cli.iso6336.meshes.s1a1.range);
  close('N', d.resonance_ratio, cli.iso6336.meshes.s1a1.resonance_ratio, 1e-12);
  const kinds = Object.keys(cli.load_sharing);
  assert.deepEqual(d.load_sharing.map((k) => k.kind).sort(), kinds.sort());
  for (const k of d.load_sharing) close(`load sharing ${k.kind}`, k.factor, cli.load_sharing[k.kind].factor, 1e-6);
  // The words on the page say the same.
  await waitText(page, '#note-dynamic', new RegExp(`dynamic factor Kv \\(ISO 6336-1, method B\\) ${d.kv.toFixed(2)}`));
  await waitText(page, '#note-dynamic', new RegExp(`the model's dynamic factor ${d.dynamic_factor.toFixed(2)}`));
  await waitText(page, '#note-dynamic', new RegExp(`${phasing} phasing: small sun – short planet ${d.load_sharing[0].factor.toFixed(3)}`));
  return s;
}

test('the dynamic factor, K_v and the load sharing agree with gearshock simulate', async () => {
  const h = await start({ viewport: { width: 1366, height: 768 } });
  try {
    // The default preset: three in-phase planets share every kind's load equally.
    let { page, errors } = await open(h.browser, h.url, QUICK);
    await waitStatus(page, (s) => s.workers_ready > 0, 60000, 'workers');
    const s0 = await check(page, [], 'in-phase');
    for (const k of s0.dynamic.load_sharing) close(`in-phase ${k.kind}`, k.factor, 1, 1e-9);
    // The model's curve from the sweep's steady states, drawn.
    const s1 = await waitStatus(page, (s) => s.bif.finished_ms && s.dynamic?.points >= 12 && s.dynamic_frame, 240000, 'the model\'s curve');
    await waitText(page, '#canvas-dynamic', new RegExp(`^Dynamic factor of mesh s1a1 over Ω .* from ${s1.dynamic.points} steady states`), { attr: 'aria-label' });
    await page.locator('#view-dynamic').scrollIntoViewIfNeeded();
    await page.locator('#view-dynamic').screenshot({ path: path.join(SHOTS, 'dynamic-1366x768.png') });
    // A click on the plot selects Ω there.
    const [x, y] = await pagePoint(page, 'canvas-dynamic', s1.dynamic_frame, 1.2, 1.5);
    await page.mouse.click(x, y);
    await waitStatus(page, (s) => Math.abs(s.omega - 1.2) < 0.01, 60000, 'Ω 1.2 selected');
    await waitText(page, '#note-dynamic', /^At Ω 1\.(19|20|21)\d/);
    assert.deepEqual(errors, []);
    await page.close();
    // Five sequential planets: the sharing is unequal, as the CLI says.
    ({ page, errors } = await open(h.browser, h.url, `${QUICK}&planets=5&phasing=sequential`));
    const s2 = await check(page, ['planets=5', 'phasing=sequential'], 'sequential');
    assert.equal(s2.dynamic.planets, 5);
    assert.ok(s2.dynamic.load_sharing.some((k) => k.factor > 1.001), JSON.stringify(s2.dynamic.load_sharing));
    await waitText(page, '#note-dynamic', /5 planets, sequential phasing/);
    assert.deepEqual(errors, []);
  } finally {
    await h.close();
  }
});
