import { describe, expect, it } from 'vitest';
import { median, pct, ratioAtZero } from './bench-support.js';

describe('bench statistics', () => {
  it('ratioAtZero gives the ratio a log-linear fit has where the difference is nought', () => {
    // ratio = 1.05 * 1.5^(x/100): at x = 0, 1.05, and a perfect correlation
    const x = [-140, -50, 0, 10, 130, 60];
    const ratios = x.map((v) => 1.05 * 1.5 ** (v / 100));
    const fit = ratioAtZero(ratios, x)!;
    expect(fit.ratio).toBeCloseTo(1.05, 6);
    expect(fit.r).toBeCloseTo(1, 6);
  });

  it('ratioAtZero reads a falling line as a negative correlation, and noise as a weak one', () => {
    const x = [-100, 0, 100];
    expect(ratioAtZero([2, 1, 0.5], x)!.r).toBeCloseTo(-1, 6);
    const weak = ratioAtZero([1.2, 0.8, 1.1, 0.9], [0, 10, 20, 30])!;
    expect(Math.abs(weak.r)).toBeLessThan(0.7);
  });

  it('ratioAtZero gives nothing when the difference does not vary or a ratio is not finite', () => {
    expect(ratioAtZero([1.1, 0.9, 1.3], [0, 0, 0])).toBeNull();
    expect(ratioAtZero([1.1, 0, 1.3], [0, 10, 20])).toBeNull();
    expect(ratioAtZero([1.1, 1.1, 1.1], [0, 10, 20])).toEqual({ ratio: expect.closeTo(1.1, 9), r: 0 });
  });

  it('pct and median', () => {
    expect(pct([5, 1, 4, 2, 3], 50)).toBe(3);
    expect(pct([], 99)).toBeNaN();
    expect(median([4, 1, 3, 2])).toBe(2.5);
  });
});
