/**
 * `contract trace LOGDIR` reads the launcher's own lines file of the folder (`contract-launch.log`,
 * `<mono_ns> <line>`, written by contract-launch alone): a module whose records stop with no exit
 * record, and whose end the launcher's line says (its pid the module's start record's), is told
 * gone at its last record, in time order, the line as the evidence. Hostile files: a line naming
 * another pid, another module's line, a cut last line, a file past the read bound, a link, a folder
 * in its place: not believed, not followed, never a crash.
 */
import { mkdirSync, mkdtempSync, rmSync, symlinkSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { runCli } from '../src/cli.js';
import { capture } from './capture-io.js';

const HEADER = 'mono_ns,wall_time,module,event,peer,port,size,detail';
const W = '2026-12-07T12:00:00.000000Z';
const rec = (mono: number, module: string, kind: string, detail: string, peer = '') => `${mono},${W},${module},${kind},${peer},,0,${detail}`;

let root: string;
let n = 0;

/** A logs folder: ORD (pid 40) runs from +0 to +3 s; MAB (pid 41) starts, its last record at +0.9 s, no exit record; `launcher`: the lines file's text (none: no file). */
function folder(launcher?: string): string {
    const dir = join(root, `logs${n++}`);
    mkdirSync(dir);
    writeFileSync(join(dir, 'ORD_7-Dec-2026-12h00m00s.csv'), [HEADER,
        rec(1_000_000_000, 'ORD', 'module_started', 'pid=40 priority=90'),
        rec(2_000_000_000, 'ORD', 'user', 'halfway'),
        rec(3_500_000_000, 'ORD', 'request_received', 'KILL', 'contract-launch'),
        rec(4_000_000_000, 'ORD', 'module_exit', 'status=0 records=4'), ''].join('\n'));
    writeFileSync(join(dir, 'MAB_7-Dec-2026-12h00m00s.csv'), [HEADER,
        rec(1_000_100_000, 'MAB', 'module_started', 'pid=41 priority=40'),
        rec(1_900_000_000, 'MAB', 'user', 'still here'), ''].join('\n'));
    if (launcher !== undefined) writeFileSync(join(dir, 'contract-launch.log'), launcher);
    return dir;
}

async function trace(dir: string): Promise<{ code: number; out: string; err: string }> {
    const io = capture(root);
    const code = await runCli(['trace', dir], io);
    return { code, out: io.stdout, err: io.stderr };
}

const KILLED = "+0.900000s MAB  its records stop here (its last record), with no exit record: it ended mid-run, while the others went on; the launcher's line, at +1.000000s: contract-launch: module MAB (pid 41) died by signal 9 (Killed)";

beforeAll(() => {
    root = mkdtempSync(join(tmpdir(), 'contract-trace-launcher-'));
});
afterAll(() => rmSync(root, { recursive: true, force: true }));

describe('contract trace: the launcher\'s lines file of a logs folder', () => {
    it('tells MAB gone at its last record, in time order, the launcher\'s line as the evidence; its last record\'s end line names the line', async () => {
        const { code, out } = await trace(folder('1000000000 run directory /tmp/x\n2000000000 module MAB (pid 41) died by signal 9 (Killed)\n4100000000 all modules stopped\n'));
        expect(code).toBe(0);
        const lines = out.split('\n');
        const at = lines.indexOf(KILLED);
        expect(at).toBeGreaterThan(0);
        // before the run's stop and ORD's exit (told at +3.0 s): at the kill, not at the end
        expect(lines.findIndex((l) => l.includes('ORD  exited ('))).toBeGreaterThan(at);
        expect(out).toContain("+0.900000s MAB  its last record: no exit record follows (the launcher's line: contract-launch: module MAB (pid 41) died by signal 9 (Killed))\n");
    });

    it('without the file (an older launcher), MAB is only said at the end, as before', async () => {
        const { out } = await trace(folder());
        expect(out).not.toContain('its records stop here');
        expect(out).toContain("MAB  its last record: no exit record follows (it crashed, was killed, or its code called exit(); the launcher's output says which)");
    });

    it('a line naming another pid, a module not started, an end at the stop or a cut last line is not believed', async () => {
        const { code, out } = await trace(folder([
            '1500000000 module MAB (pid 99) died by signal 9 (Killed)', // not MAB's pid
            '1600000000 module XYZ (pid 41) died by signal 9 (Killed)', // no such module
            '1700000000 [MAB] module MAB (pid 41) died by signal 9 (Killed)', // a module's tagged line
            '1800000000 module MAB (pid 41) terminated by signal 15 (Terminated)', // the launcher's own SIGTERM: no end on its own
            'junk',
            '2000000000 module MAB (pid 41) died by signal 9 (Killed)', // cut: no line end
        ].join('\n')));
        expect(code).toBe(0);
        expect(out).not.toContain('its records stop here');
        expect(out).not.toContain("the launcher's line");
    });

    it('a file past the read bound is read for its first MiB, said; huge lines are none', async () => {
        const filler = `${'9'.repeat(10)} ${'x'.repeat(590)}\n`;
        const big = `2000000000 module MAB (pid 41) died by signal 9 (Killed)\n${'1 '.padEnd(5000, 'y')}\n${filler.repeat(Math.ceil((1.5 * 1024 * 1024) / filler.length))}`;
        const { code, out, err } = await trace(folder(big));
        expect(code).toBe(0);
        expect(out).toContain(KILLED);
        expect(err).toMatch(/contract trace: warning: contract-launch\.log: only its first 1048576 of \d+ bytes read/);
    });

    it('a link or a folder in its place is not read, said', async () => {
        const linked = folder();
        writeFileSync(join(root, 'elsewhere.log'), '2000000000 module MAB (pid 41) died by signal 9 (Killed)\n');
        symlinkSync(join(root, 'elsewhere.log'), join(linked, 'contract-launch.log'));
        const a = await trace(linked);
        expect(a.out).not.toContain('its records stop here');
        expect(a.err).toContain('contract trace: warning: contract-launch.log: a symbolic link, not read');
        const dir = folder();
        mkdirSync(join(dir, 'contract-launch.log'));
        const b = await trace(dir);
        expect(b.code).toBe(0);
        expect(b.err).toContain('contract trace: warning: contract-launch.log: not a regular file, not read');
    });
});
