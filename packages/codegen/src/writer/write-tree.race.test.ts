/**
 * writeTree under a racing attacker: another process swaps a folder of the output tree (or the
 * output folder itself) for a symlink to a folder outside, in a tight loop, while the tree is
 * regenerated again and again (each generation reads, merges, rewrites and deletes files there).
 * Nothing outside may be written, deleted or read; the generator reports errors instead
 * (docs/codegen.md, "What generate refuses"). Bounded: ROUNDS generations or DEADLINE_MS.
 */
import { describe, it, expect, beforeEach, afterEach } from 'vitest';
import { lstatSync, mkdirSync, mkdtempSync, readdirSync, readFileSync, realpathSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { region } from '../regions/markers.js';
import { writeTree, type GeneratedFile } from './write-tree.js';
import { SymlinkRacer } from '../test-support/symlink-racer.js';

const ROUNDS = 200;
const DEADLINE_MS = 20_000;
const FILES = 16;
const MARK = 'OUTSIDE-USER-CODE';

let base: string;
let srcGen: string;
let outside: string;
let racer: SymlinkRacer | undefined;

/** `realSpin`: how long (loop turns) the real folder stays in place between two swaps. */
async function startRacer(folder: string, target: string, realSpin: number): Promise<void> {
    racer = await SymlinkRacer.start({ folder, target, countFile: join(base, 'swaps'), linkSpin: 20_000, realSpin, batch: 20 });
}

/** Stops the racer (it restores the folder); resolves how many times it had put the symlink in place. */
async function stopRacer(): Promise<number> {
    const swaps = (await racer?.stop()) ?? 0;
    racer = undefined;
    return swaps;
}

/** Round `round`'s files: every round changes them (so each is read, merged and rewritten); odd rounds drop half (deleted). */
function filesOf(round: number): GeneratedFile[] {
    const files: GeneratedFile[] = [{ path: 'generated/top.c', content: `/* round ${round} */\n` }];
    const count = round % 2 === 0 ? FILES : FILES / 2;
    for (let i = 0; i < count; i++) {
        files.push({ path: `generated/arch/f${i}.c`, content: `/* round ${round} */\n${region(`f${i}.body`, '\n// TODO\n')}` });
    }
    return files;
}

/** Every file below `dir` (links not followed) with its content: the outside folder's state. */
function snapshot(dir: string): Record<string, string> {
    const out: Record<string, string> = {};
    for (const rel of readdirSync(dir, { recursive: true }) as string[]) {
        const abs = join(dir, rel);
        const st = lstatSync(abs);
        out[rel] = st.isFile() ? readFileSync(abs, 'latin1') : st.isDirectory() ? '(folder)' : '(other)';
    }
    return out;
}

/** Files below `dir` (links not followed) holding outside content: read through a link, then copied in. */
function leakedIn(dir: string): string[] {
    return (readdirSync(dir, { recursive: true }) as string[]).filter((rel) => {
        const st = lstatSync(join(dir, rel));
        return st.isFile() && readFileSync(join(dir, rel), 'latin1').includes(MARK);
    });
}

/** Fills `dir` with files of the generated names holding user code that must never be read, changed or deleted. */
function plantVictims(dir: string): void {
    mkdirSync(dir, { recursive: true });
    for (let i = 0; i < FILES; i++) writeFileSync(join(dir, `f${i}.c`), `/* outside */\n${region(`f${i}.body`, `\n${MARK}\n`)}`);
    writeFileSync(join(dir, 'top.c'), `/* outside ${MARK} */\n`);
}

/**
 * Regenerates until ROUNDS generations got past the output folder's check (a refused output
 * folder ends one at once, which would otherwise use up the rounds), or the deadline.
 */
function regenerate(): { ran: number; entered: number; clean: number; problems: string[] } {
    const stopAt = Date.now() + DEADLINE_MS;
    const problems: string[] = [];
    let ran = 0;
    let entered = 0;
    let clean = 0;
    for (; entered < ROUNDS && Date.now() < stopAt; ran++) {
        try {
            const r = writeTree(srcGen, filesOf(ran));
            entered++;
            for (const e of r.errors) problems.push(`${e.file}: ${e.message}`);
            if (r.errors.length === 0) clean++;
        } catch (e) {
            problems.push(`thrown: ${(e as Error).message}`);
        }
    }
    return { ran, entered, clean, problems };
}

beforeEach(() => {
    base = realpathSync(mkdtempSync(join(tmpdir(), 'codegen-race-')));
    srcGen = join(base, 'proj', 'src-gen');
    outside = join(base, 'outside');
});
afterEach(async () => {
    await stopRacer();
    rmSync(base, { recursive: true, force: true });
});

describe('writeTree against a folder swapped for a symlink during generation', () => {
    // a generation refused at the output folder ends at once: src-gen stays real longer between swaps
    it.each([
        ['a folder inside src-gen (generated/arch)', 'generated/arch', '', 20_000],
        ['src-gen itself', '', 'generated/arch', 400_000],
    ])('%s: nothing outside is written, deleted or read', async (_what, swapped, victimsUnder, realSpin) => {
        writeTree(srcGen, filesOf(0));
        plantVictims(join(outside, victimsUnder));
        const before = snapshot(outside);
        await startRacer(swapped === '' ? srcGen : join(srcGen, swapped), outside, realSpin);
        const { ran, entered, clean, problems } = regenerate();
        const swaps = await stopRacer();
        const kinds = new Set(problems.map((p) => p.replace(/\(-> [^)]*\)/, '(-> …)').replace(/; .*/, '').replace(/\d+/g, 'N')));
        console.log(`race (${swapped || 'src-gen'}): ${ran} generations (${entered} past the output folder check, ${clean} without error), ${swaps} swaps, ${problems.length} problems reported: ${JSON.stringify([...kinds])}`);
        expect(swaps).toBeGreaterThan(20);
        expect(entered).toBeGreaterThan(20);
        expect(snapshot(outside)).toEqual(before);
        expect(leakedIn(join(base, 'proj'))).toEqual([]);
        // what went wrong is a refusal the generator reports, never a write through the link
        for (const p of problems) expect(p).toMatch(/is a symbolic link \(-> .*\): refused|is not a folder|kept changing while being opened|was removed or moved while the generator was writing into it/);
        expect(clean).toBeGreaterThan(0);
    }, 60_000);
});
