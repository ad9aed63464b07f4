// Browser tests of the page's one story: every view's words about the
// selected Ω come from the one classification of its steady state (the
// status's motion and impact), and where the frequency response's branch
// tells another story one sentence says both. Walked over the default
// page and the gear-pair preset at Ω 0.27, 1, 1.75 and 1.8; then Fig. 2
// (no backlash: a linear system) has no impact, no chaos, and its
// first-mode resonance on every member's curve.
import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import { start, open, waitStatus, waitText, shot } from './harness.mjs';

let h;
before(async () => {
  h = await start();
});
after(async () => {
  await h?.close();
});

// Light sweeps beside the frequency response and the selected Ω's state.
const LIGHT = 'bif_points=40&lyap_points=0&map_omega_points=2&map_value_points=1';
const PAIR = 'model=gear-pair&mesh=pg&omega_from=0.3&omega_to=2.5';

// What the student summary must say for each motion tag, and must not.
function motionWords(tag) {
  if (/^period 1 \(exact\)$/.test(tag)) return [/repeats exactly every mesh period/, /does not repeat|not periodic/];
  if (/^period \d+ \(exact\)$/.test(tag)) return [/repeats exactly every \d+ mesh periods/, /does not repeat|not periodic/];
  if (/still settling/.test(tag)) return [/still settling/, /does not repeat|exactly/];
  if (/^not periodic$/.test(tag)) return [/does not repeat/, /repeats exactly|repeats every/];
  if (/^repeats after/.test(tag)) return [/repeats only after/, /exactly/];
  return [/repeats every/, /does not repeat|exactly/];
}

// What the summary must say of the teeth for each impact name.
const IMPACT = {
  none: /stay in contact all the time/,
  'no-gap': /no backlash, so no gap/,
  'single-sided': /single-sided impact/,
  'double-sided': /double-sided impact/,
  'no-contact': /never touch/,
};

const settled = (s) => s.omega_result && !s.omega_result.preview && s.omega_job.finished_ms && s.fr.finished_ms;

async function walk(base, omega) {
  const { page, errors } = await open(h.browser, h.url, `${base}&omega=${omega}&${LIGHT}`);
  const s = await waitStatus(page, (x) => settled(x), 240000, `the state at Ω ${omega}`);
  const r = s.omega_result;
  const where = `${base} at Ω ${omega} (${r.motion}, ${r.impact})`;
  const text = async (sel, attr) => page.evaluate(([q, a]) => {
    const el = document.querySelector(q);
    return a ? el.getAttribute(a) : el.textContent;
  }, [sel, attr]);
  const [must, never] = motionWords(r.motion);
  // Written at the frame after the state arrived: waited for, then read.
  const summary = await waitText(page, '#summary', must, { timeoutMs: 120000 });
  assert.doesNotMatch(summary, never, `${where}: ${summary}`);
  assert.match(summary, IMPACT[r.impact], `${where}: ${summary}`);
  assert.match(summary, /^(Preview: )?At this speed the teeth/, `${where}: plain first: ${summary}`);
  // The orbit views name the same motion (their labels are written when
  // they are drawn: waited for, then read).
  const escaped = r.motion.replace(/[.*+?^${}()|[\]\\]/g, '\\$&');
  for (const id of ['#canvas-phase', '#canvas-poincare']) {
    await waitText(page, id, new RegExp(`, ${escaped}[,.]`), { attr: 'aria-label', timeoutMs: 120000 });
  }
  // The branch's sentence and the summary tell one story: where the
  // sentence calls the branch unstable at the selected Ω while the state
  // found is a stable orbit, both say so in words.
  const sentence = s.fr_sentence ?? '';
  const ranges = [...sentence.matchAll(/between Ω ([\d.]+) and ([\d.]+)/g)].map((m) => [Number(m[1]), Number(m[2])]);
  const inside = ranges.some(([a, b]) => omega >= a && omega <= b);
  if (inside && /\(exact\)/.test(r.motion)) {
    assert.match(sentence, /At the selected Ω/, `${where}: ${sentence}`);
    // The summary is rewritten at the frame after the branch finished:
    // waited for, not read at once.
    await waitText(page, '#summary', /The frequency response's branch/, { timeoutMs: 120000 });
  }
  if (/exact/.test(r.motion)) assert.doesNotMatch(summary, /does not repeat/, where);
  assert.deepEqual(errors, []);
  await page.close();
}

for (const [name, base] of [['the default page', 'model=ravigneaux'], ['the gear-pair preset', PAIR]]) {
  test(`${name}: every view tells the classification's story at Ω 0.27, 1, 1.75 and 1.8`, async () => {
    for (const omega of [0.27, 1, 1.75, 1.8]) await walk(base, omega);
  });
}

test('Fig. 2 (no backlash) shows no impact, no chaos, and the first mode on every member', async () => {
  const { page, errors } = await open(h.browser, h.url);
  await waitStatus(page, (s) => s.workers_ready === 2, 60000, 'the workers');
  await page.selectOption('#preset', 'fig2');
  const s = await waitStatus(
    page,
    (x) => x.family && x.family.values.length === 6 && x.fr.finished_ms && x.bif.finished_ms && x.lyap.finished_ms
      && x.family.members.every((m) => m.fr.finished_ms) && x.fr_first_mode_peaks?.length === 4
      && x.fr_first_mode_peaks.every((p) => p.length === 6),
    400000,
    'every member\'s branch, the diagram and the exponents',
  );
  // The first mode's resonance (Ω 0.2315) on every member's curve of every
  // mesh, growing with the TE (a linear response).
  for (const panel of s.fr_first_mode_peaks) {
    for (const [label, omega] of panel) assert.ok(Math.abs(omega - 0.2315) < 0.003, `${label} peaks at Ω ${omega}`);
    const values = panel.map((p) => p[2]);
    for (let k = 1; k < values.length; k++) assert.ok(values[k] > values[k - 1], JSON.stringify(panel));
  }
  const label = (id) => page.evaluate((q) => document.querySelector(q).getAttribute('aria-label'), id);
  const bif = await label('#canvas-bif');
  assert.doesNotMatch(bif, /impact/, bif);
  assert.match(bif, /no gap/, bif);
  const lyap = await label('#canvas-lyap');
  assert.doesNotMatch(lyap, /(?<!not )chaotic|: chaos/, lyap);
  const summary = await page.textContent('#summary');
  assert.doesNotMatch(summary, /impact|chaotic/, summary);
  await page.locator('#view-fr').scrollIntoViewIfNeeded();
  await shot(page.locator('#view-fr'), '42-fig2-peaks-on-every-member');
  assert.deepEqual(errors, []);
  await page.close();
});
