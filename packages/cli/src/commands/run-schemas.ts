/**
 * A run's figures from the CSV logs `contract run` saved, read as a stream as `contract trace`
 * reads them: each periodic schema's — completed cycles, longest response, deadline misses,
 * overruns (every skipped release), held cycles, ORD's missed ticks — and each asynchronous
 * module's handling of its events (events handled, handling p99 and max, the longest), each released
 * module's CPU per release, ORD's and the supervisors' own CPU: the lines its story ends with, as data
 * (`contract run --format json`'s `schemas`, `eventHandling`, `moduleCpu` and `engineCpu`,
 * docs/ci.md). With `--trace`, `contract run` tells its StoryTeller on the pass that checks the
 * trace file instead (live-trace.ts), and the logs are not read again.
 */
import { StoryTeller, type EngineCpuFigure, type EventHandlingFigures, type ModuleCpuFigure, type NamedSchemaFigures } from '@contract-studio/build-service/trace';
import { closeLogs, openLogFolder, streamTrace } from '../trace-stream.js';

export interface RunFigures {
    schemas: NamedSchemaFigures[];
    eventHandling: EventHandlingFigures[];
    moduleCpu: ModuleCpuFigure[];
    engineCpu: EngineCpuFigure[];
}

/** The figures a StoryTeller holds once it was told the run. */
export function runFiguresOf(teller: StoryTeller): RunFigures {
    return { schemas: teller.schemaFigures(), eventHandling: teller.eventHandlingFigures(), moduleCpu: teller.moduleCpuFigures(), engineCpu: teller.engineCpuFigures() };
}

export async function runFigures(logsDir: string, names: readonly string[]): Promise<RunFigures | null> {
    if (!names.length) return null;
    const logs = await openLogFolder(logsDir, names);
    if (typeof logs === 'string') return null;
    try {
        const teller = new StoryTeller();
        for await (const batch of streamTrace(logs).batches) for (const r of batch) teller.tell(r);
        return runFiguresOf(teller);
    } finally {
        await closeLogs(logs);
    }
}
