/**
 * `contract runtime-source DIR`: the runtime's sources the CLI carries, copied out for a build by
 * hand (docs/getting-started.md §4), without build products; a non-empty DIR is refused unless
 * --force. The copy builds with plain make and installs. (The packed CLI's copy:
 * test/e2e/installed-cli.e2e.test.ts.)
 */
import { execFileSync } from 'node:child_process';
import { existsSync, mkdirSync, mkdtempSync, readFileSync, readdirSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { runCli } from '../src/cli.js';
import { capture } from './capture-io.js';

const REPO_RUNTIME = fileURLToPath(new URL('../../../runtime', import.meta.url));

/** Every file path under `root`, relative. */
function files(root: string, rel = ''): string[] {
    return readdirSync(join(root, rel), { withFileTypes: true }).flatMap((e) => (e.isDirectory() ? files(root, join(rel, e.name)) : [join(rel, e.name)]));
}

describe('contract runtime-source DIR', () => {
    let root: string;
    beforeAll(() => {
        root = mkdtempSync(join(tmpdir(), 'contract-runtime-source-'));
        // the repository's runtime is built (build/ holds objects, the library, the launcher): none of it is copied
        execFileSync('make', ['-s', '-C', REPO_RUNTIME, 'build/libmodule.a', 'build/contract-launch'], { stdio: 'pipe' });
    }, 120_000);
    afterAll(() => rmSync(root, { recursive: true, force: true }));

    it('copies the sources (Makefile, include/, src/, launcher/, sim/) and no build product', async () => {
        const io = capture(root);
        expect(await runCli(['runtime-source', 'rt'], io)).toBe(0);
        const copied = files(join(root, 'rt'));
        expect(copied).toEqual(expect.arrayContaining(['Makefile', 'include/libmodule/libmodule.h', 'src/core.c', 'src/engines/ord_core.c', 'launcher/contract-launch.c', 'sim/sim.mk']));
        expect(copied.filter((f) => /(^|\/)build\/|\.(o|a)$|contract-launch$/.test(f))).toEqual([]);
        expect(existsSync(join(REPO_RUNTIME, 'build', 'libmodule.a'))).toBe(true); // there was something to leave out
        expect(readFileSync(join(root, 'rt', 'src', 'core.c'), 'utf8')).toBe(readFileSync(join(REPO_RUNTIME, 'src', 'core.c'), 'utf8'));
        expect(io.stdout).toMatch(/copied the runtime's sources \(\d+ files, no build products\) into rt/);
        expect(io.stderr).toContain('next: make -C rt');
    });

    it('refuses a folder that is not empty, changing nothing; --force overwrites the runtime\'s files and keeps the others', async () => {
        const dir = join(root, 'robot-runtime');
        mkdirSync(join(dir, 'src'), { recursive: true });
        writeFileSync(join(dir, 'src', 'core.c'), '/* my patched core */\n');
        writeFileSync(join(dir, 'NOTES.txt'), 'mine\n');
        const refused = capture(root);
        expect(await runCli(['runtime-source', 'robot-runtime'], refused)).toBe(1);
        expect(refused.stderr).toContain('robot-runtime is not empty; nothing was copied (name a new or empty folder, or add --force');
        expect(files(dir).sort()).toEqual(['NOTES.txt', 'src/core.c']);
        expect(readFileSync(join(dir, 'src', 'core.c'), 'utf8')).toBe('/* my patched core */\n');

        expect(await runCli(['runtime-source', 'robot-runtime', '--force'], capture(root))).toBe(0);
        expect(readFileSync(join(dir, 'src', 'core.c'), 'utf8')).toBe(readFileSync(join(REPO_RUNTIME, 'src', 'core.c'), 'utf8'));
        expect(readFileSync(join(dir, 'NOTES.txt'), 'utf8')).toBe('mine\n');
    });

    it('refuses a DIR that is a file, and a usage without DIR', async () => {
        writeFileSync(join(root, 'a-file'), 'x');
        const io = capture(root);
        expect(await runCli(['runtime-source', 'a-file'], io)).toBe(1);
        expect(io.stderr).toContain('a-file exists and is not a directory; nothing was copied');
        const usage = capture(root);
        expect(await runCli(['runtime-source'], usage)).toBe(2);
        expect(usage.stderr).toContain('missing DIR');
    });

    it('the copy builds with plain make and installs (what a robot without a checkout does)', () => {
        const rt = join(root, 'rt');
        execFileSync('make', ['-s', '-j2', '-C', rt, 'build/libmodule.a', 'build/contract-launch', 'CFLAGS=-O0'], { stdio: 'pipe' });
        execFileSync('make', ['-s', '-C', rt, 'install', `PREFIX=${join(root, 'opt-runtime')}`, 'CFLAGS=-O0'], { stdio: 'pipe' });
        for (const f of ['include/libmodule/libmodule.h', 'build/libmodule.a', 'build/contract-launch']) expect(existsSync(join(root, 'opt-runtime', f)), f).toBe(true);
    }, 180_000);

    it('contract build refuses an installed runtime (no sources) named by CONTRACT_RUNTIME or --runtime, before any build', async () => {
        const installed = join(root, 'opt-runtime');
        expect(existsSync(join(installed, 'build', 'libmodule.a'))).toBe(true);
        const saved = process.env.CONTRACT_RUNTIME;
        process.env.CONTRACT_RUNTIME = installed;
        try {
            const io = capture(root);
            expect(await runCli(['build', '.'], io)).toBe(2);
            expect(io.stderr).toContain(`CONTRACT_RUNTIME=${installed} names an installed runtime, which has no sources (no src/ beside its build/): contract build builds the runtime from its sources, for the compiler it uses; unset it, or name a runtime source folder`);
            expect(io.stderr).not.toContain('No rule to make target');
        } finally {
            if (saved === undefined) delete process.env.CONTRACT_RUNTIME;
            else process.env.CONTRACT_RUNTIME = saved;
        }
        const option = capture(root);
        expect(await runCli(['build', '.', '--runtime', installed], option)).toBe(2);
        expect(option.stderr).toContain(`--runtime ${installed} names an installed runtime`);
    });
});
