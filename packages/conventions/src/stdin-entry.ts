/**
 * A module's stdin from a file of the project, as `contract run --stdin MODULE=FILE` and the IDE's
 * run settings take it: the one reading of `MODULE=FILE`. The build service checks FILE against
 * the project itself (packages/build-service/src/pipeline/stdin-files.ts: inside it, a regular
 * file reached without a link, its size).
 */

/** A module name as the architecture spells it (and as make's variable STDIN_<NAME> takes it). */
export const STDIN_MODULE_NAME = /^[A-Za-z_][A-Za-z0-9_]{0,63}$/;

/**
 * Why `rel` is no plain path inside a folder, relative to it (empty, absolute, with a NUL or a
 * backslash, an empty, "." or ".." component), or undefined.
 */
export function relativePathProblem(rel: string): string | undefined {
  if (typeof rel !== 'string' || rel.length === 0 || rel.length > 4096) return 'empty or too long path';
  if (rel.includes('\0') || rel.includes('\\')) return `invalid character in path "${rel}"`;
  if (rel.startsWith('/')) return `absolute path not allowed: "${rel}"`;
  if (rel.split('/').some((p) => p === '' || p === '.' || p === '..')) return `path "${rel}" has an empty, "." or ".." component`;
  return undefined;
}

/** Module -> file, a record without a prototype (a module named `__proto__` is a name like another). */
export function emptyStdinEntries(): Record<string, string> {
  return Object.create(null) as Record<string, string>;
}

/**
 * Adds one `MODULE=FILE` (`MAA=commands.txt`) to `into` (from emptyStdinEntries); returns why it
 * is refused, or undefined. `checkPath`: FILE must be a plain path inside the project, relative to
 * it (else the build service says so).
 */
export function addStdinEntry(into: Record<string, string>, text: string, opts: { checkPath?: boolean } = {}): string | undefined {
  const eq = text.indexOf('=');
  if (eq <= 0 || eq === text.length - 1) return 'expected MODULE=FILE (e.g. MAA=commands.txt, FILE a file of the project)';
  const module = text.slice(0, eq);
  const file = text.slice(eq + 1);
  if (!STDIN_MODULE_NAME.test(module)) return `${JSON.stringify(module.slice(0, 80))} is no module name (letters, digits and _, not starting with a digit)`;
  if (Object.hasOwn(into, module)) return `module ${module} is given twice (${into[module]} and ${file}): give it once`;
  const pathProblem = opts.checkPath ? relativePathProblem(file) : undefined;
  if (pathProblem) return `${pathProblem} (a path inside the project, relative to it)`;
  into[module] = file;
  return undefined;
}
