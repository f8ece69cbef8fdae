/**
 * `contract --version` tells two builds of the same version apart: the version and the commit the
 * build was made from (dist/build-info.json, written by `npm run build`), not the version alone.
 */
import { spawnSync } from 'node:child_process';
import { mkdirSync, mkdtempSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { pathToFileURL } from 'node:url';
import { afterEach, describe, expect, it } from 'vitest';
import { versionText } from '../src/build-version.js';

const CLI = join(import.meta.dirname, '..');
const dirs: string[] = [];
afterEach(() => dirs.splice(0).forEach((d) => rmSync(d, { recursive: true, force: true })));

/** A package folder holding package.json of `version` and, when given, dist/build-info.json. */
function packageDir(version: string, info?: unknown): URL {
    const dir = mkdtempSync(join(tmpdir(), 'cli-version-'));
    dirs.push(dir);
    writeFileSync(join(dir, 'package.json'), JSON.stringify({ version }));
    if (info !== undefined) {
        mkdirSync(join(dir, 'dist'));
        writeFileSync(join(dir, 'dist', 'build-info.json'), typeof info === 'string' ? info : JSON.stringify(info));
    }
    return pathToFileURL(dir + '/');
}

describe('contract --version', () => {
    it('names the commit the build was made from, and whether it had uncommitted changes; the version alone when none was recorded', () => {
        const a = 'a'.repeat(40);
        const b = '0123456789abcdef0123456789abcdef01234567';
        expect(versionText(packageDir('0.1.0', { commit: a, modified: false }))).toBe('0.1.0 (commit aaaaaaaaaaaa)');
        expect(versionText(packageDir('0.1.0', { commit: b, modified: false }))).toBe('0.1.0 (commit 0123456789ab)');
        expect(versionText(packageDir('0.1.0', { commit: b, modified: true }))).toBe('0.1.0 (commit 0123456789ab with uncommitted changes)');
        expect(versionText(packageDir('0.2.0', {}))).toBe('0.2.0');
        expect(versionText(packageDir('0.2.0'))).toBe('0.2.0');
        expect(versionText(packageDir('0.2.0', { commit: 'HEAD; rm -rf /' }))).toBe('0.2.0');
        expect(versionText(packageDir('0.2.0', '{not json'))).toBe('0.2.0');
    });

    it('of the built command: the commit of this repository that the build recorded', () => {
        const info = JSON.parse(readFileSync(join(CLI, 'dist', 'build-info.json'), 'utf8')) as { commit?: string };
        const run = spawnSync(process.execPath, [join(CLI, 'bin', 'contract.js'), '--version'], { encoding: 'utf8' });
        expect(run.status).toBe(0);
        const version = (JSON.parse(readFileSync(join(CLI, 'package.json'), 'utf8')) as { version: string }).version;
        expect(info.commit).toMatch(/^[0-9a-f]{40}$/);
        expect(run.stdout).toMatch(new RegExp(`^contract ${version.replace(/\./g, '\\.')} \\(commit ${info.commit!.slice(0, 12)}( with uncommitted changes)?\\)\\n$`));
        // a commit of this repository
        expect(spawnSync('git', ['-C', CLI, 'cat-file', '-e', `${info.commit}^{commit}`]).status).toBe(0);
    });
});
