/**
 * `contract generate`: the tree it writes depends only on the model (teams commit src-gen,
 * docs/ci.md), and the runtime is a build-time input (docs/architecture.md, Seam 3).
 */
import { spawn } from 'node:child_process';
import { cpSync, existsSync, mkdirSync, mkdtempSync, readdirSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join, relative } from 'node:path';
import { fileURLToPath } from 'node:url';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { runCli } from '../src/cli.js';
import { capture } from './capture-io.js';

const TUTORIAL = fileURLToPath(new URL('../../../examples/tutorial', import.meta.url));


/** Every file under `root` with its bytes, by relative path. */
function tree(root: string): Map<string, string> {
    const out = new Map<string, string>();
    const walk = (dir: string) => {
        for (const e of readdirSync(dir, { withFileTypes: true })) {
            const p = join(dir, e.name);
            if (e.isDirectory()) walk(p);
            else out.set(relative(root, p), readFileSync(p, 'latin1'));
        }
    };
    walk(root);
    return new Map([...out].sort(([a], [b]) => (a < b ? -1 : 1)));
}

/** The tutorial's .contract files (no src-gen) in `dir`. */
function sources(dir: string): void {
    mkdirSync(dir, { recursive: true });
    for (const f of readdirSync(TUTORIAL)) if (f.endsWith('.contract')) cpSync(join(TUTORIAL, f), join(dir, f));
}

let scratch: string;
beforeAll(() => { scratch = mkdtempSync(join(tmpdir(), 'contract-generate-')); });
afterAll(() => rmSync(scratch, { recursive: true, force: true }));

describe('contract generate', () => {
    it('writes byte-identical trees from two folders and two working directories', async () => {
        sources(join(scratch, 'one'));
        sources(join(scratch, 'a', 'b', 'c', 'two'));
        const first = capture(scratch);
        expect(await runCli(['generate', 'one'], first)).toBe(0);
        const second = capture(join(scratch, 'a', 'b'));
        expect(await runCli(['generate', 'c/two', '-o', join(scratch, 'a', 'b', 'c', 'two', 'src-gen')], second)).toBe(0);
        const a = tree(join(scratch, 'one', 'src-gen'));
        expect(a.size).toBeGreaterThan(40);
        expect(tree(join(scratch, 'a', 'b', 'c', 'two', 'src-gen'))).toEqual(a);
        for (const [path, text] of a) expect(text, path).not.toContain(scratch);
    }, 60_000);

    it('refuses a folder without a .contract file, and the folder above a project with its own src-gen/ (nothing written); check fails on no .contract file', async () => {
        mkdirSync(join(scratch, 'nothing'));
        const empty = capture(scratch);
        expect(await runCli(['generate', 'nothing'], empty)).toBe(1);
        expect(empty.stderr).toBe('no .contract file in nothing: nothing was generated (a project is the folder of its .contract files)\n');
        const checked = capture(scratch);
        expect(await runCli(['check', 'nothing'], checked)).toBe(1);
        expect(checked.stderr).toContain('no .contract file in nothing: nothing was checked');
        expect(readdirSync(join(scratch, 'nothing'))).toEqual([]);
        sources(join(scratch, 'repo', 'robot'));
        expect(await runCli(['generate', 'repo/robot'], capture(scratch))).toBe(0);
        const above = capture(scratch);
        expect(await runCli(['generate', 'repo'], above)).toBe(1);
        expect(above.stderr).toBe('the .contract files of repo are all in robot/, which has its own src-gen/ (its generated code and yours): generate repo/robot instead (or name the output with -o OUT); nothing was generated\n');
        expect(readdirSync(join(scratch, 'repo'))).toEqual(['robot']);
    }, 60_000);

    it('the Eclipse layout (DIR/src/*.contract, DIR/src-gen/): DIR is the project; a second tree DIR/src/src-gen is said and not used', async () => {
        sources(join(scratch, 'oldproj', 'src'));
        const first = capture(scratch);
        expect(await runCli(['generate', 'oldproj'], first)).toBe(0);
        expect(first.stderr).not.toContain('second generated tree');
        expect(existsSync(join(scratch, 'oldproj', 'src-gen', '.contract-manifest.json'))).toBe(true);
        // the tree the IDE used to make beside it (defaults only)
        cpSync(join(scratch, 'oldproj', 'src-gen'), join(scratch, 'oldproj', 'src', 'src-gen'), { recursive: true });
        const again = capture(scratch);
        expect(await runCli(['generate', 'oldproj'], again)).toBe(0);
        expect(again.stderr).toContain('warning: oldproj/src/src-gen/ is a second generated tree of this project, not used: the project is oldproj and its tree oldproj/src-gen/ (the outermost folder holding a src-gen/ is the project; docs/codegen.md "Where a project is"): move any code of yours out of oldproj/src/src-gen/, then delete it\n');
        expect(again.stderr).toContain('generated oldproj/src-gen: 0 created');
    }, 60_000);

    it('refuses a folder of several projects (examples/), naming them; one of them generates', async () => {
        sources(join(scratch, 'several', 'a'));
        sources(join(scratch, 'several', 'b', 'src'));
        const io = capture(scratch);
        expect(await runCli(['generate', 'several'], io)).toBe(1);
        expect(io.stderr).toBe('several holds several projects (a/, b/): generate one of them (contract generate several/a), or name the output with -o OUT; nothing was generated\n');
        expect(readdirSync(join(scratch, 'several')).sort()).toEqual(['a', 'b']);
        expect(await runCli(['generate', 'several/b'], capture(scratch))).toBe(0);
        expect(existsSync(join(scratch, 'several', 'b', 'src-gen', 'generated', 'architecture', 'Makefile'))).toBe(true);
    }, 60_000);

    it('waits for another writer of the tree (its lock held), saying for whom, then generates', async () => {
        sources(join(scratch, 'locked'));
        expect(await runCli(['generate', 'locked'], capture(scratch))).toBe(0);
        const holder = spawn(process.execPath, ['-e', 'setTimeout(() => {}, 60000)']);
        const lock = join(scratch, 'locked', 'src-gen', '.contract-lock');
        writeFileSync(lock, `${holder.pid}\n`);
        try {
            setTimeout(() => rmSync(lock, { force: true }), 400); // the other writer ends
            const io = capture(scratch);
            const started = Date.now();
            expect(await runCli(['generate', 'locked'], io)).toBe(0);
            expect(Date.now() - started).toBeGreaterThanOrEqual(350);
            expect(io.stderr).toContain(`waiting for the other writer of locked/src-gen (pid ${holder.pid}: a contract generate or rename, or the IDE server) to finish ...\n`);
            expect(existsSync(lock)).toBe(false);
        } finally {
            holder.kill();
        }
    }, 60_000);

    it('refuses --runtime (exit 2, nothing written) and says where the runtime is given', async () => {
        sources(join(scratch, 'three'));
        const io = capture(scratch);
        expect(await runCli(['generate', 'three', '--runtime', '/somewhere/runtime'], io)).toBe(2);
        expect(io.stderr).toContain('generate takes no --runtime: the runtime is given when building (contract build --runtime PATH, or make CONTRACT_RUNTIME=PATH)');
        expect(existsSync(join(scratch, 'three', 'src-gen'))).toBe(false);
    }, 60_000);
});
