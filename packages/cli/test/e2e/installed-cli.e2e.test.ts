/**
 * The CLI as users install it (docs/getting-started.md "Installing the CLI"): scripts/pack.mjs makes
 * one tarball, `npm install -g --offline` puts it in a temp prefix (offline: every dependency is in
 * the tarball), and `contract new`, `check`, `build` and `run --duration 2s` work from a temp folder
 * outside the repository with no CONTRACT_RUNTIME: the runtime sources inside the package are built
 * into the (empty) build cache on first use; `contract-language-server` answers an LSP initialize.
 */
import { spawn, spawnSync } from 'node:child_process';
import { chmodSync, existsSync, mkdirSync, mkdtempSync, readdirSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { REPO } from './harness.js';
import { removeScratch } from '../scratch.js';

let root: string;

/** What an LSP server started as `command --stdio` answers to `initialize` (its stdout until then). */
function initializeAnswer(command: string, cwd: string, env: NodeJS.ProcessEnv): Promise<string> {
    const body = JSON.stringify({ jsonrpc: '2.0', id: 1, method: 'initialize', params: { processId: null, rootUri: null, capabilities: {} } });
    const child = spawn(command, ['--stdio'], { cwd, env, stdio: 'pipe' });
    let out = '';
    return new Promise<string>((resolve) => {
        const done = () => { clearTimeout(timer); child.kill(); resolve(out); };
        const timer = setTimeout(done, 60_000);
        child.stdout.on('data', (d: Buffer) => { out += d.toString(); if (out.includes('"capabilities"') && out.trimEnd().endsWith('}')) done(); });
        child.on('error', done);
        child.stdin.write(`Content-Length: ${Buffer.byteLength(body)}\r\n\r\n${body}`);
    });
}
beforeAll(() => {
    root = mkdtempSync(join(tmpdir(), 'contract-installed-'));
    chmodSync(root, 0o711); // the sandbox's own uid must reach the cache folder inside
});
afterAll(() => removeScratch(root), 120_000);

describe('the packed CLI installed with npm install -g', () => {
    it('packs, installs offline, and runs new, check, build and run outside the repository', async () => {
        const packs = join(root, 'packs');
        const pack = spawnSync(process.execPath, [join(REPO, 'packages/cli/scripts/pack.mjs'), packs], { encoding: 'utf8', timeout: 300_000 });
        expect(pack.status, pack.stderr).toBe(0);
        const tarballs = readdirSync(packs).filter((f) => /^contract-studio-cli-\d+\.\d+\.\d+\.tgz$/.test(f));
        expect(tarballs).toHaveLength(1);

        const prefix = join(root, 'prefix');
        const npmEnv = { ...process.env, npm_config_update_notifier: 'false', npm_config_audit: 'false', npm_config_fund: 'false' };
        const install = spawnSync('npm', ['install', '-g', '--offline', '--prefix', prefix, join(packs, tarballs[0]!)], { encoding: 'utf8', timeout: 300_000, env: npmEnv });
        expect(install.status, `${install.stdout}${install.stderr}`).toBe(0);
        const bin = join(prefix, 'bin', 'contract');
        expect(existsSync(bin)).toBe(true);

        const home = join(root, 'home');
        const work = join(root, 'work');
        mkdirSync(home);
        mkdirSync(work);
        const env: NodeJS.ProcessEnv = { PATH: `${join(prefix, 'bin')}:${process.env.PATH ?? '/usr/bin:/bin'}`, HOME: home, CONTRACT_CACHE_DIR: join(root, 'cache'), LANG: 'C.UTF-8' };
        const contract = (args: string[], timeout = 300_000) => {
            const r = spawnSync('contract', args, { cwd: work, encoding: 'utf8', timeout, env });
            return { status: r.status, out: `${r.stdout ?? ''}${r.stderr ?? ''}` };
        };

        const created = contract(['new', 'robot']);
        expect(created.status, created.out).toBe(0);
        const checked = contract(['check', 'robot']);
        expect(checked.status, checked.out).toBe(0);
        expect(checked.out).toMatch(/0 errors/);
        const built = contract(['build', 'robot', '--sandbox', 'bwrap']);
        expect(built.status, built.out).toBe(0);
        expect(readdirSync(join(root, 'cache')).some((n) => n === 'runtime')).toBe(true); // built into the cache, not in place
        const ran = contract(['run', 'robot', '--sandbox', 'bwrap', '--duration', '2s']);
        expect(ran.status, ran.out).toBe(0);

        // the language server for desktop editors comes with it (docs/editors.md)
        expect(await initializeAnswer('contract-language-server', work, env)).toMatch(/"renameProvider":/);
    }, 900_000);
});
