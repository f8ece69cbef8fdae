/**
 * `make run` of the generated architecture Makefile keeps one run per LOG_DIR, as `contract run`
 * does (docs/codegen.md "The architecture Makefile"): the CSV logs of the run before are moved to
 * LOG_DIR/previous/run-<time of the newest>/ first, never deleted. The recipe runs for real (GNU
 * make and a shell) on examples/tutorial's committed Makefile, with the launcher replaced by
 * `true` and `all` taken as made (`-o all`): only the move is exercised. With the launcher replaced
 * by `echo`, the second test reads the command line: the supervisors are given to `--stop-first`.
 */
import { spawnSync } from 'node:child_process';
import { cpSync, existsSync, mkdirSync, readdirSync, utimesSync, writeFileSync } from 'node:fs';
import { join, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';
import { afterAll, describe, expect, it } from 'vitest';
import { tempDir } from './test-support/temp-dir.js';

const REPO = resolve(fileURLToPath(new URL('.', import.meta.url)), '..', '..', '..');
const MAKEFILE = join(REPO, 'examples', 'tutorial', 'src-gen', 'generated', 'architecture', 'Makefile');
const { dir: root, cleanup } = tempDir('codegen-make-run-');
afterAll(() => cleanup());

function makeRun(arch: string, logDir: string): { status: number | null; out: string } {
    const r = spawnSync('make', ['-s', '-o', 'all', 'run', 'LAUNCH=true', `LOG_DIR=${logDir}`, `CONTRACT_RUNTIME=${join(REPO, 'runtime')}`], { cwd: arch, encoding: 'utf8' });
    return { status: r.status, out: `${r.stdout}${r.stderr}` };
}

/** A module's CSV log written at `when` (its mtime). */
function log(dir: string, name: string, when: Date): void {
    writeFileSync(join(dir, name), 'mono_ns,wall_time,module,event,peer,port,size,detail\n');
    utimesSync(join(dir, name), when, when);
}

const stamp = (d: Date) => {
    const two = (n: number) => String(n).padStart(2, '0');
    return `run-${d.getFullYear()}-${two(d.getMonth() + 1)}-${two(d.getDate())}T${two(d.getHours())}-${two(d.getMinutes())}-${two(d.getSeconds())}`;
};

describe('make run: one run per LOG_DIR', () => {
    it('moves the previous run\'s CSV logs to previous/run-<time of the newest>/, a second one beside it, and nothing when there is none', () => {
        const arch = join(root, 'architecture');
        mkdirSync(arch);
        cpSync(MAKEFILE, join(arch, 'Makefile'));
        const logs = join(root, 'my logs'); // a space in the path
        mkdirSync(logs);

        // no log yet: nothing moved, nothing said
        const first = makeRun(arch, logs);
        expect(first.status, first.out).toBe(0);
        expect(first.out).toBe('');
        expect(existsSync(join(logs, 'previous'))).toBe(false);

        const older = new Date(2026, 10, 28, 9, 30, 5), newest = new Date(2026, 10, 28, 9, 30, 7);
        log(logs, 'MAA_28-Nov-2026-09h30m05s.csv', older);
        log(logs, 'SUP_28-Nov-2026-09h30m05s.csv', newest);
        writeFileSync(join(logs, 'notes.txt'), 'mine');
        const second = makeRun(arch, logs);
        expect(second.status, second.out).toBe(0);
        const to = join(logs, 'previous', stamp(newest));
        expect(second.out).toBe(`make run: the previous run's logs moved to ${to}\n`);
        expect(readdirSync(to).sort()).toEqual(['MAA_28-Nov-2026-09h30m05s.csv', 'SUP_28-Nov-2026-09h30m05s.csv']);
        expect(readdirSync(logs).sort()).toEqual(['notes.txt', 'previous']); // what is not a log stays

        // a run whose newest log has the same time: a folder of its own, never mixed
        log(logs, 'MAA_28-Nov-2026-09h30m07s.csv', newest);
        const third = makeRun(arch, logs);
        expect(third.status, third.out).toBe(0);
        expect(readdirSync(join(logs, 'previous')).sort()).toEqual([stamp(newest), `${stamp(newest)}-2`]);
        expect(readdirSync(join(logs, 'previous', `${stamp(newest)}-2`))).toEqual(['MAA_28-Nov-2026-09h30m07s.csv']);
        expect(readdirSync(to)).toHaveLength(2);
    });
});

describe('make run: the supervisors stop first', () => {
    it('gives the architecture\'s supervisors to contract-launch --stop-first, and every executable to run', () => {
        const arch = join(root, 'stop-first');
        mkdirSync(arch);
        cpSync(MAKEFILE, join(arch, 'Makefile'));
        const r = spawnSync('make', ['-s', '-o', 'all', 'run', 'LAUNCH=echo', `LOG_DIR=${join(root, 'stop-first-logs')}`, `CONTRACT_RUNTIME=${join(REPO, 'runtime')}`], { cwd: arch, encoding: 'utf8' });
        expect(r.status, r.stderr).toBe(0);
        // echo prints the launcher's arguments, quotes removed by the shell
        expect(r.stdout).toContain(' --stop-first SUP GLB ');
        expect(r.stdout.trim().endsWith(['ORD', 'MAA', 'MAB', 'MSA', 'MSB', 'MSC', 'MSD', 'SUP', 'GLB'].map((e) => `modules/${e}_mod/${e}`).join(' '))).toBe(true);
    });
});
