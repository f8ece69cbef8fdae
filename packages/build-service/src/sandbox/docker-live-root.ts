/**
 * The host folder of a Docker work volume, for the live trace channel (docs/sandbox.md, "What the
 * host reads while a job runs"). The engine names the folder (the volume's `Mountpoint`), but
 * that folder is the containers' /work only when the engine runs on this machine, in this mount
 * namespace: not for a remote engine, rootless Docker (its own mount namespace) or Docker Desktop
 * (a VM), where the same path names nothing or something else. So the answer is PROVEN, once per
 * volume: a random nonce file is written into the volume through the engine's archive API (a
 * never-started container that mounts it), then read back at the Mountpoint, the folder opened
 * without following a link and the file through it, with the same bytes; then it is removed (by
 * the host, or through the engine when the host could not reach it), so the work tree, its digest
 * and the no-op sync digest never see it. The containers must also share this process's
 * CLOCK_MONOTONIC (no time namespace): the records' mono_ns are then comparable with
 * process.hrtime (trace-tail.ts, trace-order.ts).
 */
import { constants, promises as fsp, readlinkSync } from 'node:fs';
import { randomBytes, timingSafeEqual } from 'node:crypto';
import { isAbsolute } from 'node:path';
import type { FileHandle } from 'node:fs/promises';
import { entryPath, openDirNoFollow, openRegularFileIn } from '../util/safe-fs.js';
import type Docker from 'dockerode';
import type { ContainerCreateOptions } from 'dockerode';
import type { LiveWorkRoot } from './types.js';

/** The nonce file's name in the volume's root (a random suffix each time). */
export const PROOF_PREFIX = '.contract-volume-proof-';
const PROOF_BYTES = 32;

/** What the engine says of itself (GET /info), the fields looked at. */
export interface EngineInfo {
  SecurityOptions?: string[] | null;
  OperatingSystem?: string;
  Name?: string;
}

/**
 * Why this engine's volumes cannot be this host's folders, from its address (DOCKER_HOST or the
 * socket) and its info; null when they may be (the nonce decides).
 */
export function engineSharingProblem(address: string, info: EngineInfo): string | null {
  if ((info.SecurityOptions ?? []).some((o) => /(^|,)name=rootless(,|$)/.test(o))) {
    return 'the engine is rootless Docker: its volumes are mounted in its own mount namespace, which this process does not see';
  }
  if (/Docker Desktop/i.test(info.OperatingSystem ?? '') || info.Name === 'docker-desktop') {
    return 'the engine is Docker Desktop: its volumes live in its virtual machine, not on this host';
  }
  const m = /^(tcp|ssh|https?):\/\/(\[[^\]]*\]|[^:/]*)/i.exec(address);
  if (m && !/^(localhost|127\.\d+\.\d+\.\d+|\[::1\])$/i.test(m[2]!)) {
    return `the engine at ${address} is remote: its volumes are on another machine`;
  }
  return null;
}

/** A ustar archive of one regular file (the nonce), mode 0600, owned by uid:gid. */
export function singleFileTar(name: string, data: Buffer, uid: number, gid: number, mtime = Math.floor(Date.now() / 1000)): Buffer {
  if (Buffer.byteLength(name) > 99) throw new Error(`tar entry name too long: ${name}`);
  const header = Buffer.alloc(512);
  const field = (value: string, at: number, length: number): void => void header.write(value, at, length, 'ascii');
  const octal = (n: number, length: number): string => n.toString(8).padStart(length - 1, '0');
  field(name, 0, 100);
  field(octal(0o600, 8), 100, 8);
  field(octal(uid, 8), 108, 8);
  field(octal(gid, 8), 116, 8);
  field(octal(data.length, 12), 124, 12);
  field(octal(mtime, 12), 136, 12);
  field('        ', 148, 8); // the checksum is summed with its own field as spaces
  field('0', 156, 1);
  field('ustar\u000000', 257, 8);
  let sum = 0;
  for (const b of header) sum += b;
  field(`${octal(sum, 7)}\u0000 `, 148, 8);
  const padded = Buffer.alloc(Math.ceil(data.length / 512) * 512);
  data.copy(padded);
  return Buffer.concat([header, padded, Buffer.alloc(1024)]);
}

/** Whether process `pid` has this process's time namespace (CLOCK_MONOTONIC); null when it cannot be told. */
export function sharesTimeNamespace(pid: number): boolean | null {
  if (!Number.isInteger(pid) || pid <= 0) return null;
  try {
    return readlinkSync(`/proc/${pid}/ns/time`) === readlinkSync('/proc/self/ns/time');
  } catch {
    return null; // no time namespaces in this kernel (before 5.6), or the pid is not ours to look at
  }
}

/**
 * Reads the nonce at `<mountpoint>/<name>`: the folder opened as a directory without following a
 * link, the file through it (/proc/self/fd/N/<name>) without following a link, not blocking on a
 * FIFO, only a regular file of exactly the nonce's size. Removes the file when it could reach it.
 */
export async function readNonceAt(mountpoint: string, name: string, nonce: Buffer): Promise<{ ok: true } | { ok: false; reason: string; removed: boolean }> {
  if (!isAbsolute(mountpoint)) return { ok: false, reason: `the engine gives the volume no host path (Mountpoint ${JSON.stringify(mountpoint)})`, removed: false };
  let dir: FileHandle;
  try {
    dir = await openDirNoFollow(mountpoint);
  } catch (e) {
    const code = (e as NodeJS.ErrnoException).code ?? 'error';
    const why = code === 'ENOENT'
      ? 'does not exist on this host (the engine is not local, or mounts its volumes where this process does not see them)'
      : code === 'EACCES' || code === 'EPERM'
        ? 'cannot be read by this process (the engine\'s volumes folder is root-only: run the service as root, or without a live trace)'
        : `cannot be opened as a folder (${code})`;
    return { ok: false, reason: `the volume's mountpoint ${mountpoint} ${why}`, removed: false };
  }
  const path = entryPath(dir, name);
  try {
    let got: Buffer | null = null;
    let code = 'not a regular file of the nonce\'s size';
    try {
      const opened = await openRegularFileIn(dir, name, constants.O_RDONLY);
      if (opened) {
        try {
          if (opened.size === nonce.length) {
            const buf = Buffer.alloc(nonce.length + 1);
            const { bytesRead } = await opened.fh.read(buf, 0, buf.length, 0);
            got = buf.subarray(0, bytesRead);
          }
        } finally {
          await opened.fh.close().catch(() => {});
        }
      }
    } catch (e) {
      code = (e as NodeJS.ErrnoException).code ?? 'error';
    }
    // unlinkat in the folder opened: the name is never followed
    const removed = await fsp.unlink(path).then(() => true, () => false);
    if (got && got.length === nonce.length && timingSafeEqual(got, nonce)) return { ok: true };
    return {
      ok: false,
      reason: `the folder the engine names for the volume (${mountpoint}) does not hold the nonce written into the volume through the engine (${got ? 'other bytes' : code}): it is not the containers' volume`,
      removed,
    };
  } finally {
    await dir.close().catch(() => {});
  }
}

export interface LiveRootProof {
  docker: Docker;
  /** The engine's address as this process reaches it (DOCKER_HOST or the socket). */
  address: string;
  info: () => Promise<EngineInfo>;
  volume: string;
  /** The volume's holder container (its process shows the containers' time namespace). */
  holder: Docker.Container | undefined;
  /** A container that mounts the volume writable and, when started, runs `cmd` as the job's user (never started unless the host could not remove the nonce). */
  writer: (name: string, cmd: string[]) => ContainerCreateOptions;
  uid: number;
  gid: number;
  /** The work dir as the containers see it (/work). */
  mountedAt: string;
  /** Bounds one engine call. */
  deadline: <T>(p: Promise<T>, what: string) => Promise<T>;
}

/** Proves (or not) that the volume's Mountpoint is the containers' /work on this host; never throws. */
export async function proveLiveRoot(p: LiveRootProof): Promise<LiveWorkRoot> {
  try {
    const problem = engineSharingProblem(p.address, await p.deadline(p.info(), 'engine info'));
    if (problem) return { ok: false, reason: problem };
    const inspected = (await p.deadline(p.docker.getVolume(p.volume).inspect(), 'volume inspect')) as { Mountpoint?: string };
    const mountpoint = inspected.Mountpoint ?? '';
    if (p.holder) {
      const info = (await p.deadline(p.holder.inspect(), 'holder inspect').catch(() => null)) as { State?: { Pid?: number } } | null;
      if (sharesTimeNamespace(info?.State?.Pid ?? 0) === false) {
        return { ok: false, reason: 'the containers have their own time namespace: their mono_ns are not this host\'s CLOCK_MONOTONIC' };
      }
    }
    const name = `${PROOF_PREFIX}${randomBytes(8).toString('hex')}`;
    const nonce = randomBytes(PROOF_BYTES);
    const c = await p.deadline(p.docker.createContainer(p.writer(`contract-proof-${randomBytes(6).toString('hex')}`, ['rm', '-f', `${p.mountedAt}/${name}`])), 'proof container');
    try {
      await p.deadline(c.putArchive(singleFileTar(name, nonce, p.uid, p.gid), { path: p.mountedAt }), 'nonce write');
      const read = await readNonceAt(mountpoint, name, nonce);
      if (!read.ok && !read.removed) {
        // the host could not reach it: the engine removes it (as the job's user, who owns /work)
        await p.deadline(c.start(), 'nonce removal');
        await p.deadline(c.wait(), 'nonce removal');
      }
      return read.ok ? { ok: true, root: mountpoint } : { ok: false, reason: read.reason };
    } finally {
      await c.remove({ force: true }).catch(() => {});
    }
  } catch (e) {
    return { ok: false, reason: `the work volume's host folder could not be checked (${(e as Error).message.split('\n')[0]})` };
  }
}
