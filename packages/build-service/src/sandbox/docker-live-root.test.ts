import { execFileSync } from 'node:child_process';
import { mkdirSync, mkdtempSync, readdirSync, rmSync, symlinkSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { afterEach, beforeEach, describe, expect, test } from 'vitest';
import { readTar } from '../util/tar-reader.js';
import { engineSharingProblem, readNonceAt, sharesTimeNamespace, singleFileTar } from './docker-live-root.js';

describe('engineSharingProblem', () => {
  test('a local socket or loopback engine may share its folders; rootless, Docker Desktop, remote may not', () => {
    expect(engineSharingProblem('unix:///var/run/docker.sock', { SecurityOptions: ['name=seccomp,profile=default'], OperatingSystem: 'Debian GNU/Linux 12 (bookworm)' })).toBeNull();
    expect(engineSharingProblem('tcp://127.0.0.1:2375', {})).toBeNull();
    expect(engineSharingProblem('unix:///run/user/1000/docker.sock', { SecurityOptions: ['name=seccomp,profile=default', 'name=rootless'] })).toMatch(/^the engine is rootless Docker: /);
    expect(engineSharingProblem('unix:///var/run/docker.sock', { OperatingSystem: 'Docker Desktop', Name: 'docker-desktop' })).toMatch(/^the engine is Docker Desktop: /);
    expect(engineSharingProblem('tcp://build-host:2376', {})).toBe('the engine at tcp://build-host:2376 is remote: its volumes are on another machine');
    expect(engineSharingProblem('ssh://me@build-host', {})).toMatch(/is remote/);
  });
});

describe('singleFileTar', () => {
  test('one regular file with its bytes, as the archive reader sees it', () => {
    const data = Buffer.from('0123456789abcdef0123456789abcdef');
    const tar = singleFileTar('.contract-volume-proof-00', data, 1000, 1000);
    expect(tar.length % 512).toBe(0);
    expect(readTar(tar)).toEqual([{ name: '.contract-volume-proof-00', kind: 'file', size: data.length, data }]);
    // the header's checksum is right (GNU tar lists it)
    const dir = mkdtempSync(join(tmpdir(), 'single-tar-'));
    try {
      writeFileSync(join(dir, 'a.tar'), tar);
      expect(execFileSync('tar', ['-tvf', join(dir, 'a.tar')], { encoding: 'utf8' })).toMatch(/^-rw------- 1000\/1000 +32 .* \.contract-volume-proof-00\n$/);
    } finally {
      rmSync(dir, { recursive: true, force: true });
    }
  });
});

describe('readNonceAt', () => {
  let root: string;
  const nonce = Buffer.from('n'.repeat(32));
  beforeEach(() => {
    root = mkdtempSync(join(tmpdir(), 'nonce-'));
  });
  afterEach(() => rmSync(root, { recursive: true, force: true }));

  test('the same bytes: proven, and removed', async () => {
    writeFileSync(join(root, 'p'), nonce);
    expect(await readNonceAt(root, 'p', nonce)).toEqual({ ok: true });
    expect(readdirSync(root)).toEqual([]);
  });

  test('other bytes, a link to the nonce, a FIFO, nothing: refused, never followed, never blocked', async () => {
    writeFileSync(join(root, 'p'), Buffer.from('m'.repeat(32)));
    expect(await readNonceAt(root, 'p', nonce)).toMatchObject({ ok: false, reason: expect.stringMatching(/\(other bytes\): it is not the containers' volume$/) });
    const elsewhere = join(root, 'elsewhere');
    mkdirSync(elsewhere);
    writeFileSync(join(elsewhere, 'real'), nonce);
    symlinkSync(join(elsewhere, 'real'), join(root, 'q'));
    expect(await readNonceAt(root, 'q', nonce)).toMatchObject({ ok: false, reason: expect.stringMatching(/\(ELOOP\)/) });
    execFileSync('mkfifo', [join(root, 'f')]);
    expect(await readNonceAt(root, 'f', nonce)).toMatchObject({ ok: false, reason: expect.stringMatching(/not a regular file/) });
    expect(await readNonceAt(root, 'none', nonce)).toEqual({ ok: false, reason: expect.stringMatching(/\(ENOENT\)/), removed: false });
  });

  test('a mountpoint that is a link, or missing, or relative: refused with the reason', async () => {
    symlinkSync(root, `${root}-link`);
    try {
      expect(await readNonceAt(`${root}-link`, 'p', nonce)).toMatchObject({ ok: false, reason: expect.stringMatching(/cannot be opened as a folder \((ELOOP|ENOTDIR)\)/) });
    } finally {
      rmSync(`${root}-link`);
    }
    expect(await readNonceAt(join(root, 'missing'), 'p', nonce)).toMatchObject({ ok: false, reason: expect.stringMatching(/does not exist on this host/) });
    expect(await readNonceAt('var/lib/docker', 'p', nonce)).toMatchObject({ ok: false, reason: expect.stringMatching(/no host path/) });
  });
});

test('this process shares its own time namespace', () => {
  expect(sharesTimeNamespace(process.pid)).not.toBe(false);
  expect(sharesTimeNamespace(0)).toBeNull();
});
