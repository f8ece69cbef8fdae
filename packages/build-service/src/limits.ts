/**
 * The ONE place where the build service's sandbox limits are defined (docs/sandbox.md mirrors it).
 *
 * Isolation guarantees (not numbers, always on for bwrap and docker, impossible for `none`):
 *   - network:    no network at all (own empty network namespace / docker NetworkMode "none")
 *   - filesystem: read-only root; only the job's work dir and a private /tmp are writable
 *   - user:       a non-root uid (a distinct host uid per running job slot under bwrap)
 *   - privileges: no new privileges (PR_SET_NO_NEW_PRIVS / docker no-new-privileges, CapDrop ALL)
 *
 * Numeric limits (configurable per server, and per job downwards only):
 */
export interface Limits {
  /** Memory of the whole job (all processes, tmpfs included), MiB. */
  memoryMiB: number;
  /** Processes/threads alive at once in the job. */
  processes: number;
  /** Wall time of the build step (make all), seconds. */
  buildSeconds: number;
  /** Wall time of the run step (make run), seconds. */
  runSeconds: number;
  /** Bytes kept per output stream (stdout, stderr) of each step; then a truncation notice. */
  outputBytesPerStream: number;
}

export const DEFAULT_LIMITS: Readonly<Limits> = Object.freeze({
  memoryMiB: 512,
  processes: 256,
  buildSeconds: 120,
  runSeconds: 60,
  outputBytesPerStream: 1024 * 1024,
});

/** Time a cancel may take, end to end (documented guarantee, checked by the tests). */
export const CANCEL_DEADLINE_MS = 2000;

export type LimitName = keyof Limits;

export const LIMIT_NAMES: readonly LimitName[] = [
  'memoryMiB',
  'processes',
  'buildSeconds',
  'runSeconds',
  'outputBytesPerStream',
];

/** How a limit was enforced for a job, reported in its result. */
export type Mechanism =
  | 'cgroup-v1'
  | 'rlimit-as'
  | 'rlimit-nproc'
  | 'docker'
  | 'netns'
  | 'docker-network-none'
  | 'bwrap-ro-binds'
  | 'docker-readonly-rootfs'
  | 'service-timer'
  | 'service-counter'
  | 'none';

export interface LimitHit {
  name: 'memory' | 'processes' | 'buildSeconds' | 'runSeconds' | 'outputBytesPerStream';
  value: number;
  unit: 'bytes' | 'count' | 's';
  mechanism: Mechanism;
}

/** Merges overrides onto a base; with `lowerOnly`, an override above the base is an error. */
export function mergeLimits(base: Limits, overrides: unknown, lowerOnly: boolean): Limits {
  if (overrides === undefined || overrides === null) return { ...base };
  if (typeof overrides !== 'object' || Array.isArray(overrides)) {
    throw new LimitsError('limits must be an object');
  }
  const out: Limits = { ...base };
  for (const [key, value] of Object.entries(overrides as Record<string, unknown>)) {
    if (!(LIMIT_NAMES as readonly string[]).includes(key)) {
      throw new LimitsError(`unknown limit "${key}" (known: ${LIMIT_NAMES.join(', ')})`);
    }
    if (typeof value !== 'number' || !Number.isFinite(value) || value <= 0) {
      throw new LimitsError(`limit ${key} must be a positive number, got ${JSON.stringify(value)}`);
    }
    const name = key as LimitName;
    if (lowerOnly && value > base[name]) {
      throw new LimitsError(`limit ${key}=${value} is above the server's ${base[name]}`);
    }
    out[name] = value;
  }
  return out;
}

export class LimitsError extends Error {}

export function memoryBytes(limits: Limits): number {
  return Math.floor(limits.memoryMiB * 1024 * 1024);
}

/** "memory limit 512 MiB", "process limit 256", "run time limit 60 s", "output limit 1 MiB per stream". */
export function describeLimitHit(hit: LimitHit): string {
  switch (hit.name) {
    case 'memory':
      return `memory limit ${formatBytes(hit.value)}`;
    case 'processes':
      return `process limit ${hit.value}`;
    case 'buildSeconds':
      return `build time limit ${hit.value} s`;
    case 'runSeconds':
      return `run time limit ${hit.value} s`;
    case 'outputBytesPerStream':
      return `output limit ${formatBytes(hit.value)} per stream`;
  }
}

export function formatBytes(bytes: number): string {
  if (bytes >= 1024 * 1024 * 1024 && bytes % (1024 * 1024 * 1024) === 0) return `${bytes / 1024 ** 3} GiB`;
  if (bytes >= 1024 * 1024) return `${+(bytes / 1024 ** 2).toFixed(2)} MiB`;
  if (bytes >= 1024) return `${+(bytes / 1024).toFixed(2)} KiB`;
  return `${bytes} B`;
}
