/**
 * How many recorded runs (a job's CSV logs, a workspace folder, a trace file) the page keeps the
 * models of: each holds its logs' text and their records (a 60 s run of a 1 kHz schema: some
 * 840,000 records, tens of MB), and an engineer presses Build & Run again and again. Past these
 * bounds the runs used least recently are let go (monitor-controller.ts reads a folder or a trace
 * file again when picked, and fetches a job's logs again from the build service).
 */
export const RECORDED_RUN_BOUNDS = { runs: 6, records: 3_000_000 } as const;

/** What the bound looks at of a run of the Monitor's list. */
export interface KeptRun {
  id: string;
  live: boolean;
  /** When it was made or last shown (larger: more recent). */
  used?: number;
  recordCount: number;
}

/** Whether a run is a recorded one (a live run's worker and a simulation are bounded apart). */
export function isRecorded(r: Pick<KeptRun, 'id' | 'live'>): boolean {
  return !r.live && /^(job|dir|file):/.test(r.id);
}

/**
 * The recorded runs to let go: the most recently used are kept while they number at most
 * `bounds.runs` and hold at most `bounds.records` records together; `keep` (the run just made,
 * the one shown) are never let go.
 */
export function recordedRunsToLetGo(runs: Iterable<KeptRun>, keep: ReadonlySet<string>, bounds: { runs: number; records: number } = RECORDED_RUN_BOUNDS): string[] {
  const recorded = [...runs].filter(isRecorded).sort((a, b) => (b.used ?? 0) - (a.used ?? 0));
  const out: string[] = [];
  let records = 0;
  recorded.forEach((r, i) => {
    records += r.recordCount;
    if (keep.has(r.id) || (i < bounds.runs && records <= bounds.records)) return;
    out.push(r.id);
  });
  return out;
}
