/**
 * The run settings' stdin (docs/ide.md, Build & Run): one row per module, its module and a file of
 * the project from its folder, each in an input of its own (a path may hold a comma, a space, any
 * character a file name has) -> the run request's `stdin` (docs/build-service-api.md). Each row
 * read as `contract run --stdin` reads its option (@contract-studio/conventions addStdinEntry); the
 * file itself is the build service's to check (there, a regular file, its size): its refusal ends
 * the run before it starts.
 */
import { STDIN_MODULE_NAME, addStdinEntry, emptyStdinEntries } from '@contract-studio/conventions';

/** A refused row: its message, the row (from 0) and the column to mend (0: the module, 1: the file). */
export class StdinRowProblem extends Error {
  constructor(message: string, readonly row: number, readonly column: 0 | 1) {
    super(message);
  }
}

/**
 * The dialog's rows ([module, file], as typed) as module -> path: a row left empty is no entry; the
 * module is read without the spaces around it, the path as typed. A StdinRowProblem for a row refused.
 */
export function stdinFromRows(rows: string[][]): Record<string, string> {
  const into = emptyStdinEntries();
  rows.forEach(([typedModule = '', file = ''], n) => {
    const module = typedModule.trim();
    if (!module && !file.trim()) return;
    const at = `stdin row ${n + 1}`;
    if (!module) throw new StdinRowProblem(`${at}: no module reads ${JSON.stringify(file)}: give its name (e.g. MAA)`, n, 0);
    if (!file) throw new StdinRowProblem(`${at}: module ${module} reads no file: give a file of the project, from its folder (or remove the row)`, n, 1);
    const ofModule = !STDIN_MODULE_NAME.test(module) || Object.hasOwn(into, module);
    const refused = addStdinEntry(into, `${module}=${file}`, { checkPath: true });
    if (refused) throw new StdinRowProblem(`${at}: ${refused}`, n, ofModule ? 0 : 1);
  });
  return into;
}

/** module -> path as the dialog's rows. */
export function stdinRows(stdin: Record<string, string>): string[][] {
  return Object.entries(stdin).map(([module, file]) => [module, file]);
}

/**
 * The stdin entries kept in the browser as module -> path: this version's object, or an earlier
 * version's text (`MAA=commands.txt, MSC=in.txt`: commas between, which no path of it held); an
 * Error naming the entry refused and why (a value edited by hand).
 */
export function keptStdin(kept: unknown): Record<string, string> {
  const into = emptyStdinEntries();
  const entries = typeof kept === 'string' ? kept.split(',').map((written) => written.trim().replace(/^([^=]*?)\s*=\s*/, '$1='))
    : kept && typeof kept === 'object' ? Object.entries(kept).map(([module, file]) => `${module}=${typeof file === 'string' ? file : ''}`)
      : [];
  for (const entry of entries) {
    if (!entry) continue;
    const refused = addStdinEntry(into, entry, { checkPath: true });
    if (refused) throw new Error(`stdin: bad entry "${entry}": ${refused}`);
  }
  return into;
}
