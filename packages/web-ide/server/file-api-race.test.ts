/**
 * The file API under a racing attacker: another process swaps a workspace folder for a symlink to
 * a folder outside, in a loop, while many PUT / GET / DELETE requests name files in that folder.
 * Nothing may be written, read or deleted outside the workspace (docs/ide.md, "Localhost hardening").
 * Bounded: at most ROUNDS requests of each kind or DEADLINE_MS, whichever comes first.
 */
import { describe, it, expect, beforeEach, afterEach } from 'vitest';
import { SymlinkRacer } from '@contract-studio/codegen/test-support/symlink-racer';
import { mkdtempSync, mkdirSync, writeFileSync, readdirSync, readFileSync, rmSync, realpathSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { startIdeServer, type IdeServer } from './ide-server.js';

const ROUNDS = 1500;
const DEADLINE_MS = 25_000;
const PARALLEL = 12;

let base: string;
let ws: string;
let outside: string;
let ide: IdeServer;
let racer: SymlinkRacer | undefined;

/** Renames ws/proj away, puts a symlink to `outside` in its place, then restores it, until stopped. */
async function startRacer(): Promise<void> {
  racer = await SymlinkRacer.start({ folder: join(ws, 'proj'), target: outside, countFile: join(base, 'swaps'), linkSpin: 50_000, realSpin: 0, batch: 50 });
}

/** Stops the racer; resolves how many times it had swapped the folder for the symlink. */
async function stopRacer(): Promise<number> {
  const swaps = (await racer?.stop()) ?? 0;
  racer = undefined;
  return swaps;
}

function headers(): Record<string, string> {
  return { 'x-contract-token': ide.token };
}

/** Runs `count` calls of `one(i)` with PARALLEL in flight, stopping at the deadline; returns how many ran. */
async function hammer(count: number, one: (i: number) => Promise<void>): Promise<number> {
  const stopAt = Date.now() + DEADLINE_MS;
  let next = 0;
  const worker = async (): Promise<void> => {
    while (next < count && Date.now() < stopAt) await one(next++);
  };
  await Promise.all(Array.from({ length: PARALLEL }, worker));
  return next;
}

beforeEach(async () => {
  base = realpathSync(mkdtempSync(join(tmpdir(), 'ide-race-')));
  ws = join(base, 'ws');
  outside = join(base, 'outside');
  mkdirSync(join(ws, 'proj', 'sub'), { recursive: true });
  mkdirSync(outside);
  ide = await startIdeServer({ workspace: ws, port: 0, buildService: false, distDir: join(base, 'no-dist') });
});
afterEach(async () => {
  await stopRacer();
  await ide.close();
  rmSync(base, { recursive: true, force: true });
});

describe('file API against a folder swapped for a symlink', () => {
  it('PUT, create (files and folders) and rename never write outside the workspace', async () => {
    for (let i = 0; i < ROUNDS; i += 10) writeFileSync(join(ws, `m${i}.txt`), 'to move');
    await startRacer();
    const statuses = new Map<number, number>();
    const json = { ...headers(), 'content-type': 'application/json' };
    const ran = await hammer(ROUNDS, async (i) => {
      const path = i % 3 === 0 ? `proj/sub/f${i}.txt` : `proj/f${i}.txt`;
      const res = i % 10 === 0
        ? await fetch(`${ide.url}/api/rename`, { method: 'POST', headers: json, body: JSON.stringify({ from: `m${i}.txt`, to: path }) })
        : i % 10 === 5
          ? await fetch(`${ide.url}/api/create`, { method: 'POST', headers: json, body: JSON.stringify({ path: `proj/d${i}/inner`, type: 'dir' }) })
          : i % 5 === 4
            ? await fetch(`${ide.url}/api/create`, { method: 'POST', headers: json, body: JSON.stringify({ path, type: 'file', content: 'x' }) })
            : await fetch(`${ide.url}/api/file?path=${encodeURIComponent(path)}`, { method: 'PUT', headers: headers(), body: `file ${i}` });
      await res.arrayBuffer();
      statuses.set(res.status, (statuses.get(res.status) ?? 0) + 1);
    });
    const swaps = await stopRacer();
    const landed = readdirSync(outside, { recursive: true });
    console.log(`race PUT/create/rename: ${ran} requests, ${swaps} swaps, statuses ${JSON.stringify(Object.fromEntries(statuses))}, ${landed.length} landed outside`);
    expect(swaps).toBeGreaterThan(100);
    expect({ landedOutside: landed.length, ran }).toMatchObject({ landedOutside: 0 });
    expect(ran).toBeGreaterThan(100);
    // most requests met the real folder and succeeded; the others were refused, none crashed the server
    expect(statuses.get(200) ?? 0).toBeGreaterThan(0);
    expect(statuses.get(500) ?? 0).toBe(0);
  }, 90_000);

  it('GET never reads and DELETE never removes a file outside the workspace', async () => {
    for (let i = 0; i < 40; i++) {
      writeFileSync(join(outside, `v${i}.txt`), 'OUTSIDE');
      writeFileSync(join(ws, 'proj', `v${i}.txt`), 'inside');
    }
    writeFileSync(join(outside, 'secret.txt'), 'OUTSIDE');
    writeFileSync(join(ws, 'proj', 'secret.txt'), 'inside');
    await startRacer();
    const leaks: string[] = [];
    const ran = await hammer(ROUNDS, async (i) => {
      if (i < 40) {
        const res = await fetch(`${ide.url}/api/file?path=proj/v${i}.txt`, { method: 'DELETE', headers: headers() });
        await res.arrayBuffer();
        return;
      }
      const res = await fetch(`${ide.url}/api/file?path=proj/secret.txt`, { headers: headers() });
      const body = (await res.json()) as { content?: string };
      if (body.content === 'OUTSIDE') leaks.push(`GET ${i}`);
    });
    const tree = await fetch(`${ide.url}/api/tree`, { headers: headers() });
    await tree.arrayBuffer();
    const swaps = await stopRacer();
    console.log(`race GET/DELETE: ${ran} requests, ${swaps} swaps, ${leaks.length} outside reads`);
    expect(swaps).toBeGreaterThan(100);
    expect(ran).toBeGreaterThan(100);
    expect(leaks).toEqual([]);
    expect(readdirSync(outside).length).toBe(41);
    expect(readFileSync(join(outside, 'secret.txt'), 'utf8')).toBe('OUTSIDE');
  }, 90_000);
});
