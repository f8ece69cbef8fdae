import { describe, expect, test } from 'vitest';
import { JobEvents, type JobEvent, type TraceEvent } from './job-events.js';
import { eventPayload } from '../http/event-wire.js';
import { olderThanNewest } from '../job-service.js';

describe('JobEvents: a subscriber that throws (a client stream gone bad) affects no one else', () => {
  test('in replay and live, it is dropped; the log and the other subscribers go on', () => {
    const log = new JobEvents();
    log.append({ type: 'status', status: 'queued' });
    let calls = 0;
    const bad = (): void => {
      calls++;
      throw new Error('write after end');
    };
    expect(() => log.subscribe(0, bad)).not.toThrow(); // throws during replay
    const seen: JobEvent[] = [];
    log.subscribe(0, (e) => seen.push(e));
    log.subscribe(1, bad); // nothing to replay: throws on the first live event
    log.append({ type: 'line', step: 'build', source: 'build', stream: 'stdout', line: 'a' });
    log.append({ type: 'line', step: 'build', source: 'build', stream: 'stdout', line: 'b' });
    expect(calls).toBe(2);
    expect(seen.map((e) => e.seq)).toEqual([1, 2, 3]);
  });
});

describe('JobEvents.broadcast: live-only events (the trace past its kept bound)', () => {
  test('reach the subscribers attached now, are not kept, and carry the last kept seq', () => {
    const log = new JobEvents();
    const early: JobEvent[] = [];
    log.subscribe(0, (e) => early.push(e));
    log.append({ type: 'status', status: 'running', step: 'run' });
    log.broadcast({ type: 'trace', records: [{ file: 'M_1.csv', line: 2, text: 'x' }] });
    log.append({ type: 'line', step: 'run', source: 'run', stream: 'system', line: 'after' });
    expect(early.map((e) => `${e.type}:${e.seq}`)).toEqual(['status:1', 'trace:1', 'line:2']);
    expect(log.all.map((e) => e.type)).toEqual(['status', 'line']);
    const late: JobEvent[] = [];
    log.subscribe(0, (e) => late.push(e));
    expect(late.map((e) => `${e.type}:${e.seq}`)).toEqual(['status:1', 'line:2']);
  });
});

describe('JobEvents.onSubscribers: who follows the job (the live trace asks the modules to write sooner then)', () => {
  test('told the count on subscribe, unsubscribe, a dropped subscriber and the end; not for a subscriber that fails in replay', () => {
    const log = new JobEvents();
    const counts: number[] = [];
    log.onSubscribers = (n) => counts.push(n);
    log.append({ type: 'status', status: 'running', step: 'run' });
    const off = log.subscribe(0, () => {});
    expect(log.subscriberCount).toBe(1);
    log.subscribe(0, () => {
      throw new Error('gone'); // in replay: never added
    });
    let live = 0;
    log.subscribe(1, () => {
      if (++live === 1) throw new Error('gone'); // live: dropped
    });
    log.append({ type: 'line', step: 'run', source: 'run', stream: 'system', line: 'x' });
    off();
    off(); // twice: told once
    log.subscribe(0, () => {});
    log.append({ type: 'end', result: null } as never);
    expect(counts).toEqual([1, 2, 1, 0, 1, 0]);
    expect(log.subscriberCount).toBe(0);
  });
});

describe('JobEvents.dropTrace: an ended job lets its trace records go (the server\'s memory), keeping every event and seq', () => {
  test('its trace events replay empty, the first says how many records it held; lines, status and end stay', () => {
    const log = new JobEvents();
    log.append({ type: 'status', status: 'running', step: 'run' });
    log.append({ type: 'trace', records: [{ file: 'M_1.csv', line: 2, text: '1,a' }, { file: 'M_1.csv', line: 3, text: '2,b' }] });
    log.append({ type: 'line', step: 'run', source: 'M', stream: 'stdout', line: 'hello' });
    log.append({ type: 'trace', records: [{ file: 'M_1.csv', line: 4, text: '3,c' }] });
    expect(log.dropTrace()).toBe(0); // not ended: a client may still replay it
    log.append({ type: 'end', result: { status: 'succeeded' } });
    expect(log.dropTrace()).toBe(3);
    const replay: JobEvent[] = [];
    log.subscribe(0, (e) => replay.push(e));
    expect(replay.map((e) => `${e.seq}:${e.type}`)).toEqual(['1:status', '2:trace', '3:line', '4:trace', '5:end']);
    const traces = replay.filter((e): e is TraceEvent => e.type === 'trace');
    expect(traces.map((e) => e.records.length)).toEqual([0, 0]);
    expect(traces.map((e) => e.dropped)).toEqual([3, undefined]);
    expect(eventPayload(traces[0]!)).toMatchObject({ seq: 2, text: '', dropped: 3 });
    expect((replay[2] as { line: string }).line).toBe('hello');
    expect(log.dropTrace()).toBe(0); // once
  });

  test('only the ended jobs older than the newest few let theirs go', () => {
    expect(olderThanNewest(['a', 'b', 'c', 'd', 'e', 'f'], 4)).toEqual(['a', 'b']);
    expect(olderThanNewest(['a', 'b'], 4)).toEqual([]);
  });
});
