/**
 * `contract trace FOLDER` on a real run's logs (the tutorial, the Monitor's fixture tutorial-run,
 * under the names the runtime gives them) beside a file a module's code made in the logs folder:
 * `ORD_<date>.csv` with no header and one deadline miss of ORD whose clock agrees with ORD's log.
 * The runtime begins every log with its header, so the file is no log: refused whole and said,
 * never counted as ORD's miss, nor as ORD's second log (docs/runtime-api.md "Whose records, and
 * their times").
 */
import { copyFileSync, mkdirSync, mkdtempSync, readdirSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { afterAll, describe, expect, it } from 'vitest';
import { NOT_A_LOG_WHY } from '@contract-studio/build-service/trace';
import { runCli } from '../src/cli.js';
import { capture } from './capture-io.js';

const RUN = fileURLToPath(new URL('../../web-ide/src/monitor/fixtures/tutorial-run', import.meta.url));
const DATE = '4-Dec-2026-05h49m24s';
const FORGED = 'ORD_4-Dec-2026-05h49m59s.csv';
/** Between ORD's first cycles (its tick 0 at 52092187155629), wall time consistent with ORD's records. */
const MISS = '52092900000000,2026-12-04T05:49:27.253000Z,ORD,ord_deadline_miss,,,0,schema=schemaCommande1 cycle=3 tick_ns=52092787155629';

describe('contract trace: a file of the logs folder that does not begin with the runtime\'s header', () => {
    const root = mkdtempSync(join(tmpdir(), 'contract-not-a-log-'));
    afterAll(() => rmSync(root, { recursive: true, force: true }));
    const folder = (name: string, forged?: string): string => {
        const dir = join(root, name);
        mkdirSync(dir);
        for (const f of readdirSync(RUN).filter((n) => n.endsWith('.csv'))) copyFileSync(join(RUN, f), join(dir, `${f.slice(0, -4)}_${DATE}.csv`));
        if (forged !== undefined) writeFileSync(join(dir, FORGED), forged);
        return name;
    };
    const real = folder('real');
    const forged = folder('forged', `${MISS}\n`);

    it('is refused whole and said: no deadline miss of ORD told or counted, no second log of ORD, exit 0', async () => {
        const clean = capture(root);
        expect(await runCli(['trace', real], clean)).toBe(0);
        const io = capture(root);
        expect(await runCli(['trace', forged], io)).toBe(0);
        expect(io.stderr).toContain(`contract trace: warning: ${FORGED}: ${NOT_A_LOG_WHY}`);
        expect(io.stdout).toContain(`unreadable: ${FORGED} line 1: ${NOT_A_LOG_WHY}`);
        expect(io.stdout + io.stderr).not.toMatch(/logs of it in this folder/);
        // what the story tells of ORD's misses is the real log's, word for word
        const misses = (s: string) => s.split('\n').filter((l) => /deadline miss/i.test(l) && !/^\d+ records:/.test(l));
        expect(misses(io.stdout)).toEqual(misses(clean.stdout));
        // counted with the real log's misses (none), and the file's line 1 as the one unreadable line
        expect(io.stdout).toMatch(/^\d+ records: .* 0 deadline misses, .* 1 unreadable line$/m);
        expect(io.stdout).not.toMatch(/goTo|cycle 3\b/);
    });

    it('json: its line 1 is one `unknown` object saying why, no ord_deadline_miss record', async () => {
        const io = capture(root);
        expect(await runCli(['trace', forged, '--format', 'json'], io)).toBe(0);
        const objects = io.stdout.trim().split('\n').map((l) => JSON.parse(l) as { kind: string; file?: string; line?: number; reason?: string });
        expect(objects.filter((o) => o.kind === 'ord_deadline_miss')).toEqual([]);
        expect(objects.filter((o) => o.file === FORGED)).toEqual([expect.objectContaining({ kind: 'unknown', line: 1, reason: NOT_A_LOG_WHY })]);
    });
});
