/**
 * What every build-service benchmark shares: its progress line on stderr, rounding, percentiles,
 * and the part it writes (bench/parts/<name>.json, merged into bench/results.json by
 * bench/run-all.mjs).
 */
import { mkdirSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { REPO } from '../test-support/tutorial.js';

/** A progress line, `[bench <tag>] ...`, on stderr (stdout stays free for the part). */
export function benchLog(tag: string): (line: string) => void {
  return (line) => void process.stderr.write(`[bench ${tag}] ${line}\n`);
}

export function round(x: number, digits = 3): number {
  return Math.round(x * 10 ** digits) / 10 ** digits;
}

/** The p-th percentile (nearest rank from below) of xs; NaN when empty. */
export function pct(xs: number[], p: number): number {
  const s = [...xs].sort((a, b) => a - b);
  return s.length ? s[Math.min(s.length - 1, Math.floor((p / 100) * s.length))]! : NaN;
}

export function median(xs: number[]): number {
  const s = [...xs].sort((a, b) => a - b);
  return s.length % 2 ? s[(s.length - 1) / 2]! : (s[s.length / 2 - 1]! + s[s.length / 2]!) / 2;
}

/** Writes bench/parts/<name>.json. */
export function writePart(name: string, out: Record<string, unknown>): void {
  mkdirSync(join(REPO, 'bench', 'parts'), { recursive: true });
  writeFileSync(join(REPO, 'bench', 'parts', `${name}.json`), JSON.stringify(out, null, 2) + '\n');
}
