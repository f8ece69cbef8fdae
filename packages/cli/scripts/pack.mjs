#!/usr/bin/env node
// `npm run pack -w packages/cli` (or `node packages/cli/scripts/pack.mjs [OUT_DIR]`): the CLI as ONE
// self-contained tarball, contract-studio-cli-<version>.tgz, that installs with
// `npm install -g ./contract-studio-cli-<version>.tgz` on a machine with only Node, gcc/make and
// bwrap or Docker: no checkout, no CONTRACT_RUNTIME, no registry (docs/getting-started.md
// "Installing the CLI").
//   - every dependency is bundled (bundleDependencies): the workspace packages as `npm pack` makes
//     them, and their registry dependencies as the lock file pins them (installed here, offline
//     when the npm cache has them);
//   - the C runtime's sources are inside, under runtime/: the build service builds them into the
//     user's build cache on first use (the runtime cache of docs/getting-started.md "The build cache").
// Needs the workspace built (npm run build). Writes only into a temporary folder and OUT_DIR.
import { execFileSync } from 'node:child_process';
import { cpSync, existsSync, mkdirSync, mkdtempSync, readFileSync, readdirSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { dirname, join, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';

const cliDir = resolve(dirname(fileURLToPath(import.meta.url)), '..');
const repo = resolve(cliDir, '..', '..');
const out = resolve(process.argv[2] ?? join(repo, 'dist-packages'));
/** The workspace packages the CLI needs, in dependency order. */
const WORKSPACES = ['conventions', 'language', 'codegen', 'build-service', 'simulator'];
/** What of runtime/ a user's build needs (its tests and benchmarks stay in the repository). */
const RUNTIME_PARTS = ['Makefile', 'engines.mk', 'README.md', 'include', 'src', 'launcher', 'sim'];

function run(cmd, args, cwd) {
    return execFileSync(cmd, args, { cwd, encoding: 'utf8', stdio: ['ignore', 'pipe', 'inherit'], env: { ...process.env, npm_config_update_notifier: 'false', npm_config_fund: 'false', npm_config_audit: 'false' } });
}

for (const w of [...WORKSPACES, 'cli']) {
    if (!existsSync(join(repo, 'packages', w, 'dist'))) {
        process.stderr.write(`pack: packages/${w}/dist is missing: run \`npm run build\` at the repository root first\n`);
        process.exit(2);
    }
}

const work = mkdtempSync(join(tmpdir(), 'contract-cli-pack-'));
try {
    // 1. the workspace packages, as npm pack makes them (their "files")
    const tarballs = join(work, 'workspaces');
    mkdirSync(tarballs);
    run('npm', ['pack', ...WORKSPACES.flatMap((w) => ['-w', `packages/${w}`]), '--pack-destination', tarballs], repo);

    // 2. the CLI's own files, the runtime sources, and a package.json that depends on those tarballs
    const stage = join(work, 'cli');
    mkdirSync(stage);
    const pkg = JSON.parse(readFileSync(join(cliDir, 'package.json'), 'utf8'));
    for (const f of pkg.files) cpSync(join(cliDir, f), join(stage, f), { recursive: true });
    if (existsSync(join(cliDir, 'README.md'))) cpSync(join(cliDir, 'README.md'), join(stage, 'README.md'));
    for (const part of RUNTIME_PARTS) cpSync(join(repo, 'runtime', part), join(stage, 'runtime', part), { recursive: true, filter: (src) => !/\/build(\/|$)/.test(src.slice(join(repo, 'runtime').length)) });
    const byName = new Map(readdirSync(tarballs).map((t) => [t.replace(/-\d+\.\d+\.\d+\.tgz$/, '').replace(/^contract-studio-/, ''), join(tarballs, t)]));
    const deps = { ...pkg.dependencies };
    for (const w of WORKSPACES) {
        const tgz = byName.get(w);
        if (!tgz) throw new Error(`npm pack made no tarball for packages/${w}`);
        deps[`@contract-studio/${w}`] = `file:${tgz}`;
    }
    // the registry dependencies within the packages' ranges, with the repository's overrides
    const overrides = JSON.parse(readFileSync(join(repo, 'package.json'), 'utf8')).overrides;
    writeFileSync(join(stage, 'package.json'), JSON.stringify({ ...pkg, dependencies: deps, devDependencies: undefined, scripts: undefined, overrides }, null, 2));
    run('npm', ['install', '--omit=dev', '--omit=peer', '--ignore-scripts', '--prefer-offline', '--no-package-lock', '--install-links', '--loglevel=error'], stage);

    // 3. every dependency bundled; the workspace ones named by version again (they are inside)
    for (const w of WORKSPACES) deps[`@contract-studio/${w}`] = JSON.parse(readFileSync(join(stage, 'node_modules', '@contract-studio', w, 'package.json'), 'utf8')).version;
    const final = { ...pkg, dependencies: deps, bundleDependencies: Object.keys(deps), devDependencies: undefined, scripts: undefined };
    if (!final.files.includes('runtime')) final.files.push('runtime');
    writeFileSync(join(stage, 'package.json'), `${JSON.stringify(final, null, 2)}\n`);

    mkdirSync(out, { recursive: true });
    const name = run('npm', ['pack', '--pack-destination', out, '--loglevel=error'], stage).trim().split('\n').pop();
    process.stdout.write(`${join(out, name)}\n`);
} finally {
    rmSync(work, { recursive: true, force: true });
}
