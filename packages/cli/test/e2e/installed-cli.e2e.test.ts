/**
 * The CLI as users install it (docs/getting-started.md "Installing the CLI"), from the one tarball
 * scripts/pack.mjs makes (packed once, for both tests):
 * - packed and installed with no registry and an empty npm cache (the dependencies inside are
 *   copied from the repository's install);
 * - `npm install -g --offline` puts it in a temp prefix (offline: every dependency is in the
 *   tarball), and `contract new`, `check`, `build` and `run --duration 2s` work from a temp folder
 *   outside the repository with no CONTRACT_RUNTIME: the runtime sources inside the package are
 *   built into the (empty) build cache on first use; `contract runtime-source` copies them out
 *   (no build product) and the copy builds with plain make; `contract-language-server` answers an
 *   LSP initialize;
 * - installed offline as a devDependency of a temp project next to a copy of examples/tutorial,
 *   `npx contract check .` works there (docs/ci.md).
 * Nothing is cached in the repository (all in a temp folder).
 */
import { spawn, spawnSync } from 'node:child_process';
import { chmodSync, cpSync, existsSync, mkdirSync, mkdtempSync, readdirSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { REPO } from './harness.js';
import { removeScratch } from '../scratch.js';

let root: string;
/** The packed CLI tarball. */
let tarball: string;
/** `npm install --save-dev` of the tarball into a project beside a copy of the tutorial, started by beforeAll. */
let devInstall: Promise<{ status: number | null; out: string }>;

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
/** npm with no registry and an empty cache of its own: packing and installing need neither. */
let npmEnv: NodeJS.ProcessEnv;
beforeAll(() => {
    root = mkdtempSync(join(tmpdir(), 'contract-installed-'));
    chmodSync(root, 0o711); // the sandbox's own uid must reach the cache folder inside
    npmEnv = { ...process.env, npm_config_offline: 'true', npm_config_cache: join(root, 'npm-cache'), npm_config_update_notifier: 'false', npm_config_audit: 'false', npm_config_fund: 'false' };
    const packs = join(root, 'packs');
    const pack = spawnSync(process.execPath, [join(REPO, 'packages/cli/scripts/pack.mjs'), packs], { encoding: 'utf8', timeout: 300_000, env: npmEnv });
    expect(pack.status, pack.stderr).toBe(0);
    const tarballs = readdirSync(packs).filter((f) => f.endsWith('.tgz'));
    expect(tarballs).toHaveLength(1);
    expect(tarballs[0]).toMatch(/^contract-studio-cli-\d+\.\d+\.\d+\.tgz$/);
    tarball = join(packs, tarballs[0]!);
    // the devDependency install runs while the first test works (most of both is unpacking the tarball)
    const project = join(root, 'robot-project');
    cpSync(join(REPO, 'examples/tutorial'), join(project, 'tutorial'), { recursive: true });
    writeFileSync(join(project, 'package.json'), JSON.stringify({ name: 'robot-project', private: true }));
    devInstall = new Promise((resolve) => {
        const child = spawn('npm', ['install', '--save-dev', '--offline', tarball], { cwd: project, env: npmEnv, stdio: ['ignore', 'pipe', 'pipe'] });
        let out = '';
        child.stdout.on('data', (d: Buffer) => (out += d.toString()));
        child.stderr.on('data', (d: Buffer) => (out += d.toString()));
        child.on('error', (e) => resolve({ status: null, out: `${out}${e.message}` }));
        child.on('close', (status) => resolve({ status, out }));
    });
}, 300_000);
afterAll(() => removeScratch(root), 120_000);

describe('the packed CLI, installed as users install it', () => {
    it('installs offline with -g, and runs new, check, build and run outside the repository', async () => {
        const prefix = join(root, 'prefix');
        const install = spawnSync('npm', ['install', '-g', '--offline', '--prefix', prefix, tarball], { encoding: 'utf8', timeout: 300_000, env: npmEnv });
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
        // the CLI of the checkout, on the same cache, builds nothing again: the runtime is keyed by its
        // sources and the toolchain, the generated tree by the generator's bytes, not by where either lives
        const runtimes = readdirSync(join(root, 'cache', 'runtime')).filter((n) => n.startsWith('runtime-'));
        expect(runtimes).toHaveLength(1);
        const fromCheckout = spawnSync(process.execPath, [join(REPO, 'packages/cli/bin/contract.js'), 'build', 'robot', '--sandbox', 'bwrap', '--verbose'], { cwd: work, encoding: 'utf8', timeout: 300_000, env });
        const checkoutOut = `${fromCheckout.stdout}${fromCheckout.stderr}`;
        expect(fromCheckout.status, checkoutOut).toBe(0);
        expect(checkoutOut).toContain(`${runtimes[0]!.slice('runtime-'.length)} (`);
        expect(checkoutOut).not.toContain('building the runtime');
        expect(checkoutOut).toMatch(/project unchanged since the last build: generation skipped|generated tree taken from the build cache/);
        expect(readdirSync(join(root, 'cache', 'runtime')).filter((n) => n.startsWith('runtime-'))).toEqual(runtimes);
        const ran = contract(['run', 'robot', '--sandbox', 'bwrap', '--duration', '2s']);
        expect(ran.status, ran.out).toBe(0);

        // the runtime's sources packed with it, for a build by hand (a robot with no checkout): no build product
        const copied = contract(['runtime-source', 'robot-runtime']);
        expect(copied.status, copied.out).toBe(0);
        for (const f of ['Makefile', 'include/libmodule/libmodule.h', 'src/core.c', 'launcher/contract-launch.c']) expect(existsSync(join(work, 'robot-runtime', f)), f).toBe(true);
        expect(existsSync(join(work, 'robot-runtime', 'build'))).toBe(false);
        const made = spawnSync('make', ['-s', '-j2', '-C', join(work, 'robot-runtime'), 'build/libmodule.a', 'build/contract-launch', 'CFLAGS=-O0'], { encoding: 'utf8', timeout: 300_000 });
        expect(made.status, made.stderr).toBe(0);

        // the language server for desktop editors comes with it (docs/editors.md)
        expect(await initializeAnswer('contract-language-server', work, env)).toMatch(/"renameProvider":/);
    }, 900_000);

    it('installs offline as a devDependency: npx contract check . on a copy of the tutorial exits 0', async () => {
        const project = join(root, 'robot-project');
        const install = await devInstall;
        expect(install.status, install.out).toBe(0);

        const check = spawnSync('npx', ['contract', 'check', '.'], { cwd: join(project, 'tutorial'), encoding: 'utf8', timeout: 60_000, env: npmEnv });
        expect(check.stdout).toBe('');
        expect(check.stderr).toContain('0 errors, 0 warnings, 0 hints in 13 files');
        expect(check.status).toBe(0);

        const json = spawnSync('npx', ['contract', 'check', '.', '--format', 'json'], { cwd: join(project, 'tutorial'), encoding: 'utf8', timeout: 60_000, env: npmEnv });
        expect(JSON.parse(json.stdout)).toEqual({ diagnostics: [] });
    }, 600_000);
});
