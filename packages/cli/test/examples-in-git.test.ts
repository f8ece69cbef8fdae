/**
 * The repository's examples are kept in git as docs/getting-started.md §7 advises every project:
 * the `.gitignore` `contract new` writes, so the last generation's copy of the regions' code
 * (src-gen/.contract-regions.json) is not committed. A fresh clone (the files git tracks) has
 * none: its first `contract generate` writes the copy and changes no generated file, a second one
 * writes nothing.
 */
import { spawnSync } from 'node:child_process';
import { cpSync, existsSync, mkdirSync, mkdtempSync, readFileSync, rmSync, statSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { dirname, join } from 'node:path';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { runCli } from '../src/cli.js';
import { PROJECT_GITIGNORE } from '../src/project-gitignore.js';
import { capture } from './capture-io.js';
import { REPO } from './e2e/harness.js';

const COPY = 'src-gen/.contract-regions.json';
const EXAMPLES = ['tutorial', 'mobile-robot'];
const git = (...args: string[]) => spawnSync('git', ['-C', REPO, ...args], { encoding: 'utf8' });
const inGit = existsSync(join(REPO, '.git')) && git('rev-parse', '--is-inside-work-tree').stdout.trim() === 'true';

let scratch: string;
beforeAll(() => { scratch = mkdtempSync(join(tmpdir(), 'contract-examples-git-')); });
afterAll(() => rmSync(scratch, { recursive: true, force: true }));

describe('the examples in git', () => {
    it.each(EXAMPLES)('%s has the .gitignore contract new writes', (example) => {
        expect(readFileSync(join(REPO, 'examples', example, '.gitignore'), 'utf8')).toBe(PROJECT_GITIGNORE);
    });

    describe.skipIf(!inGit)('in a checkout of the repository', () => {
        it.each(EXAMPLES)('%s: the copy of the regions\' code is ignored and not tracked', (example) => {
            const copy = `examples/${example}/${COPY}`;
            expect(git('ls-files', '--', copy).stdout).toBe('');
            expect(git('check-ignore', '-q', '--no-index', '--', copy).status).toBe(0);
        });

        it.each(EXAMPLES)('%s, as a fresh clone has it: the first contract generate writes the copy and no generated file, the second writes nothing', async (example) => {
            const tracked = git('ls-files', '-z', '--', `examples/${example}`).stdout.split('\0').filter(Boolean);
            expect(tracked.length).toBeGreaterThan(20);
            const project = join(scratch, example);
            for (const path of tracked) {
                const to = join(project, path.slice(`examples/${example}/`.length));
                mkdirSync(dirname(to), { recursive: true });
                cpSync(join(REPO, path), to);
            }
            const generatedFiles = tracked.map((p) => p.slice(`examples/${example}/`.length)).filter((p) => p.startsWith('src-gen/'));
            const bytes = () => new Map(generatedFiles.map((p) => [p, readFileSync(join(project, p), 'latin1')]));
            const mtimes = () => new Map([...generatedFiles, COPY].map((p) => [p, statSync(join(project, p)).mtimeMs]));
            const before = bytes();
            expect(existsSync(join(project, COPY))).toBe(false);

            const first = capture(scratch);
            expect(await runCli(['generate', example], first)).toBe(0);
            expect(first.stderr).toMatch(new RegExp(`generated ${example}/src-gen: 0 created, 0 updated, \\d+ kept, 0 orphaned, 0 error\\(s\\)`));
            expect(bytes()).toEqual(before);
            const manifest = JSON.parse(before.get('src-gen/.contract-manifest.json')!) as { userCode: Record<string, string[]> };
            const held = (JSON.parse(readFileSync(join(project, COPY), 'utf8')) as { files: Record<string, Record<string, string>> }).files;
            expect(Object.keys(held).sort()).toEqual(Object.keys(manifest.userCode).sort());
            expect(Object.keys(held).length).toBeGreaterThan(0);

            const written = mtimes();
            await new Promise((r) => setTimeout(r, 20)); // a rewrite would show in the mtime
            const second = capture(scratch);
            expect(await runCli(['generate', example], second)).toBe(0);
            expect(second.stderr).toMatch(/: 0 created, 0 updated, \d+ kept, 0 orphaned, 0 error\(s\)/);
            expect(mtimes()).toEqual(written);
        }, 60_000);
    });
});
