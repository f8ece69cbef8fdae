import { describe, it, expect, afterEach, vi } from 'vitest';
import { createServer, type Server } from 'node:http';
import type { AddressInfo } from 'node:net';
import { activationsFromLogs, fetchJobLogs, localLogFolders, partlyReadText, readWorkspaceLogs, replayOrder } from './run-logs.js';
import { PIECE_CHARS, responsePieces } from '../api.js';

const HEADER = 'mono_ns,wall_time,module,event,peer,port,size,detail';
const log = (m: string, starts: number[]) =>
  [HEADER, ...starts.flatMap((t) => [`${t},w,${m},run_started,ORD,,0,`, `${t + 5},w,${m},run_finished,,,0,`])].join('\n') + '\n';

describe('run logs', () => {
  it('reads a log\'s body chunk by chunk into the text text() gives: a character split across chunks, a bad byte, an empty body', async () => {
    const bytes = new TextEncoder().encode(`${HEADER}\n1,w,MAA,user,,,0,température 12 € ✓\n`);
    const withBad = new Uint8Array([...bytes, 0xff, 0x41, 0xe2, 0x82]); // a lone 0xff, then a character cut at the end
    for (const body of [bytes, withBad, new Uint8Array()]) {
      // every split point: 1-byte chunks
      const chunked = new Response(new ReadableStream({ start(c) { for (const b of body) c.enqueue(new Uint8Array([b])); c.close(); } }));
      expect((await responsePieces(chunked)).join('')).toBe(await new Response(body).text());
    }
    expect(await responsePieces(new Response(new Uint8Array()))).toEqual([]);
  });

  it('reads a long body in pieces of whole lines, none joined longer than a piece but a line longer than one', async () => {
    const line = (i: number) => `${1000 + i},w,MSC,run_started,ORD,,0,activation=${i} ${'x'.repeat(i % 90)}\n`;
    let text = '';
    for (let i = 0; text.length < 3.5 * PIECE_CHARS; i++) text += line(i);
    const long = 'y'.repeat(PIECE_CHARS + 12345); // one line longer than a piece, then one without a line end
    for (const body of [text, text + long + '\n' + text, text + long]) {
      const bytes = new TextEncoder().encode(body);
      // 64 KiB chunks, as a socket gives them, cut anywhere
      const chunked = new Response(new ReadableStream({ start(c) { for (let at = 0; at < bytes.length; at += 65_531) c.enqueue(bytes.subarray(at, at + 65_531)); c.close(); } }));
      const pieces = await responsePieces(chunked);
      expect(pieces.join('')).toBe(body);
      expect(pieces.length).toBeGreaterThan(3);
      pieces.slice(0, -1).forEach((p) => expect(p.endsWith('\n')).toBe(true));
      for (const p of pieces) if (!p.includes(long)) expect(p.length).toBeLessThan(PIECE_CHARS + 65_531);
    }
  });

  it('merges the activations of several module logs in start order, and names an unreadable file', () => {
    const { acts, errors } = activationsFromLogs([
      { name: 'MSC_x.csv', text: log('MSC', [30, 10]) },
      { name: 'MSA_x.csv', text: log('MSA', [20]) },
      { name: 'junk.csv', text: 'a,b\n1,2\n' },
    ]);
    expect(acts.map((a) => `${a.module}@${a.start}-${a.end}`)).toEqual(['MSC@10-15', 'MSA@20-25', 'MSC@30-35']);
    expect(errors).toHaveLength(1);
    expect(errors[0]).toMatch(/^junk\.csv: not a ContrACT CSV log/);
  });

  describe('fetchJobLogs over HTTP (the artifacts API of docs/build-service-api.md)', () => {
    let server: Server | undefined;
    afterEach(() => new Promise<void>((r) => (server ? server.close(() => r()) : r())));

    async function serve(routes: Record<string, [number, string]>): Promise<typeof fetch> {
      server = createServer((req, res) => {
        const [status, body] = routes[req.url ?? ''] ?? [404, JSON.stringify({ error: `no route ${req.url}`, code: 'not_found' })];
        res.writeHead(status, { 'content-type': body.startsWith('{') ? 'application/json' : 'text/csv' });
        res.end(body);
      });
      await new Promise<void>((r) => server!.listen(0, '127.0.0.1', () => r()));
      const base = `http://127.0.0.1:${(server!.address() as AddressInfo).port}`;
      return ((url: string) => fetch(base + url)) as typeof fetch;
    }

    it('downloads every CSV of the listing and reports skipped or missing logs as problems (not other artifacts)', async () => {
      const listing = {
        id: 'j 1', status: 'succeeded',
        artifacts: {
          files: [{ name: 'MSC_1.csv', size: 1 }, { name: 'MSA_1.csv', size: 1, capped: 'the module reached its CSV log bound (CONTRACT_LOG_MAX_BYTES): later records were not written' }, { name: 'gone.csv', size: 1 }, { name: 'core.bin', size: 1 }],
          skipped: [{ name: 'planted.csv', reason: 'not a regular file (symlink): not followed' }, { name: 'core', reason: '3000000000 bytes, above the 268435456-byte file bound' }], runDirLeftovers: [], collect_ms: 1,
        },
      };
      const f = await serve({
        '/api/jobs/j%201/artifacts': [200, JSON.stringify(listing)],
        '/api/jobs/j%201/artifacts/MSC_1.csv': [200, log('MSC', [1, 11])],
        '/api/jobs/j%201/artifacts/MSA_1.csv': [200, log('MSA', [2])],
      });
      const logs = await fetchJobLogs('j 1', f);
      expect(logs.label).toBe('Build & Run job j 1');
      expect(logs.files.map((x) => x.name)).toEqual(['MSC_1.csv', 'MSA_1.csv']);
      expect(activationsFromLogs(logs.files).acts).toHaveLength(3);
      expect(logs.problems).toHaveLength(3);
      expect(logs.problems[0]).toMatch(/planted\.csv: not a regular file/);
      expect(logs.problems[1]).toBe('MSA_1.csv: not whole: the module reached its CSV log bound (CONTRACT_LOG_MAX_BYTES): later records were not written');
      expect(logs.problems[2]).toMatch(/gone\.csv: HTTP 404 no route/);
    });

    it('downloads no more than its byte bound in all: the logs past it are named, not fetched', async () => {
      const listing = { id: 'j', status: 'succeeded', artifacts: { files: [{ name: 'A_1.csv', size: 60 }, { name: 'B_1.csv', size: 50 }, { name: 'C_1.csv', size: 30 }], skipped: [] } };
      const fetched: string[] = [];
      const f = await serve({
        '/api/jobs/j/artifacts': [200, JSON.stringify(listing)],
        '/api/jobs/j/artifacts/A_1.csv': [200, log('A', [1])],
        '/api/jobs/j/artifacts/B_1.csv': [200, log('B', [2])],
        '/api/jobs/j/artifacts/C_1.csv': [200, log('C', [3])],
      });
      const counting = ((url: string) => (fetched.push(url), f(url))) as typeof fetch;
      const logs = await fetchJobLogs('j', counting, 100);
      // the smallest first: C and B kept, A past what is left
      expect(logs.files.map((x) => x.name)).toEqual(['B_1.csv', 'C_1.csv']);
      expect(logs.problems).toEqual(['A_1.csv: left out (60 bytes, past the 100 bytes a replay reads in all)']);
      expect(fetched.some((u) => u.endsWith('A_1.csv'))).toBe(false);
    });

    it('past its byte bound keeps ORD\'s and the supervisors\' logs (the rules and activations), then the smallest: the large module logs are left out', async () => {
      // the field test's folder, scaled down: two large module logs named before the small ones
      const names = { LOC: 'LOC_1.csv', MOB: 'MOB_1.csv', MON: 'MON_1.csv', ORD: 'ORD_1.csv', SUP: 'SUP_1.csv', VEL: 'VEL_1.csv' };
      const listing = { id: 'j', status: 'succeeded', artifacts: { files: [
        { name: names.LOC, size: 400 }, { name: names.MOB, size: 30 }, { name: names.MON, size: 500 },
        { name: names.ORD, size: 60 }, { name: names.SUP, size: 40 }, { name: names.VEL, size: 20 },
      ], skipped: [] } };
      const routes: Record<string, [number, string]> = { '/api/jobs/j/artifacts': [200, JSON.stringify(listing)] };
      for (const [m, n] of Object.entries(names)) routes[`/api/jobs/j/artifacts/${n}`] = [200, log(m, [1])];
      const f = await serve(routes);
      // MON is a supervisor of the model: kept before the smaller VEL and MOB
      const logs = await fetchJobLogs('j', f, 610, new Set(['SUP', 'MON']));
      expect(logs.files.map((x) => x.name)).toEqual([names.MON, names.ORD, names.SUP]);
      expect(logs.problems).toEqual([`${names.VEL}: left out (20 bytes, past the 610 bytes a replay reads in all)`, `${names.MOB}: left out (30 bytes, past the 610 bytes a replay reads in all)`, `${names.LOC}: left out (400 bytes, past the 610 bytes a replay reads in all)`]);
      // no supervisor known: ORD's first, then the smallest (a supervisor's log is small)
      const bySize = await fetchJobLogs('j', f, 160);
      expect(bySize.files.map((x) => x.name)).toEqual([names.MOB, names.ORD, names.SUP, names.VEL]);
    });

    it("gives the crash sites the build service mapped after the run (the listing's crashSites), lines only, bounded", async () => {
      const sites = ['MAA crashed: signal 11 (SIGSEGV) at address 0x0, executable build-id 71b5', '  #0 store_bad at src-gen/generated/architecture/modules/MAA_mod/module.c:74 (inlined into _exec_module_state at src-gen/generated/architecture/modules/MAA_mod/module.c:268)', '  #1 libc.so.6+0x2724a'];
      const listing = (crashSites: unknown) => JSON.stringify({ id: 'j', status: 'failed', artifacts: { files: [{ name: 'MAA_1.csv', size: 1 }, { name: 'MAA.crash', size: 200 }], skipped: [], crashSites } });
      const f = await serve({ '/api/jobs/j/artifacts': [200, listing(sites)], '/api/jobs/j/artifacts/MAA_1.csv': [200, log('MAA', [1])] });
      const logs = await fetchJobLogs('j', f);
      expect(logs.crashSites).toEqual(sites);
      expect(logs.files.map((x) => x.name)).toEqual(['MAA_1.csv']); // the crash file is no log to replay
      server!.close();
      const odd = await serve({ '/api/jobs/j/artifacts': [200, listing([7, 'x'.repeat(5000), ...Array.from({ length: 1000 }, (_, i) => `  #${i} f`)])], '/api/jobs/j/artifacts/MAA_1.csv': [200, log('MAA', [1])] });
      const bounded = (await fetchJobLogs('j', odd)).crashSites!;
      expect(bounded).toHaveLength(400);
      expect(bounded[0]).toHaveLength(2000);
      server!.close();
      const none = await serve({ '/api/jobs/j/artifacts': [200, listing(undefined)], '/api/jobs/j/artifacts/MAA_1.csv': [200, log('MAA', [1])] });
      expect((await fetchJobLogs('j', none)).crashSites).toBeUndefined();
    });

    it('fails with a clear message when the job is unknown', async () => {
      const f = await serve({});
      await expect(fetchJobLogs('nope', f)).rejects.toThrow(/artifacts: HTTP 404 no route/);
    });
  });
});

describe('local run logs', () => {
  it('are looked for where `contract run` writes them (DIR/logs) and where `make run` does (src-gen/generated/architecture/logs), older runs left out', () => {
    const files = ['robot/logs/CTL_1.csv', 'robot/logs/previous/run-1/CTL_0.csv', 'robot/logs/notes.txt', 'robot/src-gen/generated/architecture/logs/ORD_1.csv',
      'robot/a.contract', 'other/logs/X_1.csv', 'logs/ROOT_1.csv'];
    expect(localLogFolders('robot', files)).toEqual([
      { folder: 'robot/logs', csvs: ['robot/logs/CTL_1.csv'] },
      { folder: 'robot/src-gen/generated/architecture/logs', csvs: ['robot/src-gen/generated/architecture/logs/ORD_1.csv'] },
    ]);
    expect(localLogFolders('', files)).toEqual([{ folder: 'logs', csvs: ['logs/ROOT_1.csv'] }, { folder: 'src-gen/generated/architecture/logs', csvs: [] }]);
  });

  it('reads a workspace folder\'s logs past the replay\'s bound keeping ORD\'s and the supervisors\', then the smallest; the large ones left out and named', async () => {
    // GET /api/log as the IDE server answers it: the size first (x-log-bytes), then the bytes
    const texts: Record<string, string> = {
      'logs/LOC_1.csv': log('LOC', [1, 2, 3, 4, 5, 6, 7, 8]),
      'logs/MON_1.csv': log('MON', [1, 2, 3, 4, 5, 6, 7, 8, 9, 10]),
      'logs/ORD_1.csv': log('ORD', [1, 2]),
      'logs/SUP_1.csv': log('SUP', [1, 2, 3]),
    };
    const asked: string[] = [];
    vi.stubGlobal('fetch', async (url: string) => {
      const path = decodeURIComponent(/path=([^&]*)/.exec(url)![1]!);
      asked.push(path);
      return new Response(texts[path]!, { headers: { 'x-log-bytes': String(Buffer.byteLength(texts[path]!)) } });
    });
    try {
      const paths = Object.keys(texts); // by name, as GET /api/log-folder lists them
      const sizes = paths.map((p) => Buffer.byteLength(texts[p]!));
      const bound = sizes[1]! + sizes[2]! + sizes[3]!; // room for MON, ORD and SUP, not LOC too
      const { files, problems, tooLarge } = await readWorkspaceLogs(paths, (p) => p.slice(5), bound, { sizes, supervisors: new Set(['SUP', 'MON']) });
      expect(files.map((x) => x.name)).toEqual(['MON_1.csv', 'ORD_1.csv', 'SUP_1.csv']); // in the folder's order
      expect(problems).toEqual([`LOC_1.csv: ${sizes[0]} bytes, past the 0 bytes left of the replay's bound`]);
      expect(tooLarge).toBe(true);
      expect(asked).toEqual(['logs/ORD_1.csv', 'logs/SUP_1.csv', 'logs/MON_1.csv', 'logs/LOC_1.csv']); // LOC last: its size past what is left, its bytes not read
    } finally {
      vi.unstubAllGlobals();
    }
  });

  it('reads the first bytes of a log longer than the server sends of one: its whole lines, and says how much and where the rest is', async () => {
    const text = log('ORD', [1, 2, 3, 4, 5, 6]);
    const sent = text.indexOf('4,w,ORD') + 3; // the bytes stop inside a line
    vi.stubGlobal('fetch', async () => new Response(text.slice(0, sent), { headers: { 'x-log-bytes': String(text.length), 'x-log-sent': String(sent) } }));
    try {
      const { files, problems, partly, tooLarge } = await readWorkspaceLogs(['logs/ORD_1.csv'], (p) => p.slice(5));
      const whole = text.slice(0, text.indexOf('4,w,ORD')); // up to the last line end sent
      expect(files.map((f) => f.text)).toEqual([whole]);
      expect(problems).toEqual([]);
      expect(tooLarge).toBe(true);
      expect(partly).toEqual([partlyReadText('ORD_1.csv', 'logs/ORD_1.csv', { read: whole.length, size: text.length, sent })]);
      expect(partly[0]).toBe(`ORD_1.csv: only its first ${whole.length} bytes of ${text.length} bytes read (the IDE reads ${sent} bytes of a log for a replay): ` +
        'its later records are not shown; the whole log is logs/ORD_1.csv in the workspace (`contract trace` reads it whole)');
      expect(partlyReadText('X_1.csv', 'X_1.csv', { read: 268_000_000, size: 629_174_256, sent: 268_435_456 })).toMatch(/^X_1\.csv: only its first 255\.6 MiB of 600\.0 MiB read \(the IDE reads 256\.0 MiB of a log/);
    } finally {
      vi.unstubAllGlobals();
    }
  });

  it('orders a replay\'s logs: ORD\'s and the supervisors\' first, then the others, each group smallest first; unknown sizes last; equal ones as listed', () => {
    const logs = [{ name: 'A_1.csv', size: 5 }, { name: 'ORD_1.csv', size: 900 }, { name: 'B_1.csv' }, { name: 'SUP_x.csv', size: 700 }, { name: 'C_1.csv', size: 5 }, { name: 'D_1.csv', size: 1 }];
    expect(replayOrder(logs, new Set(['SUP'])).map((l) => l.name)).toEqual(['SUP_x.csv', 'ORD_1.csv', 'D_1.csv', 'A_1.csv', 'C_1.csv', 'B_1.csv']);
    expect(replayOrder(logs).map((l) => l.name)).toEqual(['ORD_1.csv', 'D_1.csv', 'A_1.csv', 'C_1.csv', 'SUP_x.csv', 'B_1.csv']);
  });
});
