// Browser test of the dynamic factor (view 11) on the default preset: the
// page reports, for the selected mesh at the selected Ω, the model's
// dynamic factor, K_v by ISO 6336-1 method B and the planets'
// load-sharing factor; each is checked against what `gearshock simulate`
// prints for the same settings, with in-phase planets and with five
// sequential ones. A click on the plot selects Ω. The accuracy grade and
// face width of K_v are page controls: a change redraws K_v as `gearshock
// simulate --accuracy-grade --face-width-mm` rates it, a value out of
// range is named with the allowed range, and the link restores both.
// Every wait is for the page's reported state, never for a time.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import path from 'node:path';
import { execFileSync } from 'node:child_process';
import { start, open, waitStatus, waitText, pagePoint, ROOT, SHOTS } from './harness.mjs';

const RUN = { transient: 120, record: 40 };
const QUICK = `bif_points=24&transient_periods=${RUN.transient}&record_periods=${RUN.record}&map_omega_points=10&map_value_points=5&lyap_points=8&fr_points=60`;

/** `gearshock simulate` at the page's selected Ω with the page's run
 * lengths and `sets` (KEY=VALUE), through cargo (built if stale). */
function simulate(omega, sets, flags = []) {
  const args = ['run', '-q', '--release', '-p', 'cli', '--', 'simulate', '--omega', String(omega), '--mesh', 's1a1',
    '--transient-periods', String(RUN.transient), '--record-periods', String(RUN.record), ...flags];
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

test('the grade and face width of K_v: set on the page, as gearshock simulate rates them, kept by the link', async () => {
  const h = await start({ viewport: { width: 1366, height: 768 } });
  try {
    await h.browser.grantPermissions(['clipboard-read', 'clipboard-write'], { origin: new URL(h.url).origin });
    const { page, errors } = await open(h.browser, h.url, QUICK);
    await waitStatus(page, (s) => s.workers_ready > 0, 60000, 'workers');
    const s0 = await waitStatus(page, (s) => s.dynamic?.kv > 1, 60000, 'K_v at the defaults');
    assert.equal(s0.dynamic.accuracy_grade, 6);
    assert.equal(s0.dynamic.face_width_mm, 50);
    assert.match(await page.textContent('#label-accuracy_grade'), /Accuracy grade for Kv/);
    // Out of range: named in words with the allowed range, nothing changed.
    await page.fill('#num-accuracy_grade', '12');
    await page.press('#num-accuracy_grade', 'Enter');
    await waitText(page, '#messages', /Accuracy grade for Kv must be a whole number between 1 and 11 \(not 12\)/);
    assert.equal((await waitStatus(page, (s) => s.dynamic, 1000, 'status')).dynamic.accuracy_grade, 6);
    // Grade 9 over 30 mm: K_v redrawn, as the command line rates it.
    await page.fill('#num-accuracy_grade', '9');
    await page.press('#num-accuracy_grade', 'Enter');
    await page.fill('#num-face_width_mm', '30');
    await page.press('#num-face_width_mm', 'Enter');
    const s1 = await waitStatus(page, (s) => s.dynamic?.accuracy_grade === 9 && s.dynamic.face_width_mm === 30
      && s.query.includes('accuracy_grade=9') && s.query.includes('face_width_mm=30'), 60000, 'grade 9 over 30 mm');
    assert.ok(s1.dynamic.kv > s0.dynamic.kv, `${s1.dynamic.kv} vs ${s0.dynamic.kv}`);
    const cli = simulate(s1.dynamic.omega, [], ['--accuracy-grade', '9', '--face-width-mm', '30']);
    close('K_v at grade 9', s1.dynamic.kv, cli.kv_iso6336, 1e-12);
    await waitText(page, '#note-dynamic', new RegExp(`dynamic factor Kv \\(ISO 6336-1, method B\\) ${s1.dynamic.kv.toFixed(2)}`));
    await waitText(page, '#canvas-dynamic', new RegExp(`Kv by ISO 6336-1 method B`), { attr: 'aria-label' });
    await waitStatus(page, (s) => s.dynamic_frame, 60000, 'view 11 drawn');
    await page.locator('#view-dynamic').scrollIntoViewIfNeeded();
    await page.locator('#view-dynamic').screenshot({ path: path.join(SHOTS, 'dynamic-grade9-1366x768.png') });
    await page.locator('#control-accuracy_grade').scrollIntoViewIfNeeded();
    await page.locator('#control-accuracy_grade').screenshot({ path: path.join(SHOTS, 'dynamic-grade-control-1366x768.png') });
    // The link restores both exactly.
    await page.click('#copy-link');
    const link = await page.evaluate(() => navigator.clipboard.readText());
    const fresh = await open(h.browser, h.url, new URL(link).search.slice(1));
    const s2 = await waitStatus(fresh.page, (s) => s.dynamic?.accuracy_grade === 9, 60000, 'the link restored');
    assert.equal(s2.dynamic.face_width_mm, 30);
    assert.equal(s2.dynamic.kv, s1.dynamic.kv);
    assert.equal(await fresh.page.inputValue('#num-accuracy_grade'), '9');
    assert.equal(await fresh.page.inputValue('#num-face_width_mm'), '30');
    assert.deepEqual(fresh.errors, []);
    assert.deepEqual(errors, []);
  } finally {
    await h.close();
  }
});
