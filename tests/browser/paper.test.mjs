// Browser test of the paper's figure presets: each figure
// preset, Figs. 2 and 3 both as the paper computed them (one harmonic) and
// as the converged branch, names the plotted quantity in plain words, the
// tooth deflection x with the TE included, in its caption (the preset's
// note) and in every claim whose button loads it.
import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import { start, open, waitStatus, waitText } from './harness.mjs';

const X_WORDS = 'tooth deflection x, TE included';

let h;
before(async () => {
  h = await start();
});
after(async () => {
  await h?.close();
});

test('every figure preset and its claims name x as the tooth deflection with the TE included', async () => {
  const { page, errors } = await open(h.browser, h.url, 'lyap_points=0&map_omega_points=2&map_value_points=1');
  await waitStatus(page, (s) => s.workers_ready === 2, 30000, 'the workers');
  const figures = await page.$$eval('#preset option', (os) => os
    .filter((o) => o.value.startsWith('fig'))
    .map((o) => ({ id: o.value, title: o.textContent })));
  const ids = figures.map((f) => f.id);
  for (const id of ['fig2', 'fig2h1', 'fig3', 'fig3h1', 'fig4', 'fig5', 'fig8', 'fig9', 'fig11']) {
    assert.ok(ids.includes(id), `${id} in ${ids}`);
  }
  // The one-harmonic presets sit one entry below the converged ones.
  assert.equal(ids.indexOf('fig2h1'), ids.indexOf('fig2') + 1);
  assert.equal(ids.indexOf('fig3h1'), ids.indexOf('fig3') + 1);
  await page.locator('#claims summary').click();
  let before = await page.textContent('#preset-note');
  const claimed = new Set();
  for (const f of figures) {
    await page.selectOption('#preset', f.id);
    // The page reports the preset by writing its note: wait for the new one.
    await page.waitForFunction((prev) => {
      const t = document.querySelector('#preset-note')?.textContent ?? '';
      return t !== '' && t !== prev;
    }, before, { timeout: 60000 });
    const note = await page.textContent('#preset-note');
    before = note;
    assert.ok(note.includes(X_WORDS), `${f.id}'s note: ${note}`);
    if (f.id.endsWith('h1')) {
      assert.match(note, /one harmonic/, f.id);
      await waitStatus(page, (s) => /harmonics=1(&|$)/.test(s.query), 10000, `${f.id}'s one harmonic`);
    }
    // Every claim whose button loads this figure names x the same way.
    const rows = await page.$$eval('#claims-rows tr', (trs, title) => trs
      .filter((tr) => tr.querySelector('button')?.getAttribute('title') === `Load the preset: ${title}`)
      .map((tr) => ({ id: tr.id, text: tr.textContent })), f.title);
    for (const r of rows) {
      assert.ok(r.text.includes(X_WORDS), `${r.id} (${f.id}): ${r.text}`);
      claimed.add(r.id);
    }
  }
  // Every numbered claim has its figure.
  for (const id of ['claim-1', 'claim-1b', 'claim-2', 'claim-3', 'claim-3b', 'claim-4', 'claim-4b', 'claim-5', 'claim-6', 'claim-7a', 'claim-7b', 'claim-8', 'claim-9', 'claim-10']) {
    assert.ok(claimed.has(id), `${id} loads a figure`);
  }
  await waitText(page, '#claim-3', /depends on a reading/);
  await waitText(page, '#claim-10', /impact-free windows below Ω 0\.8/);
  assert.deepEqual(errors, []);
  await page.close();
});
