/**
 * The front end is built before a test run only when the run may load it (test/e2e/ensure-build.ts):
 * the file filters of the vitest command line, read past the options and their values.
 */
import { describe, expect, it } from 'vitest';
import { fileFilters } from './e2e/ensure-build.js';

const argv = (...words: string[]): string[] => ['node', 'vitest.mjs', ...words];

describe('the file filters of a vitest command line', () => {
  it('are the words that are neither the command, an option nor an option\'s value', () => {
    expect(fileFilters(argv('run', 'src/monitor/line-scan.test.ts', '-t', 'reads a line', 'server/file-api.test.ts'))).toEqual(['src/monitor/line-scan.test.ts', 'server/file-api.test.ts']);
    expect(fileFilters(argv('run', '--exclude', 'test/e2e/**', '--reporter=dot', 'src/'))).toEqual(['src/']);
  });
  it('are none for a whole run, even one that names tests (every file: the front end is built)', () => {
    expect(fileFilters(argv('run'))).toEqual([]);
    expect(fileFilters(argv('run', '-t', 'monitor'))).toEqual([]);
  });
});
