/**
 * `contract run`'s line for a module that ended on its own while the run went on, told when the
 * launcher's line says it (`contract-launch: module MAB (pid 41) died by signal 9 (Killed)`), as the
 * IDE's Monitor shows it gone (web-ide monitor/gone-signs.ts): `contract run: MAB ended mid-run:
 * died by signal 9 (Killed) (a signal the launcher did not send); the other modules go on`.
 *
 * Only the launcher's own lines count (the job's `line` events of source `launcher`: a module's
 * output comes tagged with its name, whatever it holds), and only when the line's pid is the
 * module's own, as its `module_started` record on the live trace gives it; a line that comes before
 * that record (the trace is read every few ms) waits for it, a few at most.
 */
import { endedOnItsOwn, launcherEndLine, parseStreamedLine, type KnownRecord, type LauncherEnd, type TraceLine } from '@contract-studio/build-service/trace';

/** End lines kept while their module's start record has not come (a run has 256 modules at most). */
const MAX_WAITING = 256;
/** Modules followed at most (a forged log could name many). */
const MAX_MODULES = 1024;

export class LiveModuleEnds {
    private readonly pids = new Map<string, number>();
    private readonly told = new Set<string>();
    private waiting: LauncherEnd[] = [];

    /** The records of a live trace event: the lines of waiting ends their module's start now confirms. */
    records(lines: readonly TraceLine[]): string[] {
        const out: string[] = [];
        for (const l of lines) {
            if (!l.text.includes(',module_started,')) continue;
            const r = parseStreamedLine(l.file, l.line, l.text);
            if (r.kind !== 'module_started') continue;
            const k = r as KnownRecord;
            const pid = /(?:^| )pid=(\d{1,10})(?: |$)/.exec(k.detail);
            if (!pid || (!this.pids.has(k.module) && this.pids.size >= MAX_MODULES)) continue;
            this.pids.set(k.module, Number(pid[1]));
            const ready = this.waiting.filter((w) => w.module === k.module);
            if (!ready.length) continue;
            this.waiting = this.waiting.filter((w) => w.module !== k.module);
            for (const w of ready) {
                const told = this.tell(w);
                if (told) out.push(told);
            }
        }
        return out;
    }

    /** One of the launcher's own lines (without its `contract-launch: ` prefix): the line to print, or undefined. */
    launcherLine(text: string): string | undefined {
        const end = launcherEndLine(text);
        if (!end || !endedOnItsOwn(end.how)) return undefined;
        if (!this.pids.has(end.module)) {
            if (this.waiting.length < MAX_WAITING) this.waiting.push(end);
            return undefined;
        }
        return this.tell(end);
    }

    private tell(end: LauncherEnd): string | undefined {
        if (this.pids.get(end.module) !== end.pid || this.told.has(end.module)) return undefined;
        this.told.add(end.module);
        const stopping = end.how.endsWith(' while the run stopped');
        const how = stopping ? end.how.slice(0, -' while the run stopped'.length) : end.how;
        const whose = how.startsWith('died by signal') ? ' (a signal the launcher did not send)' : '';
        return stopping
            ? `contract run: ${end.module} ended on its own while the run stopped: ${how}${whose}`
            : `contract run: ${end.module} ended mid-run: ${how}${whose}; the other modules go on`;
    }
}
