/**
 * The executables of a generated architecture (what `make run` starts, ORD first), and the check of
 * the module names a run's stdin files are given to (`contract run --stdin NAME=FILE`, the run
 * request's `stdin`, `make run STDIN_<NAME>=FILE`): a NAME none of them has left every module
 * reading /dev/null, silently (field test ft69: `--stdin MAX=commands.txt` for MAA).
 */
import { closestName } from '@contract-studio/language/near-names';
import type { Architecture } from '../model/architecture.js';

/** ORD, the modules, the supervisors: the architecture Makefile's `EXECUTABLES`, in its order. */
export function architectureExecutables(arch: Pick<Architecture, 'modules' | 'supervisors'>): string[] {
    return ['ORD', ...arch.modules.map((m) => m.name), ...arch.supervisors.map((s) => s.name)];
}

/** The `EXECUTABLES = ...` line of a generated architecture Makefile as names; null when it has none. */
export function makefileExecutables(makefile: string): string[] | null {
    const m = /^EXECUTABLES = (.*)$/m.exec(makefile);
    return m ? m[1]!.split(/\s+/).filter(Boolean) : null;
}

/**
 * Why the stdin files `stdin` (module name -> file) cannot be given as asked, or null when every
 * name is one of `executables`: each other name as `given` names it (`--stdin MAX=commands.txt`),
 * with the closest executable when one is near (`. Did you mean 'MAA'?`), then the executables.
 */
export function stdinModulesProblem(stdin: Readonly<Record<string, string>>, executables: readonly string[], given: (name: string, file: string) => string): string | null {
    const unknown = Object.keys(stdin).filter((name) => !executables.includes(name));
    if (!unknown.length) return null;
    const said = unknown.map((name) => {
        const near = closestName(name, executables);
        return `${given(name, stdin[name]!)}: no module '${name}' in this architecture${near ? `. Did you mean '${near}'?` : ''}`;
    });
    return `${said.join('; ')} (its modules: ${executables.join(', ')})`;
}
