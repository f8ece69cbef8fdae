/**
 * `contract trace --format json`: each key of a record's `fields` has one JSON type whatever its
 * value's size (docs/runtime-api.md, the table of `fields`). A machine up for months has
 * CLOCK_MONOTONIC times past 15 digits (10^15 ns: 11.6 days) and past 2^53 (104 days): the same
 * run's logs, their times moved there, give the same types, the times' exact digits as JSON
 * numbers (Python and jq read them exactly), and a trace file of them tells the same story.
 * A text key is a string even when its value is digits (`value=12`), a number key whose word is
 * not an integer (a forged line) is left out.
 */
import { mkdirSync, mkdtempSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { afterAll, describe, expect, it } from 'vitest';
import { allFieldKeys, fieldJsonType } from '@contract-studio/build-service/trace';
import { runCli } from '../src/cli.js';
import { capture } from './capture-io.js';

const HEADER = 'mono_ns,wall_time,module,event,peer,port,size,detail';
const W = '2026-12-07T20:53:00.017961Z';

/** ORD's and SUP's logs of a short run, every time `base` + a small offset (as a machine up that long writes them). */
function logs(base: bigint): Record<string, string> {
    const t = (ns: number) => String(base + BigInt(ns));
    return {
        'ORD_1.csv': [HEADER,
            `${t(1000)},${W},ORD,module_started,,,0,pid=41 priority=99`,
            `${t(2000)},${W},ORD,ord_release,MSC,,0,schema=loop cycle=0 tick_ns=${t(1900)} release_ns=${t(1950)} release=1`,
            `${t(3000)},${W},ORD,ord_complete,,,0,schema=loop cycle=0 tick_ns=${t(1900)} response_ns=700`,
            `${t(3100)},${W},ORD,ord_release,MSC,,0,schema=loop cycle=1 tick_ns=12x release_ns=${t(3050)} release=2`,
            `${t(9000)},${W},ORD,module_exit,,,0,status=0 records=5`, ''].join('\n'),
        'SUP_1.csv': [HEADER,
            `${t(1001)},${W},SUP,module_started,,,0,pid=42 priority=50`,
            `${t(2500)},${W},SUP,event_received,MAA,2,4,from_port=2 latency_ns=900 taken_ns=${t(2400)} rules=0 value=12`,
            `${t(9001)},${W},SUP,module_exit,,,0,status=0 records=3`, ''].join('\n'),
    };
}

/** Each JSON line's `fields` as its raw text's key:value pairs (the digits as written) and the parsed object. */
function jsonLines(text: string): { kind: string; monoNs: unknown; fields: Record<string, unknown>; raw: string }[] {
    return text.trim().split('\n').map((raw) => ({ ...(JSON.parse(raw) as { kind: string; monoNs: unknown; fields: Record<string, unknown> }), raw }));
}

describe('contract trace --format json: one JSON type per fields key', () => {
    const root = mkdtempSync(join(tmpdir(), 'contract-json-types-'));
    afterAll(() => rmSync(root, { recursive: true, force: true }));

    async function traceJson(name: string, base: bigint): Promise<string> {
        const dir = join(root, name);
        mkdirSync(dir);
        for (const [file, text] of Object.entries(logs(base))) writeFileSync(join(dir, file), text);
        const io = capture(root);
        expect(await runCli(['trace', name, '--format', 'json'], io)).toBe(0);
        return io.stdout;
    }

    it('a machine up 6 hours, 12 days or 105 days: the same types, times as JSON numbers with their exact digits', async () => {
        const bases = { fresh: 23_357_357_727_918n - 1000n, days12: 1_000_000_000_000_000n, days105: 9_100_000_000_000_000n };
        const typesOf = (text: string) => jsonLines(text).map((r) => [r.kind, typeof r.monoNs, Object.fromEntries(Object.entries(r.fields).map(([k, v]) => [k, typeof v]))]);
        const fresh = await traceJson('fresh', bases.fresh);
        for (const [name, base] of Object.entries(bases)) {
            const text = name === 'fresh' ? fresh : await traceJson(name, base);
            expect(typesOf(text), name).toEqual(typesOf(fresh));
            const release = jsonLines(text).find((r) => r.kind === 'ord_release')!;
            // the exact digits in the text, as Python's json or jq read them
            expect(release.raw).toContain(`"tick_ns":${base + 1900n},"release_ns":${base + 1950n},`);
            const received = jsonLines(text).find((r) => r.kind === 'event_received')!;
            expect(received.raw).toContain(`"taken_ns":${base + 2400n},`);
            expect(received.fields['value']).toBe('12');
            // a number key whose word is no integer (`tick_ns=12x`) is left out, never a string
            const forged = jsonLines(text).filter((r) => r.kind === 'ord_release')[1]!;
            expect(forged.fields).not.toHaveProperty('tick_ns');
            expect(forged.raw).toContain(`"release_ns":${base + 3050n},`);
            // monoNs: always a string of digits
            expect(jsonLines(text).every((r) => typeof r.monoNs === 'string' && /^\d+$/.test(r.monoNs))).toBe(true);
        }
        expect(typesOf(fresh).find(([k]) => k === 'ord_complete')).toEqual(['ord_complete', 'string', { schema: 'string', cycle: 'number', tick_ns: 'number', response_ns: 'number' }]);
    });

    it('a trace file of those JSON lines tells the story of its logs (the exact digits read back)', async () => {
        const json = await traceJson('for-file', 9_100_000_000_000_000n);
        writeFileSync(join(root, 'old.jsonl'), json);
        const fromLogs = capture(root), fromFile = capture(root);
        expect(await runCli(['trace', 'for-file'], fromLogs)).toBe(0);
        expect(await runCli(['trace', 'old.jsonl'], fromFile)).toBe(0);
        expect(fromFile.stdout).toBe(fromLogs.stdout);
        const again = capture(root);
        expect(await runCli(['trace', 'old.jsonl', '--format', 'json'], again)).toBe(0);
        expect(again.stdout).toBe(json);
    });

    it('every key a record kind has is typed (a new key cannot be written with two types)', () => {
        const untyped = allFieldKeys().filter((k) => fieldJsonType(k) === undefined);
        expect(untyped).toEqual([]);
        expect(fieldJsonType('tick_ns')).toBe('number');
        expect(fieldJsonType('value')).toBe('string');
    });
});
