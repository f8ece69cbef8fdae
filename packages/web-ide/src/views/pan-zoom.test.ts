import { describe, expect, it } from 'vitest';
import { fitView, readableView, zoomAt, MAX_SCALE, MIN_SCALE } from './pan-zoom.js';

describe('pan-zoom', () => {
  it('zooms at the pointer: the drawing point under it stays there', () => {
    const v = { scale: 1, x: 10, y: 20 };
    const z = zoomAt(v, 2, 110, 70);
    // the point under (110, 70) was (100, 50) in drawing units; it is still under the pointer
    expect(100 * z.scale + z.x).toBeCloseTo(110);
    expect(50 * z.scale + z.y).toBeCloseTo(70);
    expect(z.scale).toBe(2);
  });

  it('clamps the scale', () => {
    expect(zoomAt({ scale: 1, x: 0, y: 0 }, 1000, 0, 0).scale).toBe(MAX_SCALE);
    expect(zoomAt({ scale: 1, x: 0, y: 0 }, 0.0001, 0, 0).scale).toBe(MIN_SCALE);
  });

  it('fits the whole drawing, centred, without magnifying past the limit', () => {
    const f = fitView({ width: 1000, height: 500 }, { width: 532, height: 800 }, 16);
    expect(f.scale).toBeCloseTo(0.5);
    expect(f.x).toBeCloseTo(16);
    expect(f.y).toBeCloseTo((800 - 250) / 2);
    expect(fitView({ width: 10, height: 10 }, { width: 1000, height: 1000 }, 16, 1.5).scale).toBe(1.5);
  });

  it('the first view keeps the text readable: fitted when it can, else at the readable scale from the top left', () => {
    // fits at 0.9: 11 px labels shown at 9.9 px >= 9
    expect(readableView({ width: 900, height: 300 }, { width: 842, height: 600 }, 11, 9).scale).toBeCloseTo(0.9);
    // fitting would need 0.3 (labels at 3.3 px): shown at 9/11 instead, panned from the top left
    const r = readableView({ width: 3000, height: 300 }, { width: 932, height: 600 }, 11, 9);
    expect(r.scale).toBeCloseTo(9 / 11);
    expect([r.x, r.y]).toEqual([16, 16]);
  });
});
