// A tiny static file server for dist/ on 127.0.0.1, used by scripts/serve.sh
// and the browser tests. It serves .wasm as application/wasm (needed for
// streaming compilation), never lists directories and never leaves the root.
import http from 'node:http';
import fs from 'node:fs';
import path from 'node:path';

const TYPES = {
  '.html': 'text/html; charset=utf-8',
  '.js': 'text/javascript; charset=utf-8',
  '.mjs': 'text/javascript; charset=utf-8',
  '.wasm': 'application/wasm',
  '.css': 'text/css; charset=utf-8',
  '.svg': 'image/svg+xml',
  '.png': 'image/png',
  '.json': 'application/json',
};

/**
 * Largest request head (request line plus headers) in bytes. Node's default
 * (16 KiB) answers 431 to a long share link before the page can load and
 * say itself that the link is too long; the app reads links of up to 64 KiB
 * characters (MAX_LINK_CHARS), which a browser may send percent-encoded at
 * up to 9 bytes per character, so the limit leaves room for that.
 */
export const MAX_HEADER_BYTES = 1024 * 1024;

/** Starts serving `root`; resolves to { server, url } once listening. */
export function serve(root, port = 0, host = '127.0.0.1') {
  const base = path.resolve(root);
  const server = http.createServer({ maxHeaderSize: MAX_HEADER_BYTES }, (req, res) => {
    let rel;
    try {
      rel = decodeURIComponent(new URL(req.url, 'http://x').pathname);
    } catch {
      res.writeHead(400).end('bad request');
      return;
    }
    if (rel.endsWith('/')) rel += 'index.html';
    const file = path.resolve(base, '.' + rel);
    if (!file.startsWith(base + path.sep)) {
      res.writeHead(403).end('forbidden');
      return;
    }
    fs.readFile(file, (err, body) => {
      if (err) {
        res.writeHead(404, { 'content-type': 'text/plain' }).end('not found');
        return;
      }
      res.writeHead(200, {
        'content-type': TYPES[path.extname(file)] ?? 'application/octet-stream',
        'cache-control': 'no-store',
      });
      res.end(body);
    });
  });
  return new Promise((resolve, reject) => {
    server.once('error', reject);
    server.listen(port, host, () => {
      const { port: p } = server.address();
      resolve({ server, url: `http://${host}:${p}/` });
    });
  });
}

if (import.meta.url === `file://${process.argv[1]}`) {
  const root = process.argv[2] ?? 'dist';
  const port = Number(process.argv[3] ?? process.env.PORT ?? 8080);
  const { url } = await serve(root, port);
  console.log(`\n  gearshock explorer: ${url}\n  (serving ${root}; Ctrl-C to stop)\n`);
}
