/** The commands of `contract`. Add a command: create `src/commands/<name>.ts` and list it here. */
import type { Command } from '../command.js';
import { checkCommand } from './check.js';
import { generateCommand } from './generate.js';
import { serveCommand } from './serve.js';
import { newCommand } from './new.js';
import { buildCommand } from './build.js';
import { runCommand } from './run.js';

export const COMMANDS: Command[] = [newCommand, checkCommand, generateCommand, buildCommand, runCommand, serveCommand];
