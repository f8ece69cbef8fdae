/**
 * The product's reference is docs/: code comments, tests, READMEs and docs cite docs/ pages and
 * sections, never a specification file that is not in the repository (a reader of a checkout
 * cannot follow such a citation). This fails when a tracked file outside node_modules and build
 * outputs (dist*) cites that file by name or by its section numbers again.
 */
import { execFileSync } from 'node:child_process';
import { readdirSync, readFileSync, statSync } from 'node:fs';
import { join, relative } from 'node:path';
import { fileURLToPath } from 'node:url';
import { describe, expect, it } from 'vitest';

const ROOT = fileURLToPath(new URL('../../../', import.meta.url));
// Built from pieces so that this file does not match itself.
const OUTSIDE_CITATION = new RegExp('\\bSP' + 'EC(\\.md\\b| ?\u00a7| section\\b)');

function excluded(path: string): boolean {
    return path.split('/').some((segment) => segment === 'node_modules' || segment === '.git' || segment.startsWith('dist'));
}

/** Tracked files (git); without git (an exported tree), every file under the root. */
function repositoryFiles(): string[] {
    try {
        const out = execFileSync('git', ['ls-files', '-z'], { cwd: ROOT, encoding: 'utf8', maxBuffer: 64 * 1024 * 1024 });
        return out.split('\0').filter((p) => p.length > 0);
    } catch {
        const files: string[] = [];
        const walk = (dir: string): void => {
            for (const entry of readdirSync(dir, { withFileTypes: true })) {
                const path = join(dir, entry.name);
                if (excluded(relative(ROOT, path))) continue;
                if (entry.isDirectory()) walk(path);
                else if (entry.isFile()) files.push(relative(ROOT, path));
            }
        };
        walk(ROOT);
        return files;
    }
}

function citations(path: string): string[] {
    const full = join(ROOT, path);
    let text: string;
    try {
        if (!statSync(full).isFile()) return [];
        const bytes = readFileSync(full);
        if (bytes.subarray(0, 8192).includes(0)) return []; // binary
        text = bytes.toString('utf8');
    } catch {
        return []; // deleted in the working tree but still tracked
    }
    const found: string[] = [];
    text.split('\n').forEach((line, i) => {
        if (OUTSIDE_CITATION.test(line)) found.push(`${path}:${i + 1}: ${line.trim().slice(0, 160)}`);
    });
    return found;
}

describe('citations', () => {
    it('matches what it must catch and not words that merely contain the letters', () => {
        expect(OUTSIDE_CITATION.test('see SP' + 'EC \u00a74.2')).toBe(true);
        expect(OUTSIDE_CITATION.test('(SP' + 'EC\u00a72.7)')).toBe(true);
        expect(OUTSIDE_CITATION.test('SP' + 'EC.md')).toBe(true);
        expect(OUTSIDE_CITATION.test('SP' + 'EC section 3.1')).toBe(true);
        expect(OUTSIDE_CITATION.test('INSPECTION of the tree')).toBe(false);
        expect(OUTSIDE_CITATION.test('docs/semantics.md "Supervisors: one event, two rules"')).toBe(false);
    });

    it('no tracked file outside node_modules and dist cites a specification file that is not in the repository', () => {
        const files = repositoryFiles().filter((p) => !excluded(p));
        expect(files.length).toBeGreaterThan(100);
        const found = files.flatMap(citations);
        expect(found, 'cite the docs/ page and section that carries the rule instead').toEqual([]);
    });
});
