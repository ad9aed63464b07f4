// What blocks the page's main thread: opens the page at a link's query,
// watches its main thread from the first paint until the views are drawn
// after every job finished (or until `--family`: the family members'
// selected-Omega results are drawn), and prints each task over 50 ms with
// its wall-clock and CPU time and what ran inside it (animation frames,
// commits, paints, garbage collection).
//   node tests/browser/trace.mjs 'QUERY' [--family] [--workers N]
import { start, open, waitStatus, watchMainThread, stopWatch, watchReport } from './harness.mjs';

const args = process.argv.slice(2);
const query = args.find((a) => !a.startsWith('--')) ?? '';
const at = args.indexOf('--workers');
const workers = at >= 0 ? Number(args[at + 1]) : undefined;
const family = args.includes('--family');

const finished = (j) => !j || j.id === 0 || j.finished_ms || j.error;
const drawnAfter = (s, slot, t) => s.last_draw_ms[slot] > t;
const done = family
  ? (s) => {
      const members = s.family?.members ?? [];
      if (!s.omega_job.finished_ms || !members.every((m) => m.omega_job.finished_ms)) return false;
      return drawnAfter(s, 2, Math.max(s.omega_job.finished_ms, ...members.map((m) => m.omega_job.finished_ms)));
    }
  : (s) => [s.fr, s.bif, s.map, s.lyap, s.omega_job].every(finished) && drawnAfter(s, 0, s.fr.finished_ms ?? 0);

const h = await start();
try {
  const { page } = await open(h.browser, h.url, query, workers);
  await waitStatus(page, (s) => s.first_draw_ms.every((t) => t > 0), 60000, 'the first paint');
  await watchMainThread(page, { detail: true });
  await waitStatus(page, done, 900000, 'the results, drawn');
  const beat = await stopWatch(page);
  console.log(watchReport(beat));
  beat.longs.forEach(([wall, cpu], k) => {
    console.log(`task ${wall} ms by the clock, ${cpu} ms CPU:`);
    for (const [name, ms] of beat.inside[k].filter(([n]) => !['v8.callFunction', 'FunctionCall'].includes(n))) console.log(`  ${name} ${ms} ms`);
  });
  await page.close();
} finally {
  await h.close();
}
