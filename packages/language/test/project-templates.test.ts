/** The "New project" templates (IDE dialog and `contract new`) form a project that checks clean. */
import { mkdtempSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { describe, expect, it } from 'vitest';
import { loadWorkspace } from '../src/node/load-workspace.js';
import { PROJECT_TEMPLATES } from '../src/index.js';

describe('project templates', () => {
    it('are the report\'s six files and check with no diagnostic', async () => {
        expect(Object.keys(PROJECT_TEMPLATES).sort()).toEqual(
            ['datatype', 'module1', 'module2', 'sched', 'schema', 'supervisor'].map((f) => `${f}.contract`));
        const dir = mkdtempSync(join(tmpdir(), 'cactal-templates-'));
        try {
            for (const [file, text] of Object.entries(PROJECT_TEMPLATES)) writeFileSync(join(dir, file), text);
            const ws = await loadWorkspace(dir);
            expect(ws.documents).toHaveLength(6);
            expect(ws.diagnostics).toEqual([]);
        } finally {
            rmSync(dir, { recursive: true, force: true });
        }
    });
});
