import type { IncomingMessage, ServerResponse } from 'node:http';
import { createReadStream } from 'node:fs';
import { stat } from 'node:fs/promises';
import { join, extname, normalize, sep } from 'node:path';

const TYPES: Record<string, string> = {
  '.html': 'text/html; charset=utf-8',
  '.js': 'text/javascript; charset=utf-8',
  '.css': 'text/css; charset=utf-8',
  '.json': 'application/json',
  '.svg': 'image/svg+xml',
  '.ttf': 'font/ttf',
  '.woff2': 'font/woff2',
  '.png': 'image/png',
  '.map': 'application/json',
};

/**
 * Serves the Vite production build in `distDir`. An unknown path without an extension falls back
 * to index.html (the app's own routes); an unknown file (`/x.js`) is 404, a malformed percent
 * escape 400.
 */
export async function serveStatic(distDir: string, req: IncomingMessage, res: ServerResponse, url: URL): Promise<void> {
  let rel: string;
  try {
    rel = decodeURIComponent(url.pathname);
  } catch {
    res.writeHead(400, { 'content-type': 'text/plain' }).end('malformed percent escape in the path');
    return;
  }
  if (rel === '/' || rel === '') rel = '/index.html';
  const abs = normalize(join(distDir, rel));
  if (!abs.startsWith(distDir + sep)) {
    res.writeHead(403).end('forbidden');
    return;
  }
  let file = abs;
  let st = await stat(file).catch(() => undefined);
  if (!st || !st.isFile()) {
    if (extname(rel) && extname(rel) !== '.html') {
      res.writeHead(404, { 'content-type': 'text/plain' }).end('not found');
      return;
    }
    file = join(distDir, 'index.html');
    st = await stat(file).catch(() => undefined);
    if (!st) {
      res.writeHead(500, { 'content-type': 'text/plain' }).end('The IDE front end is not built: run `npm run build -w packages/web-ide`.');
      return;
    }
  }
  const immutable = file.includes(`${sep}assets${sep}`);
  res.writeHead(200, {
    'content-type': TYPES[extname(file)] ?? 'application/octet-stream',
    'content-length': st.size,
    'cache-control': immutable ? 'public, max-age=31536000, immutable' : 'no-cache',
  });
  if (req.method === 'HEAD') return void res.end();
  createReadStream(file).pipe(res);
}
