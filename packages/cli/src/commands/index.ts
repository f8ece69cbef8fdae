/** The commands of `contract`. Add a command: create `src/commands/<name>.ts` and list it here. */
import type { Command } from '../command.js';
import { checkCommand } from './check.js';
import { generateCommand } from './generate.js';
import { serveCommand } from './serve.js';

export const COMMANDS: Command[] = [checkCommand, generateCommand, serveCommand];
