/**
 * A terminal's `contract generate` (another process, codegen's writeTree) and the IDE's saves of
 * a generated file, at once: each reads the file, merges, then writes it. Every save the server
 * answered 200 must still be on disk at the end — the field test lost 3 confirmed saves in 45
 * rounds when the two did not share the tree's write lock (codegen tree-lock.ts).
 */
import { describe, it, expect, beforeAll, afterAll } from 'vitest';
import { spawn } from 'node:child_process';
import { mkdtempSync, readFileSync, realpathSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { startIdeServer, type IdeServer } from './ide-server.js';

const CODEGEN = fileURLToPath(new URL('../../codegen/dist/index.js', import.meta.url));
const FILE = 'src-gen/generated/x.c';
const START = '/*PROTECTED REGION ID(user) ENABLED START*/';
const SAVES = 60;

let base: string;
let ide: IdeServer;

beforeAll(async () => {
  base = realpathSync(mkdtempSync(join(tmpdir(), 'ide-gen-race-')));
  ide = await startIdeServer({ workspace: base, port: 0, buildService: false, distDir: join(base, 'no-dist') });
});
afterAll(async () => {
  await ide?.close();
  rmSync(base, { recursive: true, force: true });
});

/**
 * A child process regenerating the tree, its skeleton changed each round (a model edited and
 * generated again): `rounds` times, or until the file `stop` exists.
 */
function generateInLoop(rounds: number): Promise<number | null> {
  const script = `
    const { existsSync } = await import('node:fs');
    const { writeTree } = await import(${JSON.stringify(CODEGEN)});
    const [out, rounds, stop] = [process.argv[1], Number(process.argv[2]), process.argv[3]];
    for (let round = 0; round < rounds && !existsSync(stop); round++) {
      const content = '/* skeleton ' + round + ' */\\nvoid f(void) {\\n${START}\\n/*PROTECTED REGION END*/\\n}\\n';
      const report = writeTree(out, [{ path: 'generated/x.c', content }]);
      if (report.errors.length) { console.error(JSON.stringify(report.errors)); process.exit(1); }
    }`;
  const child = spawn(process.execPath, ['--input-type=module', '-e', script, join(base, 'src-gen'), String(rounds), join(base, 'stop')], { stdio: ['ignore', 'inherit', 'inherit'] });
  return new Promise((resolve) => child.on('exit', (code) => resolve(code)));
}

const call = async (method: string, path: string, body?: string, extra: Record<string, string> = {}) => {
  const res = await fetch(ide.url + path, { method, headers: { 'x-contract-token': ide.token, ...extra }, body });
  return { status: res.status, body: (await res.json()) as Record<string, unknown> };
};

describe('contract generate in another process while the IDE saves a generated file', () => {
  it('loses no save the server confirmed: every tag answered 200 is in the region at the end', async () => {
    expect(await generateInLoop(1)).toBe(0);
    const generating = generateInLoop(100_000);
    const confirmed: string[] = [];
    let refused = 0;
    for (let i = 0; i < SAVES; i++) {
      const read = await call('GET', `/api/file?path=${FILE}`);
      const text = read.body.content as string;
      const tag = `/* save ${i} */`;
      const put = await call('PUT', `/api/file?path=${FILE}`, text.replace(START, `${START}\n${tag}`), { 'if-match': `"${read.body.version as string}"` });
      if (put.status === 200) confirmed.push(tag);
      else refused++; // stale: the generator wrote since the read (nothing written: the tab merges and saves again)
      await new Promise((r) => setTimeout(r, 5));
    }
    writeFileSync(join(base, 'stop'), '');
    expect(await generating).toBe(0);
    const disk = readFileSync(join(base, FILE), 'utf8');
    // both went on side by side: the generator wrote the file again and again, and saves landed between
    expect(Number(/skeleton (\d+)/.exec(disk)![1])).toBeGreaterThan(SAVES);
    expect(confirmed.length).toBeGreaterThan(2);
    expect(confirmed.filter((tag) => !disk.includes(tag))).toEqual([]);
    expect(refused + confirmed.length).toBe(SAVES);
  }, 120_000);
});

describe('contract rename in another process while the IDE saves a .contract file', () => {
  it('the save waits for the rename\'s lock, then finds the renamed file (409 stale, its text): neither the rename nor the typing is lost', async () => {
    const model = join(base, 'robot.contract');
    const loaded = 'synchronous module LOC { }\n';
    writeFileSync(model, loaded);
    const read = await call('GET', '/api/file?path=robot.contract');
    // the rename: holds the tree's lock, rewrites the model it loaded, releases (codegen tree-lock.ts)
    const script = `
      const { writeFileSync } = await import('node:fs');
      const { lockTreeSync } = await import(${JSON.stringify(CODEGEN)});
      const release = lockTreeSync(process.argv[1], 'src-gen');
      console.log('locked');
      await new Promise((r) => setTimeout(r, 1500));
      writeFileSync(process.argv[2], 'synchronous module LCX { }\\n');
      release();`;
    const child = spawn(process.execPath, ['--input-type=module', '-e', script, join(base, 'src-gen'), model], { stdio: ['ignore', 'pipe', 'inherit'] });
    // listened to from the start: the child may exit before the save's answer comes back
    const exited = new Promise((r) => child.on('exit', r));
    await new Promise<void>((resolve) => child.stdout!.once('data', () => resolve()));
    const typed = 'synchronous module LOC { } // typed\n';
    const put = await call('PUT', '/api/file?path=robot.contract', typed, { 'if-match': `"${read.body.version as string}"` });
    await exited;
    expect(put.status).toBe(409);
    expect(put.body.stale).toBe(true);
    expect(put.body.content).toBe('synchronous module LCX { }\n'); // the tab merges its typing into this
    expect(readFileSync(model, 'utf8')).toBe('synchronous module LCX { }\n');
  }, 60_000);
});
