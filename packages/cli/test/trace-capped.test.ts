/**
 * `contract trace` of a log the runtime capped (field test ft57b, defect 2): both `log-capped`
 * records are told (where the log reached its bound; at the module's end, how many records were
 * not written), and a module whose log ends capped is not told as one that crashed.
 */
import { mkdtempSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { runCli } from '../src/cli.js';
import { capture } from './capture-io.js';

const HEADER = 'mono_ns,wall_time,module,event,peer,port,size,detail';
const BOUND = '197388288';
let folder: string;

beforeAll(() => {
    folder = mkdtempSync(join(tmpdir(), 'contract-trace-capped-'));
    const log = (m: string, lines: string[]) => writeFileSync(join(folder, `${m}_6-Dec-2026-03h27m09s.csv`), [HEADER, ...lines].join('\n') + '\n');
    // CTL floods its log: capped at its bound, then at its exit the last log-capped record (no module_exit: it was not written)
    log('CTL', [
        '1000000000,w,CTL,module_started,,,0,pid=21 priority=84',
        '1500000000,w,CTL,burst,,,0,seq=1',
        `4843717000,w,CTL,log-capped,,,${BOUND},log reached its ${BOUND}-byte bound (CONTRACT_LOG_MAX_BYTES): later records are not written`,
        `6005000000,w,CTL,log-capped,,,${BOUND},667375 records not written after the log reached its ${BOUND}-byte bound`,
    ]);
    log('MOT', [
        '1000100000,w,MOT,module_started,,,0,pid=22 priority=80',
        '6005100000,w,MOT,module_exit,,,0,status=0 records=2',
    ]);
    // ENC's log stopped at a full disk (the runtime's other log-capped records): the same end
    log('ENC', [
        '1000300000,w,ENC,module_started,,,0,pid=24 priority=80',
        '2000000000,w,ENC,log-capped,,,1000,log could not be written past 1000 bytes (No space left on device): later records are not written',
        '6004000000,w,ENC,log-capped,,,1000,12 records not written after the log could not be written past 1000 bytes (No space left on device)',
    ]);
    // HMI was capped and then killed (SIGKILL): no last log-capped record, no exit record
    log('HMI', [
        '1000200000,w,HMI,module_started,,,0,pid=23 priority=10',
        `3000000000,w,HMI,log-capped,,,4096,log reached its 4096-byte bound (CONTRACT_LOG_MAX_BYTES): later records are not written`,
    ]);
});
afterAll(() => rmSync(folder, { recursive: true, force: true }));

describe('contract trace: a log the runtime capped', () => {
    it('tells both log-capped records, and says the exit record is missing because of the cap, not a crash', async () => {
        const io = capture(folder);
        expect(await runCli(['trace', '.'], io)).toBe(0);
        const lines = io.stdout.split('\n');
        expect(lines).toContain(`+3.843717s CTL  log capped: log reached its ${BOUND}-byte bound (CONTRACT_LOG_MAX_BYTES): later records are not written`);
        expect(lines).toContain(`+5.005000s CTL  log capped: 667375 records not written after the log reached its ${BOUND}-byte bound`);
        expect(lines).toContain('+5.005000s CTL  its log ends capped: the module ended after its log reached its bound, so its exit record is not in it (one of the 667375 records not written), not lost to a crash; the launcher\'s output says how it ended');
        expect(io.stdout).not.toMatch(/(CTL|ENC) {2}its last record: no exit record follows/);
        expect(lines).toContain('+1.000000s ENC  log capped: log could not be written past 1000 bytes (No space left on device): later records are not written');
        expect(lines).toContain('+5.004000s ENC  its log ends capped: the module ended after its log could not be written further (a full disk), so its exit record is not in it (one of the 12 records not written), not lost to a crash; the launcher\'s output says how it ended');
        // a capped log is not "not whole", and its exit is not told as a whole run killed
        expect(io.stdout).not.toContain('not whole');
        expect(io.stdout).not.toContain('no module wrote its exit record');
        // a module capped then killed (no last log-capped record): still told as one without its end
        expect(lines).toContain('+2.000000s HMI  log capped: log reached its 4096-byte bound (CONTRACT_LOG_MAX_BYTES): later records are not written');
        expect(lines).toContain('+2.000000s HMI  its last record: no exit record follows (it crashed, was killed, or its code called exit(); the launcher\'s output says which) (its log had reached its bound; the last log-capped record, which the runtime writes at any end but a SIGKILL, is missing too)');
    });

    it('a trace file (--format json of the same logs) tells the same log-capped lines', async () => {
        const json = capture(folder);
        expect(await runCli(['trace', '.', '--format', 'json'], json)).toBe(0);
        const kinds = json.stdout.trim().split('\n').map((l) => (JSON.parse(l) as { kind: string }).kind);
        expect(kinds.filter((k) => k === 'log-capped')).toHaveLength(5);
        const file = join(folder, 'run.jsonl');
        writeFileSync(file, json.stdout);
        try {
            const io = capture(folder);
            expect(await runCli(['trace', 'run.jsonl'], io)).toBe(0);
            expect(io.stdout).toContain(`+5.005000s CTL  log capped: 667375 records not written after the log reached its ${BOUND}-byte bound`);
            expect(io.stdout).toContain('+5.005000s CTL  its log ends capped:');
        } finally {
            rmSync(file);
        }
    });
});
