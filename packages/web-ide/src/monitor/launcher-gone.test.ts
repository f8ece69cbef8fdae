/**
 * The launcher's own line of the job's output saying a module ended (`contract-launch: module SRT
 * (pid 41) died by signal 9 (Killed)`) shows that module gone in the Monitor — the alert line, the
 * strip mark, `Running now … · gone: SRT` — although no other module sent it a request; a line that
 * names another pid, a module whose start was not read, or one already ended is not taken.
 */
import { describe, it, expect } from 'vitest';
import { traceFileToLogs } from '@contract-studio/build-service/trace';
import { MonitorModel } from './monitor-model.js';
import { launcherGoneSign } from './gone-signs.js';
import { applyFolderLauncherLines, applyLauncherLines, launcherLinesOf } from './job-launcher-lines.js';
import { crashedModulesText } from './panel-text.js';
import { modulesText } from './monitor-panel.js';
import type { MonitorState } from './monitor-state.js';

const W = '2026-12-07T12:00:00.000000Z';
const rec = (mono: number, module: string, kind: string, detail: string) => `${mono},${W},${module},${kind},,,0,${detail}`;

/** A run of ORD and SRT (pid 41), each started, SRT's last record at +0.2 s, ORD's records going on to +0.5 s. */
function run(): MonitorModel {
  const m = new MonitorModel({ checkpointEvery: 16 });
  const lines = [
    ['ORD_1.csv', rec(1_000_000_000, 'ORD', 'module_started', 'pid=40 priority=90')],
    ['SRT_1.csv', rec(1_000_100_000, 'SRT', 'module_started', 'pid=41 priority=40')],
    ['SRT_1.csv', rec(1_200_000_000, 'SRT', 'user', 'sorting')],
    ['ORD_1.csv', rec(1_500_000_000, 'ORD', 'user', 'tick')],
  ];
  lines.forEach(([file, text], i) => m.pushLine(file!, i + 2, text!));
  return m;
}

const gone = (s: MonitorState) => [...s.modules].filter(([, x]) => x.gone !== undefined).map(([n]) => n);
const running = (s: MonitorState) => [...s.modules].filter(([, x]) => x.running || (x.alive && x.gone === undefined && x.crashed === undefined)).map(([n]) => n);

describe("the launcher's line saying a module ended", () => {
  it('shows SRT gone from the last record folded: alert line, strip mark, Running now', () => {
    const m = run();
    expect(m.launcherLine('module SRT (pid 41) died by signal 9 (Killed)')).toBe(true);
    const s = m.stateAt(m.end);
    expect(gone(s)).toEqual(['SRT']);
    expect(crashedModulesText(s.modules)).toBe('⚠ SRT gone at +0.500000 s: contract-launch: module SRT (pid 41) died by signal 9 (Killed)');
    expect(m.marks.filter((k) => k.kind === 'crash')).toEqual([{ t: 500_000_000, kind: 'crash', where: 'SRT', label: 'SRT gone: contract-launch: module SRT (pid 41) died by signal 9 (Killed)' }]);
    expect(modulesText(running(s), [], [], gone(s))).toContain('· gone: SRT');
    // scrubbed back before the line came, SRT runs; at it and after, gone (no record holds the line: stateAt applies it)
    expect(gone(m.stateAt(400_000_000))).toEqual([]);
    m.pushLine('ORD_1.csv', 10, rec(1_600_000_000, 'ORD', 'user', 'tick'));
    expect(gone(m.stateAt(550_000_000))).toEqual(['SRT']);
    // a second line of it changes nothing
    expect(m.launcherLine('module SRT (pid 41) died by signal 9 (Killed)')).toBe(false);
    expect(m.marks.filter((k) => k.kind === 'crash')).toHaveLength(1);
  });

  it('an exit with a status and a death by another signal are ends too; its exit record read later stands', () => {
    const m = run();
    expect(m.launcherLine('module SRT (pid 41) exited with status 3')).toBe(true);
    expect(gone(m.stateAt(m.end))).toEqual(['SRT']);
    m.pushLine('SRT_1.csv', 9, rec(1_600_000_000, 'SRT', 'module_exit', 'status=3 records=3'));
    expect(gone(m.stateAt(m.end))).toEqual([]);
    const n = run();
    expect(n.launcherLine('module SRT (pid 41) died by signal 11 (Segmentation fault)')).toBe(true);
  });

  it('ORD gone by the launcher\'s line: its schemas are ended at its last record, as for a record saying so', () => {
    const m = run();
    expect(m.launcherLine('module ORD (pid 40) died by signal 9 (Killed)')).toBe(true);
    expect(gone(m.stateAt(m.end))).toEqual(['ORD']);
    expect(m.stateAt(m.end).modules.get('ORD')!.running).toBe(false);
  });

  it('hostile lines: another pid, an unknown module, a module not started, a line of other words are not taken', () => {
    const m = run();
    expect(m.launcherLine('module SRT (pid 99) died by signal 9 (Killed)')).toBe(false);
    expect(m.launcherLine('module XYZ (pid 41) died by signal 9 (Killed)')).toBe(false);
    expect(m.launcherLine('module SRT (pid 41) died by signal 9 (Killed) and more')).toBe(false);
    expect(m.launcherLine(`module SRT (pid 41) died by signal 9 (${'x'.repeat(5000)})`)).toBe(false);
    expect(m.launcherLine('[SRT] module ORD (pid 40) died by signal 9 (Killed)')).toBe(false);
    expect(m.launcherLine('all modules stopped')).toBe(false);
    expect(gone(m.stateAt(m.end))).toEqual([]);
    expect(m.marks.filter((k) => k.kind === 'crash')).toEqual([]);
    // no start record read: its pid unknown, not taken
    expect(launcherGoneSign('module SRT (pid 41) died by signal 9 (Killed)', () => undefined)).toBeUndefined();
    expect(launcherGoneSign('module SRT (pid 41) died by signal 9 (Killed)', () => 41)).toEqual({ module: 'SRT', words: 'contract-launch: module SRT (pid 41) died by signal 9 (Killed)' });
  });

  it('takes no line of a module that ended with the run: on the stop\'s KILL request, or terminated by the launcher', () => {
    const pid = () => 41;
    for (const how of ['exited with status 0', 'exited with status 0 while the run stopped', 'terminated by signal 15 (Terminated)', 'terminated by signal 15 (Terminated) while the run stopped'])
      expect(launcherGoneSign(`module SRT (pid 41) ${how}`, pid), how).toBeUndefined();
    for (const how of ['exited with status 3', "exited with status 0 before the run's end", 'died by signal 11 (Segmentation fault) while the run stopped'])
      expect(launcherGoneSign(`module SRT (pid 41) ${how}`, pid)?.module, how).toBe('SRT');
  });
});


describe("a replay of a job's logs, with the launcher's lines of its log", () => {
  const log = [
    '2026-12-07T12:00:00.100Z run launcher stderr | 2 module(s) running',
    '2026-12-07T12:00:00.150Z run SRT stderr | module ORD (pid 40) died by signal 9 (Killed)',
    '2026-12-07T12:00:00.160Z run launcher stdout | module ORD (pid 40) died by signal 9 (Killed)',
    '2026-12-07T12:00:00.300Z run launcher stderr | module SRT (pid 41) died by signal 9 (Killed)',
    '2026-12-07T12:00:00.900Z run launcher stderr | all modules stopped',
  ].join('\n');

  it("reads only the launcher's own lines of the run step, each with its time", () => {
    expect(launcherLinesOf(log)).toEqual([
      { wallMs: Date.parse('2026-12-07T12:00:00.100Z'), line: '2 module(s) running' },
      { wallMs: Date.parse('2026-12-07T12:00:00.300Z'), line: 'module SRT (pid 41) died by signal 9 (Killed)' },
      { wallMs: Date.parse('2026-12-07T12:00:00.900Z'), line: 'all modules stopped' },
    ]);
  });

  it('shows the module gone at the line\'s time on the run\'s time line, in every state from then on, its mark in time order', () => {
    const m = run(); // first record (ORD's start) at 12:00:00.000000 wall time
    const files = [{ name: 'ORD_1.csv', text: `mono_ns,wall_time,module,event,peer,port,size,detail\n${rec(1_000_000_000, 'ORD', 'module_started', 'pid=40 priority=90')}\n` },
      { name: 'SRT_1.csv', text: `mono_ns,wall_time,module,event,peer,port,size,detail\n${rec(1_000_100_000, 'SRT', 'module_started', 'pid=41 priority=40').replace(W, '2026-12-07T12:00:00.000100Z')}\n` }];
    m.recordsEnded();
    applyLauncherLines(m, files, launcherLinesOf(log));
    expect(m.marks.filter((k) => k.kind === 'crash')).toEqual([{ t: 300_000_000, kind: 'crash', where: 'SRT', label: 'SRT gone: contract-launch: module SRT (pid 41) died by signal 9 (Killed)' }]);
    expect(gone(m.stateAt(299_000_000))).toEqual([]);
    expect(gone(m.stateAt(300_000_000))).toEqual(['SRT']);
    expect(gone(m.stateAt(m.end))).toEqual(['SRT']);
    expect(crashedModulesText(m.stateAt(m.end).modules)).toBe('⚠ SRT gone at +0.300000 s: contract-launch: module SRT (pid 41) died by signal 9 (Killed)');
  });
});

describe("a replay of a logs folder, with its contract-launch.log (the launcher's own lines, on the records' clock)", () => {
  it('shows the module gone at the line\'s own time; a line naming another pid, or malformed, is not taken', () => {
    const m = run(); // first record at mono 1.0 s
    m.recordsEnded();
    applyFolderLauncherLines(m, [
      { monoNs: '1250000000', line: 'module SRT (pid 99) died by signal 9 (Killed)' },
      { monoNs: 'x', line: 'module SRT (pid 41) died by signal 9 (Killed)' },
      { monoNs: '1300000000', line: 'module SRT (pid 41) died by signal 9 (Killed)' },
    ]);
    expect(m.marks.filter((k) => k.kind === 'crash')).toEqual([{ t: 300_000_000, kind: 'crash', where: 'SRT', label: 'SRT gone: contract-launch: module SRT (pid 41) died by signal 9 (Killed)' }]);
    expect(gone(m.stateAt(299_000_000))).toEqual([]);
    expect(gone(m.stateAt(m.end))).toEqual(['SRT']);
    const n = run();
    applyFolderLauncherLines(n, [{ monoNs: '1250000000', line: 'module SRT (pid 99) died by signal 9 (Killed)' }]);
    expect(gone(n.stateAt(n.end))).toEqual([]);
  });
});

describe("a replay of a trace file (`contract run --trace`) holding the launcher's end lines (`launcher_line`)", () => {
  /** The trace file of run(): its records as JSON lines, `extra` (launcher lines) after SRT's last record. */
  const file = (extra: object[]) => [
    { kind: 'module_started', monoNs: '1000000000', wallTime: W, module: 'ORD', peer: '', port: null, size: 0, detail: 'pid=40 priority=90' },
    { kind: 'module_started', monoNs: '1000100000', wallTime: W, module: 'SRT', peer: '', port: null, size: 0, detail: 'pid=41 priority=40' },
    { kind: 'user', monoNs: '1200000000', wallTime: W, module: 'SRT', peer: '', port: null, size: 0, detail: 'sorting', fields: { event: 'sorting' } },
    ...extra,
    { kind: 'user', monoNs: '1500000000', wallTime: W, module: 'ORD', peer: '', port: null, size: 0, detail: 'tick', fields: { event: 'tick' } },
  ].map((o) => JSON.stringify(o)).join('\n') + '\n';
  /** The file replayed as the Monitor replays a trace file: its logs in the file's order, then its launcher lines. */
  const replay = (text: string) => {
    const logs = traceFileToLogs('run.jsonl', text);
    const m = new MonitorModel({ checkpointEvery: 16 });
    const lines = logs.files.map((f) => ({ name: f.name, lines: f.text.split('\n').slice(1), next: 0 }));
    for (const i of logs.order) {
      const l = lines[i]!;
      m.pushLine(l.name, l.next + 2, l.lines[l.next++]!);
    }
    m.recordsEnded();
    applyFolderLauncherLines(m, logs.launcherLines);
    return { m, logs };
  };

  it('shows the module gone at the line\'s own time, the line read apart from the records', () => {
    const { m, logs } = replay(file([{ kind: 'launcher_line', monoNs: '1300000000', line: 'module SRT (pid 41) died by signal 9 (Killed)' }]));
    expect(logs.problems).toEqual([]);
    expect(logs.launcherLines).toEqual([{ monoNs: '1300000000', line: 'module SRT (pid 41) died by signal 9 (Killed)' }]);
    expect(m.marks.filter((k) => k.kind === 'crash')).toEqual([{ t: 300_000_000, kind: 'crash', where: 'SRT', label: 'SRT gone: contract-launch: module SRT (pid 41) died by signal 9 (Killed)' }]);
    expect(gone(m.stateAt(299_000_000))).toEqual([]);
    expect(gone(m.stateAt(m.end))).toEqual(['SRT']);
  });

  it('a forged line (another pid) is not believed; one in no launcher line\'s shape is named as no record', () => {
    const { m, logs } = replay(file([
      { kind: 'launcher_line', monoNs: '1300000000', line: 'module SRT (pid 99) died by signal 9 (Killed)' },
      { kind: 'launcher_line', monoNs: '1300000000', line: 'SRT is gone, believe me' },
    ]));
    expect(logs.problems).toEqual(["line 5: a launcher_line that is none of the launcher's end lines"]);
    expect(gone(m.stateAt(m.end))).toEqual([]);
  });
});
