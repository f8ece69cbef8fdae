/**
 * A run's stdin files (`stdin` of a run request; `contract run --stdin NAME=FILE`): module NAME
 * reads FILE, a file of the project, on its stdin (`make run STDIN_<NAME>=…`, contract-launch
 * `--stdin NAME=FILE`); the others read /dev/null. The file is read as any project file is: a
 * plain relative path inside the project, a regular file reached without following a link, at
 * most STDIN_FILE_BYTES. It is copied into the work dir, beside the tree the sandbox runs.
 */
import { posix } from 'node:path';
import { checkRelativePath, readFileHeadNoFollow, syncFileNoFollow, UnsafePathError, type Owner } from '../util/safe-fs.js';
import type { ProjectSource } from './prepare.js';
import { PrepareError } from './prepare.js';
import { STDIN_MODULE_NAME, emptyStdinEntries } from '@contract-studio/conventions';

/** The largest stdin file a run is given (a module's commands, not data). */
export const STDIN_FILE_BYTES = 1024 * 1024;

/** The work dir's folder of the stdin files (one per module, named after it). */
export const STDIN_DIR = '.contract-stdin';

/** The `stdin` field of a request checked: module name -> project-relative path; an Error naming what is wrong. */
export function parseStdinField(raw: unknown): Record<string, string> {
  if (!raw || typeof raw !== 'object' || Array.isArray(raw)) throw new Error('stdin must be an object module name -> a file of the project, e.g. {"MAA": "commands.txt"}');
  const out = emptyStdinEntries();
  for (const [name, file] of Object.entries(raw as Record<string, unknown>)) {
    if (!STDIN_MODULE_NAME.test(name)) throw new Error(`stdin: ${JSON.stringify(name.slice(0, 80))} is no module name`);
    if (typeof file !== 'string') throw new Error(`stdin.${name} must be the path of a file of the project`);
    try {
      out[name] = checkRelativePath(file);
    } catch (e) {
      throw new Error(`stdin.${name}: ${(e as Error).message} (a path inside the project, relative to it)`);
    }
  }
  return out;
}

/**
 * Copies each stdin file from the project into `workDir`/STDIN_DIR; answers the make variables
 * (`STDIN_<NAME>=<its path in the sandbox>`, `work` the sandbox's path of the work dir). A file
 * that is not there, is no regular file, is reached through a link or is too large fails the run
 * (PrepareError) before it starts.
 */
export async function stageStdinFiles(source: ProjectSource, stdin: Record<string, string>, workDir: string, work: string, owner?: Owner): Promise<string[]> {
  const vars: string[] = [];
  for (const [name, rel] of Object.entries(stdin)) {
    let data: Buffer | null;
    try {
      data = 'files' in source
        ? (source.files[rel] !== undefined ? Buffer.from(source.files[rel]!, 'utf8') : null)
        : await readFileHeadNoFollow(source.dir, rel, STDIN_FILE_BYTES + 1);
    } catch (e) {
      if (!(e instanceof UnsafePathError)) throw e;
      data = null;
    }
    if (!data) throw new PrepareError(`stdin of ${name}: ${rel} is not a regular file of the project (not there, a folder, or reached through a symbolic link); nothing was run`);
    if (data.length > STDIN_FILE_BYTES) throw new PrepareError(`stdin of ${name}: ${rel} is larger than ${STDIN_FILE_BYTES} bytes (a module's stdin file is read up to that size); nothing was run`);
    await syncFileNoFollow(workDir, `${STDIN_DIR}/${name}`, data, owner);
    vars.push(`STDIN_${name}=${posix.join(work, STDIN_DIR, name)}`);
  }
  return vars;
}
