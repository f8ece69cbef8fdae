/** The commands of `contract`. Add a command: create `src/commands/<name>.ts` and list it here. */
import type { Command } from '../command.js';
import { checkCommand } from './check.js';
import { generateCommand } from './generate.js';
import { serveCommand } from './serve.js';
import { newCommand } from './new.js';
import { buildCommand } from './build.js';
import { runCommand } from './run.js';
import { renameCommand } from './rename.js';
import { traceCommand } from './trace.js';
import { simulateCommand } from './simulate.js';
import { cacheCommand } from './cache.js';
import { runtimeSourceCommand } from './runtime-source.js';

export const COMMANDS: Command[] = [newCommand, checkCommand, generateCommand, renameCommand, buildCommand, runCommand, traceCommand, simulateCommand, serveCommand, cacheCommand, runtimeSourceCommand];
