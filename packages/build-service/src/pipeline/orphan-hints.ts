/**
 * A link that fails on a function the project defines only in src-gen/orphans/ (docs/codegen.md,
 * "Orphans"): `contract generate` moved a file edited outside its protected regions there (a helper
 * function written between two regions), and the regenerated file no longer defines it, so ld says
 * `undefined reference to 'clamp'` with nothing saying where the code went. The hint names the
 * copy and how to bring the function back; said where the error is, in the CLI and the IDE alike,
 * as the migration hints are (migration-hints.ts).
 *
 * The orphans are the project's files (untrusted): read as text only, line by line, each line
 * looked at up to MAX_LINE_CHARS, at most MAX_NAMES names kept.
 */
import { ORPHANS_DIR, SRC_GEN_DIR } from '@contract-studio/conventions';

/** A function's name -> the project-relative orphans copies that define it (path order). */
export type OrphanedDefinitions = ReadonlyMap<string, readonly string[]>;

const MAX_LINE_CHARS = 500;
const MAX_NAMES = 10_000;
const NOT_FUNCTIONS = new Set(['if', 'for', 'while', 'switch', 'return', 'sizeof', 'do', 'else']);
/** `static inline double clamp(double v, double lo, double hi) {` or its `{` on the next line. */
const DEFINITION = /^[ \t]*(?:[A-Za-z_]\w*[ \t*]+)+([A-Za-z_]\w*)[ \t]*\([^;{}()]*\)[ \t]*(\{.*|\/\/.*|\/\*.*)?$/;

/** The functions defined in the C files of `files` (project-relative path -> bytes) under src-gen/orphans/. */
export function orphanedDefinitions(files: ReadonlyMap<string, Buffer>): Map<string, string[]> {
  const found = new Map<string, string[]>();
  const prefix = `${SRC_GEN_DIR}/${ORPHANS_DIR}/`;
  for (const [rel, data] of [...files].sort(([a], [b]) => (a < b ? -1 : a > b ? 1 : 0))) {
    if (!rel.startsWith(prefix) || !/\.(c|h)$/.test(rel)) continue;
    const lines = data.toString('utf8').split('\n');
    for (let i = 0; i < lines.length; i++) {
      const line = lines[i]!;
      if (line.length > MAX_LINE_CHARS) continue;
      const m = DEFINITION.exec(line);
      if (!m || NOT_FUNCTIONS.has(m[1]!)) continue;
      if (!m[2]?.startsWith('{') && !(lines[i + 1] ?? '').trimStart().startsWith('{')) continue;
      const at = found.get(m[1]!);
      if (at) {
        if (!at.includes(rel)) at.push(rel);
      } else if (found.size < MAX_NAMES) found.set(m[1]!, [rel]);
    }
  }
  return found;
}

/** ld's `undefined reference to `clamp'` (quoted `' or ‘’ as the locale has it). */
const UNDEFINED = /^undefined reference to [`‘']([A-Za-z_]\w*)['’]/;

/** `message` with where the function it misses is, when it is defined in an orphans copy of the project. */
export function withOrphanHint(message: string, definitions: OrphanedDefinitions | undefined): string {
  const name = definitions && UNDEFINED.exec(message)?.[1];
  const copies = name ? definitions.get(name) : undefined;
  if (!copies || copies.length === 0) return message;
  const where = copies.length === 1 ? copies[0] : `${copies.slice(0, -1).join(', ')} and ${copies[copies.length - 1]}`;
  return `${message}; \`${name}\` is defined in ${where}, where \`contract generate\` moved code written outside the protected regions: move its definition into a protected region of the file that calls it (protect_internal_functions_impl_<module> of a module.c, its declaration in protect_internal_functions_decl_<module>), then build again (docs/codegen.md "Orphans")`;
}
