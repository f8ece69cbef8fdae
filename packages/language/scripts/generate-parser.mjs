#!/usr/bin/env node
/**
 * The build's `langium generate`, run only when the grammar or langium-config.json changed since
 * the committed src/generated/ and syntaxes/ were made: their inputs' hash is committed beside
 * them (src/generated/grammar-inputs.sha256). Langium's CLI (4.2.0, through its jsonschema
 * dependency) crashes on Node 24.20 and later ("TypeError: Invalid URL ... thismessage::/"), while
 * the parser it generates runs on every supported Node: so a checkout builds on Node 20 to 26, and
 * only a grammar change needs a Node on which the CLI runs (20 or 22), said here when it fails.
 * `--force` regenerates whatever the hash says; `--check` exits 1 when the hash is not current.
 */
import { createHash } from 'node:crypto';
import { spawnSync } from 'node:child_process';
import { readFileSync, writeFileSync } from 'node:fs';
import { dirname, join } from 'node:path';
import { fileURLToPath } from 'node:url';

const pkg = join(dirname(fileURLToPath(import.meta.url)), '..');
const STAMP = join(pkg, 'src/generated/grammar-inputs.sha256');
const INPUTS = ['langium-config.json', 'src/cactal.langium'];

function inputsHash() {
    const h = createHash('sha256');
    for (const rel of INPUTS) h.update(`${rel}\n`).update(readFileSync(join(pkg, rel)));
    return h.digest('hex');
}

function stamped() {
    try {
        return readFileSync(STAMP, 'utf8').trim();
    } catch {
        return '';
    }
}

const args = new Set(process.argv.slice(2));
const current = inputsHash();
if (args.has('--check')) {
    if (stamped() === current) process.exit(0);
    console.error(`${STAMP}: the grammar or langium-config.json changed since src/generated/ was made: run npm run langium:generate -w packages/language`);
    process.exit(1);
}
if (!args.has('--force') && stamped() === current) {
    console.log('langium generate: src/generated/ is current (grammar unchanged), skipped');
    process.exit(0);
}
const run = spawnSync(process.platform === 'win32' ? 'npx.cmd' : 'npx', ['--no-install', 'langium', 'generate'], { cwd: pkg, stdio: 'inherit' });
if (run.status !== 0) {
    const [major, minor] = process.versions.node.split('.').map(Number);
    if (major > 24 || (major === 24 && minor >= 20)) {
        console.error(`langium generate failed on Node ${process.versions.node}: Langium's CLI 4.2.0 does not run on Node 24.20 or later (its jsonschema dependency). The grammar changed, so src/generated/ must be made again: run this build once with Node 20 or 22 (e.g. npx -p node@22 ...), then commit src/generated/ with its grammar-inputs.sha256.`);
    }
    process.exit(run.status ?? 1);
}
writeFileSync(STAMP, `${current}\n`);
