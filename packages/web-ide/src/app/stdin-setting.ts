/**
 * The run settings' stdin (docs/ide.md, Build & Run): `MODULE=path` entries, commas between, each
 * path a file of the project from its folder (`MAA=commands.txt, MSC=input/msc.txt`) -> the run
 * request's `stdin` (docs/build-service-api.md). Each entry read as `contract run --stdin` reads
 * its option (@contract-studio/conventions addStdinEntry); the file itself is the build service's
 * to check (there, a regular file, its size): its refusal ends the run before it starts.
 */
import { addStdinEntry, emptyStdinEntries } from '@contract-studio/conventions';

/** The field's entries as module -> path; an Error naming the entry refused and why. */
export function parseStdinSetting(text: string): Record<string, string> {
  const into = emptyStdinEntries();
  for (const written of text.split(',')) {
    const entry = written.trim().replace(/^([^=]*?)\s*=\s*/, '$1=');
    if (!entry) continue;
    const refused = addStdinEntry(into, entry, { checkPath: true });
    if (refused) throw new Error(`stdin: bad entry "${entry}": ${refused}`);
  }
  return into;
}

/** The field's text for module -> path (as parseStdinSetting reads it). */
export function stdinSettingText(stdin: Record<string, string>): string {
  return Object.entries(stdin).map(([module, file]) => `${module}=${file}`).join(', ');
}
