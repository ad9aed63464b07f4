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

/**
 * Starts watching the page's main thread: a 10 ms heartbeat (its largest
 * gap) and the long tasks (over 50 ms) the browser reports. `stopWatch`
 * returns { maxGap, long, longs }.
 */
export async function watchMainThread(page) {
  await page.evaluate(() => {
    window.__beat = { maxGap: 0, last: performance.now(), long: 0, longs: [] };
    const loop = () => {
      const t = performance.now();
      window.__beat.maxGap = Math.max(window.__beat.maxGap, t - window.__beat.last);
      window.__beat.last = t;
      if (!window.__beat.stop) setTimeout(loop, 10);
    };
    setTimeout(loop, 10);
    new PerformanceObserver((list) => {
      for (const e of list.getEntries()) {
        window.__beat.long = Math.max(window.__beat.long, e.duration);
        window.__beat.longs.push(Math.round(e.duration));
      }
    }).observe({ entryTypes: ['longtask'] });
  });
}

/** Stops the watch of `watchMainThread` and returns what it saw. */
export async function stopWatch(page) {
  return page.evaluate(() => {
    window.__beat.stop = true;
    return window.__beat;
  });
}
