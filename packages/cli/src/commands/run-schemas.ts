/**
 * Each periodic schema's figures over a run — completed cycles, longest response, deadline misses,
 * overruns (every skipped release), held cycles, ORD's missed ticks — from the CSV logs `contract
 * run` saved, read as a stream as `contract trace` reads them: the lines its story ends with, as
 * data (`contract run --format json`'s `schemas`, docs/ci.md). With `--trace`, `contract run`
 * tells its StoryTeller on the pass that checks the trace file instead (live-trace.ts), and
 * the logs are not read again.
 */
import { StoryTeller, type NamedSchemaFigures } from '@contract-studio/build-service/trace';
import { closeLogs, openLogFolder, streamTrace } from '../trace-stream.js';

export async function runSchemaFigures(logsDir: string, names: readonly string[]): Promise<NamedSchemaFigures[] | null> {
    if (!names.length) return null;
    const logs = await openLogFolder(logsDir, names);
    if (typeof logs === 'string') return null;
    try {
        const teller = new StoryTeller();
        for await (const batch of streamTrace(logs).batches) for (const r of batch) teller.tell(r);
        return teller.schemaFigures();
    } finally {
        await closeLogs(logs);
    }
}
