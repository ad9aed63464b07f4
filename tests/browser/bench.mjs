// Benchmark of the explorer page in headless chromium (not part of the test
// command): bundle sizes, first paint, slider-input-to-redraw latency and the
// bifurcation sweep time on one and two workers (window.gearshockWorkers). Prints medians as Markdown for
// docs/browser-bench.md. Needs a release build in dist/:
//
//   scripts/setup.sh && source scripts/env.sh && trunk build --release --offline
//   node tests/browser/bench.mjs [--repeats N] [--quick] [--map] [--pool-only] [--family-only] [--branches-only] [--boundaries-only] [--slider-task-only]
import fs from 'node:fs';
import path from 'node:path';
import zlib from 'node:zlib';
import { start, open, status, waitStatus, watchMainThread, stopWatch, ROOT } from './harness.mjs';

const args = process.argv.slice(2);
const REPEATS = Number(args[args.indexOf('--repeats') + 1] || 5) || 5;
const QUICK = args.includes('--quick');
// --map adds the regime-map figure (100 x 40 cells of 300 + 100 periods: about
// a minute per run, --repeats runs at most 3); --map-only measures nothing else.
const MAP_ONLY = args.includes('--map-only');
const MAP = MAP_ONLY || args.includes('--map');
// --pool-only measures only the bifurcation sweep on 1 and 2 workers.
const POOL_ONLY = args.includes('--pool-only');
// --family-only measures only the main thread while a family of six draws
// its 1000-period orbits (the heaviest drawing the page makes).
const FAMILY_ONLY = args.includes('--family-only');
// --branches-only measures only the page at its defaults with the shooting
// branches on the bifurcation diagram (the default) and off.
const BRANCHES_ONLY = args.includes('--branches-only');
// --boundaries-only measures only the page at its defaults until the
// map's traced boundaries are drawn (on by default).
const BOUNDARIES_ONLY = args.includes('--boundaries-only');
// --slider-task-only measures only the largest main-thread task after a TE
// change (the preview and every view's redraw, both workers busy).
const SLIDER_TASK_ONLY = args.includes('--slider-task-only');
const ONLY = MAP_ONLY || POOL_ONLY || FAMILY_ONLY || BRANCHES_ONLY || BOUNDARIES_ONLY || SLIDER_TASK_ONLY;

// The views' slots in the status's per-view arrays (`last_draw_ms`, ...):
// their order in figures::views::VIEWS.
const VIEW_SLOTS = { fr: 0, bif: 1, phase: 2, poincare: 3, time: 4, spectrum: 5, map: 6, lyap: 7, campbell: 8, dynamic: 9, orders: 10 };

const median = (xs) => {
  const s = [...xs].sort((a, b) => a - b);
  const n = s.length;
  return n === 0 ? NaN : n % 2 ? s[(n - 1) / 2] : (s[n / 2 - 1] + s[n / 2]) / 2;
};
const fmt = (x) => (Number.isFinite(x) ? Math.round(x).toString() : 'n/a');
// "From job start" counts from when a job's messages were posted to the
// workers (the status's posted_ms): its start, or, for the jobs the page's
// start holds until the first screen's have ended (the sweep, the map,
// the Lyapunov curve, the branches, the boundaries), their release.
const ran = (j) => j.finished_ms - j.posted_ms;
const firstAfter = (j) => j.first_data_ms - j.posted_ms;

const results = [];
const row = (what, values, unit, note = '') => {
  results.push({ what, median: median(values), min: Math.min(...values), max: Math.max(...values), n: values.length, unit, note });
  console.error(`${what}: median ${fmt(median(values))} ${unit} (n = ${values.length}; ${values.map(fmt).join(', ')})`);
};

// Bundle sizes.
const dist = path.join(ROOT, 'dist');
for (const f of fs.readdirSync(dist).filter((f) => f.endsWith('.wasm'))) {
  const buf = fs.readFileSync(path.join(dist, f));
  const gz = zlib.gzipSync(buf, { level: 9 }).length;
  results.push({ what: `bundle ${f.replace(/-[0-9a-f]{16}/, '')}`, median: buf.length / 1024, unit: 'KiB', note: `gzip -9: ${Math.round(gz / 1024)} KiB`, n: 1 });
  console.error(`${f}: ${Math.round(buf.length / 1024)} KiB (gzip ${Math.round(gz / 1024)} KiB)`);
}

// The machine's load average (1 min) at the start and the end: the
// figures scale with it on a shared machine, so the tables state it.
const loadavg = () => (fs.existsSync('/proc/loadavg') ? fs.readFileSync('/proc/loadavg', 'utf8').split(' ')[0] : 'n/a');
const loadAtStart = loadavg();

const h = await start();
try {
  // First paint from a cold load: navigation start to the first drawn frame
  // of the frequency-response axes, and to its first computed points.
  if (!ONLY) {
    const paint = [];
    const firstFr = [];
    for (let i = 0; i < REPEATS; i++) {
      const { page } = await open(h.browser, h.url, 'bif_points=20');
      const s = await waitStatus(page, (s) => s.first_draw_ms.every((t) => t > 0) && s.fr.first_data_ms, 60000, 'first paint');
      paint.push(Math.max(...s.first_draw_ms));
      firstFr.push(s.fr.first_data_ms);
      await page.close();
    }
    row('first paint: every canvas drawn (axes, contact lines, cursor)', paint, 'ms', 'from navigation start');
    row('first frequency-response point received', firstFr, 'ms', 'from navigation start');

    // Slider input to redraw. One page; each input moves the backlash slider.
    {
      const { page } = await open(h.browser, h.url, 'bif_points=10&bif_dir=up');
      await waitStatus(page, (s) => s.fr.finished_ms && s.omega_job.finished_ms && s.bif.finished_ms, 120000, 'initial jobs');
      const frRedraw = [];
      const phase = [];
      const preview = [];
      const frDone = [];
      const frFirst = [];
      let partial = 0;
      const bifFirst = [];
      const n = QUICK ? 3 : Math.max(REPEATS, 8);
      for (let i = 0; i < n; i++) {
        const value = String(90 + 7 * (i % 2 ? i : -i) + i);
        const t0 = await page.evaluate((v) => {
          const el = document.getElementById('slider-backlash_um');
          el.value = v;
          const t = performance.now();
          el.dispatchEvent(new Event('input', { bubbles: true }));
          return t;
        }, value);
        const s1 = await waitStatus(page, (s) => s.last_draw_ms[0] > t0, 10000, 'frequency-response redraw');
        frRedraw.push(s1.last_draw_ms[0] - t0);
        const sp = await waitStatus(page, (s) => s.omega_job.preview_ms >= t0 && s.last_draw_ms[2] >= s.omega_job.preview_ms, 30000, 'phase portrait preview');
        preview.push(sp.last_draw_ms[2] - t0);
        const s2 = await waitStatus(page, (s) => s.omega_job.finished_ms && s.omega_job.started_ms >= t0 && s.last_draw_ms[2] >= s.omega_job.finished_ms, 30000, 'phase portrait');
        phase.push(s2.last_draw_ms[2] - t0);
        const s3 = await waitStatus(page, (s) => s.fr.finished_ms && s.fr.started_ms >= t0, 120000, 'frequency response complete');
        frDone.push(s3.fr.finished_ms - t0);
        frFirst.push(s3.fr.first_data_ms - t0);
        if (s3.fr_partial) partial += 1;
        const s4 = await waitStatus(page, (s) => s.bif.finished_ms && s.bif.started_ms >= t0, 120000, 'bifurcation complete');
        bifFirst.push(s4.bif.first_data_ms - t0);
      }
      row('slider input to redrawn frequency response (new ±b lines, previous curve faded)', frRedraw, 'ms');
      row('slider input to redrawn phase portrait, preview (20 + 10 periods on from the last state, main thread)', preview, 'ms');
      row('slider input to redrawn phase portrait, full steady state (300 + 100 periods, worker)', phase, 'ms');
      row('slider input to the first points of the new harmonic-balance branch', frFirst, 'ms');
      row('slider input to complete frequency response (harmonic balance, 150 nominal points, H = 5, Floquet stability, 1 worker)', frDone, 'ms', partial ? `${partial} of ${n} branches ended in a solver failure (partial)` : '');
      row('slider input to first bifurcation points (restarted sweep)', bifFirst, 'ms');
      await page.close();
    }
  }

  // Bifurcation: 200 Omega points x (300 + 100) periods (4 chains), on 1
  // and 2 workers (window.gearshockWorkers): the pool's scaling on this
  // 2-core machine. The two pool sizes alternate, so that the shared
  // machine's load falls on both alike.
  if (!ONLY || POOL_ONLY) {
    const points = QUICK ? 20 : 200;
    const reps = QUICK ? 1 : POOL_ONLY ? REPEATS : Math.min(REPEATS, 3);
    const total = { 1: [], 2: [] };
    const first = { 1: [], 2: [] };
    for (let i = 0; i < reps; i++) {
      for (const workers of [1, 2]) {
        // fr_points=2: the coarsest harmonic-balance branch, so that it takes
        // little time from the worker it shares with the bifurcation chains.
        const { page } = await open(h.browser, h.url, `bif_points=${points}&bif_dir=up&fr_points=2&transient_periods=300&record_periods=100&omega_from=0.1&omega_to=2&lyap_points=0`, workers);
        const s = await waitStatus(page, (s) => s.bif.finished_ms, 900000, 'bifurcation');
        if (s.workers !== workers) throw new Error(`asked for ${workers} workers, the page runs ${s.workers}`);
        total[workers].push(ran(s.bif));
        first[workers].push(firstAfter(s.bif));
        await page.close();
      }
    }
    for (const workers of [1, 2]) {
      const w = `${workers} worker${workers > 1 ? 's' : ''}`;
      row(`bifurcation: ${points} points x (300 + 100) periods, ${w}`, total[workers], 'ms', 'upward sweep, Omega 0.1..2, default model, 4 chains');
      row(`bifurcation: first partial frame, ${w}`, first[workers], 'ms', 'from job start');
    }
    const ratio = median(total[1]) / median(total[2]);
    results.push({ what: 'bifurcation: speed-up of 2 workers over 1', median: ratio, unit: 'x', note: 'ratio of the medians', n: 1, ratio: true });
    console.error(`bifurcation speed-up 1 -> 2 workers: ${ratio.toFixed(2)}x`);
  }

  // The page at its defaults (the bifurcation diagram of 100 points up and
  // down, the frequency response, the selected Omega, the map, the
  // Lyapunov curve) with the shooting branches on (the default) and off,
  // alternating: from navigation start until every job has ended and every
  // view has drawn after the last of them (the status's job times and the
  // views' last_draw_ms, both on the page's clock).
  if (!ONLY || BRANCHES_ONLY) {
    const jobsOf = (s) => [s.fr, s.fr_overlay, s.bif, s.omega_job, s.map, s.lyap, s.bif_branches?.job, s.map_boundaries?.job].filter(Boolean);
    const settled = (j) => j.id === 0 || j.finished_ms || j.error;
    const allDrawn = (s) => {
      const jobs = jobsOf(s);
      if (!jobs.every(settled) || !s.bif.finished_ms) return false;
      const last = Math.max(...jobs.map((j) => j.finished_ms || 0));
      return Math.max(...s.last_draw_ms) >= last && s.first_draw_ms.every((t) => t > 0);
    };
    // The first screen: the frequency response (its branch and, when on,
    // its dots) and the four views of the selected Omega (phase portrait,
    // Poincaré section, time history, spectrum) each drawn after its job
    // ended; the summary is written at the end of the frame that takes the
    // selected Omega's result, so with its views. Read at the first state
    // where it holds: the latest of those five draws.
    const FIRST = ['fr', 'phase', 'poincare', 'time', 'spectrum'].map((k) => VIEW_SLOTS[k]);
    const firstScreen = (s) => {
      const frJobs = [s.fr, s.fr_overlay].filter((j) => j.id !== 0);
      if (!frJobs.every((j) => j.finished_ms || j.error) || !s.omega_job.finished_ms) return false;
      const frEnd = Math.max(...frJobs.map((j) => j.finished_ms || 0));
      const [fr, ...omega] = FIRST.map((k) => s.last_draw_ms[k]);
      return fr >= frEnd && omega.every((t) => t >= s.omega_job.finished_ms);
    };
    const all = { on: [], off: [] };
    const first = { on: [], off: [] };
    const bif = { on: [], off: [] };
    const orbits = [];
    for (let i = 0; i < (QUICK ? 1 : REPEATS); i++) {
      for (const branches of ['on', 'off']) {
        const { page } = await open(h.browser, h.url, branches === 'on' ? '' : 'branches=off');
        const s0 = await waitStatus(page, firstScreen, 900000, 'the first screen drawn');
        first[branches].push(Math.max(...FIRST.map((k) => s0.last_draw_ms[k])));
        const s = await waitStatus(page, allDrawn, 900000, 'every view drawn');
        const job = s.bif_branches.job;
        if ((branches === 'on') !== (job.id !== 0)) throw new Error(`branches=${branches}, yet the shooting branches' job is ${JSON.stringify(job)}`);
        all[branches].push(Math.max(...s.last_draw_ms));
        bif[branches].push(ran(s.bif));
        if (branches === 'on') orbits.push(ran(job));
        await page.close();
      }
    }
    row('page defaults, shooting branches on (the default): first screen drawn', first.on, 'ms', 'from navigation start; summary, frequency response, selected Omega');
    row('page defaults, shooting branches off: first screen drawn', first.off, 'ms', 'from navigation start; link key branches=off');
    row('page defaults, shooting branches on (the default): every view drawn', all.on, 'ms', 'from navigation start; bifurcation 100 points up and down');
    row('page defaults, shooting branches off: every view drawn', all.off, 'ms', 'from navigation start; link key branches=off');
    row('page defaults: bifurcation sweep, branches on', bif.on, 'ms', 'from job start to its end');
    row('page defaults: bifurcation sweep, branches off', bif.off, 'ms', 'from job start to its end');
    row('page defaults: shooting branches job', orbits, 'ms', 'from job start to its end');
  }

  // The page at its defaults: from navigation start until the map's traced
  // boundaries are drawn (the trace ended and the map drawn after it, with
  // its curves), and the trace's own time on its worker.
  if (!ONLY || BOUNDARIES_ONLY) {
    const drawn = [];
    const trace = [];
    let traced = '';
    for (let i = 0; i < (QUICK ? 1 : REPEATS); i++) {
      // The link says boundaries=on: the same page as the default, also
      // measurable where they were off by default.
      const { page } = await open(h.browser, h.url, 'boundaries=on');
      const s = await waitStatus(
        page,
        (x) => {
          const j = x.map_boundaries.job;
          return x.map_boundaries.finished && j.finished_ms && x.map_drawn?.curve_paths > 0 && x.last_draw_ms[VIEW_SLOTS.map] >= j.finished_ms;
        },
        900000,
        'the boundaries drawn',
      );
      const b = s.map_boundaries;
      if (b.job.error) throw new Error(`the trace failed: ${b.job.error}`);
      drawn.push(s.last_draw_ms[VIEW_SLOTS.map]);
      trace.push(ran(b.job));
      traced = `${b.curves} curves (${JSON.stringify(b.kinds)})`;
      console.error(`run ${i + 1}: drawn at ${fmt(drawn.at(-1))} ms, trace ${fmt(trace.at(-1))} ms, load average ${loadavg()}`);
      await page.close();
    }
    row('page defaults: the map\'s boundaries drawn', drawn, 'ms', `from navigation start; ${traced}`);
    row('page defaults: the boundaries job', trace, 'ms', 'from job start to its end, on its worker');
  }

  // A family of six at 1000 recorded periods, Fig. 6's Omega 0.84 (most
  // orbits chaotic): the longest main-thread task and frame while the six
  // results arrive and their small multiples are drawn.
  if (FAMILY_ONLY) {
    const longest = [];
    const frame = [];
    const cpu = [];
    for (let i = 0; i < (QUICK ? 1 : REPEATS); i++) {
      const { page } = await open(h.browser, h.url, 'record_periods=1000&backlash_um=200&te_meshes=s1a&omega=0.84&family=te_um:0,10,20,30,40,50');
      await waitStatus(page, (s) => s.first_draw_ms.every((t) => t > 0), 60000, 'first paint');
      await watchMainThread(page);
      const done = (s) => s.family?.members.length === 5 && s.omega_job.finished_ms && s.family.members.every((m) => m.omega_job.finished_ms);
      const s0 = await waitStatus(page, done, 900000, 'the six results');
      const last = Math.max(s0.omega_job.finished_ms, ...s0.family.members.map((m) => m.omega_job.finished_ms));
      const s = await waitStatus(page, (s) => s.last_draw_ms[2] > last, 60000, 'the phase panels drawn');
      const beat = await stopWatch(page);
      longest.push(beat.long);
      frame.push(s.max_frame_ms);
      cpu.push(beat.longCpu);
      await page.close();
    }
    row('family of six at 1000 periods: longest main-thread task (wall clock)', longest, 'ms', 'from the first paint until the six orbits are drawn');
    row('family of six at 1000 periods: most main-thread CPU time in one task', cpu, 'ms', 'the limit the tests assert is 100 ms (harness.mjs)');
    row('family of six at 1000 periods: longest frame (drawing)', frame, 'ms', '');
  }

  // The largest main-thread task after a TE change, eight changes on one
  // page whose other jobs are small, each watched until every job ended.
  if (SLIDER_TASK_ONLY) {
    const q = 'bif_points=60&fr_points=12&fr_record_periods=10&omega_from=0.3&omega_to=1.8&branches=off&boundaries=off&map_omega_points=8&map_value_points=4&lyap_points=4';
    const { page } = await open(h.browser, h.url, q);
    const done = (s) => ['fr', 'omega_job', 'bif', 'map', 'lyap'].every((k) => s[k].finished_ms);
    let s0 = await waitStatus(page, done, 240000, 'the first jobs');
    const cpu = [];
    for (let i = 0; i < (QUICK ? 3 : Math.max(REPEATS, 8)); i++) {
      await watchMainThread(page);
      await page.fill('#num-te_um', String(12 + 2 * i));
      await page.press('#num-te_um', 'Enter');
      const s = await waitStatus(page, (x) => x.bif.id > s0.bif.id && done(x), 240000, 'the jobs after the change');
      cpu.push((await stopWatch(page)).longCpu);
      s0 = s;
    }
    row('largest main-thread task after a TE change (CPU)', cpu, 'ms', 'both workers busy; tasks over 50 ms by the clock, else 0');
    await page.close();
  }

  // Regime map: 100 x 40 cells x (300 + 100) periods, two workers (opt-in).
  if (MAP) {
    const total = [];
    const longest = [];
    const cpu = [];
    for (let i = 0; i < (QUICK ? 1 : Math.min(REPEATS, 3)); i++) {
      const { page } = await open(h.browser, h.url, 'map_omega_points=100&map_value_points=40&map_transient_periods=300&map_record_periods=100&bif_points=2&fr_points=2&lyap_points=0&omega_from=0.1&omega_to=2');
      await waitStatus(page, (s) => s.first_draw_ms.every((t) => t > 0), 60000, 'first paint');
      await watchMainThread(page);
      const s = await waitStatus(page, (s) => s.map.finished_ms, 900000, 'regime map');
      const beat = await stopWatch(page);
      total.push(ran(s.map));
      longest.push(beat.long);
      cpu.push(beat.longCpu);
      await page.close();
    }
    row('regime map: 100 x 40 cells x (300 + 100) periods, 2 workers', total, 'ms', 'backlash rows, Omega 0.1..2, default model');
    row('regime map: longest main-thread task while it runs, wall clock (0: none over 50 ms)', longest, 'ms', 'from the first paint on');
    row('regime map: most main-thread CPU time in one such task', cpu, 'ms', 'the limit the tests assert is 100 ms (harness.mjs)');
  }
} finally {
  await h.close();
}

console.log(`Load average (1 min): ${loadAtStart} at the start, ${loadavg()} at the end.`);
console.log('');
console.log('| measurement | median | unit | range (n) | note |');
console.log('|---|---:|---|---|---|');
for (const r of results) {
  const range = r.n > 1 ? `${fmt(r.min)} .. ${fmt(r.max)} (${r.n})` : '';
  const value = r.ratio ? r.median.toFixed(2) : fmt(r.median);
  console.log(`| ${r.what} | ${value} | ${r.unit} | ${range} | ${r.note} |`);
}
