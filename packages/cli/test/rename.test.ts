/**
 * `contract rename` on a copy of the tutorial with user code in its regions: the .contract files,
 * the generated paths and the region IDs move together, user code is kept byte for byte and the
 * project still generates and builds; clear errors change nothing. A rename by hand (sed) instead
 * orphans the code, with a header saying how to bring it back.
 */
import { execFileSync } from 'node:child_process';
import { cpSync, existsSync, readFileSync, readdirSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { identifierRenames, parseRegions, renameIdentifier } from '@contract-studio/codegen';
import { runCli } from '../src/cli.js';
import { seedRuntime } from '@contract-studio/build-service/test-support/runtime-seed';
import { scratchCopy, type Scratch } from './e2e/harness.js';
import { capture } from './capture-io.js';


const MODULES = 'src-gen/generated/architecture/modules';
/** Region ID -> content (bytes as latin1) of a generated file. */
function regions(file: string): Map<string, string> {
    const text = readFileSync(file, 'latin1');
    return new Map(parseRegions(text, file).regions.map((r) => [r.id, r.content]));
}
/** Every file of a project but src-gen, path -> text. */
function contractFiles(dir: string): Record<string, string> {
    return Object.fromEntries(readdirSync(dir).filter((f) => f.endsWith('.contract')).map((f) => [f, readFileSync(join(dir, f), 'utf8')]));
}

let scratch: Scratch;
let dir: string;
beforeAll(async () => {
    scratch = scratchCopy('tutorial');
    await seedRuntime(scratch.cache); // the test run's built runtime
    dir = scratch.project;
    process.env.CONTRACT_CACHE_DIR = scratch.cache;
    // user code in MSC's regions, with bytes that are not UTF-8, beside the tutorial's own code
    const file = join(dir, MODULES, 'MSC_mod/module.c');
    const text = readFileSync(file, 'latin1');
    writeFileSync(file, Buffer.from(text.replace('/*PROTECTED REGION ID(protect_init_MSC) ENABLED START*/',
        '/*PROTECTED REGION ID(protect_init_MSC) ENABLED START*/\n    /* calibr\xe9 \xff by hand */ int rename_marker = 42; (void)rename_marker;'), 'latin1'));
}, 240_000);
afterAll(() => {
    delete process.env.CONTRACT_CACHE_DIR;
    scratch.dispose();
});

describe('contract rename', () => {
    it('renames module MSC to MSK: .contract files, generated paths and region IDs, user code byte for byte', async () => {
        const before = regions(join(dir, MODULES, 'MSC_mod/module.c'));
        expect(before.get('protect_init_MSC')).toContain('rename_marker = 42');
        const tool = readFileSync(join(dir, 'src-gen/generated/architecture/tools/controlMSC.c'), 'latin1');
        const io = capture(scratch.root);
        expect(await runCli(['rename', 'tutorial', 'MSC', 'MSK'], io), io.stderr).toBe(0);
        expect(io.stdout).toContain('renamed module MSC -> MSK: 15 occurrence(s) in 5 file(s)');
        expect(io.stdout).toContain('  generated/architecture/modules/MSC_mod -> generated/architecture/modules/MSK_mod');
        expect(io.stderr).toMatch(/generated tutorial\/src-gen: \d+ created, \d+ updated, \d+ kept, 0 orphaned, 0 error\(s\)/);

        // the scenarios follow, token by token (their comments are left as they are)
        expect(io.stdout).toContain('tutorial/scenarios/commutation.scenario:28: t=1.2s MSC:1 failing_data = {"overheat", 3}  ->  t=1.2s MSK:1 failing_data = {"overheat", 3}\n');
        expect(io.stdout).toContain('tutorial/scenarios/mission.scenario:19: t=1s MSC:1 {"overheat", 3}  ->  t=1s MSK:1 {"overheat", 3}\n');
        expect(readFileSync(join(dir, 'scenarios/commutation.scenario'), 'utf8')).toContain('t=1.2s MSK:1 failing_data = {"overheat", 3}\n');
        // the old name left in user code (here only in strings) is listed with file:line, not changed
        expect(io.stderr).toMatch(/note: tutorial\/src-gen\/generated\/architecture\/modules\/MSK_mod\/module\.c:\d+: protected region protect_exec_MSK mentions MSC \(the old name\) in a string or character literal: not changed\n/);
        expect(io.stderr).not.toContain('warning:');
        const files = contractFiles(dir);
        expect(Object.values(files).join('\n')).not.toMatch(/\bMSC\b/);
        expect(files['smodule3.contract']).toContain('synchronous module MSK{');
        expect(existsSync(join(dir, MODULES, 'MSC_mod'))).toBe(false);
        expect(existsSync(join(dir, 'src-gen/orphans'))).toBe(false);
        const after = regions(join(dir, MODULES, 'MSK_mod/module.c'));
        expect([...after.keys()].sort()).toEqual([...before.keys()].map((id) => id.replace(/_MSC$/, '_MSK')).sort());
        for (const [id, content] of before) expect(after.get(id.replace(/_MSC$/, '_MSK')), id).toBe(content);
        // the control tool follows too (its generated code names the new module)
        expect(existsSync(join(dir, 'src-gen/generated/architecture/tools/controlMSC.c'))).toBe(false);
        expect(readFileSync(join(dir, 'src-gen/generated/architecture/tools/controlMSK.c'), 'latin1')).not.toBe(tool);

        const check = capture(scratch.root);
        expect(await runCli(['check', 'tutorial'], check)).toBe(0);
        const again = capture(scratch.root);
        expect(await runCli(['generate', 'tutorial'], again)).toBe(0);
        expect(again.stderr).toMatch(/: 0 created, 0 updated, \d+ kept, 0 orphaned, 0 error\(s\)/);
    }, 120_000);

    it('the renamed project builds with gcc (bwrap sandbox)', async () => {
        const io = capture(scratch.root);
        expect(await runCli(['build', 'tutorial', '--sandbox', 'bwrap'], io), io.stderr).toBe(0);
    }, 300_000);

    it('renames a port by MODULE:port; a port names no generated file; its uses in the module\'s regions follow', async () => {
        const exec = regions(join(dir, MODULES, 'MSK_mod/module.c')).get('protect_exec_MSK')!;
        expect(exec).toContain('GetLatestData(&in_coordinates, ');
        const io = capture(scratch.root);
        expect(await runCli(['rename', 'tutorial', 'MSK:in_coordinates', 'position'], io), io.stderr).toBe(0);
        expect(io.stdout).toContain('renamed port in_coordinates -> position: ');
        expect(io.stdout).not.toContain('path(s) moved');
        expect(io.stdout).toMatch(/tutorial\/src-gen\/generated\/architecture\/modules\/MSK_mod\/module\.c:\d+: protected region protect_exec_MSK: 6 use\(s\) of in_coordinates renamed\n/);
        expect(contractFiles(dir)['smodule3.contract']).toContain('in :0 TypeA position;');
        const after = regions(join(dir, MODULES, 'MSK_mod/module.c'));
        expect(after.get('protect_init_MSK')).toContain('rename_marker = 42');
        // whole identifiers in code only: 'in coordinates' in a string stays
        expect(after.get('protect_exec_MSK')).toBe(exec.replace(/\bin_coordinates\b/g, 'position'));
        expect(after.get('protect_exec_MSK')).toContain('"MSC : state1 => in coordinates: "');
        expect(io.stderr).not.toContain('warning:');
    }, 120_000);

    it('the project still builds after the port rename (bwrap sandbox)', async () => {
        const io = capture(scratch.root);
        expect(await runCli(['build', 'tutorial', '--sandbox', 'bwrap'], io), io.stderr).toBe(0);
    }, 300_000);

    it('renames a port named in a scenario (M:P name = value) and in the user code that emits it', async () => {
        const io = capture(scratch.root);
        expect(await runCli(['rename', 'tutorial', 'MAA:connection_status', 'link_status'], io), io.stderr).toBe(0);
        expect(io.stdout).toContain('tutorial/scenarios/commutation.scenario:20: t=300ms MAA:2 connection_status = "disconnected"  ->  t=300ms MAA:2 link_status = "disconnected"\n');
        expect(io.stdout).toMatch(/MAA_mod\/module\.c:\d+: protected region protect_internal_functions_impl_MAA: 2 use\(s\) of connection_status renamed\n/);
        const maa = regions(join(dir, MODULES, 'MAA_mod/module.c')).get('protect_internal_functions_impl_MAA')!;
        expect(maa).toContain('strcpy(link_status, status);');
        expect(maa).toContain('PostEvent(&link_status[0]);');
    }, 120_000);

    it('a module whose description is the generated default gets the new name in it', async () => {
        const io = capture(scratch.root);
        expect(await runCli(['rename', 'tutorial', 'MSA', 'MSF'], io), io.stderr).toBe(0);
        expect(io.stdout).toMatch(/MSF_mod\/module\.c:\d+: default description "synchronous module MSA" -> "synchronous module MSF"\n/);
        expect(regions(join(dir, MODULES, 'MSF_mod/module.c')).get('protect_description_MSF')).toBe('"synchronous module MSF"');
        expect(io.stderr).toMatch(/, 0 orphaned, 0 error\(s\)/);
        expect(io.stderr).not.toContain('warning:');
    }, 120_000);

    it('renames a datatype and a function: Shared<T>.h and SharedFunction<f>.h follow with their regions', async () => {
        const COMMON = join(dir, 'src-gen/generated/architecture/common');
        for (const [from, to, file] of [['TypeA', 'Vec3', 'Shared'], ['doit', 'execute', 'SharedFunction']] as const) {
            const path = join(COMMON, `${file}${from}.h`);
            writeFileSync(path, readFileSync(path, 'latin1').replace(new RegExp(`(ID\\(protect_additional_impl_${from}\\) ENABLED START\\*/|ID\\(protect_function_impl_${from}\\) ENABLED START\\*/)`), `$1\n/* ${from} by hand */`), 'latin1');
            const before = regions(path);
            expect([...before.values()].join('')).toContain(`/* ${from} by hand */`);
            const io = capture(scratch.root);
            expect(await runCli(['rename', 'tutorial', from, to], io), io.stderr).toBe(0);
            expect(io.stderr).toMatch(/, 0 orphaned, 0 error\(s\)/);
            expect(io.stderr).not.toContain('warning:');
            expect(existsSync(path)).toBe(false);
            const after = regions(join(COMMON, `${file}${to}.h`));
            // user code byte for byte, but for the uses of the old name in code (eq_TypeA -> eq_Vec3: the build needs them)
            const kind = file === 'Shared' ? 'datatype' : 'function';
            const renamedUses = (content: string) => [...identifierRenames(kind, from, to)].reduce((text, [a, b]) => renameIdentifier(text, a, b).text, content);
            for (const [id, content] of before) expect(after.get(id.replace(new RegExp(`_${from}$`), `_${to}`)), id).toBe(renamedUses(content));
            expect(after.get(`protect_inf_${to}`) ?? '').not.toContain(`//${to} is`); // comments are not changed
        }
        // the module code that used the datatype and its functions follows (print_TypeA -> print_Vec3)
        const exec = regions(join(dir, MODULES, 'MSK_mod/module.c')).get('protect_exec_MSK')!;
        expect(exec).toContain('print_Vec3(&position);');
        expect(exec).not.toMatch(/\bprint_TypeA\b/);
    }, 120_000);

    it('renames a schema without touching the generated tree, even when its name is a region role (init)', async () => {
        const before = readFileSync(join(dir, MODULES, 'MSK_mod/module.c'));
        for (const [from, to] of [['schemaCommande1', 'init'], ['init', 'command1']]) {
            const io = capture(scratch.root);
            expect(await runCli(['rename', 'tutorial', from!, to!], io), io.stderr).toBe(0);
            expect(io.stdout).toContain(`renamed schema ${from} -> ${to}: `);
            expect(io.stderr).toMatch(/, 0 orphaned, 0 error\(s\)/);
        }
        // protect_init_MSK was not taken for the schema's name: the module's file is as it was
        expect(readFileSync(join(dir, MODULES, 'MSK_mod/module.c'))).toEqual(before);
        expect(contractFiles(dir)['supervisor.contract']).toContain('activate schema command1(');
        // the scenarios name the schema in expectations: they follow
        const scenario = readFileSync(join(dir, 'scenarios/commutation.scenario'), 'utf8');
        expect(scenario).toContain('expect schema command1 active\n');
        expect(scenario).not.toMatch(/\bschemaCommande1\b/);
    }, 120_000);

    it('renames a supervision function SUP.fn: the scenarios\' start, stop and expectations of that supervisor follow', async () => {
        const before = readFileSync(join(dir, 'scenarios/commutation.scenario'), 'utf8');
        expect(before).toContain('start SUP.action(consigne = {1.0, 2.0, 3.0})');
        const io = capture(scratch.root);
        expect(await runCli(['rename', 'tutorial', 'SUP.action', 'act'], io), io.stderr).toBe(0);
        expect(io.stdout).toContain('tutorial/scenarios/commutation.scenario:9: start SUP.action(consigne = {1.0, 2.0, 3.0})  ->  start SUP.act(consigne = {1.0, 2.0, 3.0})\n');
        const after = readFileSync(join(dir, 'scenarios/commutation.scenario'), 'utf8');
        expect(after).toContain('expect rule SUP.act.FIRST inactive\n');
        // every directive follows; the comment lines and the free-text title are as they were
        expect(after.split('\n').filter((l) => !l.startsWith('#') && !l.startsWith('scenario ') && /SUP\.action\b/.test(l))).toEqual([]);
        expect(after.split('\n').filter((l) => l.startsWith('#'))).toEqual(before.split('\n').filter((l) => l.startsWith('#')));
    }, 120_000);

    it('renames a rule label, a local and a parameter of a supervision function (SUP.fn.NAME); the scenarios follow; it generates', async () => {
        for (const [spec, to, kind, line] of [
            ['SUP.act.FIRST', 'OPENING', 'rule label', 'tutorial/scenarios/commutation.scenario:10: expect rule SUP.act.FIRST inactive  ->  expect rule SUP.act.OPENING inactive'],
            ['SUP.act.temp_mess_type', 'mess_kind', 'local', 'tutorial/scenarios/commutation.scenario:33: expect local temp_mess_type == "commutation"  ->  expect local mess_kind == "commutation"'],
            ['SUP.act.consigne', 'setpoint', 'function parameter', 'tutorial/scenarios/commutation.scenario:9: start SUP.act(consigne = {1.0, 2.0, 3.0})  ->  start SUP.act(setpoint = {1.0, 2.0, 3.0})'],
        ] as const) {
            const io = capture(scratch.root);
            expect(await runCli(['rename', 'tutorial', spec, to], io), io.stderr).toBe(0);
            expect(io.stdout).toMatch(new RegExp(`^renamed ${kind} ${spec.split('.')[2]} -> ${to}: [1-9]\\d* occurrence\\(s\\) in [12] file\\(s\\)$`, 'm'));
            expect(io.stdout).toContain(`${line}\n`);
            expect(io.stderr).toContain('0 error(s)');
        }
        const supervisor = readFileSync(join(dir, 'supervisor.contract'), 'utf8');
        expect(supervisor).toMatch(/\bOPENING\s*:/);
        expect(supervisor).toMatch(/\bstring mess_kind\b/);
        expect(supervisor).toMatch(/act\(\w+ setpoint\)/);
        expect(supervisor).not.toMatch(/\b(FIRST|temp_mess_type)\b/);
        // the parameter's uses follow, GLB's activation of SUP.act too; a schema's parameter of the same name does not
        expect(supervisor).toMatch(/\w+ temp_consigne = setpoint;/);
        expect(supervisor).toMatch(/activate schema \w+\(consigne = temp_consigne\)/);
        expect(readFileSync(join(dir, 'supervisor2.contract'), 'utf8')).toContain('activate supervisor SUP.act(setpoint=consigne_courante)');
        // a name the function does not have, and a module's "function": what there is is listed
        const io = capture(scratch.root);
        expect(await runCli(['rename', 'tutorial', 'SUP.act.NOPE', 'X'], io)).toBe(1);
        expect(io.stderr).toContain("SUP.act has no parameter, local or rule 'NOPE'; it has: setpoint (parameter), ");
        expect(io.stderr).toContain('OPENING (rule label)');
    }, 240_000);

    it('clear errors, exit 1, nothing changed: unknown entity, name taken, invalid name', async () => {
        const snapshot = contractFiles(dir);
        const tree = readFileSync(join(dir, MODULES, 'MSK_mod/module.c'));
        for (const [args, message] of [
            [['MSC', 'MSZ'], "no module, supervisor, schema, datatype, enumeration or function named 'MSC'"],
            [['MSK', 'MSD'], "'MSD' already names a module or supervisor (in smodule4.contract)"],
            [['MSK', 'msk'], "'msk' is not a valid module name: module and supervisor names are exactly three upper-case letters (A-Z)"],
            [['Vec3', 'int'], "'int' is a Cactal keyword and cannot name a datatype"],
        ] as Array<[string[], string]>) {
            const io = capture(scratch.root);
            expect(await runCli(['rename', 'tutorial', ...args], io)).toBe(1);
            expect(io.stderr).toMatch(/^contract rename: .*[^.]; nothing was renamed\n$/);
            expect(io.stderr).toContain(message);
        }
        const usage = capture(scratch.root);
        expect(await runCli(['rename', 'tutorial', 'MSK'], usage)).toBe(2);
        expect(usage.stderr).toContain('expected DIR OLD NEW, got 2 argument(s)');
        expect(contractFiles(dir)).toEqual(snapshot);
        expect(readFileSync(join(dir, MODULES, 'MSK_mod/module.c'))).toEqual(tree);
    }, 120_000);

    it('refuses when the generated tree already has the new name, before touching the .contract files', async () => {
        const snapshot = contractFiles(dir);
        cpSync(join(dir, MODULES, 'MSD_mod'), join(dir, MODULES, 'MSE_mod'), { recursive: true });
        const io = capture(scratch.root);
        expect(await runCli(['rename', 'tutorial', 'MSD', 'MSE'], io)).toBe(1);
        expect(io.stderr).toContain('cannot carry generated/architecture/modules/MSD_mod over: MSE_mod already exists; the .contract files were not changed');
        expect(contractFiles(dir)).toEqual(snapshot);
    }, 120_000);

    it('a rename by hand (sed) orphans the code instead, with a header saying where it came from and how to bring it back', async () => {
        execFileSync('sed', ['-i', 's/\\bMSB\\b/MSX/g', ...Object.keys(contractFiles(dir)).map((f) => join(dir, f))]);
        const io = capture(scratch.root);
        expect(await runCli(['generate', 'tutorial'], io)).toBe(0);
        expect(io.stdout).toContain('copied to orphans/ (code moved aside, or lines this generator does not write): ');
        const orphan = readFileSync(join(dir, 'src-gen/orphans/generated/architecture/modules/MSB_mod/module.c'), 'latin1');
        expect(orphan).toMatch(/^\/\* Orphaned user code of generated\/architecture\/modules\/MSB_mod\/module\.c \(module or supervisor MSB\), moved here on \d{4}-\d\d-\d\dT/);
        expect(orphan).toContain('`contract rename DIR OLD NEW`');
    }, 120_000);

    it('a model error that the rename fixes does not stop it (a port named time); a reference error does', async () => {
        const file = join(dir, 'smodule3.contract');
        const before = readFileSync(file, 'utf8');
        const [, type, port] = /in :0 (\w+) (\w+);/.exec(before)!; // TypeA, or its name after the renames above
        const module = /module ([A-Z]{3})/.exec(before)![1]!; // MSC, or MSK after the rename above
        writeFileSync(file, before.replace(`in :0 ${type} ${port};`, `in :0 ${type} time;`));
        const check = capture(scratch.root);
        expect(await runCli(['check', 'tutorial'], check)).toBe(1);
        expect(check.stdout + check.stderr).toContain('identifier-c-reserved');
        const io = capture(scratch.root);
        expect(await runCli(['rename', 'tutorial', `${module}:time`, 'position'], io), io.stderr).toBe(0);
        expect(contractFiles(dir)['smodule3.contract']).toContain(`in :0 ${type} position;`);

        writeFileSync(file, readFileSync(file, 'utf8').replace(`in :0 ${type} position;`, 'in :0 NoSuchType position;'));
        const snapshot = contractFiles(dir);
        const refused = capture(scratch.root);
        expect(await runCli(['rename', 'tutorial', `${module}:position`, 'pos'], refused)).toBe(1);
        expect(refused.stderr).toContain("Unknown type 'NoSuchType'");
        expect(refused.stderr).toMatch(/fix these first \(a rename needs the files parsed and every reference resolved\); nothing was renamed\n$/);
        expect(contractFiles(dir)).toEqual(snapshot);
        writeFileSync(file, readFileSync(file, 'utf8').replace('in :0 NoSuchType position;', `in :0 ${type} position;`));
    }, 120_000);

    it('a port rename whose new name the region code already uses: the code is not rewritten, each use is listed with file:line, exit 1', async () => {
        const file = join(dir, MODULES, 'MSK_mod/module.c');
        const text = readFileSync(file, 'latin1');
        writeFileSync(file, Buffer.from(text.replace('/*PROTECTED REGION ID(protect_init_MSK) ENABLED START*/', '/*PROTECTED REGION ID(protect_init_MSK) ENABLED START*/\n    int spare = 0; (void)spare;'), 'latin1'));
        const port = /in :0 \w+ (\w+);/.exec(contractFiles(dir)['smodule3.contract']!)![1]!;
        const io = capture(scratch.root);
        expect(await runCli(['rename', 'tutorial', `MSK:${port}`, 'spare'], io)).toBe(1);
        expect(io.stderr).toMatch(new RegExp(`warning: 'spare' is already used in the code of protected region protect_init_MSK \\(tutorial/src-gen/generated/architecture/modules/MSK_mod/module\\.c:\\d+\\): uses of '${port}' were not rewritten\n`));
        expect(io.stderr).toMatch(new RegExp(`warning: tutorial/src-gen/generated/architecture/modules/MSK_mod/module\\.c:\\d+: protected region protect_exec_MSK still uses ${port} \\(the old name\\) in its code: change it by hand, the build fails until then\n`));
        expect(io.stderr).toContain(`contract rename: port renamed, but 6 use(s) of ${port} in protected-region code were not changed (listed above)\n`);
        expect(regions(file).get('protect_exec_MSK')).toContain(`GetLatestData(&${port}, `);
    }, 120_000);
});
