/**
 * A `contract rename` killed half-way (docs/codegen.md, "A rename killed half-way"): it journals
 * its work in src-gen/.contract-rename.json before it changes anything, and the next `contract
 * generate` (or rename, or the IDE's Generate All) finishes it, so the renamed module's code is
 * never moved to orphans/. The killed states are made here with the library calls the rename
 * makes, in its order, stopped where a SIGKILL would stop them (after the tree's carry-over,
 * before the manifest); a hostile journal is refused and changes nothing.
 */
import { chmodSync, cpSync, existsSync, mkdtempSync, readFileSync, readdirSync, realpathSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { identifierRenames, renameIdentifiersInGeneratedTree, renameInGeneratedTree, sha256, writeRenameJournal, type RenameJournal } from '@contract-studio/codegen';
import { runCli } from '../src/cli.js';
import { capture } from './capture-io.js';
import { removeScratch } from './scratch.js';
import { seedRuntime } from '@contract-studio/build-service/test-support/runtime-seed';

const MODULES = 'src-gen/generated/architecture/modules';
const JOURNAL = 'src-gen/.contract-rename.json';
const MARK = 'int journal_marker = 7; (void)journal_marker;';

let root: string;
/** The new project's .contract files after `contract rename robot LOC LCX`, by name. */
let renamedTexts: Map<string, string>;

/** A fresh copy of the generated project with user code in LOC's init region. */
function project(name: string): string {
    const dir = join(root, name);
    cpSync(join(root, 'robot'), dir, { recursive: true });
    return dir;
}

function contractFiles(dir: string): string[] {
    return readdirSync(dir).filter((f) => f.endsWith('.contract')).sort();
}

/** The journal `contract rename robot LOC LCX` writes for project `dir` as it is now. */
function journalOf(dir: string, files = contractFiles(dir)): RenameJournal {
    return {
        version: 1, kind: 'module', oldName: 'LOC', newName: 'LCX', generatedNames: true, identifiers: [],
        files: files.filter((f) => readFileSync(join(dir, f), 'utf8') !== renamedTexts.get(f)).map((f) => ({
            path: f, before: sha256(readFileSync(join(dir, f))), after: renamedTexts.get(f)!,
        })),
    };
}

/** Where the user code is now: the module folder of the model's name, and orphans/. */
function userCode(dir: string): { module: boolean; orphans: string[] } {
    const orphans: string[] = [];
    const walk = (d: string): void => {
        if (!existsSync(d)) return;
        for (const e of readdirSync(d, { withFileTypes: true })) {
            const p = join(d, e.name);
            if (e.isDirectory()) walk(p);
            else if (readFileSync(p, 'latin1').includes('journal_marker')) orphans.push(p.slice(dir.length + 1));
        }
    };
    walk(join(dir, 'src-gen/orphans'));
    const file = join(dir, MODULES, 'LCX_mod/module.c');
    return { module: existsSync(file) && readFileSync(file, 'latin1').includes(MARK), orphans };
}

beforeAll(async () => {
    root = mkdtempSync(join(tmpdir(), 'contract-rename-journal-'));
    chmodSync(root, 0o711); // the sandbox's own uid must reach the cache folder inside
    expect(await runCli(['new', 'robot'], capture(root))).toBe(0);
    expect(await runCli(['generate', 'robot'], capture(root))).toBe(0);
    const file = join(root, 'robot', MODULES, 'LOC_mod/module.c');
    writeFileSync(file, readFileSync(file, 'latin1').replace('/*PROTECTED REGION ID(protect_init_LOC) ENABLED START*/', `/*PROTECTED REGION ID(protect_init_LOC) ENABLED START*/\n    ${MARK}`), 'latin1');
    const whole = project('whole');
    const io = capture(root);
    expect(await runCli(['rename', 'whole', 'LOC', 'LCX'], io), io.stderr).toBe(0);
    expect(existsSync(join(whole, JOURNAL))).toBe(false); // a whole rename leaves no journal
    renamedTexts = new Map(contractFiles(whole).map((f) => [f, readFileSync(join(whole, f), 'utf8')]));
}, 120_000);
// (a build's work tree stays mounted in its cache: removeScratch unmounts it first)
afterAll(() => removeScratch(root));

describe('a contract rename killed half-way', () => {
    it('killed after the tree was carried over, before the .contract files: the next generate finishes it, nothing orphaned', async () => {
        const dir = project('after-carry');
        writeRenameJournal(join(dir, 'src-gen'), journalOf(dir));
        await renameInGeneratedTree(join(dir, 'src-gen'), 'LOC', 'LCX');
        expect(readFileSync(join(dir, 'module1.contract'), 'utf8')).toContain('module LOC'); // the half state

        const io = capture(root);
        expect(await runCli(['generate', 'after-carry'], io), io.stderr).toBe(0);
        expect(io.stderr).toContain('finished the rename of module LOC -> LCX that was interrupted (its journal src-gen/.contract-rename.json): 3 file(s) written, 0 already renamed');
        expect(io.stderr).toMatch(/generated after-carry\/src-gen: \d+ created, \d+ updated, \d+ kept, 0 orphaned, 0 error\(s\)/);
        for (const f of contractFiles(dir)) expect(readFileSync(join(dir, f), 'utf8')).toBe(renamedTexts.get(f));
        expect(userCode(dir)).toEqual({ module: true, orphans: [] });
        expect(existsSync(join(dir, JOURNAL))).toBe(false);
        // the journal is gone: the next generate says nothing of it and writes nothing
        const again = capture(root);
        expect(await runCli(['generate', 'after-carry'], again)).toBe(0);
        expect(again.stderr).not.toContain('finished the rename');
        expect(again.stderr).toMatch(/: 0 created, 0 updated, \d+ kept, 0 orphaned, 0 error\(s\)/);
    });

    it('killed in the carry-over, after the files moved but before the manifest: finished, no false "edited outside its regions"', async () => {
        const dir = project('mid-carry');
        const manifest = readFileSync(join(dir, 'src-gen/.contract-manifest.json'));
        writeRenameJournal(join(dir, 'src-gen'), journalOf(dir));
        await renameInGeneratedTree(join(dir, 'src-gen'), 'LOC', 'LCX');
        writeFileSync(join(dir, 'src-gen/.contract-manifest.json'), manifest); // the manifest as the kill left it

        const io = capture(root);
        expect(await runCli(['generate', 'mid-carry'], io), io.stderr).toBe(0);
        expect(io.stderr).toContain('finished the rename of module LOC -> LCX');
        expect(io.stderr).not.toContain('edited outside its protected regions');
        expect(userCode(dir)).toEqual({ module: true, orphans: [] });
    });

    it('killed before the tree was touched, or while the .contract files were written: finished the same way', async () => {
        const before = project('before-carry');
        writeRenameJournal(join(before, 'src-gen'), journalOf(before));
        const io = capture(root);
        expect(await runCli(['generate', 'before-carry'], io), io.stderr).toBe(0);
        expect(userCode(before)).toEqual({ module: true, orphans: [] });

        const during = project('during-files');
        writeRenameJournal(join(during, 'src-gen'), journalOf(during));
        await renameInGeneratedTree(join(during, 'src-gen'), 'LOC', 'LCX');
        writeFileSync(join(during, 'module1.contract'), renamedTexts.get('module1.contract')!); // one file written, then killed
        const io2 = capture(root);
        expect(await runCli(['rename', 'during-files', 'CTL', 'CTX'], io2), io2.stderr).toBe(0); // a rename finishes it too, then renames
        expect(io2.stderr).toContain('finished the rename of module LOC -> LCX that was interrupted (its journal src-gen/.contract-rename.json): 2 file(s) written, 1 already renamed');
        expect(userCode(during)).toEqual({ module: true, orphans: [] });
        expect(readFileSync(join(during, 'module2.contract'), 'utf8')).toContain('module CTX');
    });

    it('with -o OUT: the journal names the project, and only a generate of that project into that OUT finishes it', async () => {
        const dir = project('outside');
        const out = join(root, 'outside-out');
        cpSync(join(dir, 'src-gen'), out, { recursive: true });
        rmSync(join(dir, 'src-gen'), { recursive: true });
        writeRenameJournal(out, { ...journalOf(dir), project: realpathSync(dir) });
        await renameInGeneratedTree(out, 'LOC', 'LCX');
        // another project generating into that folder: refused, nothing changed
        const other = project('other');
        const wrong = capture(root);
        expect(await runCli(['generate', 'other', '-o', 'outside-out'], wrong)).toBe(1);
        expect(wrong.stderr).toContain(`journals a rename of ${realpathSync(dir)}, not of ${join(root, 'other')}`);
        expect(readFileSync(join(other, 'module1.contract'), 'utf8')).toContain('module LOC');
        // the project itself: finished
        const io = capture(root);
        expect(await runCli(['generate', 'outside', '-o', 'outside-out'], io), io.stderr).toBe(0);
        expect(io.stderr).toContain('finished the rename of module LOC -> LCX that was interrupted');
        expect(readFileSync(join(dir, 'module1.contract'), 'utf8')).toBe(renamedTexts.get('module1.contract'));
        expect(readFileSync(join(out, 'generated/architecture/modules/LCX_mod/module.c'), 'latin1')).toContain(MARK);
        expect(existsSync(join(out, 'orphans'))).toBe(false);
    });

    it('a .contract file changed since the rename began is left as it is and named; the others are written', async () => {
        const dir = project('edited');
        writeRenameJournal(join(dir, 'src-gen'), journalOf(dir));
        await renameInGeneratedTree(join(dir, 'src-gen'), 'LOC', 'LCX');
        const edited = `${readFileSync(join(dir, 'sched.contract'), 'utf8')}// typed meanwhile\n`;
        writeFileSync(join(dir, 'sched.contract'), edited);
        const io = capture(root);
        await runCli(['generate', 'edited'], io);
        expect(io.stderr).toContain('2 file(s) written, 0 already renamed');
        expect(io.stderr).toContain('warning: edited/sched.contract changed since the rename began (or is gone): left as it is; rename LOC there by hand');
        expect(readFileSync(join(dir, 'sched.contract'), 'utf8')).toBe(edited);
        expect(readFileSync(join(dir, 'module1.contract'), 'utf8')).toBe(renamedTexts.get('module1.contract'));
    });

    describe('a datatype rename killed after some module.c files had their code rewritten', () => {
        const EXEC = (m: string) => `/*PROTECTED REGION ID(protect_exec_${m}) ENABLED START*/`;
        /** Project `name`: a copy of robot whose LOC and CTL use Position in their code (and CTL `extra` too), generated. */
        async function datatypeProject(name: string, extra = ''): Promise<string> {
            const dir = project(name);
            for (const m of ['LOC', 'CTL']) {
                const file = join(dir, MODULES, `${m}_mod/module.c`);
                writeFileSync(file, readFileSync(file, 'latin1').replace(EXEC(m), `${EXEC(m)}\n    Position copy_${m} = position; (void)copy_${m};${m === 'CTL' ? extra : ''}`), 'latin1');
            }
            return dir;
        }
        /** `contract rename DIR Position Pose` killed once LOC's module.c was rewritten: the journal, the tree's paths and IDs, LOC's code. */
        async function killedAfterLoc(dir: string): Promise<void> {
            const whole = join(root, `${dir.split('/').pop()}-whole`);
            cpSync(dir, whole, { recursive: true });
            const io = capture(root);
            await runCli(['rename', whole, 'Position', 'Pose'], io); // (CTL's capture, when there is one, is said, exit 1)
            const renames = identifierRenames('datatype', 'Position', 'Pose');
            writeRenameJournal(join(dir, 'src-gen'), {
                version: 1, kind: 'datatype', oldName: 'Position', newName: 'Pose', generatedNames: true, identifiers: [...renames],
                files: contractFiles(dir).filter((f) => readFileSync(join(dir, f), 'utf8') !== readFileSync(join(whole, f), 'utf8')).map((f) => ({
                    path: f, before: sha256(readFileSync(join(dir, f))), after: readFileSync(join(whole, f), 'utf8'),
                })),
            });
            await renameInGeneratedTree(join(dir, 'src-gen'), 'Position', 'Pose', 'datatype');
            expect(renameIdentifiersInGeneratedTree(join(dir, 'src-gen'), renames, 'LOC').rewritten.length).toBeGreaterThan(0); // LOC's file written, then killed
        }
        const code = (dir: string, m: string) => readFileSync(join(dir, MODULES, `${m}_mod/module.c`), 'latin1');

        it('finishing it rewrites the code of the others: a file already rewritten (the new name, not the old) does not stop them', async () => {
            const dir = await datatypeProject('datatype-killed');
            await killedAfterLoc(dir);
            expect(code(dir, 'LOC')).toContain('Pose copy_LOC = position;'); // the half state
            expect(code(dir, 'CTL')).toContain('Position copy_CTL = position;');

            const io = capture(root);
            expect(await runCli(['generate', 'datatype-killed'], io), io.stderr).toBe(0);
            expect(io.stderr).toContain('finished the rename of datatype Position -> Pose that was interrupted');
            expect(io.stderr).not.toContain('warning');
            expect(code(dir, 'CTL')).toContain('Pose copy_CTL = position;');
            expect(code(dir, 'LOC')).toContain('Pose copy_LOC = position;');
            expect(`${code(dir, 'CTL')}${code(dir, 'LOC')}`).not.toMatch(/\bPosition\b/);
        });

        it('a real capture (a file using Position and Pose as two things) is still refused, and said: a warning, then the regions still using Position', async () => {
            const dir = await datatypeProject('datatype-capture', ' double Pose = 1.0; (void)Pose;');
            await killedAfterLoc(dir);
            const io = capture(root);
            expect(await runCli(['generate', 'datatype-capture'], io), io.stderr).toBe(0);
            expect(io.stderr).toContain('finished the rename of datatype Position -> Pose that was interrupted');
            expect(io.stderr).toMatch(/warning: 'Pose' is already used in the code of protected region protect_exec_CTL \(datatype-capture\/src-gen\/generated\/architecture\/modules\/CTL_mod\/module\.c:\d+\): uses of 'Position', 'serialize_Position', .* were not rewritten: change them by hand, the build fails until then/);
            expect(io.stderr).toMatch(/warning: datatype-capture\/src-gen\/generated\/architecture\/modules\/CTL_mod\/module\.c:\d+: protected region protect_exec_CTL still uses Position \(the old name\) in its code: change it by hand, the build fails until then/);
            // (nothing rewritten anywhere: the header's comparisons still call eq_Position... too)
            expect(io.stderr).toMatch(/contract generate: the rename of datatype Position -> Pose is finished, but \d+ use\(s\) of Position in protected-region code were not changed \(listed above\)/);
            expect(code(dir, 'CTL')).toContain('Position copy_CTL = position; (void)copy_CTL; double Pose = 1.0;'); // nothing changed there
            expect(code(dir, 'LOC')).toContain('Pose copy_LOC = position;');
        });
    });

    it('a build of a tree holding a journal is refused before anything is built, saying to run contract generate', async () => {
        const dir = project('build-refused');
        writeRenameJournal(join(dir, 'src-gen'), journalOf(dir));
        const io = capture(root);
        const cache = join(root, 'cache');
        await seedRuntime(cache); // the test run's built runtime
        expect(await runCli(['build', 'build-refused', '--sandbox', 'none', '--cache-dir', cache], io), io.stderr).toBe(1);
        expect(io.stderr).toContain('an interrupted rename left its journal here');
        expect(io.stderr).toContain('run `contract generate build-refused` to finish the interrupted rename, then build again');
        expect(io.stderr).not.toContain('a protected-region marker broken or edited');
        expect(existsSync(join(dir, JOURNAL))).toBe(true); // a build never writes the project
    }, 120_000);

    it('a hostile journal (a path out of the project) is refused: nothing is written, the generation refuses the tree and says why', async () => {
        const dir = project('hostile');
        const journal = journalOf(dir);
        journal.files.push({ path: '../outside.contract', before: sha256(Buffer.from('')), after: 'pwned' });
        writeFileSync(join(root, 'outside.contract'), '');
        writeFileSync(join(dir, JOURNAL), JSON.stringify(journal));
        const texts = contractFiles(dir).map((f) => readFileSync(join(dir, f), 'utf8'));
        const io = capture(root);
        expect(await runCli(['generate', 'hostile'], io)).toBe(1);
        expect(io.stderr).toContain('warning: src-gen/.contract-rename.json is not the journal of an unfinished rename (file "../outside.contract": empty, "." or ".." component): nothing was changed; remove it to go on');
        expect(io.stderr).toContain('an interrupted rename left its journal here');
        expect(readFileSync(join(root, 'outside.contract'), 'utf8')).toBe('');
        expect(contractFiles(dir).map((f) => readFileSync(join(dir, f), 'utf8'))).toEqual(texts);
        expect(existsSync(join(dir, MODULES, 'LOC_mod/module.c'))).toBe(true); // the tree untouched
        // a rename neither goes past nor replaces a journal it could not finish: it may be the only record of a killed rename
        const rename = capture(root);
        expect(await runCli(['rename', 'hostile', 'LOC', 'LCY'], rename)).toBe(1);
        expect(rename.stderr).toContain('contract rename: hostile/src-gen/.contract-rename.json (an interrupted rename) could not be finished (said above): nothing was renamed');
        expect(readFileSync(join(dir, JOURNAL), 'utf8')).toBe(JSON.stringify(journal));
        expect(contractFiles(dir).map((f) => readFileSync(join(dir, f), 'utf8'))).toEqual(texts);
        // not JSON: said so
        writeFileSync(join(dir, JOURNAL), '{ truncated');
        const again = capture(root);
        expect(await runCli(['generate', 'hostile'], again)).toBe(1);
        expect(again.stderr).toContain('is not the journal of an unfinished rename (not JSON)');
    });
});
