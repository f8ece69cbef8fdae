/**
 * Race tests of the "never through a link" rule (docs/codegen.md "What generate refuses",
 * docs/ide.md): a child process that renames a folder aside, puts a symlink to `target` in its
 * place, then restores the folder, over and over, while the test drives code that must never read,
 * write or delete through the link. Used by codegen's writeTree race test and the IDE server's
 * file API race test.
 */
import { spawn, type ChildProcess } from 'node:child_process';
import { readFileSync } from 'node:fs';

export interface SymlinkRacerOptions {
    /** The folder swapped for the link (it is set aside as `<folder>.real` meanwhile). */
    folder: string;
    /** Where the link points. */
    target: string;
    /** A file the racer writes its swap count into when it exits. */
    countFile: string;
    /** Busy-loop turns the link stays in place (so that the code under test meets it). */
    linkSpin: number;
    /** Busy-loop turns the real folder stays in place between two swaps. */
    realSpin: number;
    /** Swaps per event-loop turn (SIGTERM and the IPC message get their turn between batches). */
    batch: number;
}

/** The racer, run by `node -e`; it stops by itself after 60 s. */
const RACER = `
const fs = require('node:fs');
const [folder, aside, target, countFile, linkSpin, realSpin, batchSize] = process.argv.slice(1);
const stopAt = Date.now() + 60000;
let swaps = 0;
let strays = 0;
const attempt = (f) => { try { f(); return true; } catch { return false; } };
const restore = () => {
  attempt(() => fs.unlinkSync(folder));
  if (attempt(() => fs.renameSync(aside, folder)) || !fs.existsSync(aside)) return;
  // the code under test made a new folder in the gap (it creates missing folders): set it aside, go on
  attempt(() => fs.renameSync(folder, folder + '.stray' + strays++));
  attempt(() => fs.renameSync(aside, folder));
};
function swap() {
  if (!attempt(() => fs.renameSync(folder, aside))) return restore();
  if (attempt(() => fs.symlinkSync(target, folder))) swaps++;
  for (let i = 0; i < Number(linkSpin); i++); // let the code under test meet the link
  restore();
  for (let i = 0; i < Number(realSpin); i++); // and the real folder
}
process.on('exit', () => fs.writeFileSync(countFile, String(swaps)));
function batch() {
  for (let k = 0; k < Number(batchSize); k++) swap();
  if (Date.now() < stopAt) setImmediate(batch); else process.exit(0);
}
process.on('SIGTERM', () => { restore(); process.exit(0); });
process.send('ready', () => setImmediate(batch));
`;

export class SymlinkRacer {
    private constructor(private readonly child: ChildProcess, private readonly countFile: string) {}

    /** Starts the racer; resolves once it is swapping. */
    static async start(o: SymlinkRacerOptions): Promise<SymlinkRacer> {
        const args = [o.folder, `${o.folder}.real`, o.target, o.countFile, o.linkSpin, o.realSpin, o.batch].map(String);
        const child = spawn(process.execPath, ['-e', RACER, ...args], { stdio: ['ignore', 'ignore', 'inherit', 'ipc'] });
        await new Promise<void>((resolve) => child.once('message', () => resolve()));
        return new SymlinkRacer(child, o.countFile);
    }

    /** Stops the racer (it restores the folder); resolves how many times it had put the link in place. */
    async stop(): Promise<number> {
        if (this.child.exitCode === null && this.child.signalCode === null) {
            const exited = new Promise((r) => this.child.once('exit', r));
            this.child.kill('SIGTERM');
            await exited;
        }
        try {
            return Number(readFileSync(this.countFile, 'utf8'));
        } catch {
            return 0;
        }
    }
}
