// Browser test of the TE file (the Advanced group): tests/data/te_three_harmonics.csv
// chosen through the file field is fitted to the gear pair's TE, the
// harmonics are those the command line fits from the same file (`gearshock
// params --te-file pair=...`, the parameters `simulate --te-file` runs with),
// its points and fitted curve are drawn, the link carries the harmonics and
// a fresh page restores them; a bad file, dropped or chosen, is refused with
// its line and reason and the state is kept. Every wait is for the page's
// reported state, never for a time.
import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import path from 'node:path';
import { execFileSync } from 'node:child_process';
import { start, open, waitStatus, canvasStats, shot, ROOT } from './harness.mjs';

const QUICK = 'bif_points=16&transient_periods=120&record_periods=40&map_omega_points=8&map_value_points=4&lyap_points=8&fr_points=40';
const FILE = path.join(ROOT, 'tests/data/te_three_harmonics.csv');

/** The parameters the command line fits from the file, through cargo. */
function cliParams() {
  const args = ['run', '-q', '--release', '-p', 'cli', '--', 'params', '--model', 'gear-pair',
    '--te-file', `pair=${FILE}`];
  return JSON.parse(execFileSync('cargo', args, { cwd: ROOT, encoding: 'utf8', maxBuffer: 1 << 26 }));
}

/** The gear pair's TE keys: the mean, then cosine and sine of harmonics 1..6. */
function teKeys() {
  const keys = ['te_mean_um'];
  for (let n = 1; n <= 6; n++) {
    const d = n === 1 ? '' : String(n);
    keys.push(`te_cos${d}_um`, n === 1 ? 'te_um' : `te_sin${d}_um`);
  }
  return keys;
}

/** The TE keys of a link, as numbers (0 where the link leaves a key out:
 * every TE harmonic's default is 0 but the sine's, which the file sets). */
function linkTe(query) {
  const q = new URLSearchParams(query);
  return Object.fromEntries(teKeys().map((k) => [k, q.has(k) ? Number(q.get(k)) : 0]));
}

let h;
before(async () => {
  h = await start();
});
after(async () => {
  await h?.close();
});

test('a TE file is fitted as the command line fits it, drawn, linked and restored; a bad one is refused', async () => {
  const cli = cliParams();
  await h.browser.grantPermissions(['clipboard-read', 'clipboard-write'], { origin: new URL(h.url).origin });
  const { page, errors } = await open(h.browser, h.url, `model=gear-pair&${QUICK}`);
  await waitStatus(page, (s) => s.workers_ready > 0, 60000, 'workers');
  await page.evaluate(() => {
    document.querySelector('details.advanced').open = true;
  });
  await page.selectOption('#te-file-harmonics', '6');
  await page.setInputFiles('#te-file-input', FILE);
  const s = await waitStatus(page, (st) => st.te_file?.points === 360, 60000, 'the fit of the file');
  // The page's fit is the command line's, number for number.
  assert.equal(s.te_file.kind, 'pair');
  assert.equal(s.te_file.mean_um, cli.te_mean_um);
  s.te_file.harmonics_um.forEach(([c, sn], i) => {
    const d = i === 0 ? '' : String(i + 1);
    assert.equal(c, cli[`te_cos${d}_um`] ?? 0, `cosine ${i + 1}`);
    assert.equal(sn, cli[i === 0 ? 'te_um' : `te_sin${d}_um`] ?? 0, `sine ${i + 1}`);
  });
  // The link carries them, and the fields show them.
  const linked = await waitStatus(page, (st) => st.query.includes('te_cos2_um=2.5'), 60000, 'the fit in the link');
  const te = linkTe(linked.query);
  for (const k of teKeys()) assert.equal(te[k], cli[k] ?? 0, k);
  assert.equal(await page.inputValue('#num-te_cos2_um'), '2.5');
  assert.equal(await page.inputValue('#num-te_sin3_um'), '-0.8');
  // Its points and the fitted curve are drawn, the residual said in µm.
  const ink = await canvasStats(page, 'te-file-plot');
  assert.ok(ink.ink > 2000, `the plot has ${ink.ink} inked pixels`);
  const note = await page.textContent('#te-file-note');
  assert.match(note, /te_three_harmonics\.csv: 360 points over 1 mesh period, fitted with 6 harmonics/);
  assert.match(note, /misses the points by less than 0\.000001 µm/);
  await page.locator('#te-file-drop').scrollIntoViewIfNeeded();
  await shot(page.locator('#te-file-drop'), 'tefile-fit');

  // A bad file dropped: refused with its line and reason, nothing changed.
  const before = await waitStatus(page, () => true);
  await page.evaluate(() => {
    const dt = new DataTransfer();
    dt.items.add(new File(['fraction,te_um\n0,1\n0.5,abc\n'], 'bad.csv', { type: 'text/csv' }));
    const zone = document.getElementById('te-file-drop');
    zone.dispatchEvent(new DragEvent('dragover', { dataTransfer: dt, bubbles: true, cancelable: true }));
    zone.dispatchEvent(new DragEvent('drop', { dataTransfer: dt, bubbles: true, cancelable: true }));
  });
  const bad = await waitStatus(page, (st) => st.issues.some((i) => i.includes('bad.csv')), 60000, 'the refusal');
  const said = bad.issues.find((i) => i.includes('bad.csv'));
  assert.match(said, /line 3: the TE “abc” is not a number/);
  assert.match(said, /Nothing was changed/);
  assert.equal(bad.query, before.query);
  assert.equal(bad.te_file.points, 360);
  // Too few points for the harmonics, chosen: the numbers said.
  await page.setInputFiles('#te-file-input', {
    name: 'short.csv',
    mimeType: 'text/csv',
    buffer: Buffer.from('fraction,te_um\n0,1\n0.25,2\n0.5,3\n0.75,4\n'),
  });
  const short = await waitStatus(page, (st) => st.issues.some((i) => i.includes('short.csv')), 60000, 'the second refusal');
  assert.match(short.issues.find((i) => i.includes('short.csv')), /4 points cannot fit 6 harmonics: at least 14 are needed/);
  assert.equal(short.query, before.query);
  await shot(page.locator('#messages'), 'tefile-refused');

  // The link the Copy link button gives (after both refusals: the
  // fitted state kept) restores the fitted excitation exactly in a fresh
  // page.
  await page.click('#copy-link');
  const link = await page.evaluate(() => navigator.clipboard.readText());
  assert.equal(new URL(link).search.slice(1), linked.query);
  const fresh = await open(h.browser, h.url, new URL(link).search.slice(1));
  const r = await waitStatus(fresh.page, (st) => st.workers_ready > 0, 60000, 'workers of the fresh page');
  assert.deepEqual(linkTe(r.query), te);
  assert.equal(await fresh.page.inputValue('#num-te_cos2_um'), '2.5');
  assert.deepEqual(errors, []);
  assert.deepEqual(fresh.errors, []);
  await fresh.page.close();
  await page.close();
});
