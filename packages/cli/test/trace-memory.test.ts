/**
 * `contract trace` in bounded memory whatever the logs' lines (the attacker field test: 780 MB of
 * 3.9 KB lines took 341–412 MB): a record keeps its own line only, never the chunk of the file it
 * was read from (V8 keeps a whole string alive for a piece cut out of it); a file's window holds
 * WINDOW_CHARS characters of lines at most; the story follows a bounded number of names. Measured
 * on V8's heap after a full collection.
 */
import { mkdtempSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { setFlagsFromString } from 'node:v8';
import { runInNewContext } from 'node:vm';
import { afterEach, describe, expect, it } from 'vitest';
import { CSV_HEADER, isUnknown, StoryTeller, STORY_FOLLOWED, type TraceRecord } from '@contract-studio/build-service/trace';
import { ModuleEnds } from '../src/commands/trace.js';
import { closeLogs, openLogFolder, streamTrace, WINDOW_CHARS } from '../src/trace-stream.js';

setFlagsFromString('--expose-gc');
const gc = runInNewContext('gc') as () => void;
/** Bytes of V8's heap in use after a full collection. */
function heapUsed(): number {
    gc();
    gc();
    return process.memoryUsage().heapUsed;
}
const MB = 1024 * 1024;

const dirs: string[] = [];
afterEach(() => {
    for (const d of dirs.splice(0)) rmSync(d, { recursive: true, force: true });
});

/** A folder of logs, each `lines` lines made by `line(module, i)` (written here: their text is not kept). */
function folder(modules: string[], lines: number, line: (module: string, i: number) => string): string {
    const dir = mkdtempSync(join(tmpdir(), 'contract-trace-memory-'));
    dirs.push(dir);
    for (const m of modules) {
        const rows = [CSV_HEADER];
        for (let i = 0; i < lines; i++) rows.push(line(m, i));
        writeFileSync(join(dir, `${m}_1.csv`), rows.join('\n') + '\n');
    }
    return dir;
}

describe('contract trace memory', () => {
    it('a record keeps its own line, not the chunk it was read from: 48 lines of 1 MB kept as records hold kilobytes', async () => {
        const dir = folder(['SUP'], 48, (m, i) => `${i + 1},w,${m},error,,,0,${'v'.repeat(1_000_000)}`);
        const logs = await openLogFolder(dir);
        if (typeof logs === 'string') throw new Error(logs);
        const before = heapUsed();
        const records: TraceRecord[] = [];
        try {
            for await (const batch of streamTrace(logs).batches) records.push(...batch);
        } finally {
            await closeLogs(logs);
        }
        const kept = heapUsed() - before; // measured before `expect` holds the records
        expect(records).toHaveLength(48);
        expect(records.every((r) => isUnknown(r) && r.text.length === 200)).toBe(true);
        // each unknown record keeps why and 200 characters (the old reader kept a 1 MiB chunk each: 48 MiB)
        expect(kept).toBeLessThan(4 * MB);
    });

    it('a window holds WINDOW_CHARS characters of lines at most: 4 logs of 4,096 lines of 4,000 characters (64 MB) are merged in a few MB', async () => {
        const dir = folder(['MAA', 'MAB', 'MSC', 'ORD'], 4096, (m, i) => {
            const line = `${1000 + i * 10},2026-11-24T18:30:15.123456Z,${m},data_received,MAA,0,24,latency_ns=9000 value=`;
            return line + 'v'.repeat(4000 - line.length);
        });
        const logs = await openLogFolder(dir);
        if (typeof logs === 'string') throw new Error(logs);
        const before = heapUsed();
        let during = 0;
        let records = 0;
        try {
            const batches = streamTrace(logs).batches;
            for (let b = await batches.next(); !b.done; b = await batches.next()) {
                records += b.value.length;
                if (records === 4096) during = heapUsed() - before; // the windows full, a quarter of the run told
            }
        } finally {
            await closeLogs(logs);
        }
        // 4 windows of WINDOW_CHARS characters, the batch handed on (1,024 records) and a batch of lines
        // read ahead per log; the old reader held 4,096 records a log, and those already told: 64 MB and more
        expect(during).toBeLessThan(16 * MB);
        expect(records).toBe(4 * 4096);
        expect(WINDOW_CHARS).toBe(512 * 1024);
    });

    it('the story follows a bounded number of schemas and modules: a forged log of 100,000 names keeps a few MB', () => {
        // what they keep: the heap with them less the heap once they are dropped
        let teller = new StoryTeller();
        let ends = new ModuleEnds([{ name: 'ORD_1.csv' }]);
        for (let i = 0; i < 100_000; i++) {
            const schema = `schema_number_${i}_${'s'.repeat(40)}`;
            const module = `module_number_${i}`;
            const release: TraceRecord = { kind: 'ord_release', monoNs: String(1000 + i), wallTime: 'w', module: 'ORD', peer: module, port: null, size: 0, detail: '', fields: { schema, cycle: 0, tick_ns: 1000, release_ns: 1000 + i, release: i } };
            teller.tell(release);
            ends.see({ ...release, module });
        }
        const lines = ends.lines();
        const withThem = heapUsed();
        teller = new StoryTeller();
        ends = new ModuleEnds([]);
        const kept = withThem - heapUsed();
        // followed without a bound: 100,000 schemas with their cycles, 100,000 modules in three maps (17 MB)
        expect(kept).toBeLessThan(6 * MB);
        expect(lines).toEqual([`${''.padStart(10)} ${100_000 - 4095} record(s) of modules past the first 4096 not followed (more modules than a run has)`]);
        expect(STORY_FOLLOWED).toBe(4096);
    });
});
