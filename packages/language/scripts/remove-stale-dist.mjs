#!/usr/bin/env node
// Removes compiled files under dist/ whose source under src/ no longer exists (tsc -b never deletes
// them, and the package ships dist/): e.g. a deleted module that would otherwise still be importable.
import { existsSync, readdirSync, rmSync } from 'node:fs';
import { join, relative } from 'node:path';
import { fileURLToPath } from 'node:url';

const root = fileURLToPath(new URL('..', import.meta.url));
const dist = join(root, 'dist');
const src = join(root, 'src');
const OUTPUT = /\.(js|js\.map|d\.ts|d\.ts\.map)$/;

function* files(dir) {
    for (const entry of readdirSync(dir, { withFileTypes: true })) {
        const path = join(dir, entry.name);
        if (entry.isDirectory()) yield* files(path);
        else yield path;
    }
}

if (existsSync(dist)) {
    for (const file of files(dist)) {
        const rel = relative(dist, file);
        if (!OUTPUT.test(rel)) continue;
        const source = join(src, rel.replace(OUTPUT, '.ts'));
        if (!existsSync(source)) {
            rmSync(file);
            console.log(`removed stale dist/${rel} (no src/${relative(src, source)})`);
        }
    }
}
