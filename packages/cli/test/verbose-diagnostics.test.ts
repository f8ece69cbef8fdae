/**
 * `contract build --verbose` (and run) prints every build line, and each gcc diagnostic as the CLI
 * writes it (its path from where the command ran, its protected region): a diagnostic's own line
 * in the service's log (the same diagnostic, its path relative to src-gen) is not printed a second
 * time; its notes follow it; a log line no diagnostic event stands for (past the job's diagnostics
 * bound) is still printed.
 */
import { describe, expect, it } from 'vitest';
import type { GccDiagnostic, JobEvent } from '@contract-studio/build-service';
import { renderDiagnostic } from '@contract-studio/build-service';
import { makePrinter, type JobOptions } from '../src/job-runner.js';
import { capture } from './capture-io.js';

const FILE = 'generated/architecture/modules/MSC_mod/module.c';
const region = { id: 'protect_init_MSC', startLine: 230, endLine: 240 } as unknown as GccDiagnostic['protectedRegion'];
const diagnostic = (severity: GccDiagnostic['severity'], line: number, message: string, children: GccDiagnostic[] = []): GccDiagnostic =>
    ({ severity, message, file: FILE, line, column: 9, protectedRegion: region, children });

const warning = { ...diagnostic('warning', 237, 'unused variable ‘w’'), option: '-Wunused-variable' };
const note = diagnostic('note', 236, 'previous definition of ‘x’ with type ‘int’');
const error = diagnostic('error', 238, 'redefinition of ‘x’', [note]);
const uncounted = diagnostic('error', 239, 'a diagnostic past the job\'s bound');

let seq = 0;
const diagnosticEvent = (d: GccDiagnostic): JobEvent => ({ type: 'diagnostic', seq: seq++, t: 0, diagnostic: d }) as JobEvent;
const buildLine = (line: string): JobEvent => ({ type: 'line', seq: seq++, t: 0, step: 'build', source: 'build', stream: 'stdout', line }) as JobEvent;

/** stderr of the printer fed a compilation as the service sends it: the diagnostic events (errors first), then the log's lines in gcc's order. */
function stderrOf(verbose: boolean): string {
    const io = capture('/tmp');
    const opts = { dir: '/tmp/robot', dirArg: 'robot', sandbox: 'bwrap', format: 'text', verbose, progress: false, runtime: undefined, cacheDir: undefined } as JobOptions;
    const print = makePrinter(opts, io, [], []);
    const events = [
        diagnosticEvent(error), diagnosticEvent(warning),
        buildLine(renderDiagnostic(warning)), buildLine(renderDiagnostic(error)), buildLine(renderDiagnostic(note)),
        buildLine(renderDiagnostic(uncounted)), // no event: the job kept its diagnostics bound
        buildLine("make[1]: Leaving directory '/work/src-gen/generated/architecture/modules/MSC_mod'"),
    ];
    for (const e of events) print(e);
    return io.stderr;
}

describe('contract build --verbose: gcc diagnostics', () => {
    it('each is printed once, as the CLI writes it, its notes after it; the other build lines all stay', () => {
        const at = (line: number) => `robot/src-gen/${FILE}:${line}:9`;
        expect(stderrOf(true)).toBe([
            `${at(238)}: error: redefinition of ‘x’ [in protected region protect_init_MSC]`,
            `${at(236)}: note: previous definition of ‘x’ with type ‘int’ [in protected region protect_init_MSC]`,
            `${at(237)}: warning: unused variable ‘w’ [-Wunused-variable] [in protected region protect_init_MSC]`,
            renderDiagnostic(uncounted),
            "make[1]: Leaving directory '/work/src-gen/generated/architecture/modules/MSC_mod'",
            '',
        ].join('\n'));
    });

    it('without --verbose only the diagnostics, as before', () => {
        expect(stderrOf(false)).toBe([
            `robot/src-gen/${FILE}:238:9: error: redefinition of ‘x’ [in protected region protect_init_MSC]`,
            `robot/src-gen/${FILE}:237:9: warning: unused variable ‘w’ [-Wunused-variable] [in protected region protect_init_MSC]`,
            '',
        ].join('\n'));
    });

    it("a linker error is printed once too: ld's two lines of it (its place from the debug info, and the same after /usr/bin/ld:) are not printed again; its 'in function' line stays", () => {
        const io = capture('/tmp');
        const opts = { dir: '/tmp/robot', dirArg: 'robot', sandbox: 'bwrap', format: 'text', verbose: true, progress: false, runtime: undefined, cacheDir: undefined } as JobOptions;
        const print = makePrinter(opts, io, [], []);
        const FILE_CTL = 'generated/architecture/modules/CTL_mod/module.c';
        const linked: GccDiagnostic = { severity: 'error', message: "undefined reference to `no_such_function' (in function _exec_module_state)", file: FILE_CTL, line: 249, column: null, protectedRegion: { id: 'protect_exec_CTL', startLine: 247, endLine: 251 } as unknown as GccDiagnostic['protectedRegion'], children: [] };
        for (const e of [
            buildLine("/usr/bin/ld: /tmp/ccwsWicQ.o: in function `_exec_module_state':"),
            diagnosticEvent(linked),
            buildLine(`/work/src-gen/${FILE_CTL}:249: undefined reference to \`no_such_function'`),
            buildLine(`/usr/bin/ld: /work/src-gen/${FILE_CTL}:249: undefined reference to \`no_such_function'`),
            buildLine(`/usr/bin/ld: /work/src-gen/${FILE_CTL}:250: undefined reference to \`another_function'`),
            buildLine('collect2: error: ld returned 1 exit status'),
        ]) print(e);
        expect(io.stderr).toBe([
            "/usr/bin/ld: /tmp/ccwsWicQ.o: in function `_exec_module_state':",
            `robot/src-gen/${FILE_CTL}:249: error: undefined reference to \`no_such_function' (in function _exec_module_state) [in protected region protect_exec_CTL]`,
            `/usr/bin/ld: /work/src-gen/${FILE_CTL}:250: undefined reference to \`another_function'`,
            'collect2: error: ld returned 1 exit status',
            '',
        ].join('\n'));
    });
});
