import { defineConfig } from 'vitest/config';

export default defineConfig({
  test: {
    // one module graph for every test file (no per-file re-import of the CLI, the language, the
    // generator, the build service and the simulator): 14 of its files took 34.7 -> 18.8 s of CPU;
    // a test file that sets process.env (CONTRACT_CACHE_DIR, PATH) puts it back in its own hooks
    isolate: false,
    // vitest's 5 s default fails a test on a loaded CI machine (two cores, suites compiling C
    // beside it); a test that needs longer says so itself
    testTimeout: 30_000,
    hookTimeout: 60_000,
  },
});
