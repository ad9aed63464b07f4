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
 * `workers` (optional) sets the page's worker pool (window.gearshockWorkers);
 * `init` (optional) is a function run in the page before its own scripts.
 */
export async function open(browser, url, query = '', workers = undefined, init = undefined) {
  const page = await browser.newPage();
  if (init !== undefined) await page.addInitScript(init);
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

/**
 * Waits for the page's next change of state after `last` (a status read
 * before): checked in the page at every animation frame, it resolves with
 * the new status once the status differs from `last` apart from its clock
 * (`now_ms`), which alone changes on a page at rest. `null` only if
 * `timeoutMs` passed without a change (the bound of a failed wait).
 */
export async function nextStatus(page, last, timeoutMs) {
  const key = (s) => {
    const { now_ms: _, ...rest } = s;
    return JSON.stringify(rest);
  };
  try {
    const h = await page.waitForFunction(
      (prev) => {
        const { now_ms: _, ...rest } = JSON.parse(window.gearshockStatus());
        const k = JSON.stringify(rest);
        return k !== prev ? k : false;
      },
      key(last),
      { polling: 'raf', timeout: Math.max(1, timeoutMs) },
    );
    return JSON.parse(await h.jsonValue());
  } catch (e) {
    if (e.name === 'TimeoutError') return null;
    throw e;
  }
}

/**
 * Waits until `pred(status)` holds: the status is read again at each of
 * the page's changes of state ([`nextStatus`]), so what is waited for is
 * the state, never a time.
 */
export async function waitStatus(page, pred, timeoutMs = 60000, what = 'condition') {
  // The bound only ends a wait that failed: at least a minute, whatever a
  // test asked, so a busy machine never fails a state that was coming.
  timeoutMs = Math.max(timeoutMs, 60000);
  const t0 = Date.now();
  let s = await status(page);
  for (;;) {
    if (pred(s)) return s;
    const left = timeoutMs - (Date.now() - t0);
    const next = left > 0 ? await nextStatus(page, s, left) : null;
    if (next === null) {
      throw new Error(`timed out after ${timeoutMs} ms waiting for ${what}; status: ${JSON.stringify(s).slice(0, 2000)}`);
    }
    s = next;
  }
}

/**
 * Waits until the text of the element `selector` (or its attribute `attr`)
 * matches `re` (with `not`, until it no longer does) and returns it. The
 * page writes its text in the animation frame after a result arrives, so
 * a test that waited for the status then reads the text waits for it too.
 */
export async function waitText(page, selector, re, { not = false, attr = null, timeoutMs = 60000 } = {}) {
  const read = () =>
    page.evaluate(({ selector, attr }) => {
      const e = document.querySelector(selector);
      return e ? (attr ? e.getAttribute(attr) ?? '' : e.textContent) : null;
    }, { selector, attr });
  try {
    await page.waitForFunction(
      ({ selector, src, flags, not, attr }) => {
        const e = document.querySelector(selector);
        const t = e ? (attr ? e.getAttribute(attr) ?? '' : e.textContent) : null;
        return t !== null && new RegExp(src, flags).test(t) !== not;
      },
      { selector, src: re.source, flags: re.flags, not, attr },
      { timeout: timeoutMs },
    );
  } catch {
    throw new Error(`${selector}${attr ? ` [${attr}]` : ''} did not ${not ? 'stop matching' : 'match'} ${re} within ${timeoutMs} ms; it reads: ${await read()}`);
  }
  return read();
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

/**
 * Records each file the page offers as it offers it (the anchor with a
 * download name it clicks) in `window.offers`, `{ name, href }` each, to be
 * read back from its object URL.
 */
export async function recordOffers(page) {
  await page.evaluate(() => {
    window.offers = [];
    const click = HTMLAnchorElement.prototype.click;
    HTMLAnchorElement.prototype.click = function () {
      if (this.download) window.offers.push({ name: this.download, href: this.href });
      return click.call(this);
    };
  });
}

/** Saves a screenshot of the whole page or an element. */
export async function shot(pageOrLocator, name) {
  const file = path.join(SHOTS, `${name}.png`);
  await pageOrLocator.screenshot({ path: file, fullPage: pageOrLocator.url ? true : undefined });
  return file;
}

/**
 * The limit on one main-thread task's own work (ms): its CPU time on the
 * main thread, as the browser's trace records it (`tdur`).
 *
 * Not its wall-clock time: on this 2-core machine, with both of the page's
 * workers computing, a frame of 17 ms of main-thread work took 60-140 ms
 * by the clock, waiting for the browser's compositor and raster threads to
 * get a core (`node tests/browser/trace.mjs`, 2026-12-01); any other process on the
 * machine stretches it further. The CPU time is what the page's code spends
 * and what this limit is about; the wall-clock times are reported beside it.
 */
export const TASK_LIMIT_MS = 100;

/** Each watched page's trace session (see `watchMainThread`). */
const watches = new WeakMap();

/**
 * Starts watching the page's main thread: a browser trace (the DevTools
 * timeline's category) that records every task with its wall-clock and
 * CPU time, until `stopWatch`. With `detail`, also what ran inside the
 * long tasks (animation frames, commits, paints, garbage collection).
 */
export async function watchMainThread(page, { detail = false } = {}) {
  const cdp = await page.context().newCDPSession(page);
  const events = [];
  // Only what `stopWatch` reads: tasks over 50 ms (of every process: the
  // page's renderer is known at the end), thread names, the traced page,
  // and with `detail` every other event of 3 ms or more.
  const keep = (x) => {
    if (x.name === 'RunTask') return x.dur > 50000;
    if (x.name === 'thread_name' || x.name === 'TracingStartedInBrowser') return true;
    return detail && x.ph === 'X' && x.dur >= 3000;
  };
  cdp.on('Tracing.dataCollected', (e) => {
    for (const x of e.value) if (keep(x)) events.push(x);
  });
  const complete = new Promise((resolve) => cdp.once('Tracing.tracingComplete', resolve));
  const categories = detail ? 'devtools.timeline,disabled-by-default-devtools.timeline' : 'disabled-by-default-devtools.timeline';
  await cdp.send('Tracing.start', { categories, transferMode: 'ReportEvents' });
  watches.set(page, { cdp, events, complete });
}

/**
 * Stops the watch of `watchMainThread` and returns what it saw on the
 * page's main thread: { long, longCpu, longs, over, inside }: the longest
 * task by the clock, the largest CPU time of a task, every task over 50 ms
 * as [wall ms, CPU ms], those whose CPU time reaches `TASK_LIMIT_MS`, and
 * (with `detail`) per long task the events inside it as [name, ms].
 */
export async function stopWatch(page) {
  const w = watches.get(page);
  if (!w) throw new Error('stopWatch without watchMainThread');
  watches.delete(page);
  await w.cdp.send('Tracing.end');
  await w.complete;
  await w.cdp.detach();
  // The page's renderer: the process of the traced page's main frame.
  const started = w.events.find((e) => e.name === 'TracingStartedInBrowser');
  const pid = started?.args?.data?.frames?.find((f) => f.isOutermostMainFrame ?? true)?.processId;
  const main = w.events.find((e) => e.name === 'thread_name' && e.pid === pid && e.args?.name === 'CrRendererMain');
  if (!main) throw new Error(`the trace holds no main thread for the page (renderer ${pid})`);
  const onMain = w.events.filter((e) => e.ph === 'X' && e.pid === pid && e.tid === main.tid);
  const tasks = onMain.filter((e) => e.name === 'RunTask' && e.dur > 50000);
  const longs = tasks.map((e) => [Math.round(e.dur / 1000), Math.round((e.tdur ?? e.dur) / 1000)]);
  const inside = tasks.map((t) =>
    onMain
      .filter((e) => e !== t && e.ts >= t.ts && e.ts + e.dur <= t.ts + t.dur)
      .map((e) => [e.name, Math.round(e.dur / 100) / 10]),
  );
  return {
    long: Math.max(0, ...longs.map(([d]) => d)),
    longCpu: Math.max(0, ...longs.map(([, c]) => c)),
    longs,
    over: longs.filter(([, c]) => c >= TASK_LIMIT_MS),
    inside,
  };
}

/** One line on what `stopWatch` saw, for the test log. */
export function watchReport(beat) {
  const tasks = beat.longs.map(([d, c]) => `${d} ms (${c} ms CPU)`).join(', ');
  return `main-thread tasks over 50 ms by the clock: ${beat.longs.length}${tasks ? `: ${tasks}` : ''}; the most CPU time in one task ${beat.longCpu} ms (limit ${TASK_LIMIT_MS} ms)`;
}

/** Page coordinates of the data point (x, y) of a canvas whose frame is [l, t, r, b, x0, x1, y0, y1]. */
export async function pagePoint(page, canvasId, frame, x, y) {
  const [l, t, r, b, x0, x1, y0, y1] = frame;
  await page.locator(`#${canvasId}`).scrollIntoViewIfNeeded();
  const box = await page.locator(`#${canvasId}`).boundingBox();
  const width = await page.evaluate((id) => document.getElementById(id).width, canvasId);
  const scale = box.width / width;
  const px = l + ((x - x0) / (x1 - x0)) * (r - l);
  const py = b - ((y - y0) / (y1 - y0)) * (b - t);
  return [box.x + px * scale, box.y + py * scale];
}
