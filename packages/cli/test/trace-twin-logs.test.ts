/**
 * `contract trace FOLDER` on a folder holding two runs' logs of the same modules: they are read as
 * one (the Monitor's rule), and that is impossible to miss — said on stderr before anything, as the
 * story's first lines in text, and the exit status is 1 in every format unless `--merge-logs` asks
 * for it (packages/cli/README.md "trace").
 */
import { mkdirSync, mkdtempSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { afterAll, describe, expect, it } from 'vitest';
import { runCli } from '../src/cli.js';
import { capture } from './capture-io.js';

const HEADER = 'mono_ns,wall_time,module,event,peer,port,size,detail';
const W = '2026-12-07T20:53:00.017961Z';

/** One run's logs of ORD and ALM from `t0`, one schema cycle of ALM. */
function run(dir: string, date: string, t0: number): void {
    const t = (ns: number) => String(t0 + ns);
    writeFileSync(join(dir, `ORD_${date}.csv`), [HEADER,
        `${t(1000)},${W},ORD,module_started,,,0,pid=41 priority=99`,
        `${t(2000)},${W},ORD,ord_release,ALM,,0,schema=loop cycle=0 tick_ns=${t(1900)} release_ns=${t(1950)} release=1`,
        `${t(3000)},${W},ORD,ord_complete,,,0,schema=loop cycle=0 tick_ns=${t(1900)} response_ns=1100`,
        `${t(9000)},${W},ORD,module_exit,,,0,status=0 records=4`, ''].join('\n'));
    writeFileSync(join(dir, `ALM_${date}.csv`), [HEADER,
        `${t(1001)},${W},ALM,module_started,,,0,pid=42 priority=50`,
        `${t(9001)},${W},ALM,module_exit,,,0,status=0 records=2`, ''].join('\n'));
}

const SAID = 'ALM: 2 logs of it in this folder (ALM_6-Dec-2026-10h00m00s.csv, ALM_7-Dec-2026-10h00m00s.csv), read as one: a run writes one log per module (two runs\' logs together, or a file named as its log that is not one); the story and its figures add them up';

describe('contract trace of a folder holding two runs\' logs', () => {
    const root = mkdtempSync(join(tmpdir(), 'contract-twin-logs-'));
    afterAll(() => rmSync(root, { recursive: true, force: true }));
    const dir = join(root, 'logs');
    mkdirSync(dir);
    run(dir, '6-Dec-2026-10h00m00s', 5_000_000_000);
    run(dir, '7-Dec-2026-10h00m00s', 90_000_000_000);

    it('text: said first on stderr and as the story\'s first lines (not after it), exit 1; --merge-logs: exit 0, still said', async () => {
        const io = capture(root);
        expect(await runCli(['trace', 'logs'], io)).toBe(1);
        const lines = io.stdout.split('\n');
        expect(lines.slice(0, 2)).toEqual([`warning: ${SAID}`, expect.stringMatching(/^warning: ORD: 2 logs of it/)]);
        expect(lines.filter((l) => l.includes('logs of it in this folder'))).toHaveLength(2); // not told again after the story
        expect(io.stderr.split('\n')[0]).toBe(`contract trace: warning: ${SAID}`);
        expect(io.stderr).toMatch(/contract trace: logs holds two or more logs of 2 module\(s\), said above .*: exit 1; .*--merge-logs/);
        expect(io.stdout).toMatch(/schema loop: 2 completed cycles/); // the figures add both runs: that is why it is said

        const merged = capture(root);
        expect(await runCli(['trace', 'logs', '--merge-logs'], merged)).toBe(0);
        expect(merged.stdout.split('\n')[0]).toBe(`warning: ${SAID}`);
        expect(merged.stderr).toContain(`contract trace: warning: ${SAID}`);
        expect(merged.stderr).not.toContain('exit 1');
    });

    it('json: the warning on stderr before any line, exit 1 (a script sees it); --merge-logs: exit 0', async () => {
        const io = capture(root);
        expect(await runCli(['trace', 'logs', '--format', 'json'], io)).toBe(1);
        expect(io.stderr.split('\n')[0]).toBe(`contract trace: warning: ${SAID}`);
        expect(io.stdout.trim().split('\n').map((l) => (JSON.parse(l) as { kind: string }).kind).filter((k) => k === 'module_started')).toHaveLength(4);
        const merged = capture(root);
        expect(await runCli(['trace', 'logs', '--format', 'json', '--merge-logs'], merged)).toBe(0);
        expect(merged.stdout).toBe(io.stdout);
    });

    it('one run\'s folder: nothing said, exit 0', async () => {
        const one = join(root, 'one');
        mkdirSync(one);
        run(one, '7-Dec-2026-10h00m00s', 90_000_000_000);
        const io = capture(root);
        expect(await runCli(['trace', 'one'], io)).toBe(0);
        expect(io.stderr).toBe('');
        expect(io.stdout).not.toContain('warning');
    });
});
