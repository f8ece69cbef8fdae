import { defineConfig } from 'vitest/config';

export default defineConfig({
  test: {
    include: ['server/**/*.test.ts', 'src/**/*.test.ts', 'test/**/*.test.ts'],
    globalSetup: ['test/e2e/ensure-build.ts'],
    testTimeout: 30_000,
    hookTimeout: 120_000,
    // one file at a time (browsers and sandboxed runs), in one module graph: each file imported
    // the server, language and Playwright modules again (45-57 s of a run); a file puts back what
    // it changes in process.env
    fileParallelism: false,
    isolate: false,
  },
});
