/**
 * `contract trace LOGDIR` tells where a module crashed from the logs folder's crash file
 * (MODULE.crash, saved by contract-launch: docs/runtime-api.md "Crash file"): mapped by addr2line
 * in the module's executable beside the logs (ARCH/modules/M_mod/M) when its build-id is the
 * report's, else the raw offsets and the command that maps them; a hostile crash file (a link, too
 * large, another module's report, a path for an object) is not read or not followed.
 */
import { execFileSync } from 'node:child_process';
import { mkdirSync, mkdtempSync, rmSync, symlinkSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { runCli } from '../src/cli.js';
import { capture } from './capture-io.js';

const HEADER = 'mono_ns,wall_time,module,event,peer,port,size,detail';
const SOURCE = ['#include <stdio.h>', 'static volatile int *target;', '__attribute__((noinline)) int crash_here(int v)', '{', '    *target = v; /* the crash */', '    return v;', '}', 'int main(void) { return crash_here(1); }', ''].join('\n');
const CRASH_LINE = SOURCE.split('\n').findIndex((l) => l.includes('the crash')) + 1;

let arch: string;
let logs: string;
let exe: string;

function buildExe(extra: string[] = []): { buildId: string; offset: string } {
    execFileSync('gcc', ['-g', '-O1', ...extra, '-o', exe, join(arch, 'modules', 'EST_mod', 'module.c')]);
    const notes = execFileSync('readelf', ['-n', exe], { encoding: 'utf8' });
    const buildId = /Build ID: ([0-9a-f]+)/.exec(notes)![1]!;
    const sym = execFileSync('nm', [exe], { encoding: 'utf8' }).split('\n').find((l) => / T crash_here$/.test(l))!;
    return { buildId, offset: (parseInt(sym.split(' ')[0]!, 16) + 1).toString(16) };
}

function crashFile(module: string, buildId: string, offset: string): string {
    return [`==contract-crash== module ${module} signal 11 SIGSEGV addr 0x0`, `==contract-crash== build-id ${buildId}`, `==contract-crash== frame 0 exe 0x${offset}`, '==contract-crash== frame 1 libc.so.6 0x2724a', '==contract-crash== end 2 frames', ''].join('\n');
}

async function trace(): Promise<{ code: number; out: string; err: string }> {
    const io = capture(arch);
    const code = await runCli(['trace', logs], io);
    return { code, out: io.stdout, err: io.stderr };
}

beforeAll(() => {
    arch = mkdtempSync(join(tmpdir(), 'contract-trace-crash-'));
    logs = join(arch, 'logs');
    mkdirSync(join(arch, 'modules', 'EST_mod'), { recursive: true });
    mkdirSync(logs);
    writeFileSync(join(arch, 'modules', 'EST_mod', 'module.c'), SOURCE);
    exe = join(arch, 'modules', 'EST_mod', 'EST');
    writeFileSync(join(logs, 'EST_24-Nov-2026-18h30m15s.csv'), [HEADER, '2000000000,w,EST,request_received,ORD,,0,START', '2000100000,w,EST,module_crashed,,,0,signal 11 (SIGSEGV) records=3', ''].join('\n'));
});
afterAll(() => rmSync(arch, { recursive: true, force: true }));

describe('contract trace: the crash files of a logs folder', () => {
    it('maps the frames in the executable beside the logs whose build-id is the report\'s: file, line, function', async () => {
        const { buildId, offset } = buildExe();
        writeFileSync(join(logs, 'EST.crash'), crashFile('EST', buildId, offset));
        const { code, out } = await trace();
        expect(code).toBe(0);
        expect(out).toContain('crashed: signal 11 (SIGSEGV)'); // the story, from the log
        expect(out).toContain(`\ncrash sites (the logs' crash files):\nEST crashed: signal 11 (SIGSEGV) at address 0x0 (a bad pointer: NULL, freed, or past the end of an array), executable build-id ${buildId}\n`);
        // the offset is crash_here's first instruction + 1: a line of crash_here, from its opening brace on
        const line = Number(/\n  #0 crash_here at \S*\/modules\/EST_mod\/module\.c:(\d+)\n  #1 libc\.so\.6\+0x2724a\n/.exec(out)?.[1]);
        expect(line).toBeGreaterThanOrEqual(CRASH_LINE - 2);
        expect(line).toBeLessThanOrEqual(CRASH_LINE + 2);
    });

    it('a rebuilt executable (another build-id) is not mapped: the raw offsets and the addr2line command', async () => {
        const { buildId: first, offset } = buildExe();
        writeFileSync(join(logs, 'EST.crash'), crashFile('EST', first, offset));
        const { buildId: second } = buildExe(['-DREBUILT=1', '-O2']);
        expect(second).not.toBe(first);
        const { out } = await trace();
        expect(out).toContain(`  #0 the executable+0x${offset}\n`);
        expect(out).toContain(`  not mapped to the code: ${exe} is another build (build-id ${second}), not the executable that crashed\n`);
        // the command names where the build puts the executable of that build, not the rebuilt one beside the logs
        expect(out).toContain(`  map them with EST's executable of the build that crashed (its build-id must be ${first}: \`readelf -n\` shows it): addr2line -f -i -e ARCH/modules/EST_mod/EST 0x${offset} (ARCH: `);
        expect(out).not.toContain(`-e ${exe}`);
        expect(out).not.toContain('crash_here at');
    });

    it('a logs folder copied elsewhere (no executable beside it): says where it looked, and the command needs the executable of that build, not a path that does not exist', async () => {
        const { buildId, offset } = buildExe();
        writeFileSync(join(logs, 'EST.crash'), crashFile('EST', buildId, offset));
        rmSync(exe);
        const { out } = await trace();
        expect(out).toContain(`  not mapped to the code: no executable of EST at ${exe} (looked for beside the logs folder, where the generated Makefile builds it: a logs folder copied elsewhere has none there)\n`);
        expect(out).toContain(`  map them with EST's executable of the build that crashed (its build-id must be ${buildId}: \`readelf -n\` shows it): addr2line -f -i -e ARCH/modules/EST_mod/EST 0x${offset} (ARCH: the generated architecture folder it was built in`);
        expect(out).not.toContain(`-e ${exe}`);
    });

    it('a frame in inlined code is one frame: its inlined function, then the function it is inlined into', async () => {
        const source = join(arch, 'modules', 'EST_mod', 'module.c');
        writeFileSync(source, ['#include <stdio.h>', 'static volatile int *target;', 'static inline __attribute__((always_inline)) void store(int v)', '{', '    *target = v; /* the crash */', '}',
            '__attribute__((noinline)) int crash_here(int v)', '{', '    store(v);', '    return v;', '}', 'int main(void) { return crash_here(1); }', ''].join('\n'));
        try {
            const { buildId } = buildExe();
            // an address of crash_here in store's inlined code (addr2line -i names both there)
            const [start, size] = execFileSync('nm', ['-S', exe], { encoding: 'utf8' }).split('\n').find((l) => / T crash_here$/.test(l))!.split(' ').map((h) => parseInt(h, 16));
            const offset = Array.from({ length: size! }, (_, i) => (start! + i).toString(16))
                .find((a) => /^store\n.*\ncrash_here\n/.test(execFileSync('addr2line', ['-f', '-i', '-e', exe, `0x${a}`], { encoding: 'utf8' })))!;
            expect(offset).toBeDefined();
            writeFileSync(join(logs, 'EST.crash'), crashFile('EST', buildId, offset));
            const { out } = await trace();
            expect(out).toMatch(/\n  #0 store at \S*\/modules\/EST_mod\/module\.c:5 \(inlined into crash_here at \S*\/modules\/EST_mod\/module\.c:9\)\n  #1 libc\.so\.6\+0x2724a\n/);
            expect(out.match(/\n  #0 /g)).toHaveLength(1);
        } finally {
            writeFileSync(source, SOURCE);
        }
    });

    it('hostile crash files: a link, too large, another module\'s report, a path as an object, a bad name: not read, named in warnings', async () => {
        const { buildId, offset } = buildExe();
        rmSync(join(logs, 'EST.crash'), { force: true });
        const hostile = mkdtempSync(join(tmpdir(), 'contract-trace-crash-hostile-'));
        try {
            writeFileSync(join(hostile, 'target.crash'), crashFile('MSC', buildId, offset));
            symlinkSync(join(hostile, 'target.crash'), join(logs, 'MSC.crash'));
            writeFileSync(join(logs, 'MAA.crash'), crashFile('MAA', buildId, offset) + 'x'.repeat(40 * 1024));
            writeFileSync(join(logs, 'ORD.crash'), crashFile('EST', buildId, offset)); // EST's report in ORD's file
            writeFileSync(join(logs, 'SUP.crash'), crashFile('SUP', buildId, offset).replace('frame 0 exe', 'frame 0 /etc/passwd'));
            writeFileSync(join(logs, 'a;b.crash'), crashFile('EST', buildId, offset));
            const { code, out, err } = await trace();
            expect(code).toBe(0);
            expect(out).not.toContain('crash sites');
            for (const name of ['MSC.crash', 'MAA.crash', 'ORD.crash', 'SUP.crash', 'a;b.crash']) expect(err).toContain(`contract trace: warning: ${name}: not`);
        } finally {
            for (const n of ['MSC', 'MAA', 'ORD', 'SUP', 'a;b']) rmSync(join(logs, `${n}.crash`), { force: true });
            rmSync(hostile, { recursive: true, force: true });
        }
    });
});
