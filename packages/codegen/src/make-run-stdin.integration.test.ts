/**
 * `make run STDIN_<NAME>=file` of the generated architecture Makefile: a NAME that is none of its
 * EXECUTABLES (a typo: STDIN_MAX for MAA) stops make before anything is built or started, naming it
 * (the run line passes STDIN_$(e) on only for e in EXECUTABLES: the file was dropped, silently, and
 * every module read /dev/null: field test ft69). Only the names given on make's command line are
 * checked: the environment holds other programs' variables. GNU make for real on
 * examples/tutorial's committed Makefile, with the launcher replaced by `echo` and `all` taken as made.
 */
import { spawnSync } from 'node:child_process';
import { join, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';
import { describe, expect, it } from 'vitest';

const REPO = resolve(fileURLToPath(new URL('.', import.meta.url)), '..', '..', '..');
const ARCH = join(REPO, 'examples', 'tutorial', 'src-gen', 'generated', 'architecture');

/** `make run` with the launcher replaced by `echo`: its command line, or make's error. */
function makeRun(vars: string[], env: Record<string, string> = {}): { status: number | null; out: string; err: string } {
    const args = ['-s', '-o', 'all', 'run', 'LAUNCH=echo', 'LOG_DIR=/nonexistent-logs', `CONTRACT_RUNTIME=${join(REPO, 'runtime')}`, ...vars];
    const r = spawnSync('make', args, { cwd: ARCH, encoding: 'utf8', env: { ...process.env, ...env } });
    return { status: r.status, out: r.stdout, err: r.stderr };
}

describe('make run STDIN_<NAME>=file', () => {
    it('stops before anything is built or started when NAME is no executable, naming it and the executables', () => {
        const typo = makeRun(['STDIN_MAX=commands.txt']);
        expect(typo.status).toBe(2);
        expect(typo.out).toBe('');
        expect(typo.err).toMatch(/^Makefile:\d+: \*\*\* STDIN_MAX=commands.txt: no module MAX; this architecture's executables are ORD MAA MAB MSA MSB MSC MSD SUP GLB; nothing was built or run\. {2}Stop\.\n$/);
        // with a good one beside it: refused all the same (a stop, not a run without the file meant)
        const both = makeRun(['STDIN_MAA=a.txt', 'STDIN_msc=b.txt']);
        expect(both.status).toBe(2);
        expect(both.err).toContain('*** STDIN_msc=b.txt: no module msc; ');
        // make all is not concerned
        const all = spawnSync('make', ['-n', 'all', 'STDIN_MAX=x', `CONTRACT_RUNTIME=${join(REPO, 'runtime')}`], { cwd: ARCH, encoding: 'utf8' });
        expect(all.stderr).not.toContain('no module');
    });

    it('gives an executable its file; a STDIN_ variable of the environment is not looked at', () => {
        const good = makeRun(['STDIN_MAA=commands.txt'], { STDIN_ELSEWHERE: 'x' });
        expect(good.err).toBe('');
        expect(good.status).toBe(0);
        expect(good.out).toContain(" --stdin MAA=commands.txt modules/ORD_mod/ORD ");
    });
});
