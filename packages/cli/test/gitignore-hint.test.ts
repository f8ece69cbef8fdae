/**
 * A project that an older `contract new` made has no .gitignore: the first command that writes a
 * file git should not commit (generate: src-gen/.contract-regions.json; run: logs/, logs/previous/)
 * says once which lines to add, in a git work tree that does not ignore it; never otherwise.
 */
import { spawnSync } from 'node:child_process';
import { cpSync, mkdtempSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { afterEach, describe, expect, it } from 'vitest';
import { runCli } from '../src/cli.js';
import { gitignoreHint } from '../src/gitignore-hint.js';
import { PROJECT_GITIGNORE } from '../src/project-gitignore.js';
import { capture } from './capture-io.js';

/** The one-module project and the tree commit 097201b3 generated for it, a region holding code (codegen's fixture). */
const OLD = join(import.meta.dirname, '..', '..', 'codegen', 'src', 'test-support', 'fixtures', 'older-version');
const LINES = PROJECT_GITIGNORE.split('\n').filter((l) => l !== '' && !l.startsWith('#'));
const dirs: string[] = [];
afterEach(() => dirs.splice(0).forEach((d) => rmSync(d, { recursive: true, force: true })));

function oldProject(git: boolean): string {
    const dir = mkdtempSync(join(tmpdir(), 'gitignore-hint-'));
    dirs.push(dir);
    cpSync(join(OLD, 'ctl.contract'), join(dir, 'ctl.contract'));
    cpSync(join(OLD, 'tree-of-097201b3'), join(dir, 'src-gen'), { recursive: true });
    if (git) expect(spawnSync('git', ['init', '-q', dir]).status).toBe(0);
    return dir;
}

async function generate(dir: string): Promise<string> {
    const io = capture(dir);
    expect(await runCli(['generate', '.'], io)).toBe(0);
    return io.stderr;
}

const NOTE = /^note: \. is a git repository whose \.gitignore does not ignore src-gen\/\.contract-regions\.json, just written by ContrACT Studio/m;

describe('the .gitignore lines that contract new writes', () => {
    it('are named once by generate when it creates src-gen/.contract-regions.json in a git work tree that does not ignore it', async () => {
        const dir = oldProject(true);
        const first = await generate(dir);
        expect(first).toMatch(NOTE);
        expect(first.slice(first.search(NOTE))).toContain(LINES.map((l) => `  ${l}\n`).join(''));
        // the file exists now: not said again
        expect(await generate(dir)).not.toMatch(/^note:/m);
    });

    it('only the lines missing, and nothing when the .gitignore of contract new is there, or outside git', async () => {
        const partial = oldProject(true);
        writeFileSync(join(partial, '.gitignore'), 'logs/\n*.o\n');
        const said = await generate(partial);
        expect(said).toMatch(NOTE);
        expect(said.slice(said.search(NOTE))).toContain(LINES.filter((l) => l !== 'logs/' && l !== '*.o').map((l) => `  ${l}\n`).join(''));
        expect(said).not.toContain('  logs/\n');
        const whole = oldProject(true);
        writeFileSync(join(whole, '.gitignore'), PROJECT_GITIGNORE);
        expect(await generate(whole)).not.toMatch(/^note:/m);
        expect(readFileSync(join(whole, 'src-gen', '.contract-regions.json'), 'utf8')).toContain('user_counter');
        expect(await generate(oldProject(false))).not.toMatch(/^note:/m);
    });

    it('for a run: logs/previous/ created in a git work tree, named by the line logs/', async () => {
        const dir = oldProject(true);
        const hint = await gitignoreHint(dir, 'robot', ['logs/previous/run-2026-12-03T02-05-31']);
        expect(hint).toMatch(/^note: robot is a git repository whose \.gitignore does not ignore logs\/previous\/run-2026-12-03T02-05-31, /);
        expect(hint).toContain('  logs/\n');
        writeFileSync(join(dir, '.gitignore'), 'logs/\n');
        expect(await gitignoreHint(dir, 'robot', ['logs/previous/run-2026-12-03T02-05-31'])).toBeUndefined();
    });
});
