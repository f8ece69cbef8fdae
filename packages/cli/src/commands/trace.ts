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
import { closeLogs, openLogFolder, streamTrace, WINDOW } from '../trace-stream.js';

/** JSON lines are printed in pieces of about this many characters, each after the reader took the last. */
const PIECE_CHARS = 64 * 1024;

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
            const stream = streamTrace(logs);
            const teller = new StoryTeller();
            let piece = '';
            const flush = async () => {
                io.out(piece);
                piece = '';
                await io.drained?.();
            };
            for await (const batch of stream.batches) {
                for (const r of batch) {
                    if (format === 'json') piece += JSON.stringify(r) + '\n';
                    else {
                        const line = teller.tell(r);
                        if (line !== undefined) piece += line + '\n';
                    }
                }
                // the story's lines are few: printed as they come (and a reader gone is seen at the next)
                if (piece.length >= PIECE_CHARS || (format === 'text' && piece)) {
                    await flush();
                    if (io.outputClosed?.aborted) return EXIT_OK; // the reader went away (`| head`): its choice
                }
            }
            if (format === 'text') piece += teller.summary() + '\n';
            await flush();
            const late = stream.outOfOrder();
            if (late) io.err(`contract trace: warning: ${late} record(s) were more than ${WINDOW} lines from their time's place in their log: told later than their time\n`);
            return EXIT_OK;
        } finally {
            await closeLogs(logs);
        }
    },
};
