/**
 * `npx contract` from a project outside this repository: the CLI's one tarball (scripts/pack.mjs)
 * installed offline as a devDependency of a temp project next to a copy of examples/tutorial,
 * then `npx contract check .` there. Nothing is cached in the repository (all in a temp folder).
 */
import { spawnSync } from 'node:child_process';
import { cpSync, mkdirSync, mkdtempSync, readdirSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { REPO } from './harness.js';

let root: string;

function npm(args: string[], cwd: string, timeout = 120_000) {
    const r = spawnSync('npm', args, { cwd, encoding: 'utf8', timeout, env: { ...process.env, npm_config_update_notifier: 'false' } });
    return { code: r.status, out: `${r.stdout ?? ''}${r.stderr ?? ''}` };
}

beforeAll(() => { root = mkdtempSync(join(tmpdir(), 'contract-npx-')); });
afterAll(() => rmSync(root, { recursive: true, force: true }), 120_000);

describe('npx contract from a project outside the repository', () => {
    it('installs from npm pack tarballs and checks a copy of the tutorial with exit 0', () => {
        const packs = join(root, 'packs');
        mkdirSync(packs);
        const pack = spawnSync(process.execPath, [join(REPO, 'packages/cli/scripts/pack.mjs'), packs], { encoding: 'utf8', timeout: 300_000 });
        expect(pack.status, pack.stderr).toBe(0);
        const tarballs = readdirSync(packs).filter((f) => f.endsWith('.tgz'));
        expect(tarballs).toHaveLength(1);

        const project = join(root, 'robot-project');
        cpSync(join(REPO, 'examples/tutorial'), join(project, 'tutorial'), { recursive: true });
        writeFileSync(join(project, 'package.json'), JSON.stringify({ name: 'robot-project', private: true }));
        const install = npm(['install', '--save-dev', '--offline', '--no-audit', '--no-fund', ...tarballs.map((t) => join(packs, t))], project, 300_000);
        expect(install.code, install.out).toBe(0);

        const check = spawnSync('npx', ['contract', 'check', '.'], { cwd: join(project, 'tutorial'), encoding: 'utf8', timeout: 60_000 });
        expect(check.stdout).toBe('');
        expect(check.stderr).toContain('0 errors, 0 warnings, 0 hints in 13 files');
        expect(check.status).toBe(0);

        const bad = spawnSync('npx', ['contract', 'check', '.', '--format', 'json'], { cwd: join(project, 'tutorial'), encoding: 'utf8', timeout: 60_000 });
        expect(JSON.parse(bad.stdout)).toEqual({ diagnostics: [] });
    }, 600_000);
});
