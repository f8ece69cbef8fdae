/**
 * The Monitor's run list labels of a Build & Run job: the run it followed live, at each stage (while
 * it runs, once it ended: how, said once, once its CSV logs are shown: what the stream did not
 * receive), and the run of its CSV logs.
 * Pure, so that the order in which the job's end and its logs reach the page is tested without one
 * (live-run-label.test.ts).
 */
import type { RecordCounts } from '@contract-studio/build-service/trace';
import { count, unreadableNote } from './record-counts.js';

/** How a job ended, as every label ends with it: ` · ended: cancelled` (nothing when not known yet). */
function endedText(outcome: string | undefined): string {
  return outcome ? ` · ended: ${outcome}` : '';
}

/** While it runs: `Build & Run job j-… · live`. */
export function liveRunLabel(jobId: string): string {
  return `Build & Run job ${jobId} · live`;
}

/**
 * Its label once the job ended with `outcome`: `· live` becomes `· ended: cancelled`, a note of
 * what the stream missed kept after it; a label its CSV logs gave first (`· as streamed`: the
 * stream's end came late, or only the build panel's end said it) gets the outcome at its end.
 */
export function endedRunLabel(label: string, stillLive: boolean, outcome: string): string {
  return stillLive ? label.replace(' · live', endedText(outcome)) : `${label}${endedText(outcome)}`;
}

/**
 * Its label once the job's end became known after its trace stream was lost (`lost`: that outcome,
 * `lostTrace`: the note it left): the outcome said instead, and the note's promise of CSV logs
 * dropped with it (the job gone with the IDE server left none); any other note kept.
 */
export function endKnownAfterLossLabel(label: string, lost: string, lostTrace: string, outcome: string): string {
  return label
    .replace(endedText(lost), endedText(outcome))
    .replace(` (trace not whole: ${lostTrace})`, '')
    .replace(`; ${lostTrace}`, '');
}

/**
 * Its label once its CSV logs are shown: `· as streamed`, with the records the stream did not
 * receive (a stream attached late, or taken up again past the service's bound: its first records
 * and its newest, a gap between) and how it ended when that is known yet.
 */
export function streamedRunLabel(jobId: string, outcome: string | undefined, records?: { streamed: number; logged: number }): string {
  const cut = records && records.streamed > 0 && records.streamed < records.logged
    ? ` (${count(records.streamed)} of the ${count(records.logged)} records of its logs: ${count(records.logged - records.streamed)} not received)`
    : '';
  return `Build & Run job ${jobId} · as streamed${cut}${endedText(outcome)}`;
}

/**
 * The run of its CSV logs: `Build & Run job j-… · CSV logs`, its records and unreadable lines when
 * some lines are unreadable (`counts`: unreadableNote), what the replay lacks (a log left out or
 * capped, one not downloaded) and how the job ended when that run carries it (the live run was
 * forgotten for want of records).
 */
export function csvLogsRunLabel(jobId: string, problems: readonly string[], outcome?: string, counts?: RecordCounts, crashSites: readonly string[] = []): string {
  return `Build & Run job ${jobId} · CSV logs${counts ? unreadableNote(counts) : ''}${problems.length ? ` (not whole: ${problems.join('; ')})` : ''}${endedText(outcome)}${crashSitesNote(crashSites, 'mapped by the build service')}`;
}

/**
 * ` — crash sites (the logs' crash files): MSC crashed: signal 11 (SIGSEGV) ...; #0 ...` at the end
 * of a replay's label, each line of the sites (contract trace's, crash-files.ts) trimmed, '' for
 * none; `whose`: whose sites they are (a folder's crash files, unmapped; a job's, mapped by the
 * build service after its run).
 */
export function crashSitesNote(lines: readonly string[], whose: string): string {
  return lines.length ? ` — crash sites (${whose}): ${lines.map((l) => l.trim()).join('; ')}` : '';
}
