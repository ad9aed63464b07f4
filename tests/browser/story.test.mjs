
test('the bifurcation diagram draws the shooting branches, stable solid and unstable thin, each bifurcation explained', async () => {
  // The gear pair's branches are short (its period-1 branch turns back at
  // a fold near Ω 0.32), so the continuation finishes quickly.
  const { page, errors } = await open(h.browser, h.url, 'model=gear-pair&bif_points=40&lyap_points=0&map_omega_points=2&map_value_points=1');
  const s = await waitStatus(
    page,
    (x) => x.bif_branches && x.bif_branches.job.finished_ms && x.bif.finished_ms,
    240000,
    'the shooting branches',
  );
  const b = s.bif_branches;
  assert.ok(b.points > 3, JSON.stringify(b));
  assert.ok(b.stable_lines + b.unstable_lines >= 1, JSON.stringify(b));
  const label = await waitText(page, '#canvas-bif', /branches of periodic motion found by shooting/, { attr: 'aria-label' });
  assert.match(label, /stable and \d+ unstable stretches/);
  await page.locator('#view-bif').scrollIntoViewIfNeeded();
  await shot(page.locator('#view-bif'), '42-bif-shooting-branches');
  // One choice hides them.
  await page.selectOption('#sel-branches', 'off');
  await waitStatus(page, (x) => x.bif_branches.stable_lines + x.bif_branches.unstable_lines === 0, 10000, 'no branches');
  assert.deepEqual(errors, []);
  await page.close();
});
