/** The report's complete example (examples/tutorial) checks clean with the Node workspace loader. */
import { fileURLToPath } from 'node:url';
import { describe, expect, it } from 'vitest';
import { loadWorkspace } from '../src/node/load-workspace.js';
import { isSupervisor } from '../src/generated/ast.js';

const TUTORIAL = fileURLToPath(new URL('../../../examples/tutorial', import.meta.url));
const FILES = ['amodule1', 'amodule2', 'aschema1', 'datatype', 'sched', 'smodule1', 'smodule2', 'smodule3', 'smodule4',
    'sschema1', 'sschema2', 'supervisor', 'supervisor2'].map((f) => `${f}.contract`);

describe('examples/tutorial', () => {
    it('loads the 13 files of report §8.1 with zero diagnostics (no error, warning or hint)', async () => {
        const ws = await loadWorkspace(TUTORIAL);
        expect(ws.documents.map((d) => d.file)).toEqual(FILES);
        expect(ws.diagnostics).toEqual([]);
        const sup = ws.documents.find((d) => d.file === 'supervisor.contract')!.model.elements[0]!;
        expect(isSupervisor(sup) && sup.functions[0]!.rules[0]!.rules.map((r) => r.name)).toEqual(['FIRST', 'SECOND', 'THIRD', 'FOURTH', 'RECEPTION']);
    });

    it('keeps the report identifiers as written', async () => {
        const ws = await loadWorkspace(TUTORIAL);
        const text = ws.documents.map((d) => d.document.textDocument.getText()).join('\n');
        expect(text).toContain('out_coordinates_commmmand');
        expect(text).toContain('frfrrrf');
        expect(text).toContain('gdyegdyegdyge');
    });

    it('refuses a path that is not a directory with a clear error', async () => {
        await expect(loadWorkspace(`${TUTORIAL}/datatype.contract`)).rejects.toThrow(/is not a directory/);
    });
});
