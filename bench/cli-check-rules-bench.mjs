#!/usr/bin/env node
// `contract check` of a supervisor with a long endof chain, as a user runs it (whole processes,
// node packages/cli/bin/contract.js): a copy of examples/tutorial plus a supervisor CHN whose rules
// R0: [elapsed=1ms], R1: [endof(R0)], ... each subscribe MAA:2 to one input port and end on an
// MAA:2 event: every pair of them is a question of the subscribe-conflict check, which the rules'
// reasoning (packages/language/src/model/rule-activity.ts) answers "apart", and which its index of
// each port's subscribes (model/first-overlapping.ts) passes over in a few steps. Writes bench/parts/check-rules.json:
//   cli.check_rule_chain_300_s    median wall of `contract check`, 300 rules (5 runs)
//   cli.check_rule_chain_1000_s   the same, 1,000 rules
//   cli.check_rule_chain_1000_cpu_s  CPU (user + system) of those 1,000-rule runs, median: tells contention apart from cost
// About 30 s on the 2-core dev machine.
import { spawnSync } from 'node:child_process';
import { cpSync, mkdirSync, mkdtempSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { dirname, join } from 'node:path';
import { fileURLToPath } from 'node:url';

const RUNS = 5;
const repo = join(dirname(fileURLToPath(import.meta.url)), '..');
const bin = join(repo, 'packages', 'cli', 'bin', 'contract.js');
const root = mkdtempSync(join(tmpdir(), 'contract-check-rules-bench-'));
const median = (xs) => [...xs].sort((a, b) => a - b)[Math.floor(xs.length / 2)];
const round = (x) => Math.round(x * 100) / 100;

/** The tutorial with CHN, `n` rules in one endof chain. */
function chainProject(dir, n) {
  cpSync(join(repo, 'examples', 'tutorial'), dir, { recursive: true, filter: (src) => !/\/(logs|run|src-gen)(\/|$)/.test(src) });
  const rules = Array.from({ length: n }, (_, i) =>
    `    R${i}: [${i === 0 ? 'elapsed=1ms' : `endof(R${i - 1})`}] subscribe MAA:2 =* :0 [MAA:2<status == "done">]`);
  writeFileSync(join(dir, 'chain.contract'), ['import "amodule1.contract";', 'supervisor CHN {', '  event flows { in :0 string status; }', '  run() { rules {', ...rules, '  } }', '}', ''].join('\n'));
}

const seconds = (t) => { const m = /^(\d+)m([\d.]+)s$/.exec(t); return m ? Number(m[1]) * 60 + Number(m[2]) : Number.NaN; };

/**
 * Wall and CPU (user + system) seconds of one `contract check` (through sh, whose `times` gives
 * its children's CPU); fails on any diagnostic: the chain is clean.
 */
function check(dir) {
  const t0 = process.hrtime.bigint();
  const r = spawnSync('sh', ['-c', '"$0" "$1" check "$2" && times', process.execPath, bin, dir], { encoding: 'utf8' });
  const wall = Number(process.hrtime.bigint() - t0) / 1e9;
  if (r.status !== 0 || !/0 errors, 0 warnings/.test(r.stderr)) throw new Error(`contract check ${dir}: exit ${r.status}\n${r.stdout}\n${r.stderr}`);
  const [user, sys] = r.stdout.trim().split('\n').pop().trim().split(/\s+/).map(seconds);
  return { wall, cpu: user + sys };
}

try {
  const out = {};
  for (const n of [300, 1000]) {
    const dir = join(root, `chain${n}`);
    mkdirSync(dir);
    chainProject(dir, n);
    check(dir); // warm the file cache
    const walls = [];
    const cpus = [];
    for (let i = 0; i < RUNS; i++) {
      const { wall, cpu } = check(dir);
      walls.push(wall);
      cpus.push(cpu);
    }
    out[`cli.check_rule_chain_${n}_s`] = round(median(walls));
    if (n === 1000) out['cli.check_rule_chain_1000_cpu_s'] = round(median(cpus));
    process.stderr.write(`[check-rules] ${n} rules: wall ${walls.map(round).join(' ')} s, cpu ${cpus.map(round).join(' ')} s\n`);
  }
  mkdirSync(join(repo, 'bench', 'parts'), { recursive: true });
  writeFileSync(join(repo, 'bench', 'parts', 'check-rules.json'), JSON.stringify(out, null, 2) + '\n');
  console.log(JSON.stringify(out));
} finally {
  rmSync(root, { recursive: true, force: true });
}
