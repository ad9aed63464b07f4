// A second headless chromium beside the browser suite (the load it makes):
// it loads the page at its defaults, waits until the page reports every
// view computed (or 120 s), closes it and loads it again, until killed.
// scripts/test-under-load.sh runs it with two busy loops while the suite
// runs, so that the suite's tests must wait for the events the page
// reports, never for an order of events that the machine's speed decides.
import { start, open, waitStatus } from './harness.mjs';

const h = await start();
let loads = 0;
let stopping = false;
const stop = async () => {
  stopping = true;
  await h.close();
  process.exit(0);
};
process.on('SIGTERM', stop);
process.on('SIGINT', stop);
while (!stopping) {
  try {
    const { page } = await open(h.browser, h.url, '');
    loads += 1;
    await waitStatus(page, (s) => s.fr.finished_ms && s.bif.finished_ms && s.omega_job.finished_ms && s.map.finished_ms, 120000, 'every view').catch(() => {
      // A slow load is fine here: the point is the load on the machine.
    });
    await page.close();
    console.log(`beside: ${loads} page loads`);
  } catch (e) {
    // The browser closes under the loop when the script is stopped.
    if (!stopping) throw e;
  }
}
