import { execFileSync } from 'node:child_process';
import { existsSync } from 'node:fs';
import { join, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';

/** The repository's runtime folder (tests run inside the repo). */
export const RUNTIME_DIR = resolve(fileURLToPath(new URL('.', import.meta.url)), '..', '..', '..', '..', 'runtime');
export const STRICT_CFLAGS = ['-std=c11', '-Wall', '-Wextra', '-Werror', '-D_POSIX_C_SOURCE=200809L'];

/** Builds the runtime library (and launcher) if needed; returns the path of libmodule.a. */
export function ensureRuntimeLibrary(): string {
    execFileSync('make', ['-s', '-C', RUNTIME_DIR, 'build/libmodule.a', 'build/contract-launch'], { stdio: 'pipe' });
    const lib = join(RUNTIME_DIR, 'build', 'libmodule.a');
    if (!existsSync(lib)) throw new Error(`runtime library not built: ${lib}`);
    return lib;
}

/** Runs a command; on failure throws with its combined output (so that test failures show gcc's messages). */
export function run(cmd: string, args: string[], cwd?: string): string {
    try {
        return execFileSync(cmd, args, { cwd, encoding: 'utf8', stdio: ['ignore', 'pipe', 'pipe'] });
    } catch (e) {
        const err = e as { stdout?: string; stderr?: string; message: string };
        throw new Error(`${cmd} ${args.join(' ')} failed:\n${err.stdout ?? ''}${err.stderr ?? ''}`);
    }
}
