/**
 * Fuzz-style robustness: the tutorial files with random tokens deleted or duplicated (seeded, so
 * failures reproduce) must never crash the parser, linker or validators, nor take long.
 */
import { readdirSync, readFileSync } from 'node:fs';
import { fileURLToPath } from 'node:url';
import { EmptyFileSystem } from 'langium';
import { describe, expect, it } from 'vitest';
import { createCactalServices } from '../src/cactal-module.js';
import { build } from './helpers.js';

const TUTORIAL = fileURLToPath(new URL('../../../examples/tutorial/', import.meta.url));
const ORIGINAL: Record<string, string> = Object.fromEntries(
    readdirSync(TUTORIAL).filter((f) => f.endsWith('.contract')).sort().map((f) => [f, readFileSync(TUTORIAL + f, 'utf8')]));

/** mulberry32: small deterministic PRNG. */
function prng(seed: number): () => number {
    let a = seed >>> 0;
    return () => {
        a = (a + 0x6d2b79f5) >>> 0;
        let t = a;
        t = Math.imul(t ^ (t >>> 15), t | 1);
        t ^= t + Math.imul(t ^ (t >>> 7), t | 61);
        return ((t ^ (t >>> 14)) >>> 0) / 4294967296;
    };
}

const TOKEN = /"(?:\\.|[^"\\])*"|[A-Za-z_][A-Za-z0-9_]*|-?[0-9]+(?:\.[0-9]*)?(?:[eE][-+]?[0-9]+)?(?:ns|us|ms|s)?|==\*|==>|=\*|=>|->|==|!=|<=|>=|\s+|\/\/[^\n]*|./g;

/** Deletes or duplicates `count` random non-blank tokens. */
export function mutate(text: string, random: () => number, count: number): string {
    const tokens = text.match(TOKEN) ?? [];
    for (let i = 0; i < count; i++) {
        const candidates = tokens.map((t, k) => (t.trim() ? k : -1)).filter((k) => k >= 0);
        if (!candidates.length) break;
        const k = candidates[Math.floor(random() * candidates.length)]!;
        if (random() < 0.5) tokens.splice(k, 1);
        else tokens.splice(k, 0, tokens[k]!, ' ');
    }
    return tokens.join('');
}

const MUTATIONS = 60;
// CPU time (the test process's own, so a loaded machine that delays it does not count)
const MAX_MS_PER_WORKSPACE = 2000;

/** CPU milliseconds this process has used so far (user + system). */
function cpuMs(): number {
    const u = process.cpuUsage();
    return (u.user + u.system) / 1000;
}

describe('fuzz: mutated tutorial files', () => {
    it(`survives ${MUTATIONS} seeded mutations (delete/duplicate tokens) with bounded CPU time`, async () => {
        const services = createCactalServices(EmptyFileSystem).Cactal;
        const random = prng(20101026);
        const names = Object.keys(ORIGINAL);
        let withErrors = 0;
        let slowest = 0;
        for (let i = 0; i < MUTATIONS; i++) {
            const file = names[Math.floor(random() * names.length)]!;
            const mutated = mutate(ORIGINAL[file]!, random, 1 + Math.floor(random() * 4));
            const t0 = cpuMs();
            const built = await build({ ...ORIGINAL, [file]: mutated }, services);
            const ms = cpuMs() - t0;
            slowest = Math.max(slowest, ms);
            const internal = built.diagnostics.filter((d) => d.message.startsWith('An error occurred'));
            expect(internal, `mutation ${i} of ${file}:\n${mutated}`).toEqual([]);
            expect(ms, `mutation ${i} of ${file}`).toBeLessThan(MAX_MS_PER_WORKSPACE);
            if (built.diagnostics.some((d) => d.severity === 'error')) withErrors++;
        }
        // the mutations are real: most of them break something
        expect(withErrors).toBeGreaterThan(MUTATIONS / 2);
        expect(slowest).toBeLessThan(MAX_MS_PER_WORKSPACE);
    }, 120_000);

    it('survives truncated files (every 60th prefix of the supervisor)', async () => {
        const services = createCactalServices(EmptyFileSystem).Cactal;
        const text = ORIGINAL['supervisor.contract']!;
        for (let n = 0; n < text.length; n += 60) {
            const built = await build({ ...ORIGINAL, 'supervisor.contract': text.slice(0, n) }, services);
            expect(built.diagnostics.filter((d) => d.message.startsWith('An error occurred'))).toEqual([]);
        }
    }, 120_000);
});

describe('pathological input', () => {
    it('refuses brackets nested thousands deep with a clear error instead of overflowing the stack', async () => {
        const services = createCactalServices(EmptyFileSystem).Cactal;
        const deep = `datatype T {int a = ${'{'.repeat(5000)}1${'}'.repeat(5000)}};`;
        const built = await build({ 'deep.contract': deep, 'ok.contract': 'datatype U {int b = 1};' }, services);
        expect(built.diagnostics.map((d) => `${d.file} ${d.code}`)).toEqual(['deep.contract lexing-error']);
        expect(built.diagnostics[0]!.message).toContain('nested 65 levels deep');
        const again = await build({ 'ok.contract': 'datatype U {int b = {1}};' }, services);
        expect(again.diagnostics.map((d) => d.code)).toEqual(['value-type-mismatch']);
    });

    it('still parses realistic nesting (a few levels) normally', async () => {
        const built = await build({ 'a.contract': 'datatype A {int x};\ndatatype B {A a};\ndatatype C {B b = {{1}}};' });
        expect(built.lines).toEqual([]);
    });
});
