import { describe, it, expect } from 'vitest';
import { LogStore, type LogLine } from './log-store.js';

const line = (source: string, stream: LogLine['stream'], text: string): LogLine => ({ t: 0, step: 'run', source, stream, line: text });

describe('LogStore', () => {
  it('filters by source, stream and text, and re-filters existing lines', () => {
    const s = new LogStore();
    s.push(line('MSC', 'stdout', 'msc tick 1'));
    s.push(line('MAA', 'stdout', 'maa event'));
    s.push(line('MSC', 'stderr', 'msc warning'));
    expect(s.visibleCount).toBe(3);
    s.setFilter({ hiddenSources: new Set(['MAA']) });
    expect([0, 1].map((i) => s.visibleAt(i)?.line)).toEqual(['msc tick 1', 'msc warning']);
    s.setFilter({ hiddenStreams: new Set(['stderr']) });
    expect(s.visibleCount).toBe(1);
    s.push(line('MSC', 'stderr', 'hidden too'));
    s.push(line('MSC', 'stdout', 'msc tick 2'));
    expect(s.visibleCount).toBe(2);
    s.setFilter({ hiddenSources: new Set(), hiddenStreams: new Set(), text: 'TICK' });
    expect(s.visibleCount).toBe(2);
    expect(s.sources.get('MSC')).toBe(4);
  });

  it('stays bounded and keeps the newest lines and a consistent index', () => {
    const s = new LogStore(1000);
    for (let i = 0; i < 5000; i++) s.push(line(i % 2 ? 'A' : 'B', 'stdout', `l${i}`));
    expect(s.total).toBeLessThanOrEqual(1250);
    expect(s.visibleAt(s.visibleCount - 1)?.line).toBe('l4999');
    s.setFilter({ hiddenSources: new Set(['B']) });
    expect(s.visibleAt(s.visibleCount - 1)?.line).toBe('l4999');
    expect(s.visibleAt(0)?.source).toBe('A');
  });

  it('counts the lines it let go (the panel says how many), none after a clear', () => {
    const s = new LogStore(1000);
    for (let i = 0; i < 1250; i++) s.push(line('A', 'stdout', `l${i}`));
    expect(s.dropped).toBe(0);
    s.push(line('A', 'stdout', 'l1250'));
    expect(s.dropped).toBe(251);
    expect(s.total + s.dropped).toBe(1251);
    for (let i = 1251; i < 5000; i++) s.push(line('A', 'stdout', `l${i}`));
    expect(s.total + s.dropped).toBe(5000);
    expect(s.visibleAt(0)?.line).toBe(`l${s.dropped}`);
    s.clear();
    expect(s.dropped).toBe(0);
  });

  it('appends 100k lines quickly (no quadratic work)', () => {
    const s = new LogStore();
    const t0 = performance.now();
    for (let i = 0; i < 100_000; i++) s.push(line('MSC', 'stdout', `line ${i}`));
    expect(performance.now() - t0).toBeLessThan(1000);
    expect(s.visibleCount).toBe(100_000);
  });
});
