/** The commands of `contract`. Add a command: create `src/commands/<name>.ts` and list it here. */
import type { Command } from '../command.js';
import { checkCommand } from './check.js';

export const COMMANDS: Command[] = [checkCommand];
