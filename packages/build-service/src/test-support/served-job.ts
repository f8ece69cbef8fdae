/**
 * The stream tests' job (ws-batch, ws-trace-filter): a test build server (sandbox none) whose
 * service hands out, for job `id`, a bare event log of the test's own, new for each test. A test
 * appends events to it and watches what a client of the job's streams gets.
 */
import { afterEach, beforeEach, vi } from 'vitest';
import { JobEvents } from '../pipeline/job-events.js';
import { useBuildServer, type TestBuildServer } from './build-server.js';

export interface ServedJob {
  readonly built: TestBuildServer;
  /** This test's event log of the job. */
  readonly events: JobEvents;
}

export function useServedJob(id: string): ServedJob {
  const built = useBuildServer({ sandbox: 'none', allowNoneSandbox: true }, { snapshotRuntime: false });
  let events = new JobEvents();
  beforeEach(() => {
    events = new JobEvents();
    const service = built.server.service;
    const real = service.get.bind(service);
    vi.spyOn(service, 'get').mockImplementation((asked) => (asked === id ? ({ id, events } as never) : real(asked)));
  });
  afterEach(() => {
    vi.restoreAllMocks();
  });
  return { built, get events() { return events; } };
}
