/**
 * Parses the runtime's per-module CSV logs (docs/runtime-api.md: columns
 * `mono_ns,wall_time,module,event,peer,port,size,detail`) into activations: each `run_started`
 * paired with the module's next `run_finished` (fields split by the trace reader's splitCsvLine). Pure: used by
 * the timeline view and tests.
 */
import { splitCsvLine } from '@contract-studio/build-service/trace';

export interface Activation {
  module: string;
  /** Monotonic start/end in ns; end undefined if the log stops while running. */
  start: number;
  end?: number;
  detail: string;
}

export function activationsFromCsv(text: string): Activation[] {
  const lines = text.split(/\r?\n/).filter((l) => l.length > 0);
  if (!lines.length) return [];
  const header = splitCsvLine(lines[0]!);
  const col = (name: string) => header.indexOf(name);
  const [iMono, iModule, iEvent, iDetail] = [col('mono_ns'), col('module'), col('event'), col('detail')];
  if (iMono < 0 || iModule < 0 || iEvent < 0) throw new Error('not a ContrACT CSV log (missing mono_ns/module/event columns)');
  const open = new Map<string, Activation>();
  const out: Activation[] = [];
  // only run_started / run_finished lines matter (a 1 kHz run's logs are most of a million lines):
  // with the event column between two others, such a line holds `,run_started,` or `,run_finished,`
  const inside = iEvent > 0 && iEvent < header.length - 1;
  for (let n = 1; n < lines.length; n++) {
    const l = lines[n]!;
    if (inside && !l.includes(',run_started,') && !l.includes(',run_finished,')) continue;
    const f = splitCsvLine(l);
    const t = Number(f[iMono]);
    const module = f[iModule] ?? '?';
    if (!Number.isFinite(t)) continue;
    if (f[iEvent] === 'run_started') {
      const a: Activation = { module, start: t, detail: f[iDetail] ?? '' };
      const prev = open.get(module);
      if (prev && prev.end === undefined) prev.end = t;
      open.set(module, a);
      out.push(a);
    } else if (f[iEvent] === 'run_finished') {
      const a = open.get(module);
      if (a && a.end === undefined) a.end = t;
    }
  }
  return out.sort((a, b) => a.start - b.start);
}

/**
 * The period guess: the median gap between consecutive activations of the most active module
 * (ns), and that module (a run with loops of several periods has its grid drawn at its period).
 */
export function inferPeriodOf(acts: Activation[]): { ns: number; module: string } | undefined {
  const byModule = new Map<string, number[]>();
  for (const a of acts) (byModule.get(a.module) ?? byModule.set(a.module, []).get(a.module)!).push(a.start);
  let best: number[] = [];
  let module = '';
  for (const [m, starts] of byModule) if (starts.length > best.length) [best, module] = [starts, m];
  if (best.length < 3) return undefined;
  const gaps = best.slice(1).map((s, i) => s - best[i]!).sort((a, b) => a - b);
  return { ns: gaps[Math.floor(gaps.length / 2)]!, module };
}
