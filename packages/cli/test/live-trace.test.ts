/** `contract run --trace FILE`: records written as the trace events arrive, not only at the end. */
import { createHash } from 'node:crypto';
import { spawn, spawnSync } from 'node:child_process';
import { existsSync, lstatSync, mkdirSync, mkdtempSync, readFileSync, renameSync, rmSync, statSync, symlinkSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { afterEach, beforeEach, describe, expect, it } from 'vitest';
import type { JobEvent } from '@contract-studio/build-service';
import { CSV_HEADER, parseRecordLine, parseTrace, type TraceRecord } from '@contract-studio/build-service/trace';
import { LiveTrace, settleTraceFile } from '../src/live-trace.js';
import { toJsonLines, traceNameProblem } from '../src/trace-files.js';

const line = (n: number) => ({ file: 'SUP_1.csv', line: n + 1, text: `${1000 + n},2026-11-24T18:30:15.123456Z,SUP,module_started,,,0,pid=${n} priority=98` });
const trace = (from: number, count: number): JobEvent => ({ type: 'trace', seq: from, t: 0, records: Array.from({ length: count }, (_, i) => line(from + i)) });

describe('LiveTrace', () => {
    let dir: string;
    beforeEach(() => void (dir = mkdtempSync(join(tmpdir(), 'live-trace-'))));
    afterEach(() => rmSync(dir, { recursive: true, force: true }));

    it('writes each trace event\'s records as JSON lines as they come, ignores other events', async () => {
        const path = join(dir, 'run.jsonl');
        const live = await LiveTrace.open(path);
        live.event({ type: 'line', seq: 1, t: 0, step: 'run', source: 'SUP', stream: 'stdout', line: 'hello' });
        live.event(trace(1, 3));
        for (let i = 0; i < 100 && statSync(path).size === 0; i++) await new Promise((r) => setTimeout(r, 5));
        const want1 = toJsonLines([1, 2, 3].map((n) => parseRecordLine('SUP_1.csv', n + 1, line(n).text)));
        expect(readFileSync(path, 'utf8')).toBe(want1); // before the end of the run
        live.event(trace(4, 2));
        const whole = want1 + toJsonLines([4, 5].map((n) => parseRecordLine('SUP_1.csv', n + 1, line(n).text)));
        expect(await live.close()).toEqual({ digest: createHash('sha256').update(whole).digest('hex'), intact: true }); // all a long run keeps of it
        expect(readFileSync(path, 'utf8')).toBe(whole);
        expect(live.counts).toEqual({ records: 5, unreadable: 0 });
    });

    it('writes the launcher\'s end line as it comes (a launcher_line at the latest record\'s time), never a module\'s output in its words', async () => {
        const path = join(dir, 'l.jsonl');
        const live = await LiveTrace.open(path);
        live.event({ type: 'line', seq: 1, t: 0, step: 'run', source: 'launcher', stream: 'stderr', line: 'module SUP (pid 1) died by signal 9 (Killed)' }); // no record yet: no module to match
        live.event(trace(1, 2));
        live.event({ type: 'line', seq: 4, t: 0, step: 'run', source: 'SUP', stream: 'stderr', line: 'contract-launch: module SUP (pid 2) died by signal 9 (Killed)' });
        live.event({ type: 'line', seq: 5, t: 0, step: 'run', source: 'SUP', stream: 'stderr', line: 'module SUP (pid 2) died by signal 9 (Killed)' });
        live.event({ type: 'line', seq: 6, t: 0, step: 'run', source: 'launcher', stream: 'stderr', line: 'run directory /x' });
        live.event({ type: 'line', seq: 7, t: 0, step: 'run', source: 'launcher', stream: 'stderr', line: 'module SUP (pid 2) died by signal 9 (Killed)' });
        await live.close();
        const records = toJsonLines([1, 2].map((n) => parseRecordLine('SUP_1.csv', n + 1, line(n).text)));
        expect(readFileSync(path, 'utf8')).toBe(`${records}{"kind":"launcher_line","monoNs":"1002","line":"module SUP (pid 2) died by signal 9 (Killed)"}\n`);
        expect(live.counts).toEqual({ records: 2, unreadable: 0 }); // a launcher line is no record
    });

    it('settles the file with the logs folder\'s launcher end lines at their own time, in time order among the records', async () => {
        const logs = join(dir, 'logs');
        mkdirSync(logs);
        writeFileSync(join(logs, 'SUP_1.csv'), `${CSV_HEADER}\n${[1, 2, 3].map((n) => line(n).text).join('\n')}\n`);
        writeFileSync(join(logs, 'contract-launch.log'), '1001 run directory /x\n1002 module SUP (pid 2) died by signal 9 (Killed)\n');
        const path = join(dir, 's.jsonl');
        const live = await LiveTrace.open(path);
        live.event(trace(1, 3));
        live.event({ type: 'line', seq: 4, t: 0, step: 'run', source: 'launcher', stream: 'stderr', line: 'module SUP (pid 2) died by signal 9 (Killed)' });
        const closed = await live.close();
        expect(await settleTraceFile(logs, ['SUP_1.csv'], path, { ...closed, counts: live.counts })).toEqual({ records: 3, unreadable: 0, rewritten: true });
        live.release();
        const rec = (n: number) => toJsonLines([parseRecordLine('SUP_1.csv', n + 1, line(n).text)]);
        expect(readFileSync(path, 'utf8')).toBe(`${rec(1)}${rec(2)}{"kind":"launcher_line","monoNs":"1002","line":"module SUP (pid 2) died by signal 9 (Killed)"}\n${rec(3)}`);
    });

    it('a normal run\'s stop (`exited with status 0` lines): no launcher_line live nor settled, the file left as written (the same file: a follower by name reads nothing twice)', async () => {
        const logs = join(dir, 'stop-logs');
        mkdirSync(logs);
        writeFileSync(join(logs, 'SUP_1.csv'), `${CSV_HEADER}\n${[1, 2, 3].map((n) => line(n).text).join('\n')}\n`);
        writeFileSync(join(logs, 'contract-launch.log'), '1001 run directory /x\n1002 stopping: the run\'s duration (3 s) is over\n1002 module SUP (pid 2) exited with status 0\n1004 all modules stopped cleanly\n');
        const path = join(dir, 'stop.jsonl');
        const live = await LiveTrace.open(path);
        live.event(trace(1, 2));
        live.event({ type: 'line', seq: 4, t: 0, step: 'run', source: 'launcher', stream: 'stderr', line: 'module SUP (pid 2) exited with status 0' });
        live.event(trace(3, 1));
        const closed = await live.close();
        const before = statSync(path).ino;
        expect(await settleTraceFile(logs, ['SUP_1.csv'], path, { ...closed, counts: live.counts })).toEqual({ records: 3, unreadable: 0 });
        live.release();
        expect(statSync(path).ino).toBe(before);
        expect(readFileSync(path, 'utf8')).toBe(toJsonLines([1, 2, 3].map((n) => parseRecordLine('SUP_1.csv', n + 1, line(n).text))));
    });

    it('counts an unreadable line apart from the records, as `contract trace` and the Monitor do', async () => {
        const live = await LiveTrace.open(join(dir, 'u.jsonl'));
        live.event({ type: 'trace', seq: 1, t: 0, records: [line(1), { file: 'SUP_1.csv', line: 3, text: 'not a record at all' }, line(2)] });
        await live.close();
        expect(live.counts).toEqual({ records: 2, unreadable: 1 });
    });

    it('its digest differs from that of another text (the caller then rewrites the file)', async () => {
        const live = await LiveTrace.open(join(dir, 'a.jsonl'));
        live.event(trace(1, 1));
        expect((await live.close()).digest).not.toBe(createHash('sha256').update('something else\n').digest('hex'));
    });

    it('never writes through a link', async () => {
        symlinkSync(join(dir, 'target'), join(dir, 'link.jsonl'));
        await expect(LiveTrace.open(join(dir, 'link.jsonl'))).rejects.toThrow(/it is a symbolic link: a trace file is never written through a link/);
    });

    it('never opens a FIFO, a folder or a device as the trace (a FIFO would wait for a reader for ever)', async () => {
        expect(spawnSync('mkfifo', [join(dir, 'fifo.jsonl')]).status).toBe(0);
        await expect(LiveTrace.open(join(dir, 'fifo.jsonl'))).rejects.toThrow(/it is a FIFO: a trace file is a regular file/);
        mkdirSync(join(dir, 'folder.jsonl'));
        await expect(LiveTrace.open(join(dir, 'folder.jsonl'))).rejects.toThrow(/it is a folder/);
        await expect(LiveTrace.open('/dev/null')).rejects.toThrow(/it is not a regular file/);
    });

    it('keeps an earlier trace until the run\'s first record; a run that ran empties it, one that never ran leaves it', async () => {
        const earlier = 'earlier run\n';
        writeFileSync(join(dir, 'kept.jsonl'), earlier);
        const kept = await LiveTrace.open(join(dir, 'kept.jsonl'));
        expect(readFileSync(join(dir, 'kept.jsonl'), 'utf8')).toBe(earlier); // the opening alone empties nothing
        expect(await kept.abandon()).toBe(true);
        expect(readFileSync(join(dir, 'kept.jsonl'), 'utf8')).toBe(earlier);
        // a run that came to its first record: the earlier text is gone, not mixed with the new
        const ran = await LiveTrace.open(join(dir, 'kept.jsonl'));
        ran.event(trace(1, 1));
        await ran.close();
        expect(readFileSync(join(dir, 'kept.jsonl'), 'utf8')).toBe(toJsonLines([parseRecordLine('SUP_1.csv', 2, line(1).text)]));
        // a run that ran without a record: emptied at its end
        writeFileSync(join(dir, 'kept.jsonl'), earlier);
        await (await LiveTrace.open(join(dir, 'kept.jsonl'))).close();
        expect(readFileSync(join(dir, 'kept.jsonl'), 'utf8')).toBe('');
    });

    it('takes only a *.jsonl name, so that a slip of the name never overwrites a model or a source', () => {
        for (const bad of ['supervisor.contract', 'run.json', 'trace', '.jsonl', 'dir/.jsonl', 'x.jsonl.bak', 'up.JSONL'])
            expect(traceNameProblem(bad), bad).toMatch(/a trace file is named \*\.jsonl/);
        for (const good of ['run.jsonl', 'ci/out/run.jsonl', '../t.jsonl']) expect(traceNameProblem(good), good).toBeUndefined();
    });

    describe('settleTraceFile (the end of the run)', () => {
        const logs: Record<string, string> = {
            'SUP_1.csv': [CSV_HEADER, line(1).text, line(3).text].join('\n') + '\n',
            'ORD_1.csv': [CSV_HEADER, '1002,w,ORD,scheduler,,,0,activate S'].join('\n') + '\n',
        };
        const whole = () => toJsonLines(parseTrace(Object.entries(logs).map(([name, text]) => ({ name, text }))));
        const sha = (t: string) => createHash('sha256').update(t).digest('hex');
        const told = (r: TraceRecord) => ('monoNs' in r ? `${r.module} ${r.monoNs}` : 'unknown');
        beforeEach(() => {
            for (const [name, text] of Object.entries(logs)) writeFileSync(join(dir, name), text);
            writeFileSync(join(dir, 'OLD_1.csv'), `${CSV_HEADER}\n5,w,OLD,error,,,0,an earlier run's log in the same folder\n`);
        });

        it('rewrites the file from the run\'s logs (only those) when the live text differs', async () => {
            const file = join(dir, 'run.jsonl');
            writeFileSync(file, 'live, partly\n');
            const seen: string[] = [];
            expect(await settleTraceFile(dir, ['ORD_1.csv', 'SUP_1.csv'], file, { digest: sha('live, partly\n'), counts: { records: 1, unreadable: 0 } }, (r) => seen.push(told(r)))).toEqual({ records: 3, unreadable: 0, rewritten: true });
            expect(readFileSync(file, 'utf8')).toBe(whole());
            // each record seen once (the pass that rewrote the file shows it none again), in time order
            expect(seen).toEqual(parseTrace(Object.entries(logs).map(([name, text]) => ({ name, text }))).map(told));
        });

        it('leaves the file as written live when it is the whole trace', async () => {
            const file = join(dir, 'run.jsonl');
            writeFileSync(file, 'as written live\n'); // stands for the same text: not written again
            let seen = 0;
            expect(await settleTraceFile(dir, ['ORD_1.csv', 'SUP_1.csv'], file, { digest: sha(whole()), counts: { records: 3, unreadable: 0 } }, () => seen++)).toEqual({ records: 3, unreadable: 0 });
            expect(seen).toBe(3);
            expect(readFileSync(file, 'utf8')).toBe('as written live\n');
        });

        it('keeps what came live when the run left no logs; never rewrites through a link (a link put there is replaced, its target untouched)', async () => {
            expect(await settleTraceFile(dir, [], join(dir, 'none.jsonl'), { digest: 'x', counts: { records: 7, unreadable: 1 } })).toEqual({ records: 7, unreadable: 1 });
            writeFileSync(join(dir, 'target'), 'not a trace\n');
            symlinkSync(join(dir, 'target'), join(dir, 'link.jsonl'));
            await settleTraceFile(dir, ['ORD_1.csv', 'SUP_1.csv'], join(dir, 'link.jsonl'), { digest: 'x', counts: { records: 0, unreadable: 0 } });
            expect(readFileSync(join(dir, 'target'), 'utf8')).toBe('not a trace\n');
            expect(lstatSync(join(dir, 'link.jsonl')).isFile()).toBe(true);
            expect(readFileSync(join(dir, 'link.jsonl'), 'utf8')).toBe(whole());
        });

        it('one writer at a time: a trace file another live command writes is refused, saying whose; a dead writer\'s lock is taken over; none is left', async () => {
            const file = join(dir, 'both.jsonl');
            const other = spawn('sleep', ['30']);
            try {
                writeFileSync(`${file}.writing`, `${other.pid}\n`);
                await expect(LiveTrace.open(file)).rejects.toThrow(`it is being written by another contract command (pid ${other.pid}; its lock both.jsonl.writing): wait for it to end, or name another file`);
                expect(existsSync(file)).toBe(false); // nothing created nor emptied
            } finally {
                other.kill();
            }
            await new Promise((r) => other.once('exit', r));
            // its writer is gone (killed): taken over
            const live = await LiveTrace.open(file);
            expect(readFileSync(`${file}.writing`, 'utf8')).toBe(`${process.pid}\n`);
            live.event(trace(1, 1));
            await live.close();
            live.release();
            expect(existsSync(`${file}.writing`)).toBe(false);
        });

        it('a trace file moved aside during the run: written again at its path, whole', async () => {
            const file = join(dir, 'moved.jsonl');
            const live = await LiveTrace.open(file);
            live.event(trace(1, 3));
            await new Promise((r) => setTimeout(r, 20));
            renameSync(file, join(dir, 'aside.jsonl'));
            const end = await live.close();
            expect(end.intact).toBe(false);
            expect(await settleTraceFile(dir, ['ORD_1.csv', 'SUP_1.csv'], file, { ...end, counts: live.counts })).toMatchObject({ replaced: true });
            expect(readFileSync(file, 'utf8')).toBe(whole());
        });
    });
});
