/**
 * Incremental rebuilds keep project-wide diagnostics fresh: a change in one file refreshes the
 * diagnostics of other files that depend on it without referring to it (scheduler configuration,
 * duplicate names, cycles through several files).
 */
import { mkdirSync, mkdtempSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { Cancellation, DocumentState, OperationCancelled, URI } from 'langium';
import { afterEach, describe, expect, it } from 'vitest';
import { loadWorkspace } from '../src/node/load-workspace.js';

interface LiveWorkspace {
    codesOf(file: string): string[];
    write(file: string, text: string): Promise<void>;
    remove(file: string): Promise<void>;
    /** Writes `file` and starts its update, cancelled (as by the next keystroke) once the changed files are parsed. */
    writeCancelledAfterParsing(file: string, text: string): Promise<void>;
    /** The files validated while `action` runs, sorted. */
    validatedDuring(action: () => Promise<void>): Promise<string[]>;
}

const dirs: string[] = [];
afterEach(() => {
    for (const dir of dirs.splice(0)) rmSync(dir, { recursive: true, force: true });
});

async function liveWorkspace(files: Record<string, string>): Promise<LiveWorkspace> {
    const dir = mkdtempSync(join(tmpdir(), 'cactal-refresh-'));
    dirs.push(dir);
    for (const [file, text] of Object.entries(files)) {
        mkdirSync(join(dir, file, '..'), { recursive: true });
        writeFileSync(join(dir, file), text);
    }
    const ws = await loadWorkspace(dir);
    const workspace = ws.services.shared.workspace;
    let validated: string[] | undefined;
    workspace.DocumentBuilder.onBuildPhase(DocumentState.Validated, (docs) => {
        validated?.push(...docs.map((d) => d.uri.path.slice(d.uri.path.lastIndexOf('/') + 1)));
    });
    return {
        codesOf: (file) => (workspace.LangiumDocuments.getDocument(URI.file(join(dir, file)))?.diagnostics ?? []).map((d) => String(d.code)).sort(),
        write: async (file, text) => {
            writeFileSync(join(dir, file), text);
            await workspace.DocumentBuilder.update([URI.file(join(dir, file))], []);
        },
        remove: async (file) => {
            rmSync(join(dir, file), { recursive: true });
            await workspace.DocumentBuilder.update([], [URI.file(join(dir, file))]);
        },
        writeCancelledAfterParsing: async (file, text) => {
            writeFileSync(join(dir, file), text);
            const source = new Cancellation.CancellationTokenSource();
            const listener = workspace.DocumentBuilder.onBuildPhase(DocumentState.IndexedContent, () => source.cancel());
            try {
                await expect(workspace.DocumentBuilder.update([URI.file(join(dir, file))], [], source.token)).rejects.toBe(OperationCancelled);
            } finally {
                listener.dispose();
            }
        },
        validatedDuring: async (action) => {
            validated = [];
            await action();
            const files = [...new Set(validated)].sort();
            validated = undefined;
            return files;
        }
    };
}

const syncModule = (name: string, c = '1ms') => `synchronous module ${name} { scheduling { C=${c}; } }\n`;
const periodicSchema = (name: string, module = 'MSA', period = '10ms') =>
    `import "msa.contract";\nperiodic schema ${name}() { realtime { PERIOD=${period}; CRITICAL_DELAY=${period}; } modules { ${module} (); } }\n`;
const scheduler = (schemas: string[]) =>
    `import "msa.contract";\n${schemas.map((s) => `import "${s}.contract";`).join('\n')}\n` +
    `scheduler configuration { modules { MSA; } schemas { ${schemas.map((s) => `${s};`).join(' ')} } }\n`;
const supervisor = (name: string, body: string, imports: string[] = []) =>
    `${imports.map((i) => `import "${i}";`).join('\n')}\nsupervisor ${name} {\n    f() {\n        rules {\n            R:[elapsed=1ms] ${body} [elapsed=1ms]\n        }\n    }\n}\n`;

describe('project-wide diagnostics refresh on changes of other files', () => {
    it('scheduler-missing on a schema clears when the scheduler configuration is added, and comes back when it is deleted', async () => {
        const ws = await liveWorkspace({ 'msa.contract': syncModule('MSA'), 'sch.contract': periodicSchema('sch') });
        expect(ws.codesOf('sch.contract')).toEqual(['scheduler-missing']);
        await ws.write('sched.contract', scheduler(['sch']));
        expect(ws.codesOf('sch.contract')).toEqual([]);
        await ws.remove('sched.contract');
        expect(ws.codesOf('sch.contract')).toEqual(['scheduler-missing']);
    });

    it('scheduler-duplicate appears on the first configuration when a second one is added, and goes away with it', async () => {
        const ws = await liveWorkspace({ 'msa.contract': syncModule('MSA'), 'sch.contract': periodicSchema('sch'), 'sched.contract': scheduler(['sch']) });
        expect(ws.codesOf('sched.contract')).toEqual([]);
        await ws.write('sched2.contract', scheduler(['sch']));
        expect(ws.codesOf('sched.contract')).toEqual(['scheduler-duplicate']);
        await ws.remove('sched2.contract');
        expect(ws.codesOf('sched.contract')).toEqual([]);
    });

    it('scheduler-schema-unlisted on a supervisor follows the schemas the configuration lists', async () => {
        const ws = await liveWorkspace({
            'msa.contract': syncModule('MSA'),
            'one.contract': periodicSchema('one'),
            'two.contract': periodicSchema('two'),
            'sched.contract': scheduler(['one']),
            'sup.contract': supervisor('SUP', 'activate schema two()', ['two.contract'])
        });
        expect(ws.codesOf('sup.contract')).toEqual(['scheduler-schema-unlisted']);
        await ws.write('sched.contract', scheduler(['one', 'two']));
        expect(ws.codesOf('sup.contract')).toEqual([]);
        await ws.write('sched.contract', scheduler(['one']));
        expect(ws.codesOf('sup.contract')).toEqual(['scheduler-schema-unlisted']);
    });

    it('scheduler-utilisation on the configuration follows the compute time of a module it lists', async () => {
        const ws = await liveWorkspace({ 'msa.contract': syncModule('MSA', '1ms'), 'sch.contract': periodicSchema('sch'), 'sched.contract': scheduler(['sch']) });
        expect(ws.codesOf('sched.contract')).toEqual([]);
        // C = 12ms > PERIOD = 10ms: the schema's own timing warnings and the configuration's utilisation
        await ws.write('msa.contract', syncModule('MSA', '12ms'));
        expect(ws.codesOf('sched.contract')).toEqual(['scheduler-utilisation']);
        await ws.write('msa.contract', syncModule('MSA', '1ms'));
        expect(ws.codesOf('sched.contract')).toEqual([]);
    });

    it('schema-name-duplicate appears in the other file when a schema of the same name is added or renamed to it', async () => {
        const ws = await liveWorkspace({
            'msa.contract': syncModule('MSA'),
            'one.contract': periodicSchema('one'),
            'two.contract': periodicSchema('two'),
            'sched.contract': scheduler(['one', 'two'])
        });
        expect(ws.codesOf('one.contract')).toEqual([]);
        await ws.write('two.contract', periodicSchema('one'));
        expect(ws.codesOf('one.contract')).toContain('schema-name-duplicate');
        await ws.write('two.contract', periodicSchema('two'));
        expect(ws.codesOf('one.contract')).not.toContain('schema-name-duplicate');
    });

    it('module-name-duplicate appears when a new file defines the same module, and goes away when it is deleted', async () => {
        const ws = await liveWorkspace({ 'msa.contract': syncModule('MSA') });
        await ws.write('copy.contract', syncModule('MSA'));
        expect(ws.codesOf('msa.contract')).toEqual(['module-name-duplicate']);
        await ws.remove('copy.contract');
        expect(ws.codesOf('msa.contract')).toEqual([]);
    });

    it('import-cycle is reported on the unused import of a cycle closed or opened by an edit of another file', async () => {
        const ws = await liveWorkspace({
            'a.contract': 'import "b.contract";\ndatatype A {int x};\n',
            'b.contract': 'import "c.contract";\ndatatype B {C c};\n',
            'c.contract': 'datatype C {int x};\nfunction void g(int v);\n'
        });
        expect(ws.codesOf('a.contract')).toEqual(['import-unused']);
        // c closes the cycle with an import it uses (only c's imports and uses change): the import to remove is a's
        await ws.write('c.contract', 'import "a.contract";\ndatatype C {int x};\nfunction void g(A v);\n');
        expect(ws.codesOf('a.contract')).toEqual(['import-cycle', 'import-unused']);
        expect(ws.codesOf('b.contract')).toEqual([]);
        expect(ws.codesOf('c.contract')).toEqual([]);
        await ws.write('c.contract', 'datatype C {int x};\nfunction void g(int v);\n');
        expect(ws.codesOf('a.contract')).toEqual(['import-unused']);
    });

    const cTypes = (argType: string) => `import "a.contract";\ndatatype C {int x};\nfunction void g(${argType} v);\n`;
    it('import-cycle comes and goes on the import an edit stops or starts using, and nowhere else on the cycle', async () => {
        const ws = await liveWorkspace({
            'a.contract': 'import "b.contract";\ndatatype A {B b};\ndatatype A2 {int x};\n',
            'b.contract': 'import "c.contract";\ndatatype B {C c};\n',
            'c.contract': cTypes('A2')
        });
        // files using each other's names import each other: no cycle to fix
        for (const f of ['a.contract', 'b.contract', 'c.contract']) expect(ws.codesOf(f), f).toEqual([]);
        // c's function no longer uses a's type (no other fact of c changes; a refers to nothing of c)
        await ws.write('c.contract', cTypes('C'));
        expect(ws.codesOf('c.contract')).toEqual(['import-cycle', 'import-unused']);
        expect(ws.codesOf('a.contract')).toEqual([]);
        expect(ws.codesOf('b.contract')).toEqual([]);
        await ws.write('c.contract', cTypes('A2'));
        for (const f of ['a.contract', 'b.contract', 'c.contract']) expect(ws.codesOf(f), f).toEqual([]);
    });

    it('an edit that stops using what a file of a cycle imports revalidates that file and its importers, not the rest of the cycle', async () => {
        const ws = await liveWorkspace({
            'a.contract': 'import "b.contract";\ndatatype A {B b};\ndatatype A2 {int x};\n',
            'b.contract': 'import "c.contract";\ndatatype B {C c};\n',
            'c.contract': cTypes('A2')
        });
        // the warning goes on c's import (c is validated); b imports c (its import diagnostics follow c's); a's depend on neither
        expect(await ws.validatedDuring(() => ws.write('c.contract', cTypes('C')))).toEqual(['b.contract', 'c.contract']);
        expect(ws.codesOf('c.contract')).toEqual(['import-cycle', 'import-unused']);
    });

    it('type-recursive is reported on every datatype of a cycle closed by an edit of one file whose imports do not change', async () => {
        const ws = await liveWorkspace({
            'a.contract': 'import "b.contract";\ndatatype A {B b};\n',
            'b.contract': 'import "c.contract";\ndatatype B {C c};\n',
            'c.contract': 'import "a.contract";\ndatatype C {int x};\n'
        });
        expect(ws.codesOf('a.contract')).toEqual([]);
        expect(ws.codesOf('c.contract')).toEqual(['import-cycle', 'import-unused']);
        await ws.write('c.contract', 'import "a.contract";\ndatatype C {A a};\n');
        // each import of the cycle is used now: no import-cycle (files that use each other import each other)
        expect(ws.codesOf('a.contract')).toEqual(['type-recursive']);
        expect(ws.codesOf('c.contract')).toEqual(['type-recursive']);
        await ws.write('c.contract', 'import "a.contract";\ndatatype C {int x};\n');
        expect(ws.codesOf('a.contract')).toEqual([]);
        expect(ws.codesOf('c.contract')).toEqual(['import-cycle', 'import-unused']);
    });

    it('supervisor-activation-cycle is reported on every supervisor of a cycle closed or opened by an edit of one file', async () => {
        const ws = await liveWorkspace({
            'saa.contract': supervisor('SAA', 'activate supervisor SAB.f()', ['sab.contract']),
            'sab.contract': supervisor('SAB', 'activate supervisor SAC.f()', ['sac.contract']),
            'sac.contract': supervisor('SAC', 'activate supervisor SAD.f()', ['sad.contract']),
            'sad.contract': supervisor('SAD', 'compute nothing()', ['fns.contract']),
            'fns.contract': 'function void nothing();\n'
        });
        expect(ws.codesOf('saa.contract')).toEqual([]);
        await ws.write('sac.contract', supervisor('SAC', 'activate supervisor SAA.f()', ['saa.contract']));
        expect(ws.codesOf('saa.contract')).toContain('supervisor-activation-cycle');
        await ws.write('sac.contract', supervisor('SAC', 'activate supervisor SAD.f()', ['sad.contract']));
        expect(ws.codesOf('saa.contract')).toEqual([]);
    });

    it('an edit that changes no project-wide fact revalidates only the edited file and the files that refer to it', async () => {
        const ws = await liveWorkspace({
            'msa.contract': syncModule('MSA'),
            'msb.contract': syncModule('MSB'),
            'one.contract': periodicSchema('one'),
            'two.contract': periodicSchema('two'),
            'sched.contract': scheduler(['one', 'two']),
            'sup.contract': supervisor('SUP', 'activate schema two()', ['two.contract'])
        });
        expect(await ws.validatedDuring(() => ws.write('msb.contract', syncModule('MSB', '2ms')))).toEqual(['msb.contract']);
        expect(await ws.validatedDuring(() => ws.write('sched.contract', scheduler(['one', 'two']) + '\n'))).toEqual(['sched.contract']);
        expect(await ws.validatedDuring(() => ws.write('sched.contract', scheduler(['two', 'one'])))).toEqual(['sched.contract', 'sup.contract']);
    });

    it('a change whose update was cancelled after parsing still refreshes the other files at the next update', async () => {
        const ws = await liveWorkspace({ 'msa.contract': syncModule('MSA'), 'sch.contract': periodicSchema('sch'), 'sched.contract': '// scheduler to come\n' });
        expect(ws.codesOf('sch.contract')).toEqual(['scheduler-missing']);
        await ws.writeCancelledAfterParsing('sched.contract', scheduler(['sch']));
        // the next keystroke changes no project-wide fact
        await ws.write('sched.contract', scheduler(['sch']) + ' ');
        expect(ws.codesOf('sch.contract')).toEqual([]);
    });

    it('deleting a folder refreshes the files that depended on the files in it', async () => {
        const ws = await liveWorkspace({ 'msa.contract': syncModule('MSA'), 'sch.contract': periodicSchema('sch'), 'config/sched.contract': scheduler(['sch']).replace(/import "/g, 'import "../') });
        expect(ws.codesOf('config/sched.contract')).toEqual([]);
        expect(ws.codesOf('sch.contract')).toEqual([]);
        await ws.remove('config');
        expect(ws.codesOf('sch.contract')).toEqual(['scheduler-missing']);
    });
});
