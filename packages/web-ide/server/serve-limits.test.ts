/**
 * `contract serve --limit`: the build service's own check of the limits is the only one. The IDE
 * server refuses to start on limits the service refuses (BuildLimitsRefused, with the service's
 * message), and `contract serve` makes that its exit 2 (packages/cli/test/serve-token.test.ts runs
 * the command). Before, `contract serve` loaded the build service a second time to check them
 * first, because the IDE server started anyway, its build service "unavailable".
 */
import { chmodSync, mkdirSync, mkdtempSync, realpathSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { startIdeServer } from './ide-server.js';
import { BuildLimitsRefused } from './integrations.js';

let base: string;
const previous = process.env.CONTRACT_CACHE_DIR;
beforeAll(() => {
  base = realpathSync(mkdtempSync(join(tmpdir(), 'ide-serve-limits-')));
  chmodSync(base, 0o711);
  mkdirSync(join(base, 'ws'));
  // the build cache the server would use: this test's own
  process.env.CONTRACT_CACHE_DIR = join(base, 'cache');
});
afterAll(() => {
  if (previous === undefined) delete process.env.CONTRACT_CACHE_DIR;
  else process.env.CONTRACT_CACHE_DIR = previous;
  rmSync(base, { recursive: true, force: true });
});

describe('the IDE server with limits its build service refuses', () => {
  it('does not start (the service\'s own message), rather than start without its build service', async () => {
    for (const [limits, message] of [
      [{ bogus: 1 }, 'unknown limit "bogus"'],
      [{ processes: 10.5 }, 'limit processes must be a whole number (a count or a size), got 10.5'],
    ] as const) {
      const started = await startIdeServer({ workspace: join(base, 'ws'), port: 0, distDir: join(base, 'no-dist'), limits: { ...limits } }).then(
        async (ide) => {
          const note = ide.buildServiceNote;
          await ide.close();
          return note;
        },
        (e: unknown) => e,
      );
      expect(started).toBeInstanceOf(BuildLimitsRefused);
      expect((started as Error).message).toContain(message);
    }
  });

  it('limits the service takes: it starts with its build service', async () => {
    const ide = await startIdeServer({ workspace: join(base, 'ws'), port: 0, distDir: join(base, 'no-dist'), limits: { runSeconds: 3660 } });
    try {
      expect(ide.buildServiceNote).toBe('build service mounted at /api/jobs');
    } finally {
      await ide.close();
    }
  });
});
