/**
 * `make run` of the generated architecture Makefile keeps one run per LOG_DIR, as `contract run`
 * does (docs/codegen.md "The architecture Makefile"): the CSV logs of the run before are moved to
 * LOG_DIR/previous/run-<time of the newest>/ first (the launcher's contract-launch.log with them), never deleted. The recipe runs for real (GNU
 * make and a shell) on examples/tutorial's committed Makefile, with the launcher replaced by
 * `true` and `all` taken as made (`-o all`): only the move is exercised. With the launcher replaced
 * by `echo`, the second test reads the command line: the supervisors are given to `--stop-first`.
 */
import { execFileSync, spawnSync } from 'node:child_process';
import { chmodSync, cpSync, existsSync, mkdirSync, readdirSync, utimesSync, writeFileSync } from 'node:fs';
import { join, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';
import { afterAll, describe, expect, it } from 'vitest';
import { tempDir } from './test-support/temp-dir.js';

const REPO = resolve(fileURLToPath(new URL('.', import.meta.url)), '..', '..', '..');
const MAKEFILE = join(REPO, 'examples', 'tutorial', 'src-gen', 'generated', 'architecture', 'Makefile');
const { dir: root, cleanup } = tempDir('codegen-make-run-');
afterAll(() => cleanup());

/** `make run` with the launcher replaced by `true`; `asUser` (root only): as that user (setpriv). */
function makeRun(arch: string, logDir: string, asUser?: string): { status: number | null; out: string } {
    const args = ['-s', '-o', 'all', 'run', 'LAUNCH=true', `LOG_DIR=${logDir}`, `CONTRACT_RUNTIME=${join(REPO, 'runtime')}`];
    const r = asUser
        ? spawnSync('setpriv', [`--reuid=${asUser}`, `--regid=${asUser === 'nobody' ? 'nogroup' : asUser}`, '--clear-groups', 'make', ...args], { cwd: arch, encoding: 'utf8' })
        : spawnSync('make', args, { cwd: arch, encoding: 'utf8' });
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
        writeFileSync(join(logs, 'contract-launch.log'), '1000 module MAA (pid 41) died by signal 9 (Killed)\n'); // the launcher's lines go with the run's logs
        const second = makeRun(arch, logs);
        expect(second.status, second.out).toBe(0);
        const to = join(logs, 'previous', stamp(newest));
        expect(second.out).toBe(`make run: the previous run's logs moved to ${to}\n`);
        expect(readdirSync(to).sort()).toEqual(['MAA_28-Nov-2026-09h30m05s.csv', 'SUP_28-Nov-2026-09h30m05s.csv', 'contract-launch.log']);
        expect(readdirSync(logs).sort()).toEqual(['notes.txt', 'previous']); // what is not a log stays

        // a run whose newest log has the same time: a folder of its own, never mixed
        log(logs, 'MAA_28-Nov-2026-09h30m07s.csv', newest);
        const third = makeRun(arch, logs);
        expect(third.status, third.out).toBe(0);
        expect(readdirSync(join(logs, 'previous')).sort()).toEqual([stamp(newest), `${stamp(newest)}-2`]);
        expect(readdirSync(join(logs, 'previous', `${stamp(newest)}-2`))).toEqual(['MAA_28-Nov-2026-09h30m07s.csv']);
        expect(readdirSync(to)).toHaveLength(3);
    });
});

describe('make run: a logs folder it may not write', () => {
    const asRoot = process.getuid?.() === 0;
    // field test 68: `make run` as a user over root's earlier logs said only mkdir's `Permission denied`
    it.runIf(asRoot)('says whose the logs folder is and what to do, when the previous logs cannot be moved (another user\'s folder)', () => {
        const top = join(root, 'shared');
        mkdirSync(top);
        chmodSync(root, 0o755);
        chmodSync(top, 0o777);
        const arch = join(top, 'architecture');
        mkdirSync(arch);
        cpSync(MAKEFILE, join(arch, 'Makefile'));
        const logs = join(top, 'logs'); // root's, from an earlier run
        mkdirSync(logs);
        log(logs, 'MAA_28-Nov-2026-09h30m05s.csv', new Date(2026, 10, 28, 9, 30, 5));
        const r = makeRun(arch, logs, 'nobody');
        expect(r.status, r.out).toBe(2);
        expect(r.out).toContain('Permission denied'); // mkdir's own line first
        expect(r.out).toContain(`make run: cannot move the previous run's logs to ${join(logs, 'previous', 'run-2026-11-28T09-30-05')}: ` +
            `the logs folder belongs to root, and this is nobody: remove it (as root: rm -rf '${logs}'), run as root, or give another LOG_DIR=`);
        expect(readdirSync(logs)).toEqual(['MAA_28-Nov-2026-09h30m05s.csv']); // nothing lost
    });

    it.runIf(!asRoot)('says the previous logs could not be moved and what to do (a folder of this user it may not write)', () => {
        const logs = join(root, 'read-only logs');
        mkdirSync(logs);
        log(logs, 'MAA_28-Nov-2026-09h30m05s.csv', new Date(2026, 10, 28, 9, 30, 5));
        chmodSync(logs, 0o555);
        const arch = join(root, 'ro-architecture');
        mkdirSync(arch);
        cpSync(MAKEFILE, join(arch, 'Makefile'));
        const r = makeRun(arch, logs);
        chmodSync(logs, 0o755);
        expect(r.status, r.out).toBe(2);
        expect(r.out).toContain("(the line above says why): move them away, or give another LOG_DIR=");
    });
});

describe('make run: REQUIRE_REALTIME', () => {
    it('gives contract-launch --require-realtime with REQUIRE_REALTIME=1 only', () => {
        const arch = join(root, 'realtime');
        mkdirSync(arch);
        cpSync(MAKEFILE, join(arch, 'Makefile'));
        const run = (...extra: string[]) => spawnSync('make', ['-s', '-o', 'all', 'run', 'LAUNCH=echo', `LOG_DIR=${join(root, 'realtime-logs')}`, `CONTRACT_RUNTIME=${join(REPO, 'runtime')}`, ...extra], { cwd: arch, encoding: 'utf8' });
        expect(run('REQUIRE_REALTIME=1').stdout).toContain(' --require-realtime ');
        expect(run().stdout).not.toContain('--require-realtime');
        expect(run('REQUIRE_REALTIME=0').stdout).not.toContain('--require-realtime');
    });
});

describe('make run: REQUIRE_REALTIME refused', () => {
    it('leaves the previous run\'s logs in LOG_DIR: real time is checked (contract-launch --check-realtime) before they are moved', () => {
        execFileSync('make', ['-s', '-C', join(REPO, 'runtime'), 'build/contract-launch'], { stdio: 'pipe' });
        const arch = join(root, 'realtime-refused');
        mkdirSync(arch);
        cpSync(MAKEFILE, join(arch, 'Makefile'));
        const logs = join(root, 'realtime-refused-logs');
        mkdirSync(logs);
        log(logs, 'MAA_28-Nov-2026-09h30m05s.csv', new Date(2026, 10, 28, 9, 30, 5));
        // CONTRACT_SCHED=other contradicts the requirement: refused here even as root
        const r = spawnSync('make', ['-s', '-o', 'all', 'run', 'REQUIRE_REALTIME=1', `LOG_DIR=${logs}`, `CONTRACT_RUNTIME=${join(REPO, 'runtime')}`], {
            cwd: arch,
            encoding: 'utf8',
            env: { ...process.env, CONTRACT_SCHED: 'other' },
        });
        expect(r.status, r.stderr).toBe(2);
        expect(r.stderr).toContain('contract-launch: real-time is required');
        expect(r.stderr).not.toContain('previous run');
        expect(readdirSync(logs)).toEqual(['MAA_28-Nov-2026-09h30m05s.csv']);
    }, 120_000);
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

    it('gives them to contract-launch --kill too (make kill): a launcher that died leaves modules that stop in the same order', () => {
        const arch = join(root, 'stop-first-kill');
        mkdirSync(arch);
        cpSync(MAKEFILE, join(arch, 'Makefile'));
        const r = spawnSync('make', ['-s', 'kill', 'LAUNCH=echo', `RUN_DIR=${join(root, 'a-run')}`, `CONTRACT_RUNTIME=${join(REPO, 'runtime')}`], { cwd: arch, encoding: 'utf8' });
        expect(r.status, r.stderr).toBe(0);
        expect(r.stdout.trim()).toBe(`--stop-first SUP GLB --kill ${join(root, 'a-run')}`);
    });
});
