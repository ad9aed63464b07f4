// The worker pool in the browser: its size follows
// navigator.hardwareConcurrency (one core left to the page, 2 to 8
// workers), and the results do not depend on it: the bifurcation sweep's
// chains are fixed by its point count and dealt over the pool.
import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import fs from 'node:fs';
import { start, waitStatus } from './harness.mjs';

// 200 points make 4 chains (one per 50 points): dealt over 2 or 5 workers.
const LINK = 'bif_points=200&bif_dir=both&omega_from=0.6&omega_to=1.4&transient_periods=40&record_periods=8&fr_points=20&lyap_points=0';

let h;
before(async () => {
  h = await start();
});
after(async () => {
  await h?.close();
});

/** Opens the page as on a machine with `cores` logical cores. */
async function openWithCores(cores) {
  const page = await h.browser.newPage();
  const errors = [];
  page.on('console', (m) => {
    if (m.type() === 'error') errors.push(m.text());
  });
  page.on('pageerror', (e) => errors.push(String(e)));
  await page.addInitScript((n) => {
    Object.defineProperty(Navigator.prototype, 'hardwareConcurrency', { get: () => n, configurable: true });
  }, cores);
  await page.goto(`${h.url}?${LINK}`);
  await page.waitForFunction(() => typeof window.gearshockStatus === 'function');
  return { page, errors };
}

/** The bifurcation diagram's CSV and CLI JSON once the sweep is done. */
async function sweepExports(page) {
  await waitStatus(page, (s) => s.bif.finished_ms, 300000, 'the bifurcation sweep');
  const grab = async (label) => {
    const [dl] = await Promise.all([
      page.waitForEvent('download', { timeout: 60000 }),
      page.locator('#exports-bif button', { hasText: new RegExp(`^${label}$`) }).click(),
    ]);
    return fs.readFileSync(await dl.path(), 'utf8');
  };
  return { csv: await grab('CSV'), cli: await grab('CLI JSON') };
}

test('the pool has hardwareConcurrency - 1 workers and the sweep is the same as with 2 workers', async () => {
  const runs = {};
  for (const [cores, workers] of [[3, 2], [6, 5], [32, 8]]) {
    const { page, errors } = await openWithCores(cores);
    const s = await waitStatus(page, (s) => s.workers_ready === s.workers, 60000, 'every worker ready');
    assert.equal(s.workers, workers, `${cores} cores`);
    if (cores !== 32) {
      runs[cores] = await sweepExports(page);
    }
    assert.deepEqual(errors, []);
    await page.close();
  }
  const [two, five] = [runs[3], runs[6]];
  // 2 directions x 200 points, each with its Poincaré samples.
  assert.ok(two.csv.trim().split('\n').length > 400, 'the sweep has its points');
  const cli = JSON.parse(five.cli);
  assert.equal(cli.spec.chains, 4);
  assert.equal(cli.spec.shard, null);
  assert.equal(cli.points.length, 400);
  assert.equal(five.csv, two.csv, 'the bifurcation CSV differs between 5 and 2 workers');
  assert.equal(five.cli, two.cli, 'the CLI JSON differs between 5 and 2 workers');
});
