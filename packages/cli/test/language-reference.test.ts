/**
 * Every ```cactal block of docs/language-reference.md is one file (named by the `<!-- file: X -->`
 * comment above it); together they must load with the real language services with 0 errors and
 * 0 warnings, and every block must be used (a block without a file name fails). Its "Keywords"
 * lists are the grammar's (packages/language/src/cactal.langium): every keyword, and those the
 * grammar's `Name` rule does not take.
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

/** The grammar's keywords that are words, and those its `Name` rule (a field's, a port's, a local's... name) takes. */
export function grammarKeywords(grammar: string): { all: string[]; names: string[] } {
    const code = grammar.replace(/\/\*[\s\S]*?\*\//g, '').replace(/\/\/[^\n]*/g, '');
    const words = (text: string) => [...new Set([...text.matchAll(/'([A-Za-z_]\w*)'/g)].map((m) => m[1]!))];
    const nameRule = /^Name returns string:([^;]*);/m.exec(code);
    if (!nameRule) throw new Error('the grammar has no Name rule');
    return { all: words(code), names: words(nameRule[1]!) };
}

describe('docs/language-reference.md "Keywords"', () => {
    const doc = readFileSync(DOC, 'utf8');
    const section = /\n### Keywords\n([\s\S]*?)\n##/.exec(doc)?.[1] ?? '';
    // the lists: the paragraphs that are only `word`, `word`, ... `word`.
    const lists = section.split(/\n\s*\n/).map((p) => p.trim()).filter((p) => /^`\w+`(, `\w+`)*\.$/.test(p))
        .map((p) => [...p.matchAll(/`(\w+)`/g)].map((m) => m[1]!));
    const { all, names } = grammarKeywords(readFileSync(join(REPO, 'packages/language/src/cactal.langium'), 'utf8'));
    const sorted = (l: string[]) => [...l].sort();

    it('lists every keyword of the grammar, then those no name may be (not in its Name rule)', () => {
        expect(lists).toHaveLength(2);
        expect(all.length).toBeGreaterThan(40);
        expect(sorted(lists[0]!)).toEqual(sorted(all));
        expect(sorted(lists[1]!)).toEqual(sorted(all.filter((k) => !names.includes(k))));
    });

    it('says what the checker says: a keyword names no function; the others name a field, a reserved one does not', async () => {
        const kw = mkdtempSync(join(tmpdir(), 'contract-keywords-'));
        try {
            expect(section).toContain("`function void critical(int level);` is the syntax error\n`Expected a name but found 'critical'`");
            writeFileSync(join(kw, 'f.contract'), 'function void critical(int level);\n');
            writeFileSync(join(kw, 'ok.contract'), `datatype Ok { ${names.map((n) => `int ${n}`).join(', ')} }\n`);
            writeFileSync(join(kw, 'bad.contract'), lists[1]!.map((n, i) => `datatype Bad${i} { int ${n} }`).join('\n') + '\n');
            const errors = (await loadWorkspace(kw)).diagnostics.filter((d) => d.severity === 'error');
            expect(errors.filter((d) => d.file.endsWith('f.contract')).map((d) => d.message)).toEqual(["Expected a name but found 'critical'."]);
            expect(errors.filter((d) => d.file.endsWith('ok.contract'))).toEqual([]);
            expect(errors.filter((d) => d.file.endsWith('bad.contract')).map((d) => d.line).sort((a, b) => a - b)).toEqual(lists[1]!.map((_, i) => i + 1));
        } finally {
            rmSync(kw, { recursive: true, force: true });
        }
    }, 60_000);
});
