/**
 * Every ```cactal block of docs/language-reference.md is one file (named by the `<!-- file: X -->`
 * comment above it); together they must load with the real language services with 0 errors and
 * 0 warnings, and every block must be used (a block without a file name fails).
 */
import { mkdtempSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { afterAll, describe, expect, it } from 'vitest';
import { loadWorkspace } from '@contract-studio/language/node';
import { REPO } from './e2e/harness.js';

const DOC = join(REPO, 'docs/language-reference.md');

export function cactalBlocks(markdown: string): { file: string | null; text: string; line: number }[] {
    const blocks: { file: string | null; text: string; line: number }[] = [];
    const re = /(?:<!--\s*file:\s*([\w./-]+)\s*-->\s*\n)?```cactal\n([\s\S]*?)```/g;
    for (const m of markdown.matchAll(re)) {
        blocks.push({ file: m[1] ?? null, text: m[2]!, line: markdown.slice(0, m.index).split('\n').length });
    }
    return blocks;
}

const dir = mkdtempSync(join(tmpdir(), 'contract-langref-'));
afterAll(() => rmSync(dir, { recursive: true, force: true }));

describe('docs/language-reference.md', () => {
    const blocks = cactalBlocks(readFileSync(DOC, 'utf8'));

    it('names a file for every cactal block, each once', () => {
        expect(blocks.length).toBeGreaterThanOrEqual(10);
        for (const b of blocks) expect(b.file, `block at line ${b.line}`).not.toBeNull();
        const names = blocks.map((b) => b.file);
        expect(new Set(names).size).toBe(names.length);
    });

    it('checks with 0 errors and 0 warnings', async () => {
        for (const b of blocks) writeFileSync(join(dir, b.file!), b.text);
        const workspace = await loadWorkspace(dir);
        expect(workspace.documents.length).toBe(blocks.length);
        const problems = workspace.diagnostics
            .filter((d) => d.severity === 'error' || d.severity === 'warning')
            .map((d) => `${d.file}:${d.line}:${d.column} ${d.severity} ${d.code} ${d.message}`);
        expect(problems).toEqual([]);
    }, 60_000);
});
