import { describe, it, expect, afterEach } from 'vitest';
import { parseRecordLine } from '@contract-studio/build-service/trace';
import { MonitorModel } from './monitor-model.js';
import { cloneState, MAX_NAMES } from './monitor-state.js';
import { namesPastBoundText } from './panel-text.js';
import { activeSchemas } from './active-schemas.js';
import { supervisorRows, type SupervisorCatalogue } from './supervisor-rows.js';

// Names in a model or a log are anybody's: a supervisor function may be called `constructor`, and a
// log line (hostile: it comes out of the sandbox) may name a rule, a schema or a module `__proto__`.
const W = '2026-11-26T12:00:00.000000Z';
const NAMES = ['constructor', '__proto__', 'toString', 'hasOwnProperty', 'valueOf'];

function hostileRun(): MonitorModel {
  const m = new MonitorModel({ checkpointEvery: 4 });
  let ns = 1000;
  const lines: string[] = [];
  for (const n of NAMES) {
    lines.push(`${ns++},${W},SUP,supervisor,,,0,function ${n} started`);
    lines.push(`${ns++},${W},SUP,sup_rule,,,0,${n}.${n} active cause=elapsed=1ns`);
    lines.push(`${ns++},${W},SUP,sup_rule,,,0,action.${n} active cause=started(${n})`);
    lines.push(`${ns++},${W},ORD,request_received,SUP,,0,START ${n}`);
    lines.push(`${ns++},${W},ORD,scheduler,,,0,activate ${n}`);
    lines.push(`${ns++},${W},ORD,ord_release,,,0,schema=${n} cycle=0 release_ns=${ns}`);
    lines.push(`${ns++},${W},ORD,ord_complete,,,0,schema=${n} cycle=0 tick_ns=${ns} response_ns=1000`);
    lines.push(`${ns++},${W},SUP,module_hold,${n},,0,hold taken`);
  }
  lines.forEach((l, i) => m.push(parseRecordLine('SUP.csv', i + 2, l)));
  return m;
}

afterEach(() => {
  // nothing read from a trace may reach Object.prototype
  for (const k of ['active', 'by', 'since', 'releases', 'started', 'functions', 'rules']) expect(Object.prototype).not.toHaveProperty(k);
});

describe('names from a model or a log that are also Object.prototype names', () => {
  it('are folded like any other name and pollute nothing', () => {
    const s = hostileRun().live;
    const sup = s.supervisors.get('SUP')!;
    for (const n of NAMES) {
      expect(sup.functions.get(n)?.state, n).toBe('running');
      expect(sup.rules.get(`${n}.${n}`), n).toMatchObject({ function: n, rule: n, active: true, cause: 'elapsed=1ns' });
      expect(s.schemas.get(n), n).toMatchObject({ active: true, activations: 1 });
      expect(s.periodic.get(n), n).toMatchObject({ releases: 1, completions: 1 });
    }
    expect(s.schemas.get('action')).toBeUndefined();
    expect(({} as Record<string, unknown>)['by']).toBeUndefined();
  });

  it('are kept by the checkpoints and the state far back', () => {
    const m = hostileRun();
    const mid = m.stateAt(m.end / 2);
    const copy = cloneState(mid);
    expect(copy).toEqual(mid);
    expect(mid.supervisors.get('SUP')!.functions.get('constructor')?.state).toBe('running');
    expect(m.stateAt(m.end)).toEqual(m.live);
  });

  it('list every function and rule in the supervisors panel, catalogue and trace alike', () => {
    const catalogue: SupervisorCatalogue = new Map([['SUP', new Map([['constructor', ['__proto__', 'toString']], ['action', ['FIRST']]])], ['__proto__', new Map([['valueOf', []]])]]);
    const rows = supervisorRows(catalogue, hostileRun().live);
    expect(rows.map((r) => r.name)).toEqual(['SUP', '__proto__']);
    const fns = rows[0]!.functions;
    expect(fns.get('constructor')).toEqual(['__proto__', 'toString', 'constructor']);
    expect(fns.get('action')).toEqual(['FIRST', ...NAMES]);
    expect(fns.get('__proto__')).toEqual(['__proto__']);
    expect([...rows[1]!.functions]).toEqual([['valueOf', []]]);
  });

  it('name schemas and holders in the active schemas', () => {
    const s = hostileRun().live;
    const active = activeSchemas(s, [{ name: 'constructor', kind: 'periodic', modules: [] }, { name: 'ev', kind: 'event', modules: ['__proto__', 'toString'] }]);
    expect(active.find((a) => a.name === 'constructor')).toMatchObject({ kind: 'periodic', by: 'SUP.action.constructor' });
    expect(active.find((a) => a.name === 'ev')).toMatchObject({ kind: 'event' });
    expect(active.find((a) => a.name === '__proto__')).toMatchObject({ kind: 'periodic' });
  });
});

describe('a log that names something new on every line (a module may write its own log)', () => {
  it('folds at most MAX_NAMES names, counts the records past them, and says so; a real name keeps being folded', () => {
    const m = new MonitorModel();
    const N = 20_000;
    let i = 0;
    const push = (detail: string, kind: string, module = 'CAM', peer = '') => m.push(parseRecordLine('CAM.csv', ++i + 1, `${1000 + i},${W},${module},${kind},${peer},0,8,${detail}`));
    push('pid=1 priority=80', 'module_started');
    for (let k = 0; k < N; k++) {
      push('to_port=0', 'data_posted', 'CAM', `P${k}`);                 // a new flow
      push('activation=1', 'run_started', `M${k}`);                     // a new module
      push(`schema=S${k} cycle=0 release_ns=${k}`, 'ord_release', 'ORD', 'CAM'); // a new schema
      push(`fn.R${k} active cause=elapsed=1ns`, 'sup_rule', 'SUP');            // a new rule
    }
    push('activation=1', 'run_started');                                // CAM, known: still folded
    const s = m.live;
    expect(s.names).toBe(MAX_NAMES);
    const folded = s.dataFlows.size + s.modules.size + s.periodic.size + s.supervisors.size + [...s.supervisors.values()].reduce((n, sv) => n + sv.rules.size, 0);
    expect(folded).toBe(MAX_NAMES);
    expect(s.namesPastBound).toBe(4 * N + 2 - MAX_NAMES);              // 4 new names a step, CAM's and SUP's
    expect(s.modules.get('CAM')).toMatchObject({ running: true, runs: 1 });
    expect(s.records).toBe(4 * N + 2);
    // each checkpoint's copy stays as small as the bound: scrubbing back works
    expect(m.stateAt(s.t / 2).names).toBe(MAX_NAMES);
    expect(namesPastBoundText(s.namesPastBound)).toMatch(/^⚠ 78,978 record\(s\) named more .* \(1,024\): left out\./);
    expect(namesPastBoundText(0)).toBe('');
  });
});
