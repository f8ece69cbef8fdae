/**
 * The runtime cache (runtime-cache.ts) with a small runtime source folder built by the real make
 * and gcc: one build per key, shared by two caches on the same folder (two processes), a new key
 * when a source changes, a half-finished build folder never used, the build folders of killed
 * processes removed, the least recently used beyond the bound removed, a planted link refused.
 */
import { spawn, spawnSync } from 'node:child_process';
import { chmodSync, existsSync, mkdirSync, mkdtempSync, readdirSync, rmSync, statSync, symlinkSync, utimesSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { basename, join } from 'node:path';
import { afterAll, describe, expect, test } from 'vitest';
import { SERVICE_BOUNDS } from '../limits.js';
import { installedRuntimeProblem, RuntimeCache, toolchainIdentity } from './runtime-cache.js';

const scratch = mkdtempSync(join(tmpdir(), 'runtime-cache-test-'));
chmodSync(scratch, 0o711);
afterAll(() => rmSync(scratch, { recursive: true, force: true }));

/** A runtime source folder: its Makefile builds build/libmodule.a and build/contract-launch. */
function runtimeSources(dir: string, value: number): void {
  mkdirSync(join(dir, 'src'), { recursive: true });
  writeFileSync(join(dir, 'src', 'lib.c'), `int contract_value(void) { return ${value}; }\n`);
  writeFileSync(join(dir, 'src', 'launch.c'), 'int contract_value(void);\nint main(void) { return contract_value() == 0; }\n');
  writeFileSync(
    join(dir, 'Makefile'),
    'all: build/libmodule.a build/contract-launch\n' +
      'build/libmodule.a: src/lib.c\n\tmkdir -p build && cc -c -o build/lib.o src/lib.c && ar rcs $@ build/lib.o\n' +
      'build/contract-launch: src/launch.c build/libmodule.a\n\tcc -o $@ src/launch.c build/libmodule.a\n',
  );
}

const lines: string[] = [];
const log = (l: string): void => void lines.push(l);

describe('RuntimeCache', () => {
  const source = join(scratch, 'runtime');
  const cacheDir = join(scratch, 'cache', 'runtime');
  runtimeSources(source, 1);

  test('builds once; a second cache on the same folder (another process) reuses the build', async () => {
    const first = await new RuntimeCache(source, cacheDir).ensure(log);
    expect(basename(first)).toMatch(/^runtime-[0-9a-f]{16}$/);
    expect(statSync(join(first, 'build', 'contract-launch')).isFile()).toBe(true);
    const built = statSync(join(first, 'build', 'libmodule.a')).mtimeMs;
    lines.length = 0;
    const second = await new RuntimeCache(source, cacheDir).ensure(log);
    expect(second).toBe(first);
    expect(statSync(join(second, 'build', 'libmodule.a')).mtimeMs).toBe(built);
    expect(lines.join('\n')).toContain(`already built in ${first}`);
    expect(lines.join('\n')).toContain(toolchainIdentity());
    expect(lines.join('\n')).not.toContain('building the runtime');
  });

  test('two caches building the same key at once both get one complete build', async () => {
    const other = join(scratch, 'cache2', 'runtime');
    const [a, b] = await Promise.all([new RuntimeCache(source, other).ensure(log), new RuntimeCache(source, other).ensure(log)]);
    expect(a).toBe(b);
    expect(statSync(join(a, '.contract-built')).isFile()).toBe(true);
    // no temporary build folder is left behind
    expect(readdirSync(other).filter((n) => n.startsWith('.building-'))).toEqual([]);
  });

  test('the key changes when a runtime source changes', async () => {
    const before = await new RuntimeCache(source, cacheDir).ensure(log);
    writeFileSync(join(source, 'src', 'lib.c'), 'int contract_value(void) { return 2; }\n');
    const after = await new RuntimeCache(source, cacheDir).ensure(log);
    expect(after).not.toBe(before);
    runtimeSources(source, 1);
    expect(await new RuntimeCache(source, cacheDir).ensure(log)).toBe(before);
  });

  test('the key is the sources a build takes, not where they are: a checkout (with tests/, bench/) and the packed copy share it', async () => {
    const checkout = join(scratch, 'checkout-runtime');
    runtimeSources(checkout, 1);
    mkdirSync(join(checkout, 'tests'), { recursive: true });
    writeFileSync(join(checkout, 'tests', 'test_lib.c'), 'int main(void) { return 0; }\n');
    mkdirSync(join(checkout, 'bench'), { recursive: true });
    writeFileSync(join(checkout, 'bench', 'Makefile'), 'all:\n');
    const packed = join(scratch, 'elsewhere', 'node_modules', 'cli', 'runtime');
    runtimeSources(packed, 1);
    const fromCheckout = await new RuntimeCache(checkout, cacheDir).sources();
    const fromPacked = await new RuntimeCache(packed, cacheDir).sources();
    expect(fromPacked.key).toBe(fromCheckout.key);
    expect([...fromCheckout.contents.keys()].sort()).toEqual(['Makefile', 'src/launch.c', 'src/lib.c']);
    // a built one is reused by the other
    const built = await new RuntimeCache(checkout, cacheDir).ensure(log);
    lines.length = 0;
    expect(await new RuntimeCache(packed, cacheDir).ensure(log)).toBe(built);
    expect(lines.join('\n')).not.toContain('building the runtime');
    // a test's change is no change of the runtime
    writeFileSync(join(checkout, 'tests', 'test_lib.c'), 'int main(void) { return 1; }\n');
    expect((await new RuntimeCache(checkout, cacheDir).sources()).key).toBe(fromCheckout.key);
  });

  test('a make that builds nothing (no build/libmodule.a) fails and is never cached as built', async () => {
    const empty = join(scratch, 'builds-nothing');
    mkdirSync(join(empty, 'include'), { recursive: true });
    writeFileSync(join(empty, 'Makefile'), 'all:\n\t@true\n');
    const cache = join(scratch, 'cache-empty', 'runtime');
    await expect(new RuntimeCache(empty, cache).ensure(log)).rejects.toThrow(/runtime build failed: make -C .* ended without producing build\/libmodule\.a and build\/contract-launch/);
    // the next job builds again (and fails again), not "already built"
    lines.length = 0;
    await expect(new RuntimeCache(empty, cache).ensure(log)).rejects.toThrow(/runtime build failed/);
    expect(lines.join('\n')).not.toContain('already built');
    expect(readdirSync(cache).filter((n) => n.startsWith('runtime-'))).toEqual([]);
  });

  test('an installed runtime (build/ products, no src/) is refused before any build, saying what to give instead', async () => {
    const installed = join(scratch, 'installed');
    mkdirSync(join(installed, 'build'), { recursive: true });
    writeFileSync(join(installed, 'build', 'libmodule.a'), '!<arch>\n');
    writeFileSync(join(installed, 'Makefile'), 'all:\n\t@true\n');
    expect(installedRuntimeProblem(source, 'CONTRACT_RUNTIME')).toBeUndefined();
    expect(installedRuntimeProblem(installed, `CONTRACT_RUNTIME=${installed}`)).toMatch(/^CONTRACT_RUNTIME=.* names an installed runtime, which has no sources .*: contract build builds the runtime from its sources, .*; unset it, or name a runtime source folder/);
    lines.length = 0;
    await expect(new RuntimeCache(installed, join(scratch, 'cache-installed', 'runtime')).ensure(log)).rejects.toThrow(/names an installed runtime, which has no sources/);
    expect(lines.join('\n')).not.toContain('building the runtime');
  });

  test('a build folder without its completion stamp (a killed build) is rebuilt, not trusted', async () => {
    const dir = await new RuntimeCache(source, cacheDir).ensure(log);
    rmSync(join(dir, '.contract-built'));
    rmSync(join(dir, 'build', 'contract-launch'));
    lines.length = 0;
    expect(await new RuntimeCache(source, cacheDir).ensure(log)).toBe(dir);
    expect(lines.join('\n')).toContain('building the runtime');
    expect(statSync(join(dir, 'build', 'contract-launch')).isFile()).toBe(true);
  });

  test('the build folder a killed process left is removed by the next build; a live or recent one is kept', async () => {
    // a pid that existed and ended: `true`, waited for
    const dead = spawnSync('true').pid!;
    const live = spawn('sleep', ['30']);
    try {
      const old = (Date.now() - 20 * 60_000) / 1000;
      const folder = (pid: number, rand: string, age: number | undefined) => {
        const d = join(cacheDir, `.building-0123456789abcdef-${pid}-${rand}`);
        mkdirSync(join(d, 'build'), { recursive: true });
        writeFileSync(join(d, 'build', 'lib.o'), 'half a build');
        if (age !== undefined) utimesSync(d, age, age);
        return d;
      };
      const abandoned = folder(dead, 'aaaaaaaa', old);
      const running = folder(live.pid!, 'bbbbbbbb', old);
      const recent = folder(dead, 'cccccccc', undefined);
      // a link with a build folder's name is not followed: its target stays
      mkdirSync(join(scratch, 'kept-target'), { recursive: true });
      writeFileSync(join(scratch, 'kept-target', 'file'), 'x');
      const link = join(cacheDir, `.building-0123456789abcdef-${dead}-dddddddd`);
      symlinkSync(join(scratch, 'kept-target'), link);
      // a new key: a build, which sweeps first
      writeFileSync(join(source, 'src', 'lib.c'), 'int contract_value(void) { return 3; }\n');
      await new RuntimeCache(source, cacheDir).ensure(log);
      expect(existsSync(abandoned)).toBe(false);
      expect(existsSync(running) && existsSync(recent)).toBe(true);
      expect(existsSync(join(scratch, 'kept-target', 'file'))).toBe(true);
      for (const d of [running, recent, link]) rmSync(d, { recursive: true, force: true });
    } finally {
      live.kill('SIGKILL');
      runtimeSources(source, 1);
    }
  });

  test('keeps the keptRuntimes most recently used: a new build removes the least recently used beyond it; each job marks its runtime used', async () => {
    const bounded = join(scratch, 'bounded', 'runtime');
    mkdirSync(bounded, { recursive: true });
    // runtimes of earlier versions, last used 5, 4, 3 and 2 days ago
    const earlier = [5, 4, 3, 2].map((days, i) => {
      const d = join(bounded, `runtime-${String(i).padStart(16, '0')}`);
      mkdirSync(join(d, 'build'), { recursive: true });
      writeFileSync(join(d, '.contract-built'), 'earlier');
      const t = (Date.now() - days * 86_400_000) / 1000;
      utimesSync(d, t, t);
      return basename(d);
    });
    const built = await new RuntimeCache(source, bounded).ensure(log);
    const left = readdirSync(bounded).filter((n) => /^runtime-[0-9a-f]{16}$/.test(n));
    expect(left.sort()).toEqual([...earlier.slice(-(SERVICE_BOUNDS.keptRuntimes - 1)), basename(built)].sort());
    // another process's job on it marks it used
    const t = (Date.now() - 9 * 86_400_000) / 1000;
    utimesSync(built, t, t);
    expect(await new RuntimeCache(source, bounded).ensure(log)).toBe(built);
    expect(Date.now() - statSync(built).mtimeMs).toBeLessThan(60_000);
  });

  test('a link planted in place of the runtime folder is refused with a clear message', async () => {
    const dir = await new RuntimeCache(source, cacheDir).ensure(log);
    rmSync(dir, { recursive: true });
    mkdirSync(join(scratch, 'evil', 'build'), { recursive: true });
    symlinkSync(join(scratch, 'evil'), dir);
    await expect(new RuntimeCache(source, cacheDir).ensure(log)).rejects.toThrow(/is a symbolic link \(planted\?\)/);
  });
});
