import { describe, it, expect, beforeAll, afterAll } from 'vitest';
import { mkdtempSync, mkdirSync, writeFileSync, symlinkSync, rmSync, realpathSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { WorkspacePaths } from './workspace-paths.js';
import { HttpError } from './http-error.js';

let base: string;
let ws: string;
let paths: WorkspacePaths;

beforeAll(() => {
  base = realpathSync(mkdtempSync(join(tmpdir(), 'ide-paths-')));
  ws = join(base, 'ws');
  mkdirSync(join(ws, 'sub'), { recursive: true });
  mkdirSync(join(base, 'outside'));
  writeFileSync(join(base, 'outside', 'secret.txt'), 'secret');
  writeFileSync(join(ws, 'sub', 'a.contract'), 'x');
  symlinkSync(join(base, 'outside'), join(ws, 'link-out'));
  symlinkSync(join(base, 'outside', 'secret.txt'), join(ws, 'file-link-out'));
  symlinkSync(join(ws, 'sub'), join(ws, 'link-in'));
  symlinkSync(join(base, 'nowhere'), join(ws, 'dangling'));
  paths = new WorkspacePaths(ws);
});
afterAll(() => rmSync(base, { recursive: true, force: true }));

function refusal(p: unknown): HttpError {
  try {
    paths.resolve(p);
  } catch (e) {
    if (e instanceof HttpError) return e;
    throw e;
  }
  throw new Error(`expected ${String(p)} to be refused`);
}

describe('WorkspacePaths', () => {
  it('resolves plain relative paths inside the workspace, existing or not', () => {
    expect(paths.resolve('sub/a.contract')).toBe(join(ws, 'sub', 'a.contract'));
    expect(paths.resolve('./sub//new/file.contract')).toBe(join(ws, 'sub', 'new', 'file.contract'));
    expect(paths.resolve('')).toBe(ws);
  });

  it('refuses .. segments anywhere, even when they would stay inside', () => {
    for (const p of ['..', '../ws/sub', 'sub/../../outside/secret.txt', 'sub/..', 'sub\\..\\..\\x']) {
      const e = refusal(p);
      expect(e.status).toBe(403);
      expect(e.message).toContain('..');
    }
  });

  it('refuses absolute paths with a clear message', () => {
    const e = refusal('/etc/passwd');
    expect(e.status).toBe(403);
    expect(e.message).toMatch(/absolute/);
    expect(refusal('C:\\Windows').status).toBe(403);
  });

  it('refuses symlinks that point outside, and anything below them', () => {
    expect(refusal('link-out').message).toMatch(/leaves the workspace/);
    expect(refusal('link-out/secret.txt').status).toBe(403);
    expect(refusal('link-out/new-file.txt').status).toBe(403);
    expect(refusal('file-link-out').status).toBe(403);
    expect(refusal('dangling').status).toBe(403);
  });

  it('accepts symlinks that stay inside the workspace', () => {
    expect(paths.resolve('link-in/a.contract')).toBe(join(ws, 'link-in', 'a.contract'));
  });

  it('refuses missing paths, NUL bytes and the root for entry operations', () => {
    expect(refusal(undefined).status).toBe(400);
    expect(refusal('a\0b').status).toBe(400);
    expect(() => paths.resolveEntry('')).toThrow(/root/);
  });

  it('rejects a workspace that does not exist', () => {
    expect(() => new WorkspacePaths(join(base, 'missing'))).toThrow(/not found/);
  });
});
