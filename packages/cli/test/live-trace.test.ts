/** `contract run --trace FILE`: records written as the trace events arrive, not only at the end. */
import { mkdtempSync, readFileSync, rmSync, statSync, symlinkSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { afterEach, beforeEach, describe, expect, it } from 'vitest';
import type { JobEvent } from '@contract-studio/build-service';
import { parseRecordLine } from '@contract-studio/build-service/trace';
import { LiveTrace } from '../src/live-trace.js';
import { toJsonLines } from '../src/trace-files.js';

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
        expect(await live.close(whole)).toBe(true);
        expect(readFileSync(path, 'utf8')).toBe(whole);
        expect(live.records).toBe(5);
    });

    it('says when the live text is not the whole trace (the caller rewrites it)', async () => {
        const live = await LiveTrace.open(join(dir, 'a.jsonl'));
        live.event(trace(1, 1));
        expect(await live.close('something else\n')).toBe(false);
    });

    it('never writes through a link', async () => {
        symlinkSync(join(dir, 'target'), join(dir, 'link.jsonl'));
        await expect(LiveTrace.open(join(dir, 'link.jsonl'))).rejects.toThrow(/ELOOP/);
    });
});
