// The static server answers long share links with the page (so the page can
// show its own message about a too-long link) instead of HTTP 431, and still
// refuses request heads beyond its limit. Needs no browser.
import test from 'node:test';
import assert from 'node:assert/strict';
import fs from 'node:fs';
import http from 'node:http';
import os from 'node:os';
import path from 'node:path';
import { serve, MAX_HEADER_BYTES } from '../../scripts/static-server.mjs';

function get(url) {
  return new Promise((resolve, reject) => {
    http
      .get(url, (res) => {
        let body = '';
        res.on('data', (c) => (body += c));
        res.on('end', () => resolve({ status: res.statusCode, body }));
      })
      .on('error', reject);
  });
}

test('links of 16 to 64 KiB and percent-encoded ones get the page, not 431', async () => {
  const root = fs.mkdtempSync(path.join(os.tmpdir(), 'gearshock-serve-'));
  fs.writeFileSync(path.join(root, 'index.html'), '<p>page</p>');
  const { server, url } = await serve(root, 0);
  try {
    // 17 KiB was refused by Node's default 16 KiB head limit.
    for (const kib of [17, 32, 64]) {
      const query = `model=ravigneaux&x=${'1'.repeat(kib * 1024)}`;
      const r = await get(`${url}?${query}`);
      assert.equal(r.status, 200, `${kib} KiB`);
      assert.equal(r.body, '<p>page</p>');
    }
    // 64 Ki characters of three-byte UTF-8, as a browser sends them: 9 bytes each.
    const r = await get(`${url}?x=${'%E6%BC%A2'.repeat(64 * 1024)}`);
    assert.equal(r.status, 200);
    // Beyond the limit the head is still refused.
    const huge = await get(`${url}?x=${'1'.repeat(MAX_HEADER_BYTES + 1)}`).catch((e) => ({ status: e.code }));
    assert.notEqual(huge.status, 200);
  } finally {
    await new Promise((r) => server.close(r));
    fs.rmSync(root, { recursive: true, force: true });
  }
});
