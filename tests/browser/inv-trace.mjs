import { start, open, waitStatus } from './harness.mjs';
import fs from 'node:fs';
const h = await start();
const { page } = await open(h.browser, h.url, 'bif_points=40&fr_points=12&fr_record_periods=10&omega_from=0.3&omega_to=1.8');
const client = await page.context().newCDPSession(page);
const chunks = [];
client.on('Tracing.dataCollected', (e) => chunks.push(...e.value));
const done = new Promise((r) => client.on('Tracing.tracingComplete', r));
await client.send('Tracing.start', { categories: 'devtools.timeline,disabled-by-default-devtools.timeline,v8.execute,blink,cc', transferMode: 'ReportEvents' });
await waitStatus(page, (s) => s.bif.finished_ms, 240000, 'bif');
await client.send('Tracing.end');
await done;
// main thread: find the renderer main thread id (CrRendererMain)
const names = chunks.filter((e) => e.name === 'thread_name');
const main = names.find((e) => e.args.name === 'CrRendererMain');
const tid = main?.tid;
const tasks = chunks.filter((e) => e.tid === tid && e.ph === 'X' && e.name === 'RunTask' && e.dur > 50000).sort((a, b) => b.dur - a.dur).slice(0, 5);
for (const t of tasks) {
  const kids = chunks.filter((e) => e.tid === tid && e.ph === 'X' && e.ts >= t.ts && e.ts + (e.dur || 0) <= t.ts + t.dur && e.dur > 5000 && e !== t);
  const agg = {};
  for (const k of kids) agg[k.name] = (agg[k.name] || 0) + k.dur / 1000;
  console.log(Math.round(t.dur / 1000), 'ms:', JSON.stringify(Object.fromEntries(Object.entries(agg).map(([k, v]) => [k, Math.round(v)]))));
}
await page.close(); await h.close();
