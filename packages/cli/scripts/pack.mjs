#!/usr/bin/env node
// `npm run pack -w packages/cli` (or `node packages/cli/scripts/pack.mjs [OUT_DIR]`): the CLI as ONE
// self-contained tarball, contract-studio-cli-<version>.tgz, that installs with
// `npm install -g ./contract-studio-cli-<version>.tgz` on a machine with only Node, gcc/make and
// bwrap or Docker: no checkout, no CONTRACT_RUNTIME, no registry (docs/getting-started.md
// "Installing the CLI").
//   - every dependency is bundled (bundleDependencies): the workspace packages as `npm pack` makes
//     them, and their registry dependencies copied from the repository's node_modules, so at the
//     versions package-lock.json pins and the tests ran (no registry: it works offline after `npm ci`);
//   - the C runtime's sources are inside, under runtime/: the build service builds them into the
//     user's build cache on first use (the runtime cache of docs/getting-started.md "The build cache").
// Needs the workspace built (npm run build). Writes only into a temporary folder and OUT_DIR.
import { execFileSync } from 'node:child_process';
import { cpSync, existsSync, mkdirSync, mkdtempSync, readFileSync, readdirSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { dirname, join, relative, resolve, sep } from 'node:path';
import { fileURLToPath } from 'node:url';
// what of runtime/ a user's build needs, copied without build products (as contract runtime-source does)
import { copyRuntimeSources } from '../dist/runtime-source.js';

const cliDir = resolve(dirname(fileURLToPath(import.meta.url)), '..');
const repo = resolve(cliDir, '..', '..');
const out = resolve(process.argv[2] ?? join(repo, 'dist-packages'));
/** The workspace packages the CLI needs, in dependency order. */
const WORKSPACES = ['conventions', 'language', 'codegen', 'build-service', 'simulator'];

function run(cmd, args, cwd) {
    return execFileSync(cmd, args, { cwd, encoding: 'utf8', stdio: ['ignore', 'pipe', 'inherit'], env: { ...process.env, npm_config_update_notifier: 'false', npm_config_fund: 'false', npm_config_audit: 'false' } });
}

/**
 * The registry packages the given package folders need at run time (dependencies and optional
 * dependencies, transitively; the workspace packages are not among them), each as the folder Node
 * resolves it to from its dependent in this repository (`from`) and where it goes in the staging
 * folder (`to`): the same node_modules path, so every package resolves there to the version it
 * resolves to here. A required package the install does not hold stops the pack.
 */
function registryPackages(roots) {
    const found = new Map(); // path under the repository -> the package folder
    const need = (name, fromDir, dependent, optional) => {
        if (name.startsWith('@contract-studio/')) return;
        for (let dir = fromDir; ; dir = dirname(dir)) {
            const candidate = join(dir, 'node_modules', name);
            if (existsSync(join(candidate, 'package.json'))) return visit(candidate);
            if (dir === repo || dir === dirname(dir)) break;
        }
        if (!optional) throw new Error(`pack: ${name} (needed by ${dependent}) is not installed: run \`npm ci\` at the repository root first`);
    };
    const visit = (dir) => {
        const at = relative(repo, dir);
        if (found.has(at)) return;
        found.set(at, dir);
        requirements(dir);
    };
    const requirements = (dir) => {
        const manifest = JSON.parse(readFileSync(join(dir, 'package.json'), 'utf8'));
        for (const name of Object.keys(manifest.dependencies ?? {})) need(name, dir, manifest.name, false);
        // an optional one may be missing: not for this platform
        for (const name of Object.keys(manifest.optionalDependencies ?? {})) need(name, dir, manifest.name, true);
    };
    for (const root of roots) requirements(root);
    return [...found].map(([at, from]) => {
        if (!at.startsWith(`node_modules${sep}`)) throw new Error(`pack: ${at} is installed inside a workspace; only the root node_modules is bundled`);
        return { from, to: at };
    });
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
    run('npm', ['pack', ...WORKSPACES.flatMap((w) => ['-w', `packages/${w}`]), '--pack-destination', tarballs, '--loglevel=error'], repo);

    // 2. the CLI's own files, the runtime sources, and its dependencies in node_modules
    const stage = join(work, 'cli');
    mkdirSync(stage);
    const pkg = JSON.parse(readFileSync(join(cliDir, 'package.json'), 'utf8'));
    for (const f of pkg.files) cpSync(join(cliDir, f), join(stage, f), { recursive: true });
    if (existsSync(join(cliDir, 'README.md'))) cpSync(join(cliDir, 'README.md'), join(stage, 'README.md'));
    copyRuntimeSources(join(repo, 'runtime'), join(stage, 'runtime'));
    const byName = new Map(readdirSync(tarballs).map((t) => [t.replace(/-\d+\.\d+\.\d+\.tgz$/, '').replace(/^contract-studio-/, ''), join(tarballs, t)]));
    for (const w of WORKSPACES) if (!byName.get(w)) throw new Error(`npm pack made no tarball for packages/${w}`);
    // the workspace packages unpacked as npm would install them, and the registry packages they
    // and the CLI need, copied from where the repository's install put them
    for (const w of WORKSPACES) {
        const into = join(stage, 'node_modules', '@contract-studio', w);
        mkdirSync(into, { recursive: true });
        run('tar', ['-xzf', byName.get(w), '-C', into, '--strip-components=1'], stage);
    }
    for (const { from, to } of registryPackages([cliDir, ...WORKSPACES.map((w) => join(repo, 'packages', w))])) {
        cpSync(from, join(stage, to), { recursive: true, dereference: true, filter: (src) => !src.slice(from.length).startsWith('/node_modules') });
    }

    // 3. every dependency bundled; the workspace ones named by version (they are inside)
    const deps = { ...pkg.dependencies };
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
