import { defineConfig } from 'vitest/config';

export default defineConfig({
  test: {
    // vitest's 5 s default fails a test on a loaded CI machine (two cores, suites compiling C
    // beside it); a test that needs longer says so itself
    testTimeout: 30_000,
    hookTimeout: 60_000,
  },
});
