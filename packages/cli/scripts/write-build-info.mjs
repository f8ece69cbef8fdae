#!/usr/bin/env node
// Run by `npm run build -w packages/cli` after tsc: writes dist/build-info.json, the commit of the
// repository this build was made from and whether tracked files differed from it, so that
// `contract --version` tells two builds of the same version apart (build-version.ts). Outside a
// git checkout (a source tarball) it writes no commit: --version then prints the version alone.
import { execFileSync } from 'node:child_process';
import { mkdirSync, writeFileSync } from 'node:fs';
import { dirname, join, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';

const cliDir = resolve(dirname(fileURLToPath(import.meta.url)), '..');
const git = (...args) => execFileSync('git', ['-C', cliDir, ...args], { encoding: 'utf8', stdio: ['ignore', 'pipe', 'ignore'] }).trim();
let info = {};
try {
    const commit = git('rev-parse', 'HEAD');
    if (/^[0-9a-f]{40}$/.test(commit)) info = { commit, modified: git('status', '--porcelain', '--untracked-files=no') !== '' };
} catch {
    // no git, or not a checkout: no commit known
}
mkdirSync(join(cliDir, 'dist'), { recursive: true });
writeFileSync(join(cliDir, 'dist', 'build-info.json'), JSON.stringify(info) + '\n');
