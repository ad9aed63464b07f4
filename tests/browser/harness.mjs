// Shared set-up of the browser tests and the benchmark: serves dist/ on
// 127.0.0.1, launches Debian's headless chromium through playwright-core
// (never a downloaded browser) and collects console errors per page.
import { chromium } from 'playwright-core';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { serve } from '../../scripts/static-server.mjs';

export const ROOT = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '../..');
export const SHOTS = path.join(ROOT, 'tests/browser/screenshots');

const FLAGS = [
  '--headless',
  '--no-sandbox',
  '--disable-gpu',
  '--disable-quic',
  '--no-first-run',
  '--disable-background-networking',
  '--disable-component-update',
  '--disable-sync',
];

/**
 * Starts the server and the browser; returns { url, browser, close }.
 * `context` (optional) overrides the browser context's options, e.g. a
 * phone's { viewport, hasTouch, isMobile }.
 */
export async function start(context = {}) {
  const dist = path.join(ROOT, 'dist');
  if (!fs.existsSync(path.join(dist, 'index.html'))) {
    throw new Error('dist/ is missing: run `trunk build --release --offline` first');
  }
  const { server, url } = await serve(dist, 0);
  const userDataDir = fs.mkdtempSync(path.join(os.tmpdir(), 'gearshock-chromium-'));
  const executablePath = process.env.CHROMIUM ?? '/usr/bin/chromium';
  // A persistent context is how Playwright takes a fresh --user-data-dir.
  const browser = await chromium.launchPersistentContext(userDataDir, {
    executablePath,
    headless: true,
    args: FLAGS,
    viewport: { width: 1500, height: 1100 },
    acceptDownloads: true,
    ...context,
  });
  fs.mkdirSync(SHOTS, { recursive: true });
  return {
    url,
    browser,
    async close() {
      await browser.close();
      await new Promise((r) => server.close(r));
      fs.rmSync(userDataDir, { recursive: true, force: true });
    },
  };
}

/**
 * Opens a page at `query`, recording console errors and page errors;
 * `workers` (optional) sets the page's worker pool (window.gearshockWorkers).
 */
export async function open(browser, url, query = '', workers = undefined) {
  const page = await browser.newPage();
  const errors = [];
  page.on('console', (m) => {
    if (m.type() === 'error') errors.push(m.text());
  });
  page.on('pageerror', (e) => errors.push(String(e)));
  if (workers !== undefined) {
    await page.addInitScript((n) => {
      window.gearshockWorkers = n;
    }, workers);
  }
  await page.goto(url + (query ? `?${query}` : ''));
  await page.waitForFunction(() => typeof window.gearshockStatus === 'function');
  return { page, errors };
}

/** The app's status object (see web.rs `expose_status`). */
export async function status(page) {
  return JSON.parse(await page.evaluate(() => window.gearshockStatus()));
}

/** Waits until `pred(status)` holds, polling. */
export async function waitStatus(page, pred, timeoutMs = 60000, what = 'condition') {
  const t0 = Date.now();
  for (;;) {
    const s = await status(page);
    if (pred(s)) return s;
    if (Date.now() - t0 > timeoutMs) {
      throw new Error(`timed out after ${timeoutMs} ms waiting for ${what}; status: ${JSON.stringify(s).slice(0, 600)}`);
    }
    await page.waitForTimeout(50);
  }
}

/** Non-background pixel count of a canvas and a cheap hash of its pixels. */
export async function canvasStats(page, id) {
  return page.evaluate((id) => {
    const c = document.getElementById(id);
    const d = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;
    let ink = 0;
    let h = 2166136261;
    for (let i = 0; i < d.length; i += 4) {
      if (!(d[i] === 255 && d[i + 1] === 255 && d[i + 2] === 255) && d[i + 3] !== 0) ink++;
      h = Math.imul(h ^ (d[i] + 3 * d[i + 1] + 7 * d[i + 2]), 16777619) >>> 0;
    }
    return { ink, hash: h, total: d.length / 4 };
  }, id);
}

/** Saves a screenshot of the whole page or an element. */
export async function shot(pageOrLocator, name) {
  const file = path.join(SHOTS, `${name}.png`);
  await pageOrLocator.screenshot({ path: file, fullPage: pageOrLocator.url ? true : undefined });
  return file;
}

/** The main-thread task limit (ms) on an unloaded machine. */
export const TASK_LIMIT_MS = 100;

/**
 * How much slower the page's main thread runs now than unhindered: a fixed
 * reference workload (integer arithmetic, about 1.5 ms) is timed 40 times
 * alone (the fastest run is its unhindered time: a run that short usually
 * finishes within one scheduler time slice) and 40 times back to back in
 * one task, as long as the tasks under test; the ratio of the two is the
 * slowdown that other processes (and the page's own workers) impose on a
 * task of that length. At least 1. While a watch runs (`watchMainThread`)
 * the measurement's own time is noted, so that its task is not counted.
 */
export async function slowdown(page) {
  return page.evaluate(() => {
    const t0 = performance.now();
    const unit = () => {
      let x = 2463534242;
      for (let i = 0; i < 800000; i++) {
        x ^= x << 13;
        x ^= x >>> 17;
        x ^= x << 5;
      }
      return x;
    };
    let sink = 0;
    for (let i = 0; i < 20; i++) sink ^= unit();
    let alone = Infinity;
    for (let i = 0; i < 40; i++) {
      const t = performance.now();
      sink ^= unit();
      alone = Math.min(alone, performance.now() - t);
    }
    const runs = [];
    for (let r = 0; r < 3; r++) {
      const t = performance.now();
      for (let i = 0; i < 40; i++) sink ^= unit();
      runs.push((performance.now() - t) / 40);
    }
    runs.sort((a, b) => a - b);
    window.__sink = sink;
    const factor = Math.max(1, runs[1] / Math.max(alone, 0.1));
    if (window.__beat && !window.__beat.stopped) {
      window.__beat.own.push([t0, performance.now()]);
      window.__beat.factors.push(factor);
    }
    return factor;
  });
}

/**
 * Starts watching the page's main thread: every long task (over 50 ms)
 * the browser reports, and the machine's slowdown (see `slowdown`),
 * measured now, whenever `waitWatched` asks, and at `stopWatch`.
 */
export async function watchMainThread(page) {
  await page.evaluate(() => {
    window.__beat = { tasks: [], own: [], factors: [], stopped: false };
    const seen = (list) => {
      for (const e of list) window.__beat.tasks.push([e.startTime, e.duration]);
    };
    window.__beat.observer = new PerformanceObserver((list) => seen(list.getEntries()));
    window.__beat.observer.observe({ type: 'longtask' });
    window.__beat.seen = seen;
  });
  await slowdown(page);
}

/**
 * `waitStatus` for a watched page: it also measures the slowdown about
 * every `everyMs` of waiting, so that a spell of load during a long wait
 * is known.
 */
export async function waitWatched(page, pred, timeoutMs, what, everyMs = 3000) {
  const t0 = Date.now();
  for (;;) {
    const until = Date.now() + everyMs;
    const left = timeoutMs - (Date.now() - t0);
    const s = await waitStatus(page, (s) => pred(s) || Date.now() > until, Math.max(left, 0), what);
    if (pred(s)) return s;
    await slowdown(page);
  }
}

/**
 * Stops the watch of `watchMainThread` and returns what it saw: { long,
 * longs, factors, over }: the longest task (the slowdown measurements' own
 * tasks left out), all of them as [duration, limit], every slowdown
 * measured, and the tasks over their limit. A task's limit is
 * `TASK_LIMIT_MS` times the larger of the slowdowns measured just before
 * and just after it.
 */
export async function stopWatch(page) {
  await slowdown(page);
  return page.evaluate((limit) => {
    const b = window.__beat;
    b.seen(b.observer.takeRecords());
    b.observer.disconnect();
    b.stopped = true;
    const m = b.own.map(([a, z], i) => [a, z, b.factors[i]]);
    const longs = [];
    for (const [t, d] of b.tasks) {
      if (m.some(([a, z]) => t < z && t + d > a)) continue;
      const before = m.filter(([, z]) => z <= t).pop();
      const after = m.find(([a]) => a >= t + d);
      const f = Math.max(before?.[2] ?? 1, after?.[2] ?? 1);
      longs.push([Math.round(d), Math.round(limit * f)]);
    }
    return {
      long: Math.max(0, ...longs.map(([d]) => d)),
      longs,
      factors: b.factors,
      over: longs.filter(([d, l]) => d >= l),
    };
  }, TASK_LIMIT_MS);
}

/** One line on what `stopWatch` saw, for the test log. */
export function watchReport(beat) {
  const f = beat.factors.map((x) => x.toFixed(1)).join(', ');
  const tasks = beat.longs.map(([d, l]) => `${d} (limit ${l})`).join(', ');
  return `longest main-thread task ${beat.long} ms; ${beat.longs.length} over 50 ms: ${tasks || 'none'}; slowdowns measured ${f}`;
}
