/**
 * ORD's story over a scenario's steps, as `contract trace` tells it (the StoryTeller of the trace
 * reader): the verbose report's deadline misses and each periodic schema's figures (the counts
 * `expect deadline misses` and `expect overruns` check). The report tells it from the steps it
 * has; the runner tells it as the records come when it does not keep them all (run-scenario.ts
 * RECORD_BOUNDS), so that the figures stay the whole scenario's.
 */
import { schedulerLineFields, StoryTeller, type KnownRecord, type NamedSchemaFigures } from '@contract-studio/build-service/trace';
import type { StepRecord } from './protocol.js';
import { engineLine, typedRecord } from '../trace/steps-to-trace.js';

/**
 * A terminal-safe piece of a line: control characters of simulated output (a newline in a string
 * value too: one line stays one line), line separators and bidi overrides shown as `?`; a tab is
 * kept (a scenario line indented with tabs read `start?SUP.f()`).
 */
export function safe(s: string): string {
    return s.replace(/[\u0000-\u0008\u000a-\u001f\u007f-\u009f\u2028\u2029\u202a-\u202e\u2066-\u2069]/g, '?');
}

/** What an engine's line is when ORD wrote it, read as the trace reader reads it (`release`, `activate`, `deadline_miss`, ...), else ''. */
export function ordWhat(l: { who: string; line: string }): { what: string; fields: Record<string, string | number> } {
    if (l.who !== 'ORD') return { what: '', fields: {} };
    const fields = schedulerLineFields(l.line);
    return { what: String(fields['what']), fields };
}

/** ORD's lines that count in a periodic schema's figures (StoryTeller's countSchema). */
const FIGURE_LINES = new Set(['overrun', 'overrun_ended', 'held', 'missed_tick', 'missed_ticks_ended', 'late_release']);

/** ORD's own line of a deadline miss; the verbose report says it from the typed record instead. */
export const isMissLine = (l: { who: string; line: string }) => ordWhat(l).what === 'deadline_miss';

/**
 * The verbose report's deadline misses, told as `contract trace` tells them: `deadline miss (ORD:0):
 * S cycle k (not finished: ARM)` or `(held: nothing released, CTL still runs an earlier release)`,
 * from ORD's typed records and its held/resumed lines (followed over the scenario's steps), in place
 * of ORD's bare `deadline miss: S cycle k (ORD:0)` line.
 */
export class MissTeller {
    private readonly story = new StoryTeller();

    /** The step's misses, at their times; follows the step's cycles for the next. */
    misses(step: Pick<StepRecord, 'log'> & { records?: StepRecord['records'] }): Array<{ t: number; seq: number; text: string }> {
        const out: Array<{ t: number; seq: number; text: string }> = [];
        const ord = [
            ...(step.records ?? []).filter((r) => r.module === 'ORD').map((r) => ({ t: r.timeNs, seq: r.seq ?? -1, rec: typedRecord(r) })),
            ...step.log.filter((l) => l.who === 'ORD' && !isMissLine(l)).map((l) => ({ t: l.timeNs, seq: l.seq ?? -1, rec: engineLine(l.timeNs, 'ORD', 'scheduler', l.line) })),
        ].map((x, i) => ({ ...x, i })).sort((a, b) => a.t - b.t || a.seq - b.seq || a.i - b.i);
        for (const { t, seq, rec } of ord) {
            if (rec.kind === 'ord_deadline_miss') out.push({ t, seq, text: `  ORD| ${safe(this.story.missText(rec as KnownRecord))}` });
            this.story.tell(rec);
        }
        return out;
    }

    /**
     * Tells only what each periodic schema's figures count (StoryTeller's countSchema: ORD's
     * completions and deadline misses, its overrun, held and missed-tick lines), in misses()'s
     * order: the same figures for much less work, where no miss is told (the runner's).
     */
    count(step: Pick<StepRecord, 'log'> & { records?: StepRecord['records'] }): void {
        const ord = [
            ...(step.records ?? []).filter((r) => r.module === 'ORD' && (r.kind === 'ord_complete' || r.kind === 'ord_deadline_miss'))
                .map((r) => ({ t: r.timeNs, seq: r.seq ?? -1, rec: () => typedRecord(r) })),
            ...step.log.filter((l) => FIGURE_LINES.has(ordWhat(l).what))
                .map((l) => ({ t: l.timeNs, seq: l.seq ?? -1, rec: () => engineLine(l.timeNs, 'ORD', 'scheduler', l.line) })),
        ];
        if (!ord.length) return;
        for (const { rec } of ord.map((x, i) => ({ ...x, i })).sort((a, b) => a.t - b.t || a.seq - b.seq || a.i - b.i)) this.story.tell(rec());
    }

    /** Each periodic schema's figures over the scenario, as `contract trace` ends a run's story. */
    schemaLines(): string[] {
        return this.story.schemaLines();
    }

    /** The same as data (`--format json`): the counts `expect deadline misses` and `expect overruns` check. */
    schemaFigures(): NamedSchemaFigures[] {
        return this.story.schemaFigures();
    }
}
