/**
 * `contract generate|build|run` of a folder inside a project (docs/codegen.md "Where a project is"):
 * the Eclipse layout `P/src/*.contract` + `P/src-gen/` generated as `contract generate P/src` made
 * an empty second tree `P/src/src-gen` (defaults only), and `contract build P/src` built it, the
 * user's code in `P/src-gen` left out, silently (field test ft69). Refused, naming the project
 * and the command to run; `generate -o OUT` names its output and is taken as meant.
 */
import { cpSync, existsSync, mkdirSync, mkdtempSync, readdirSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { runCli } from '../src/cli.js';
import { capture } from './capture-io.js';
import { removeScratch } from './scratch.js';

const TUTORIAL = fileURLToPath(new URL('../../../examples/tutorial', import.meta.url));

let scratch: string;
beforeAll(() => {
    scratch = mkdtempSync(join(tmpdir(), 'contract-inside-'));
    // the Eclipse tool's project: its tree has no manifest, only generated/architecture/
    mkdirSync(join(scratch, 'MyProject', 'src'), { recursive: true });
    for (const f of readdirSync(TUTORIAL)) if (f.endsWith('.contract')) cpSync(join(TUTORIAL, f), join(scratch, 'MyProject', 'src', f));
    mkdirSync(join(scratch, 'MyProject', 'src-gen', 'generated', 'architecture', 'modules', 'MAA_mod'), { recursive: true });
    writeFileSync(join(scratch, 'MyProject', 'src-gen', 'generated', 'architecture', 'modules', 'MAA_mod', 'module.c'), '/* the user\'s code */\n');
});
afterAll(() => removeScratch(scratch));

const said = (dir: string, project: string, command: string, nothing: string) =>
    `contract ${command}: ${dir} is inside project ${project}, whose generated tree ${project}/src-gen/ holds your code (the folder holding a src-gen/ is the project: docs/codegen.md "Where a project is"): ${command} the project instead, contract ${command} ${project}; nothing was ${nothing}\n`;

describe('a folder inside a project', () => {
    it('generate, build and run of it are refused (exit 1), naming the project and the command; nothing written', async () => {
        for (const [command, nothing] of [['generate', 'generated'], ['build', 'built'], ['run', 'built or run']] as const) {
            const io = capture(scratch);
            expect(await runCli([command, 'MyProject/src', '--sandbox', 'none'].slice(0, command === 'generate' ? 2 : 4), io)).toBe(1);
            expect(io.stderr).toBe(said('MyProject/src', 'MyProject', command, nothing));
            expect(io.stdout).toBe('');
        }
        expect(existsSync(join(scratch, 'MyProject', 'src', 'src-gen'))).toBe(false);
        expect(existsSync(join(scratch, 'MyProject', 'src', 'logs'))).toBe(false);
        // from inside the folder: the project as a path from there
        const here = capture(join(scratch, 'MyProject', 'src'));
        expect(await runCli(['generate', '.'], here)).toBe(1);
        expect(here.stderr).toBe(said('.', '..', 'generate', 'generated'));
    }, 60_000);

    it('a tree of ContrACT Studio (its manifest) above counts too; -o OUT is taken as meant; the project itself generates', async () => {
        expect(await runCli(['generate', 'MyProject'], capture(scratch))).toBe(0);
        expect(existsSync(join(scratch, 'MyProject', 'src-gen', '.contract-manifest.json'))).toBe(true);
        const again = capture(scratch);
        expect(await runCli(['generate', 'MyProject/src'], again)).toBe(1);
        expect(again.stderr).toBe(said('MyProject/src', 'MyProject', 'generate', 'generated'));
        const out = capture(scratch);
        expect(await runCli(['generate', 'MyProject/src', '-o', 'elsewhere'], out)).toBe(0);
        expect(existsSync(join(scratch, 'elsewhere', 'generated', 'architecture', 'Makefile'))).toBe(true);
        // a src-gen/ with neither a manifest nor generated/architecture/ is no generated tree
        mkdirSync(join(scratch, 'plain', 'src-gen'), { recursive: true });
        cpSync(join(scratch, 'MyProject', 'src'), join(scratch, 'plain', 'robot'), { recursive: true });
        expect(await runCli(['generate', 'plain/robot'], capture(scratch))).toBe(0);
    }, 60_000);
});
