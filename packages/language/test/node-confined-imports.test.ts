/** loadWorkspace with confineImportsTo: no import reads a file outside the folder (docs/sandbox.md "Imports stay in the project"). */
import { execFileSync } from 'node:child_process';
import { mkdirSync, mkdtempSync, rmSync, symlinkSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { loadWorkspace } from '../src/node/load-workspace.js';

const SECRET = 'datatype HostSecret {int leaked_value_7391};\n';
let root: string;
let proj: string;
const importer = (path: string) => `import "${path}";\ndatatype A {int x};\n`;

beforeAll(() => {
    root = mkdtempSync(join(tmpdir(), 'cactal-confined-'));
    proj = join(root, 'proj');
    mkdirSync(join(proj, 'lib'), { recursive: true });
    writeFileSync(join(root, 'secret.contract'), SECRET);
    writeFileSync(join(proj, 'lib/types.contract'), 'datatype Vec {float x};\n');
});
afterAll(() => rmSync(root, { recursive: true, force: true }));

/** Loads `proj` with only main.contract = `text` (plus lib/), confined to proj. */
async function loadWith(text: string, confined = true) {
    writeFileSync(join(proj, 'main.contract'), text);
    return loadWorkspace(proj, confined ? { confineImportsTo: proj } : {});
}

function refusal(ws: Awaited<ReturnType<typeof loadWith>>) {
    expect(ws.documents.map((d) => d.file).sort()).toEqual(['lib/types.contract', 'main.contract']);
    expect(JSON.stringify(ws.diagnostics)).not.toContain('HostSecret');
    const errors = ws.diagnostics.filter((d) => d.severity === 'error');
    expect(errors.map((d) => [d.file, d.line, d.code])).toEqual([['main.contract', 1, 'import-refused']]);
    return errors[0]!.message;
}

describe('loadWorkspace confineImportsTo', () => {
    it('still loads imports inside the folder', async () => {
        const ws = await loadWith('import "lib/types.contract";\ndatatype A {Vec v};\n');
        expect(ws.documents.map((d) => d.file).sort()).toEqual(['lib/types.contract', 'main.contract']);
        expect(ws.diagnostics.filter((d) => d.severity === 'error')).toEqual([]);
    });

    it('loads a file outside the folder when not confined (the CLI and IDE behaviour)', async () => {
        const ws = await loadWith(importer('../secret.contract'), false);
        expect(ws.documents.map((d) => d.file)).toContain('../secret.contract');
    });

    it('refuses a `..` escape', async () => {
        expect(refusal(await loadWith(importer('../secret.contract')))).toBe(
            'import "../secret.contract" is refused: it leads outside the project folder (imports must stay inside the project folder)');
        expect(refusal(await loadWith(importer('lib/../../../../../../../../etc/passwd.contract')))).toContain('outside the project folder');
        expect(refusal(await loadWith(importer('../../../../../../../../etc/passwd')))).toBe(
            'import "../../../../../../../../etc/passwd" is refused: it leads outside the project folder (imports must stay inside the project folder)');
    });

    it('refuses an absolute path', async () => {
        expect(refusal(await loadWith(importer(join(root, 'secret.contract'))))).toContain('absolute import paths are not allowed');
    });

    it('refuses a symbolic link inside the folder, to a file or on the way', async () => {
        symlinkSync(join(root, 'secret.contract'), join(proj, 'link.contract'));
        symlinkSync(root, join(proj, 'linkdir'));
        try {
            expect(refusal(await loadWith(importer('link.contract')))).toContain('link.contract is a symbolic link');
            expect(refusal(await loadWith(importer('linkdir/secret.contract')))).toContain('linkdir is a symbolic link');
        } finally {
            rmSync(join(proj, 'link.contract'));
            rmSync(join(proj, 'linkdir'));
        }
    });

    it('refuses a FIFO without waiting on it', async () => {
        execFileSync('mkfifo', [join(proj, 'lib/pipe.contract')]);
        try {
            expect(refusal(await loadWith(importer('lib/pipe.contract')))).toContain('it is not a regular file');
        } finally {
            rmSync(join(proj, 'lib/pipe.contract'));
        }
    }, 10_000);

    it('refuses a file above maxImportBytes', async () => {
        // in node_modules: not part of the project walk, so only the import would load it
        mkdirSync(join(proj, 'node_modules'), { recursive: true });
        const big = join(proj, 'node_modules', 'big.contract');
        writeFileSync(big, `datatype B {int ${'x'.repeat(200)}};\n`);
        try {
            writeFileSync(join(proj, 'main.contract'), importer('node_modules/big.contract'));
            const ws = await loadWorkspace(proj, { confineImportsTo: proj, maxImportBytes: 100 });
            const errors = ws.diagnostics.filter((d) => d.file === 'main.contract' && d.severity === 'error');
            expect(errors.map((d) => d.message)).toEqual(['import "node_modules/big.contract" is refused: it is larger than 100 bytes (imports must stay inside the project folder)']);
        } finally {
            rmSync(big);
        }
    });

    it('keeps "does not exist" for a missing file inside the folder', async () => {
        const ws = await loadWith(importer('lib/nosuch.contract'));
        expect(ws.diagnostics.filter((d) => d.severity === 'error').map((d) => d.code)).toEqual(['import-missing-file']);
    });
});

describe('loadWorkspace without confinement (contract check)', () => {
    it('warns of an import of the project that is a link, or in a linked folder, which a build refuses; a plain import gets none', async () => {
        const dir = mkdtempSync(join(root, 'linked-'));
        mkdirSync(join(dir, 'real'));
        writeFileSync(join(dir, 'real/vec.contract'), 'datatype Vec {float x};\n');
        writeFileSync(join(dir, 'real/pose.contract'), 'datatype Pose {float t};\n');
        writeFileSync(join(dir, 'plain.contract'), 'datatype Plain {int p};\n');
        symlinkSync(join(dir, 'real/vec.contract'), join(dir, 'vec.contract'));
        symlinkSync(join(dir, 'real'), join(dir, 'lib'));
        writeFileSync(join(dir, 'main.contract'), 'import "vec.contract";\nimport "lib/pose.contract";\nimport "plain.contract";\ndatatype A {Vec v, Pose p, Plain q};\n');
        const ws = await loadWorkspace(dir, { skipDirs: ['real', 'lib'] });
        expect(ws.diagnostics.filter((d) => d.severity === 'error')).toEqual([]);
        const links = ws.diagnostics.filter((d) => d.code === 'import-link');
        expect(links.map((d) => [d.file, d.line, d.severity])).toEqual([['main.contract', 1, 'warning'], ['main.contract', 2, 'warning']]);
        expect(links[0]!.message).toBe('"vec.contract" is a symbolic link, or in a linked folder: read here, but a build (contract build, the IDE\'s build service) and contract simulate never read a project\'s source through a link and refuse it; put the file itself there');
    });
});
