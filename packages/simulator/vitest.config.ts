import { defineConfig } from 'vitest/config';

export default defineConfig({
  test: {
    include: ['test/**/*.test.ts'],
    globalSetup: ['test/cache-folder.global.ts'],
    testTimeout: 120_000,
    hookTimeout: 240_000,
    // the harness builds with gcc and the differential test runs a real sandboxed run: one file at a
    // time, in one module graph (each file imported the language and build service again: 43 -> 28 s)
    fileParallelism: false,
    isolate: false,
  },
});
