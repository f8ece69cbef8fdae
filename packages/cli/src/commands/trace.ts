/**
 * `contract trace LOGDIR [--format text|json]`: tells a recorded run from its CSV logs (the
 * run-time trace, docs/runtime-api.md "Trace records"): supervisor decisions with their causes,
 * schema activations, deadline misses with their cycle; `--format json` prints every record as
 * one JSON line, in time order.
 */
import { resolve } from 'node:path';
import { parseTrace, renderStory } from '@contract-studio/build-service/trace';
import { parseArgs } from '../args.js';
import { EXIT_FAILURE, EXIT_OK, UsageError, type CliIO, type Command } from '../command.js';
import { readLogFolder, toJsonLines } from '../trace-files.js';

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
        const files = await readLogFolder(dir);
        if (typeof files === 'string') {
            io.err(`contract trace: ${files}\n`);
            return EXIT_FAILURE;
        }
        const records = parseTrace(files);
        io.out(format === 'json' ? toJsonLines(records) : renderStory(records).join('\n') + '\n');
        return EXIT_OK;
    },
};
