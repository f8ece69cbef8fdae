/**
 * `contract run --stdin MODULE=FILE`: a module reads a file of the project on its stdin (the old
 * tutorial's MAA reads its commands with scanf: on /dev/null it looped on `BAD INPUT` until the
 * output limit stopped the run). Real runs in the bwrap sandbox, through the build service,
 * `make run STDIN_<MODULE>=` and contract-launch `--stdin`.
 */
import { spawnSync } from 'node:child_process';
import { chmodSync, cpSync, mkdtempSync, readFileSync, symlinkSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { runCli } from '../src/cli.js';
import { REPO } from './e2e/harness.js';
import { capture } from './capture-io.js';
import { removeScratch } from './scratch.js';
import { seedRuntime } from '@contract-studio/build-service/test-support/runtime-seed';

const hasBwrap = spawnSync('bwrap', ['--ro-bind', '/', '/', 'true']).status === 0;
const MSC_C = 'src-gen/generated/architecture/modules/MSC_mod/module.c';

let root: string;
let project: string;
beforeAll(async () => {
    root = mkdtempSync(join(tmpdir(), 'contract-stdin-'));
    chmodSync(root, 0o711);
    process.env.CONTRACT_CACHE_DIR = join(root, 'cache');
    await seedRuntime(join(root, 'cache'));
    project = join(root, 'robot');
    cpSync(join(REPO, 'examples/tutorial'), project, { recursive: true, filter: (src) => !/[/]logs$/.test(src) });
    // MSC's init reads one line of its stdin and says what it read
    const c = readFileSync(join(project, MSC_C), 'utf8');
    const init = '    printf("initialization of MSC\\n");\n';
    expect(c).toContain(init);
    writeFileSync(join(project, MSC_C), c.replace(init, `${init}    { char line[80]; if (fgets(line, sizeof line, stdin)) printf("MSC read: %s", line); else printf("MSC read nothing\\n"); }\n`));
    writeFileSync(join(project, 'commands.txt'), 'hello from stdin\n');
    writeFileSync(join(root, 'outside.txt'), 'not the project\'s\n');
    symlinkSync(join(root, 'outside.txt'), join(project, 'linked.txt'));
}, 240_000);
afterAll(() => {
    delete process.env.CONTRACT_CACHE_DIR;
    removeScratch(root);
});

const run = async (...extra: string[]) => {
    const io = capture(root);
    const status = await runCli(['run', 'robot', '--duration', '1s', '--sandbox', 'bwrap', ...extra], io);
    return { status, ...io };
};

describe.skipIf(!hasBwrap)('contract run --stdin', () => {
    it('gives the module the project file on its stdin; the others, and every module without it, read /dev/null', async () => {
        const given = await run('--stdin', 'MSC=commands.txt');
        expect(given.stderr).toContain('contract-launch: module MSC reads its stdin from ');
        expect(given.stdout).toContain('[MSC] MSC read: hello from stdin\n');
        expect(given.status).toBe(0);
        const none = await run();
        expect(none.stdout).toContain('[MSC] MSC read nothing\n');
        expect(none.status).toBe(0);
    }, 240_000);

    it('refuses a file outside the project, through a link, or not there, and a bad option, running nothing', async () => {
        const outside = await run('--stdin', 'MSC=../outside.txt');
        expect(outside.status).toBe(1);
        expect(outside.stderr).toContain('stdin.MSC: path "../outside.txt" has an empty, "." or ".." component (a path inside the project, relative to it)');
        const linked = await run('--stdin', 'MSC=linked.txt');
        expect(linked.status).toBe(1);
        expect(linked.stderr).toContain('stdin of MSC: linked.txt is not a regular file of the project (not there, a folder, or reached through a symbolic link); nothing was run');
        expect(linked.stdout).not.toContain('[MSC]');
        const missing = await run('--stdin', 'MSC=nothing.txt');
        expect(missing.stderr).toContain('stdin of MSC: nothing.txt is not a regular file of the project');
        // a module the model does not have (a typo): refused before the build, with the one meant
        const typo = await run('--stdin', 'MSX=commands.txt');
        expect(typo.status).toBe(2);
        expect(typo.stderr).toContain("contract run: bad --stdin MSX=commands.txt: no module 'MSX' in this architecture. Did you mean 'MSA'? (its modules: ORD, MAA, MAB, MSA, MSB, MSC, MSD, SUP, GLB); nothing was started\n");
        expect(typo.stdout).toBe('');
        const bad = await run('--stdin', 'MSC');
        expect(bad.status).toBe(2);
        expect(bad.stderr).toContain("bad --stdin 'MSC': expected MODULE=FILE");
    }, 240_000);
});
