/**
 * `contract build` on a project whose generated tree holds a GNUmakefile or makefile (the build
 * service's foreign-makefile refusal): the refusal is printed once, its paths from where the command
 * ran (`DIR/src-gen/...`, as the CLI's other paths), and a link of that name gets the same advice
 * (remove it), not the link's (copy the file in).
 */
import { chmodSync, cpSync, mkdtempSync, symlinkSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { runCli } from '../src/cli.js';
import { REPO } from './e2e/harness.js';
import { capture } from './capture-io.js';
import { removeScratch } from './scratch.js';

let root: string;
beforeAll(() => {
    root = mkdtempSync(join(tmpdir(), 'contract-foreign-makefile-'));
    chmodSync(root, 0o711); // a root build's cache folder must be reachable by the sandboxes' uids
    process.env.CONTRACT_CACHE_DIR = join(root, 'cache');
});
afterAll(() => {
    delete process.env.CONTRACT_CACHE_DIR;
    removeScratch(root);
});

const REFUSAL = 'a makefile in the generated tree that is not the generated one (GNU make would read it instead of the generated Makefile, and its recipes would be the build); a Cactal build runs only the generated Makefiles: remove it, or rename it (the generated Makefiles never read it); nothing was built';

/** stderr of `contract build NAME` (no sandbox: prepare refuses before one is used), its exit code checked. */
async function build(name: string, verbose = false): Promise<string> {
    const io = capture(root);
    expect(await runCli(['build', name, '--sandbox', 'none', ...(verbose ? ['--verbose'] : [])], io), io.stderr).toBe(1);
    return io.stderr;
}

describe('contract build: the foreign-makefile refusal', () => {
    it('is said once, at DIR/src-gen/..., with or without --verbose', async () => {
        cpSync(join(REPO, 'examples/tutorial'), join(root, 'plain'), { recursive: true });
        writeFileSync(join(root, 'plain/src-gen/generated/GNUmakefile'), 'all: ; echo PWNED\n');
        for (const verbose of [false, true]) {
            const stderr = await build('plain', verbose);
            expect(stderr.split(REFUSAL).length - 1, stderr).toBe(1);
            expect(stderr).toContain(`FAILED: prepare failed: plain/src-gen/generated/GNUmakefile: ${REFUSAL} [`);
            expect(stderr).not.toMatch(/^error: /m);
        }
    }, 120_000);

    it('a link named GNUmakefile gets that refusal (remove it), not the advice to copy the file in', async () => {
        cpSync(join(REPO, 'examples/tutorial'), join(root, 'linked'), { recursive: true });
        writeFileSync(join(root, 'linked/mine.mk'), 'all: ; echo PWNED\n');
        symlinkSync(join(root, 'linked/mine.mk'), join(root, 'linked/src-gen/generated/architecture/GNUmakefile'));
        const stderr = await build('linked');
        expect(stderr).toContain(`FAILED: prepare failed: linked/src-gen/generated/architecture/GNUmakefile: ${REFUSAL} [`);
        expect(stderr).not.toContain('cp --remove-destination');
    }, 120_000);
});
