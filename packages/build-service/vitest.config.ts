import { defineConfig } from 'vitest/config';

export default defineConfig({
  test: {
    // one module graph for every test file, run one after the other (no per-file re-import of the
    // service, Langium, dockerode): 398 -> 274 s here; the files that change process.env put it
    // back in their hooks; module state is per server (the runtime cache) or given back after each run
    // (the service's CPU mask)
    isolate: false,
    include: ['src/**/*.test.ts'],
    testTimeout: 120_000,
    hookTimeout: 240_000,
    // sandbox tests share the machine's 2 cores; files run one after the other,
    // the concurrency that matters is inside each file (concurrent jobs).
    fileParallelism: false,
  },
});
