/**
 * `contract trace LOGDIR [--format text|json]`: tells a recorded run from its CSV logs (the
 * run-time trace, docs/runtime-api.md "Trace records"): supervisor decisions with their causes,
 * schema activations, deadline misses with their cycle; `--format json` prints every record as
 * one JSON line, in time order. The logs are streamed (trace-stream.ts): a run of any length is
 * told in bounded memory, and printing stops when the reader goes away.
 */
import { resolve } from 'node:path';
import { StoryTeller } from '@contract-studio/build-service/trace';
import { parseArgs } from '../args.js';
import { EXIT_FAILURE, EXIT_OK, UsageError, type CliIO, type Command } from '../command.js';
import { closeLogs, jsonLinesOf, openLogFolder, streamTrace, windowFor, type OpenLog } from '../trace-stream.js';

export const traceCommand: Command = {
    name: 'trace',
    summary: 'tell a recorded run from its CSV logs (rule changes with causes, schemas, deadline misses)',
    usage: [
        'usage: contract trace LOGDIR [--format text|json]',
        '  LOGDIR: the folder of a run\'s CSV logs (`contract run --logs`, default PROJECT/logs)',
        '  --format: text (default: the story, then a count of the records) or json (one JSON object per record and line, time order)',
        'exit status: 0 success, 1 no readable log in LOGDIR, 2 bad usage',
    ].join('\n'),
    async run(args: string[], io: CliIO): Promise<number> {
        const parsed = parseArgs(args, ['format']);
        if (parsed.positionals.length !== 1) throw new UsageError('expected one LOGDIR');
        const format = parsed.options.get('format') ?? 'text';
        if (format !== 'text' && format !== 'json') throw new UsageError(`unknown format '${String(format)}' (expected text or json)`);
        const dir = resolve(io.cwd, parsed.positionals[0]!);
        const logs = await openLogFolder(dir);
        if (typeof logs === 'string') {
            io.err(`contract trace: ${logs}\n`);
            return EXIT_FAILURE;
        }
        try {
            const { late, problems } = format === 'json' ? await printJson(logs, io) : await printStory(logs, io);
            for (const p of problems) io.err(`contract trace: warning: ${p}\n`);
            if (late) io.err(`contract trace: warning: ${late} record(s) were more than ${windowFor(logs.length)} lines from their time's place in their log: told later than their time\n`);
            return EXIT_OK;
        } finally {
            await closeLogs(logs);
        }
    },
};

/** Every record as a JSON line, each piece printed once the reader took the last; stops when the reader went away (`| head`: its choice). */
async function printJson(logs: readonly OpenLog[], io: CliIO): Promise<{ late: number; problems: string[] }> {
    const { outOfOrder, problems } = await jsonLinesOf(logs, async (piece) => {
        io.out(piece);
        await io.drained?.();
        return !io.outputClosed?.aborted;
    });
    return { late: outOfOrder, problems };
}

/** The story: its lines printed as they come (few: a reader gone is seen at the next), then the counts. */
async function printStory(logs: readonly OpenLog[], io: CliIO): Promise<{ late: number; problems: string[] }> {
    const stream = streamTrace(logs);
    const teller = new StoryTeller();
    for await (const batch of stream.batches) {
        let piece = '';
        for (const r of batch) {
            const line = teller.tell(r);
            if (line !== undefined) piece += line + '\n';
        }
        if (!piece) continue;
        io.out(piece);
        await io.drained?.();
        if (io.outputClosed?.aborted) return { late: stream.outOfOrder(), problems: stream.problems() };
    }
    io.out(teller.summary() + '\n');
    return { late: stream.outOfOrder(), problems: stream.problems() };
}
