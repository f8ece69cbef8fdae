/**
 * What the build sandboxes share with the generated Makefiles and the clients (docs/sandbox.md):
 * the sandbox names, where the runtime is mounted inside a sandbox, the identity jobs run as, and
 * the CPU-list syntax of `--cpus` / `make run CPUS=…`.
 */

/** The sandboxes a job can run in. */
export const SANDBOX_NAMES = ['bwrap', 'docker', 'none'] as const;
export type SandboxName = (typeof SANDBOX_NAMES)[number];

/** What a client may ask for: a sandbox, or `auto` (bwrap, else Docker). */
export const SANDBOX_CHOICES = ['auto', ...SANDBOX_NAMES] as const;
export type SandboxChoice = (typeof SANDBOX_CHOICES)[number];

/** Where the C runtime is mounted inside the bwrap and Docker sandboxes (and the generator's default). */
export const SANDBOX_RUNTIME_DIR = '/opt/contract/runtime';

/** The uid and gid the sandboxed build and run have inside the sandbox (bwrap's namespace, Docker's user). */
export const SANDBOX_UID = 1000;
export const SANDBOX_GID = 1000;

/**
 * The process name (the kernel's `comm`, 15 characters at most) of the runtime's launcher, which
 * `make run` starts in the sandbox: a cancelled run asks it, by this name, to stop the architecture
 * as at the end of a run (SIGTERM) before anything is killed.
 */
export const LAUNCHER_PROCESS_NAME = 'contract-launch';

/**
 * Why the build service stops a run: the value it queues with the launcher's SIGTERM (sigqueue,
 * through `kill -q N`). contract-launch says it (`stopping: the build service's memory limit was
 * reached`) and sends it with every module's KILL, whose request_received record reads `KILL (...)`:
 * the run's CSV logs say why it stopped (runtime/launcher/contract-launch.c stop_reason: the same
 * numbers, its texts).
 */
export const STOP_REASON_CODES = { memory: 1, processes: 2, workDiskMiB: 3, runSeconds: 4, cancel: 5 } as const;
export type StopReason = keyof typeof STOP_REASON_CODES;

/** The Docker image holding gcc, make and the runtime (built by scripts/docker-up.sh). */
export const DOCKER_IMAGE = 'contract-gcc';

/** contract-launch's ready timeout (`--ready-timeout`'s default): seconds every module's init may take before the start request. */
export const DEFAULT_READY_TIMEOUT_SECONDS = 10;
/** The least ready timeout a run may ask for (`contract run --ready-timeout`, the API's `readyTimeout`, the IDE's run settings). */
export const MIN_READY_TIMEOUT_SECONDS = 0.1;

const CPU_LIST = /^\d+(-\d+)?(,\d+(-\d+)?)*$/;

/**
 * True for a CPU list such as `1`, `0-1` or `0,2`, its ranges upwards (contract-launch checks that
 * the CPUs exist on the machine that runs).
 */
export function isCpuList(text: string): boolean {
    if (!CPU_LIST.test(text)) return false;
    // a range runs upwards (`1-0` is what contract-launch refuses after the build: refused before it)
    return text.split(',').every((part) => {
        const [a, b] = part.split('-');
        return b === undefined || Number(b) >= Number(a);
    });
}

/**
 * The first CPU of a well-formed CPU list (isCpuList) that a machine with `online` CPUs (numbered
 * 0 to online-1) does not have, or undefined when it has them all. The CLI and the build service
 * refuse such a list before building; contract-launch checks the rest (a CPU online but outside
 * the run's affinity).
 */
export function cpuMissingFrom(text: string, online: number): number | undefined {
    for (const part of text.split(',')) {
        const [lo, hi = lo] = part.split('-').map(Number) as [number, number?];
        if (hi >= online) return Math.max(lo, online);
    }
    return undefined;
}
