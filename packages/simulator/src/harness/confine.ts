/**
 * Where the simulator runs the project's own C (docs/simulation.md "What runs where"): the user
 * functions of the datatype files (`testit`, `doit`) are compiled into the harness and run at each
 * step, so the compiler and the harness are untrusted like a build job. With bubblewrap (the
 * default) each compile, the link and each scenario run get: new user/pid/net/ipc/uts namespaces,
 * uid 1000 inside, the host toolchain read-only, only the folders the command needs bound (the
 * build folder read-write for the compiler, the simulator's own folder read-only for a run), a
 * private /tmp, no environment but PATH, --die-with-parent, --new-session, and an address-space
 * limit. `none` (`--sandbox none`, `CONTRACT_SIMULATOR_SANDBOX=none`) runs them as the user who
 * asked: for your own code on your own machine only.
 */
import { execFile } from 'node:child_process';
import { promisify } from 'node:util';
import { SANDBOX_GID, SANDBOX_UID } from '@contract-studio/conventions';
import { toolchainBinds as toolchainArgs } from '@contract-studio/build-service/toolchain';

const exec = promisify(execFile);

export const SIMULATOR_SANDBOXES = ['auto', 'bwrap', 'none'] as const;
export type SimulatorSandboxChoice = (typeof SIMULATOR_SANDBOXES)[number];

/** The limits of one confined command (the wall time is the caller's timer). */
export const SIMULATOR_LIMITS = {
    /** Address space of the compiler, the linker and the harness. */
    memoryBytes: 2 * 1024 ** 3,
    /** Size of the private /tmp (the compiler's temporary files). */
    tmpBytes: 256 * 1024 ** 2,
    /** CPU seconds: a backstop behind the caller's wall-time limit. */
    cpuSeconds: 120,
} as const;

export interface Confinement {
    readonly kind: 'bwrap' | 'none';
    /**
     * The argv that runs `argv` confined: `readWrite` and `readOnly` folders are bound at their own
     * paths (so paths in arguments stay valid), nothing else of the host but the toolchain.
     */
    wrap(argv: string[], binds: { cwd: string; readWrite?: string[]; readOnly?: string[] }): string[];
}

class BwrapConfinement implements Confinement {
    readonly kind = 'bwrap' as const;
    constructor(private readonly bwrap: string) {}

    wrap(argv: string[], binds: { cwd: string; readWrite?: string[]; readOnly?: string[] }): string[] {
        return [
            'prlimit', `--as=${SIMULATOR_LIMITS.memoryBytes}`, `--cpu=${SIMULATOR_LIMITS.cpuSeconds}`, '--',
            this.bwrap,
            '--unshare-user', '--unshare-pid', '--unshare-net', '--unshare-ipc', '--unshare-uts', '--unshare-cgroup-try',
            '--disable-userns',
            '--uid', String(SANDBOX_UID), '--gid', String(SANDBOX_GID),
            '--hostname', 'contract-simulator',
            ...toolchainArgs(),
            '--proc', '/proc',
            '--dev', '/dev',
            '--size', String(SIMULATOR_LIMITS.tmpBytes), '--tmpfs', '/tmp',
            ...(binds.readOnly ?? []).flatMap((d) => ['--ro-bind', d, d]),
            ...(binds.readWrite ?? []).flatMap((d) => ['--bind', d, d]),
            '--remount-ro', '/',
            '--chdir', binds.cwd,
            '--die-with-parent',
            '--new-session',
            '--clearenv',
            '--setenv', 'PATH', '/usr/local/bin:/usr/bin:/bin',
            '--setenv', 'TMPDIR', '/tmp',
            '--setenv', 'LANG', 'C.UTF-8',
            '--',
            ...argv,
        ];
    }
}

const UNCONFINED: Confinement = { kind: 'none', wrap: (argv) => argv };

/** Probes by PATH searched: one per process and PATH. */
const probed = new Map<string, Promise<string | undefined>>();

/** Undefined when bubblewrap can make the namespaces here, else why not. */
function probeBwrap(bwrap: string, path: string): Promise<string | undefined> {
    let p = probed.get(path);
    if (!p) {
        p = exec(bwrap, ['--unshare-user', '--unshare-pid', '--unshare-net', '--disable-userns', ...toolchainArgs(), '--', '/bin/true'], { timeout: 10_000, env: { PATH: path } })
            .then(() => undefined, (e: Error) => (e.message.split('\n').find((l) => l.trim()) ?? 'cannot run').trim());
        probed.set(path, p);
    }
    return p;
}

/**
 * The confinement for a choice: `auto` and `bwrap` need a working bubblewrap (an error says how to
 * get one, or to choose `none`); `none` runs unconfined. The default choice is
 * `$CONTRACT_SIMULATOR_SANDBOX`, else `auto`.
 */
export async function chooseConfinement(choice?: SimulatorSandboxChoice, env: NodeJS.ProcessEnv = process.env): Promise<Confinement | { error: string }> {
    const wanted = choice ?? (env.CONTRACT_SIMULATOR_SANDBOX as SimulatorSandboxChoice | undefined) ?? 'auto';
    if (!SIMULATOR_SANDBOXES.includes(wanted)) return { error: `CONTRACT_SIMULATOR_SANDBOX=${String(wanted)}: expected auto, bwrap or none` };
    if (wanted === 'none') return UNCONFINED;
    const why = await probeBwrap('bwrap', env.PATH ?? '/usr/local/bin:/usr/bin:/bin');
    if (why === undefined) return new BwrapConfinement('bwrap');
    return {
        error: `the simulator runs your project's C functions and confines them with bubblewrap, which does not work here (${why}): `
            + 'install it ("apt-get install bubblewrap" on Debian/Ubuntu, "dnf install bubblewrap" on Fedora) and allow unprivileged user namespaces, '
            + 'or run your own code unconfined with --sandbox none (CONTRACT_SIMULATOR_SANDBOX=none for the IDE)',
    };
}
