/** GET /api/log: a run's CSV log of the workspace for a replay, past the editor's 8 MiB bound, never through a link or a FIFO. */
import { describe, it, expect, beforeAll, afterAll } from 'vitest';
import { execFileSync } from 'node:child_process';
import { mkdirSync, writeFileSync, symlinkSync, truncateSync } from 'node:fs';
import { join } from 'node:path';
import type { IdeServer } from './ide-server.js';
import { startTempIdeServer, type TempIdeServer } from './temp-ide-server.test-support.js';
import { LOG_READ_BYTES } from './log-api.js';

let base: string;
let ws: string;
let ide: IdeServer;
let big: string;

let server: TempIdeServer;
beforeAll(async () => {
  server = await startTempIdeServer('ide-log-api-', { prepare: (b, w) => {
    base = b;
    ws = w;
    mkdirSync(join(ws, 'logs'), { recursive: true });
    // 9.5 MiB of a 1 kHz schema's releases: past GET /api/file's 8 MiB
    const lines = ['mono_ns,wall_time,module,event,peer,port,size,detail'];
    for (let i = 0; lines.length < 90_000; i++) lines.push(`${1_000_000_000 + i * 1_000_000},w,ORD,ord_release,CTL,,0,schema=S cycle=${i} tick_ns=${1_000_000_000 + i * 1_000_000} release_ns=${1_000_000_100 + i * 1_000_000} release=${i + 1}`);
    big = lines.join('\n') + '\n';
    writeFileSync(join(ws, 'logs', 'ORD_29-Nov-2026-10h00m00s.csv'), big);
    writeFileSync(join(ws, 'logs', 'empty_1.csv'), '');
    writeFileSync(join(ws, 'notes.txt'), 'not a log');
    writeFileSync(join(ws, 'logs', 'run.jsonl'), '{"kind":"module_started"}\n');
    writeFileSync(join(ws, 'huge_1.csv'), '');
    truncateSync(join(ws, 'huge_1.csv'), LOG_READ_BYTES + 1); // sparse: no disk used
    writeFileSync(join(base, 'secret.csv'), 'secret');
    symlinkSync(join(base, 'secret.csv'), join(ws, 'logs', 'link_1.csv'));
    execFileSync('mkfifo', [join(ws, 'logs', 'fifo_1.csv')]);
    // 300 one-record logs: past a replay's 256
    mkdirSync(join(ws, 'many'));
    for (let i = 0; i < 300; i++) writeFileSync(join(ws, 'many', `M${String(i).padStart(3, '0')}_1.csv`), `mono_ns,wall_time,module,event,peer,port,size,detail\n${i},w,M,module_started,,,0,pid=1\n`);
    symlinkSync(join(base), join(ws, 'many', 'dir_1.csv'));
    mkdirSync(join(ws, 'many', 'sub_1.csv'));
    symlinkSync(join(ws, 'logs'), join(ws, 'linked-logs'));
  } });
  ({ base, ws, ide } = server);
});
afterAll(() => server.close());

const get = (path: string) => fetch(`${ide.url}${path}`, { headers: { 'x-contract-token': ide.token } });

describe('GET /api/log', () => {
  it('gives a log past 8 MiB whole, as text, where GET /api/file refuses it', async () => {
    expect(big.length).toBeGreaterThan(8 * 1024 * 1024);
    const file = await get('/api/file?path=logs/ORD_29-Nov-2026-10h00m00s.csv');
    expect(file.status).toBe(413);
    const log = await get('/api/log?path=logs/ORD_29-Nov-2026-10h00m00s.csv');
    expect(log.status).toBe(200);
    expect(log.headers.get('content-type')).toMatch(/^text\/plain/);
    expect(await log.text()).toBe(big);
    // a trace file (contract run --trace) is read the same way
    expect(await (await get('/api/log?path=logs/run.jsonl')).text()).toBe('{"kind":"module_started"}\n');
    const empty = await get('/api/log?path=logs/empty_1.csv');
    expect(empty.status).toBe(200);
    expect(await empty.text()).toBe('');
  });

  it('sends the first LOG_READ_BYTES of a longer log, saying its size and the bytes sent (it was refused whole: 413)', async () => {
    const res = await get('/api/log?path=huge_1.csv');
    expect(res.status).toBe(200);
    expect(res.headers.get('x-log-bytes')).toBe(String(LOG_READ_BYTES + 1));
    expect(res.headers.get('x-log-sent')).toBe(String(LOG_READ_BYTES));
    // counted as it streams, not held
    let n = 0;
    const reader = res.body!.getReader();
    for (let r = await reader.read(); !r.done; r = await reader.read()) n += r.value.length;
    expect(n).toBe(LOG_READ_BYTES);
  });

  it('refuses what is not a CSV log of the workspace, each with its reason', async () => {
    const cases: Array<[string, number, RegExp]> = [
      ['notes.txt', 400, /not a CSV log \(\*\.csv\) nor a trace file/],
      ['logs/link_1.csv', 403, /link/i],
      ['logs/fifo_1.csv', 400, /not a regular file/],
      ['../secret.csv', 403, /'\.\.'/],
      ['logs/none.csv', 404, /./],
    ];
    for (const [path, status, why] of cases) {
      const res = await get(`/api/log?path=${encodeURIComponent(path)}`);
      expect(res.status, path).toBe(status);
      expect(((await res.json()) as { error: string }).error, path).toMatch(why);
    }
  });

  it('needs the session token', async () => {
    expect((await fetch(`${ide.url}/api/log?path=logs/empty_1.csv`)).status).toBe(401);
  });
});

describe('GET /api/log-folder', () => {
  it('lists the logs a replay reads, and says which entries it does not read and why', async () => {
    const res = await get('/api/log-folder?path=logs');
    expect(res.status).toBe(200);
    expect(await res.json()).toEqual({
      logs: ['logs/ORD_29-Nov-2026-10h00m00s.csv', 'logs/empty_1.csv'], // by name, as contract trace orders them
      sizes: [Buffer.byteLength(big), 0], // each log's bytes: a replay reads the small ones first under its bound
      more: 0,
      max: 256,
      notRead: ['fifo_1.csv: a FIFO, not read', 'link_1.csv: a symbolic link, not read (logs are never read through a link)'],
      notReadCount: 2,
    });
    const root = (await (await get('/api/log-folder?path=')).json()) as { logs: string[] };
    expect(root.logs).toEqual(['huge_1.csv']);
  });

  it('tells the crash sites of the folder\'s crash files (MODULE.crash), unmapped; a hostile one is not read', async () => {
    const block = (m: string, obj = 'exe') => [`==contract-crash== module ${m} signal 11 SIGSEGV addr 0x0`, '==contract-crash== build-id 0011aabb', `==contract-crash== frame 0 ${obj} 0x40d8`, '==contract-crash== frame 1 libc.so.6 0x2724a', '==contract-crash== end 2 frames', ''].join('\n');
    mkdirSync(join(ws, 'crashed'));
    writeFileSync(join(ws, 'crashed', 'EST_1.csv'), 'mono_ns,wall_time,module,event,peer,port,size,detail\n');
    writeFileSync(join(ws, 'crashed', 'EST.crash'), block('EST'));
    writeFileSync(join(ws, 'crashed', 'MSC.crash'), block('EST')); // EST's report in MSC's file
    writeFileSync(join(ws, 'crashed', 'SUP.crash'), block('SUP', '/etc/passwd'));
    symlinkSync(join(ws, 'crashed', 'EST.crash'), join(ws, 'crashed', 'ORD.crash'));
    const listing = (await (await get('/api/log-folder?path=crashed')).json()) as { logs: string[]; crashSites?: string[] };
    expect(listing.logs).toEqual(['crashed/EST_1.csv']);
    expect(listing.crashSites).toEqual([
      'EST crashed: signal 11 (SIGSEGV) at address 0x0 (a bad pointer: NULL, freed, or past the end of an array), executable build-id 0011aabb',
      '  #0 the executable+0x40d8',
      '  #1 libc.so.6+0x2724a',
      "  not mapped to the code: `contract trace crashed` maps them to files and lines when the module's executable of that build is beside the logs (crashed/../modules/EST_mod/EST)",
      "  map them with EST's executable of the build that crashed (its build-id must be 0011aabb: `readelf -n` shows it): addr2line -f -i -e ARCH/modules/EST_mod/EST 0x40d8 " +
        "(ARCH: the generated architecture folder it was built in, a project's src-gen/generated/architecture; each caller's return address less 1: its call)",
      ...['MSC', 'ORD', 'SUP'].map((m) => `crashed/${m}.crash: not read (a crash file is a regular file of at most 32768 bytes holding one crash report of the module it is named after)`),
    ]);
    // no crash file: no crashSites
    expect('crashSites' in ((await (await get('/api/log-folder?path=logs')).json()) as object)).toBe(false);
  });

  it("sends the end lines of the folder's contract-launch.log (the launcher's own lines), each with its time; a link there is not read, said", async () => {
    mkdirSync(join(ws, 'launched'));
    writeFileSync(join(ws, 'launched', 'MAB_1.csv'), 'mono_ns,wall_time,module,event,peer,port,size,detail\n');
    writeFileSync(join(ws, 'launched', 'contract-launch.log'), '100 run directory /x\n300 module MAB (pid 41) died by signal 9 (Killed)\n200 module MAA (pid 40) exited with status 3\nnot a line\n400 module MSC (pid 42) died by signal 9 (Killed)');
    const listing = (await (await get('/api/log-folder?path=launched')).json()) as { logs: string[]; launcherLines?: unknown; launcherLinesProblem?: string };
    expect(listing.logs).toEqual(['launched/MAB_1.csv']); // the file is no log
    // end lines only, in time order; the last one, cut (no line end), is none
    expect(listing.launcherLines).toEqual([{ monoNs: '200', line: 'module MAA (pid 40) exited with status 3' }, { monoNs: '300', line: 'module MAB (pid 41) died by signal 9 (Killed)' }]);
    expect(listing.launcherLinesProblem).toBeUndefined();
    mkdirSync(join(ws, 'linked-launcher'));
    symlinkSync(join(ws, 'launched', 'contract-launch.log'), join(ws, 'linked-launcher', 'contract-launch.log'));
    const linked = (await (await get('/api/log-folder?path=linked-launcher')).json()) as { launcherLines?: unknown; launcherLinesProblem?: string };
    expect(linked.launcherLines).toBeUndefined();
    expect(linked.launcherLinesProblem).toMatch(/^linked-launcher\/contract-launch\.log: not read \(/);
  });

  it('past 256 logs: the first 256 by name, the others counted', async () => {
    const many = (await (await get('/api/log-folder?path=many')).json()) as { logs: string[]; more: number; notRead: string[]; notReadCount: number };
    expect(many.logs).toHaveLength(256);
    expect(many.logs[0]).toBe('many/M000_1.csv');
    expect(many.logs.at(-1)).toBe('many/M255_1.csv');
    expect(many.more).toBe(44);
    expect(many.notRead).toEqual(['dir_1.csv: a symbolic link, not read (logs are never read through a link)', 'sub_1.csv: a folder, not read']);
    expect(many.notReadCount).toBe(2);
  });

  it('refuses a folder reached through a link, or outside the workspace, and needs the token', async () => {
    const cases: Array<[string, number, RegExp]> = [
      ['linked-logs', 403, /link/i],
      ['../', 403, /'\.\.'/],
      ['/etc', 403, /absolute/],
      ['none', 404, /not found/],
    ];
    for (const [path, status, why] of cases) {
      const res = await get(`/api/log-folder?path=${encodeURIComponent(path)}`);
      expect(res.status, path).toBe(status);
      expect(((await res.json()) as { error: string }).error, path).toMatch(why);
    }
    expect((await fetch(`${ide.url}/api/log-folder?path=logs`)).status).toBe(401);
  });
});
