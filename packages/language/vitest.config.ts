import { defineConfig } from 'vitest/config';

export default defineConfig({
  test: {
    // one module graph for every test file (no per-file re-import of Langium and the grammar):
    // 74 -> 26 s here; no test file keeps state in a module or process.env past its own hooks
    isolate: false,
    // vitest's 5 s default fails a test on a loaded CI machine (two cores, suites compiling C
    // beside it); a test that needs longer says so itself
    testTimeout: 30_000,
    hookTimeout: 60_000,
  },
});
