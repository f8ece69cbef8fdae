/**
 * writeTree under a racing attacker: another process swaps a folder of the output tree (or the
 * output folder itself) for a symlink to a folder outside, in a tight loop, while the tree is
 * regenerated again and again (each generation reads, merges, rewrites and deletes files there).
 * Nothing outside may be written, deleted or read; the generator reports errors instead
 * (docs/codegen.md, "What generate refuses"). Bounded: ROUNDS generations or DEADLINE_MS.
 */
import { describe, it, expect, beforeEach, afterEach } from 'vitest';
import { spawn, type ChildProcess } from 'node:child_process';
import { lstatSync, mkdirSync, mkdtempSync, readdirSync, readFileSync, realpathSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { region } from '../regions/markers.js';
import { writeTree, type GeneratedFile } from './write-tree.js';

const ROUNDS = 200;
const DEADLINE_MS = 20_000;
const FILES = 16;
const MARK = 'OUTSIDE-USER-CODE';

let base: string;
let srcGen: string;
let outside: string;
let racer: ChildProcess | undefined;

/** Renames `folder` aside, puts a symlink to `target` in its place, then restores it; until killed (or 60 s). */
const RACER = `
const fs = require('node:fs');
const [folder, aside, target, countFile, realSpin] = process.argv.slice(1);
const stopAt = Date.now() + 60000;
let swaps = 0;
let strays = 0;
const attempt = (f) => { try { f(); return true; } catch { return false; } };
const restore = () => {
  attempt(() => fs.unlinkSync(folder));
  if (attempt(() => fs.renameSync(aside, folder)) || !fs.existsSync(aside)) return;
  // the generator made a new folder in the gap (it creates missing folders): set it aside, go on
  attempt(() => fs.renameSync(folder, folder + '.stray' + strays++));
  attempt(() => fs.renameSync(aside, folder));
};
function swap() {
  if (!attempt(() => fs.renameSync(folder, aside))) return restore();
  if (attempt(() => fs.symlinkSync(target, folder))) swaps++;
  for (let i = 0; i < 20000; i++); // let the generator meet the link
  restore();
  for (let i = 0; i < Number(realSpin); i++); // and the real folder
}
process.on('exit', () => fs.writeFileSync(countFile, String(swaps)));
// batches, so that SIGTERM and the IPC message get their turn on the event loop
function batch() {
  for (let k = 0; k < 20; k++) swap();
  if (Date.now() < stopAt) setImmediate(batch); else process.exit(0);
}
process.on('SIGTERM', () => { restore(); process.exit(0); });
process.send('ready', () => setImmediate(batch));
`;

/** `realSpin`: how long (loop turns) the real folder stays in place between two swaps. */
function startRacer(folder: string, target: string, realSpin: number): Promise<void> {
    racer = spawn(process.execPath, ['-e', RACER, folder, `${folder}.real`, target, join(base, 'swaps'), String(realSpin)], { stdio: ['ignore', 'ignore', 'inherit', 'ipc'] });
    return new Promise((resolve) => racer!.once('message', () => resolve()));
}

/** Stops the racer (it restores the folder); resolves how many times it had put the symlink in place. */
async function stopRacer(): Promise<number> {
    if (racer && racer.exitCode === null) {
        const exited = new Promise((r) => racer!.once('exit', r));
        racer.kill('SIGTERM');
        await exited;
    }
    racer = undefined;
    try {
        return Number(readFileSync(join(base, 'swaps'), 'utf8'));
    } catch {
        return 0;
    }
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
