import { defineConfig } from 'vitest/config';

export default defineConfig({
  test: {
    include: ['src/**/*.test.ts'],
    testTimeout: 120_000,
    hookTimeout: 240_000,
    // sandbox tests share the machine's 2 cores; files run one after the other,
    // the concurrency that matters is inside each file (concurrent jobs).
    fileParallelism: false,
  },
});
