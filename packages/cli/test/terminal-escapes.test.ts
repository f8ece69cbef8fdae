/**
 * Control characters from a sandbox or a project never reach the terminal raw: a module printing
 * OSC/CSI/C1/CR sequences through a real `contract run` (bwrap), and a project file whose name
 * carries escapes, through the real `contract` binary. `--format json` keeps the raw text.
 */
import { spawnSync } from 'node:child_process';
import { chmodSync, mkdirSync, mkdtempSync, readFileSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { escapeControls } from '../src/terminal-text.js';
import { BIN } from './e2e/harness.js';
import { removeScratch } from './scratch.js';
import { seedRuntime } from '@contract-studio/build-service/test-support/runtime-seed';

/** What a terminal would act on: C0 except tab and newline, DEL, C1. */
const RAW_CONTROL = /[\x00-\x08\x0b-\x1f\x7f-\x9f]/;

let root: string;
beforeAll(async () => {
    root = mkdtempSync(join(tmpdir(), 'contract-esc-'));
    chmodSync(root, 0o711);
    await seedRuntime(join(root, 'cache')); // the test run's built runtime
}, 240_000);
afterAll(() => removeScratch(root));

function contract(args: string[]): { code: number | null; stdout: string; stderr: string } {
    const r = spawnSync(process.execPath, [BIN, ...args], {
        cwd: root,
        encoding: 'utf8',
        timeout: 300_000,
        env: { ...process.env, CONTRACT_CACHE_DIR: join(root, 'cache') },
    });
    return { code: r.status, stdout: r.stdout ?? '', stderr: r.stderr ?? '' };
}

describe('escapeControls', () => {
    it('renders C0 (but tab and newline), DEL, C1, bidi overrides and directional marks as visible \\uXXXX, and leaves other text alone', () => {
        expect(escapeControls('\x1b]0;pwned\x07\x1b[2J')).toBe('\\u001b]0;pwned\\u0007\\u001b[2J');
        expect(escapeControls('a\tb\n')).toBe('a\tb\n');
        expect(escapeControls('100%\rOVER')).toBe('100%\\u000dOVER');
        expect(escapeControls('\x9b31m\x85\x7f\0')).toBe('\\u009b31m\\u0085\\u007f\\u0000');
        expect(escapeControls('héllo → ü 日本 עברית')).toBe('héllo → ü 日本 עברית');
        // bidi overrides and isolates, line and paragraph separators: they reorder or break the terminal's line
        expect(escapeControls('ok \u202eevil\u202c \u2066x\u2069 a\u2028b')).toBe('ok \\u202eevil\\u202c \\u2066x\\u2069 a\\u2028b');
        // the directional marks reorder it too (the IDE's rule, conventions' visibleText)
        expect(escapeControls('live \u200f(1) \u200e\u061c\n')).toBe('live \\u200f(1) \\u200e\\u061c\n');
        // the JSON view stays valid JSON with the same strings
        const json = JSON.stringify({ line: '\x9b\x7f\x1b' });
        expect(JSON.parse(escapeControls(json))).toEqual({ line: '\x9b\x7f\x1b' });
    });
});

describe('project file names', () => {
    it('contract check prints a file name with escapes visibly; json keeps it raw', () => {
        const dir = join(root, 'names');
        mkdirSync(dir);
        const name = 'evil\x1b]0;pwned\x07\x1b[2J\x9b1m.contract';
        writeFileSync(join(dir, name), 'datatype T {int a = 1.5};\n');
        const text = contract(['check', 'names']);
        expect(text.code).toBe(1);
        expect(text.stdout + text.stderr).not.toMatch(RAW_CONTROL);
        expect(text.stdout).toContain('evil\\u001b]0;pwned\\u0007\\u001b[2J\\u009b1m.contract:1:');
        const json = contract(['check', 'names', '--format', 'json']);
        expect(json.stdout).not.toMatch(RAW_CONTROL);
        const parsed = JSON.parse(json.stdout) as { diagnostics: { file: string }[] };
        expect(parsed.diagnostics.map((d) => d.file)).toContain(name);
    }, 120_000);
});

describe('sandbox output through a real contract run (bwrap)', () => {
    // OSC title, CSI clear, an 8-bit C1 CSI (UTF-8 U+009B), a raw 0x9b byte, a bare CR overwrite, DEL, BEL
    const printed = '\\033]0;pwned\\007\\033[2J\\302\\23331mred\\233x\\rOVER\\177\\a';
    const expectedRaw = '\x1b]0;pwned\x07\x1b[2J\x9b31mred\ufffdx\rOVER\x7f\x07';
    // the characters of no width: U+200B, U+200C, U+200D, the word joiner U+2060, the BOM U+FEFF (UTF-8, as C octal escapes)
    const zeroWidth = 'go\\342\\200\\213|\\342\\200\\214|\\342\\200\\215|\\342\\201\\240|\\357\\273\\277';

    beforeAll(() => {
        expect(contract(['new', 'esc']).code).toBe(0);
        expect(contract(['generate', 'esc']).code).toBe(0);
        const file = join(root, 'esc', 'src-gen/generated/architecture/modules/CTL_mod/module.c');
        const source = readFileSync(file, 'utf8');
        const patched = source.replace(
            /(PROTECTED REGION ID\(protect_init_CTL\) ENABLED START\*\/)/,
            `$1\n    printf("ESC<${printed}>\\n"); printf("ZW<${zeroWidth}>\\n"); fflush(stdout);`,
        );
        expect(patched).not.toBe(source);
        writeFileSync(file, patched);
    }, 120_000);

    it('text output shows the escapes visibly and writes no control character', () => {
        const r = contract(['run', 'esc', '--sandbox', 'bwrap', '--duration', '1s', '--logs', 'esc-logs']);
        expect(r.stderr).toContain('ok: run finished');
        expect(r.stdout + r.stderr).not.toMatch(RAW_CONTROL);
        expect(r.stdout).toContain('[CTL] ESC<\\u001b]0;pwned\\u0007\\u001b[2J\\u009b31mred\ufffdx\\u000dOVER\\u007f\\u0007>\n');
    }, 300_000);

    it('characters of no width are shown as their escapes: two values that differ never look the same', () => {
        const r = contract(['run', 'esc', '--sandbox', 'bwrap', '--duration', '1s', '--logs', 'esc-logs']);
        expect(r.stderr).toContain('ok: run finished');
        expect(r.stdout + r.stderr).not.toMatch(/[\u200b-\u200d\u2060\ufeff]/);
        expect(r.stdout).toContain('[CTL] ZW<go\\u200b|\\u200c|\\u200d|\\u2060|\\ufeff>\n');
    }, 300_000);

    it('--format json keeps the raw line (escaped as JSON, no raw control character on stdout)', () => {
        const r = contract(['run', 'esc', '--sandbox', 'bwrap', '--duration', '1s', '--logs', 'esc-logs', '--format', 'json']);
        expect(r.stdout).not.toMatch(RAW_CONTROL);
        const json = JSON.parse(r.stdout) as { ok: boolean; output: { source: string; line: string }[] };
        expect(json.ok).toBe(true);
        expect(json.output).toContainEqual(expect.objectContaining({ source: 'CTL', line: `ESC<${expectedRaw}>` }));
    }, 300_000);
});

describe('a #warning holding a control character, through a real contract build (bwrap)', () => {
    // the field tester's region: gcc wrote the BEL raw inside its JSON line, which then read as no
    // JSON; the build said "no compiler or linker error was reported" over a real error
    const region = ['#warning "plain warning one"', '#warning "bell \x07 here"', 'int undeclared_use(void){ return nosuchvar; }'].join('\n');

    beforeAll(() => {
        expect(contract(['new', 'bel']).code).toBe(0);
        expect(contract(['generate', 'bel']).code).toBe(0);
        const file = join(root, 'bel', 'src-gen/generated/architecture/modules/CTL_mod/module.c');
        const source = readFileSync(file, 'utf8');
        const patched = source.replace(/(PROTECTED REGION ID\(protect_additional_import_CTL\) ENABLED START\*\/)/, `$1\n${region}`);
        expect(patched).not.toBe(source);
        writeFileSync(file, patched);
    }, 120_000);

    it('reports the error at its line and both warnings, the BEL written \\u0007', () => {
        const r = contract(['build', 'bel', '--sandbox', 'bwrap']);
        expect(r.code).toBe(1);
        expect(r.stdout + r.stderr).not.toMatch(RAW_CONTROL);
        expect(r.stderr).not.toContain('no compiler or linker error was reported');
        expect(r.stderr).toMatch(/module\.c:\d+:\d+: error: .nosuchvar. undeclared .*\[in protected region protect_additional_import_CTL\]/);
        expect(r.stderr).toMatch(/module\.c:\d+:\d+: warning: #warning "plain warning one" \[-Wcpp\]/);
        expect(r.stderr).toMatch(/module\.c:\d+:\d+: warning: #warning "bell \\u0007 here" \[-Wcpp\]/);
        expect(r.stderr).toContain('FAILED: build failed: 1 error(s) (make exit 2)');
    }, 300_000);
});
