// Browser test of the gear set's GIF export: the button offers a file
// named like the other exports (view, mesh, Ω), a real download, that is
// a GIF89a of the page's gear set canvas size, looping for ever, with the
// frames and the delay the page planned (one period of the orbit), and
// frames that differ, made without a long task on the page's main
// thread. The file's blocks are read here (a GIF's structure
// is simple); the pixels are decoded by the native test (page::gif).
// Every wait is for a state the page reports, never a time.
import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import fs from 'node:fs';
import { start, open, waitStatus, recordOffers, status, watchMainThread, stopWatch, watchReport } from './harness.mjs';

const QUICK = 'bif_points=16&transient_periods=120&record_periods=40&map_omega_points=8&map_value_points=4&lyap_points=8';

/** A GIF's screen size, loop count and frames (delay, image data bytes). */
function readGif(b) {
  const head = b.subarray(0, 6).toString('latin1');
  const width = b.readUInt16LE(6);
  const height = b.readUInt16LE(8);
  const flags = b[10];
  let i = 13;
  if (flags & 0x80) i += 3 * (1 << ((flags & 7) + 1));
  const frames = [];
  let loops = null;
  let delay = null;
  const subBlocks = () => {
    const parts = [];
    for (let n = b[i++]; n > 0; n = b[i++]) {
      parts.push(b.subarray(i, i + n));
      i += n;
    }
    return Buffer.concat(parts);
  };
  for (;;) {
    const t = b[i++];
    if (t === 0x3b) break;
    if (t === 0x21) {
      const label = b[i++];
      const data = subBlocks();
      if (label === 0xf9) delay = data.readUInt16LE(1);
      if (label === 0xff && data.subarray(0, 11).toString('latin1') === 'NETSCAPE2.0') loops = data.readUInt16LE(12);
    } else if (t === 0x2c) {
      const w = b.readUInt16LE(i + 4);
      const h = b.readUInt16LE(i + 6);
      const f = b[i + 8];
      i += 9;
      if (f & 0x80) i += 3 * (1 << ((f & 7) + 1));
      i++; // The LZW minimum code size.
      frames.push({ w, h, delay, data: subBlocks() });
    } else {
      throw new Error(`unknown block 0x${t?.toString(16)} at ${i - 1}`);
    }
  }
  return { head, width, height, loops, frames };
}

let h;
before(async () => {
  h = await start();
});
after(async () => {
  await h?.close();
});

test('the GIF button gives one period of the gear set in motion as a looping GIF', async () => {
  const { page, errors } = await open(h.browser, h.url, `${QUICK}&omega=0.35`);
  const s0 = await waitStatus(page, (x) => x.omega_job.finished_ms && x.anim && x.anim.frames >= 1 && x.draws[2] > 0, 120000, 'the motion computed and drawn');
  await recordOffers(page);
  const real = page.waitForEvent('download', { timeout: 120000 });
  await watchMainThread(page);
  await page.click('#anim-gif');
  const s = await waitStatus(page, (x) => x.gif && x.gif.frames > 0, 60000, 'the GIF made');
  // The frames are made a few at a time: the page stays responsive.
  const beat = await stopWatch(page);
  console.log(`# GIF: ${s.gif.frames} frames, ${s.gif.bytes} bytes; ${watchReport(beat)}`);
  assert.deepEqual(beat.over, [], watchReport(beat));
  assert.equal(await page.$eval('#anim-gif', (b) => b.disabled), false, 'the button is back');
  assert.deepEqual(s.issues, [], 'the period-1 orbit closes the loop, so nothing is said');
  const dl = await real;
  const name = dl.suggestedFilename();
  assert.equal(name, `gearshock-anim-s1a1-omega${s0.omega}.gif`);
  const offered = await page.evaluate(() => window.offers.map((o) => o.name));
  assert.deepEqual(offered, [name]);
  const bytes = fs.readFileSync(await dl.path());
  assert.equal(bytes.length, s.gif.bytes);
  const g = readGif(bytes);
  assert.equal(g.head, 'GIF89a');
  assert.deepEqual([g.width, g.height], [760, 600]);
  assert.equal(g.loops, 0, 'loops for ever');
  // One mesh period (period 1) in the page's steps: 64 samples, one frame
  // each, shown 1/64 of the 2 s a period takes at the default slow motion.
  assert.deepEqual([s.gif.span, s.gif.stride, s.gif.closes], [64, 1, true]);
  assert.equal(g.frames.length, s.gif.frames);
  assert.equal(g.frames.length, 64);
  for (const f of g.frames) {
    assert.deepEqual([f.w, f.h, f.delay], [760, 600, s.gif.delay_cs]);
  }
  assert.equal(s.gif.delay_cs, 3);
  const distinct = new Set(g.frames.map((f) => f.data.toString('base64')));
  assert.ok(distinct.size > 32, `${distinct.size} distinct frames of ${g.frames.length}`);
  // The page's own animation goes on as before.
  const after = await waitStatus(page, (x) => x.anim.frames > s.anim.frames, 60000, 'the animation running on');
  assert.ok((await status(page)).anim.playing && after.anim.frames > 0);
  assert.deepEqual(errors, []);
  await page.close();
});
