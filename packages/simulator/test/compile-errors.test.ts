/**
 * A project whose own C does not compile for the simulator (a protected region of a src-gen common
 * header) is told as `contract build` tells it: the user's src-gen file, the line in that file and
 * the protected region, through the build service's gcc reader — never the temporary folder of the
 * cache the simulator compiles in. The line is the user's also when the simulator's copy of the
 * header differs from it (src-gen older than the model: lines mapped through the region); a line
 * that cannot be mapped says so. A link error (a function a region calls that nobody defines) is
 * told the same way, from ld's lines. Module code (module.c) is not the simulator's to compile.
 */
import { cpSync, mkdirSync, mkdtempSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { afterAll, describe, expect, it } from 'vitest';
import { compileDiagnostics, DEFAULT_RUNTIME_DIR, describeCompileFailure, linkDiagnostics, loadScenario, prepareProject, runLoadedScenario, type SimSources } from '../src/index.js';
import { CACHE, TUTORIAL } from './support.js';

const scratch = mkdtempSync(join(tmpdir(), 'contract-sim-compile-errors-'));
afterAll(() => rmSync(scratch, { recursive: true, force: true }));

const TESTIT = 'generated/architecture/common/SharedFunctiontestit.h';

/** A tutorial copy with `edit` applied to the text of one file of its src-gen (path relative to src-gen). */
function brokenCopy(name: string, file: string, edit: (text: string) => string): string {
    const dir = join(scratch, name);
    cpSync(TUTORIAL, dir, { recursive: true });
    const path = join(dir, 'src-gen', file);
    writeFileSync(path, edit(readFileSync(path, 'latin1')), 'latin1');
    return dir;
}

/** `text` with `line` added right after the START marker of region `id`. */
function intoRegion(text: string, id: string, line: string): string {
    const start = text.indexOf(`ID(${id}) ENABLED START*/`);
    expect(start, id).toBeGreaterThan(0);
    const at = text.indexOf('\n', start) + 1;
    return text.slice(0, at) + line + '\n' + text.slice(at);
}

/** The 1-based line of `needle` in the file. */
function lineOf(dir: string, file: string, needle: string): number {
    return readFileSync(join(dir, 'src-gen', file), 'latin1').split('\n').findIndex((l) => l.includes(needle)) + 1;
}

async function problems(dir: string) {
    const p = await prepareProject(dir, { runtimeDir: DEFAULT_RUNTIME_DIR, cacheDir: CACHE });
    if ('build' in p) throw new Error('the simulator was built');
    return p;
}

describe('compile errors of the project\'s C name the user\'s file, line and protected region', () => {
    it('a test function\'s region: its src-gen path, its line, the region; no cache path in the message', async () => {
        const dir = brokenCopy('impl', TESTIT, (t) => intoRegion(t, 'protect_function_impl_testit', '    int x = 1 oops;'));
        const p = await problems(dir);
        const line = lineOf(dir, TESTIT, '1 oops;');
        expect(p.compile?.diagnostics[0]).toMatchObject({
            severity: 'error', file: TESTIT, line, protectedRegion: { id: 'protect_function_impl_testit' },
        });
        expect(p.buildError).toMatch(/cannot compile .* for the simulator/);
        expect(p.buildError).toContain(`src-gen/${TESTIT}:${line}:`);
        expect(p.buildError).toContain('protect_function_impl_testit');
        expect(p.buildError).not.toContain(CACHE);
        expect(p.buildError).not.toMatch(/sim-[0-9a-f]{20}/);
        // the header is included by every supervisor's tables: its error once
        expect(p.compile!.diagnostics.filter((d) => d.line === line)).toHaveLength(1);
    });

    it('a datatype header whose src-gen copy differs from the simulator\'s (two lines more on top): the line of the user\'s file, through the region', async () => {
        const typeA = 'generated/architecture/common/SharedTypeA.h';
        const dir = brokenCopy('shifted', typeA, (t) => '// my notes\n// more notes\n' + intoRegion(t, 'protect_additional_impl_TypeA', 'static int broken_ = oops_undeclared;'));
        const p = await problems(dir);
        const d = p.compile?.diagnostics.find((x) => x.message.includes('oops_undeclared'));
        expect(d).toMatchObject({ file: typeA, line: lineOf(dir, typeA, 'oops_undeclared;'), protectedRegion: { id: 'protect_additional_impl_TypeA' } });
        expect(d!.message).not.toContain('as the simulator generated it');
        expect(p.buildError).not.toContain(CACHE);
    });

    it('a function the region calls that nobody defines (a link error): the user\'s header, the line of the call, the region, the function it is in', async () => {
        const dir = brokenCopy('link', TESTIT, (t) => intoRegion(t, 'protect_function_impl_testit', '    extern int gripper_ready(void); if (gripper_ready()) { }'));
        const p = await problems(dir);
        expect(p.compile?.stage).toBe('link');
        const line = lineOf(dir, TESTIT, 'gripper_ready()) {');
        expect(p.compile?.diagnostics).toHaveLength(1);
        expect(p.compile?.diagnostics[0]).toMatchObject({
            severity: 'error', file: TESTIT, line, protectedRegion: { id: 'protect_function_impl_testit' },
        });
        expect(p.compile!.diagnostics[0]!.message).toMatch(/^undefined reference to `gripper_ready' \(in function \w+\)$/);
        expect(p.buildError).toMatch(/^cannot link the project's C for the simulator \(1 error\(s\) in src-gen\/\):/);
        expect(p.buildError).toContain(`src-gen/${TESTIT}:${line}: error: undefined reference to \`gripper_ready'`);
        expect(p.buildError).not.toContain(CACHE);
        expect(p.buildError).not.toMatch(/sim-[0-9a-f]{20}|unit\d+\.o/);
    });

    it('a compute function calling libmodule\'s GetTime() links, and reads the virtual time (ns since the simulation started)', async () => {
        const doit = 'generated/architecture/common/SharedFunctiondoit.h';
        const dir = brokenCopy('gettime', doit, (t) => intoRegion(intoRegion(t, 'protect_function_impl_doit', 'printf("virtual now=%lld\\n", (long long)GetTime());'),
            'protect_additional_import_function_doit', '#include <libmodule/libmodule.h>'));
        const p = await prepareProject(dir, { runtimeDir: DEFAULT_RUNTIME_DIR, cacheDir: CACHE });
        if (!('build' in p)) throw new Error(p.buildError ?? 'not built');
        const file = join(dir, 'scenarios/mission.scenario');
        const result = await runLoadedScenario(p, loadScenario(file, 'mission.scenario', readFileSync(file, 'utf8'), p.index));
        const printed = result.steps.flatMap((st) => (st.record?.output ?? '').split('\n').filter((l) => l.startsWith('virtual now=')).map((l) => ({ at: st.timeNs, now: Number(l.slice(12)) })));
        expect(printed.length).toBeGreaterThan(0);
        for (const x of printed) expect(x.now).toBe(x.at); // the step's virtual instant, not the host's clock
    });

    it('a broken module.c region does not stop the simulation: modules are virtual, their code is not compiled', async () => {
        const maa = 'generated/architecture/modules/MAA_mod/module.c';
        const dir = brokenCopy('module', maa, (t) => intoRegion(t, 'protect_additional_import_MAA', 'int broken oops;'));
        const p = await prepareProject(dir, { runtimeDir: DEFAULT_RUNTIME_DIR, cacheDir: CACHE });
        expect('build' in p ? 'built' : p.buildError).toBe('built');
    });
});

describe('compileDiagnostics (gcc\'s text output of the temporary folder, told against src-gen)', () => {
    const work = '/var/cache/contract-studio/sim/sim-0123456789abcdef0123.tmp-1-abc';
    const srcGen = join(scratch, 'unit', 'src-gen');
    const header = (extra: string) => [
        '#ifndef X_H', // 1
        extra, // 2
        '/*PROTECTED REGION ID(protect_function_impl_f) ENABLED START*/', // 3
        '    x oops;', // 4
        '/*PROTECTED REGION END*/', // 5
        'int after;', // 6
        '#endif', // 7
        '',
    ].join('\n');
    const sources = (userText: string | undefined): SimSources => {
        rmSync(srcGen, { recursive: true, force: true });
        mkdirSync(join(srcGen, 'generated', 'architecture', 'common'), { recursive: true });
        if (userText !== undefined) writeFileSync(join(srcGen, 'generated', 'architecture', 'common', 'SharedFunctionf.h'), userText);
        return {
            files: [{ path: 'common/SharedFunctionf.h', content: header('') }, { path: 'modules/SUP_mod/vocabulary.c', content: '' }, { path: 'sim_tables.c', content: '' }],
            units: ['modules/SUP_mod/vocabulary.c', 'sim_tables.c'], includes: new Map(), supervisors: ['SUP'], hasOrd: false, warnings: [], srcGen,
        };
    };
    const gcc = (line: number) => [
        `In file included from ${work}/modules/SUP_mod/vocabulary.c:7:`,
        `${work}/common/SharedFunctionf.h: In function 'f':`,
        `${work}/common/SharedFunctionf.h:${line}:7: error: expected ';' before 'oops'`,
        `    ${line} |     x oops;`,
        '      |       ^~~~~',
        `${work}/common/SharedFunctionf.h:6:5: note: declared here`,
        `   16 | ${work}/common/SharedFunctionf.h:1:1: error: an excerpt of the source is no diagnostic`,
        '',
    ].join('\n');

    it('the user\'s file byte for byte: same line, its region; notes under their error; each error once; no folder path', () => {
        const f = compileDiagnostics([gcc(4), gcc(4)], work, sources(header('')));
        expect(f.diagnostics).toHaveLength(1);
        expect(f.diagnostics[0]).toMatchObject({
            file: 'generated/architecture/common/SharedFunctionf.h', line: 4, column: 7, protectedRegion: { id: 'protect_function_impl_f', startLine: 3 },
            children: [{ severity: 'note', line: 6, protectedRegion: null }],
        });
        expect(f.other).toEqual([]);
        const text = describeCompileFailure(f);
        expect(text).toContain("src-gen/generated/architecture/common/SharedFunctionf.h:4:7: error: expected ';' before 'oops' (in protected region protect_function_impl_f)");
        expect(text).not.toContain(work);
    });

    it('a copy that differs: a line in a region mapped to the user\'s line; one outside kept and said; no user file said too', () => {
        const shifted = compileDiagnostics([gcc(4)], work, sources('// mine\n// mine\n' + header('')));
        expect(shifted.diagnostics[0]).toMatchObject({ line: 6, protectedRegion: { id: 'protect_function_impl_f', startLine: 5 } });
        // the note at line 6 is outside the regions: the simulator's line, said as such
        expect(shifted.diagnostics[0]!.children[0]!.message).toMatch(/line 6 of the file as the simulator generated it: your copy differs/);
        const none = compileDiagnostics([gcc(4)], work, sources(undefined));
        expect(none.diagnostics[0]).toMatchObject({ line: 4, protectedRegion: { id: 'protect_function_impl_f' } });
        expect(none.diagnostics[0]!.message).toMatch(/you have no readable copy of it/);
    });

    it('ld\'s output: a reference at the user\'s line and region, once; a definition twice with its first place; ld\'s placeless lines without the folder', () => {
        const ld = [
            `/usr/bin/ld: ${work}/unit0.o: in function \`f':`,
            `${work}/common/SharedFunctionf.h:4: undefined reference to \`gripper_ready'`,
            `/usr/bin/ld: ${work}/common/SharedFunctionf.h:4: undefined reference to \`gripper_ready'`,
            `/usr/bin/ld: ${work}/unit1.o:${work}/common/SharedFunctionf.h:6: multiple definition of \`after'; ${work}/unit0.o:${work}/common/SharedFunctionf.h:6: first defined here`,
            `/usr/bin/ld: cannot find ${work}/libx.a: No such file or directory`,
            'collect2: error: ld returned 1 exit status',
            '',
        ].join('\n');
        const f = linkDiagnostics(ld, work, sources(header('')));
        expect(f.stage).toBe('link');
        expect(f.diagnostics).toHaveLength(3);
        expect(f.diagnostics[0]).toMatchObject({
            file: 'generated/architecture/common/SharedFunctionf.h', line: 4, protectedRegion: { id: 'protect_function_impl_f' },
            message: "undefined reference to `gripper_ready' (in function f)",
        });
        expect(f.diagnostics[1]).toMatchObject({ line: 6, protectedRegion: null, message: "multiple definition of `after'", children: [{ severity: 'note', line: 6, message: 'first defined here' }] });
        expect(f.diagnostics[2]).toMatchObject({ file: null, message: 'cannot find libx.a: No such file or directory' });
        expect(f.other).toEqual([]);
        expect(describeCompileFailure(f)).toMatch(/^cannot link the project's C for the simulator \(3 error\(s\) in src-gen\/\):/);
        expect(describeCompileFailure(f)).not.toContain(work);
    });

    it('output that holds no diagnostic is told without the folder\'s path; the simulator\'s own table file is named as such', () => {
        const f = compileDiagnostics([`bwrap: cannot mount ${work}/x: denied\n`], work, sources(header('')));
        expect(f.diagnostics).toEqual([]);
        expect(f.other).toEqual(['bwrap: cannot mount x: denied']);
        expect(describeCompileFailure(f)).not.toContain(work);
        const own = compileDiagnostics([`${work}/sim_tables.c:3:1: error: bad table\n`], work, sources(header('')));
        expect(own.diagnostics[0]).toMatchObject({ file: null, message: "sim_tables.c:3:1 (the simulator's own table file): bad table" });
    });
});
