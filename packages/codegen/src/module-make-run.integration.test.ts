/**
 * `make run` / `make kill` in a module's folder (the ContrACT Eclipse tool's per-module Makefiles had
 * them): one line pointing at the architecture's Makefile, which runs and stops the modules
 * together, instead of make's bare `No rule to make target 'run'` (field test ft69). GNU make for
 * real on examples/tutorial's committed Makefiles (every module, supervisor and ORD).
 */
import { spawnSync } from 'node:child_process';
import { readdirSync } from 'node:fs';
import { join, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';
import { describe, expect, it } from 'vitest';

const REPO = resolve(fileURLToPath(new URL('.', import.meta.url)), '..', '..', '..');
const MODULES = join(REPO, 'examples', 'tutorial', 'src-gen', 'generated', 'architecture', 'modules');

describe('make run / make kill in a module\'s folder', () => {
    it('stops with one line naming the architecture\'s Makefile and its target; nothing built', () => {
        const folders = readdirSync(MODULES).filter((f) => f.endsWith('_mod'));
        expect(folders).toHaveLength(9);
        for (const folder of folders) {
            const name = folder.slice(0, -'_mod'.length);
            for (const target of ['run', 'kill']) {
                // with and without a runtime given: neither needs one
                for (const runtime of [[`CONTRACT_RUNTIME=${join(REPO, 'runtime')}`], []]) {
                    const r = spawnSync('make', ['-s', '-C', join(MODULES, folder), target, ...runtime], { encoding: 'utf8' });
                    expect(r.status).toBe(2);
                    expect(r.stdout).toBe('');
                    expect(r.stderr).toMatch(new RegExp(`^Makefile:\\d+: \\*\\*\\* ${name} is run and stopped with the whole architecture, by its Makefile in \\.\\./\\.\\. \\(generated/architecture/\\): make -C \\.\\./\\.\\. ${target}\\.  Stop\\.\\n$`));
                }
            }
        }
        // make (all) is not concerned
        const all = spawnSync('make', ['-n', '-C', join(MODULES, 'MAA_mod'), `CONTRACT_RUNTIME=${join(REPO, 'runtime')}`], { encoding: 'utf8' });
        expect(all.status).toBe(0);
    });
});
