#!/usr/bin/env node
// The edit–build–run loop from the command line, whole `contract` processes as a user runs them
// (node packages/cli/bin/contract.js, no npx), on copies of examples/tutorial with a fresh build
// cache (docs/getting-started.md "The build cache"). Writes bench/parts/cli.json:
//   cli.check_s                 median wall of `contract check` (3 runs)
//   cli.build_noop_s            median wall of `contract build` of the unchanged project (3 runs)
//   cli.build_noop_ratio        build_noop_s / check_s (goal <= 1.5)
//   cli.build_one_module_s      one protected region edited in MSA, then `contract build`
//   cli.build_one_module_compiled  executables gcc produced in that build (goal: 1, MSA)
//   cli.build_cold_s            `contract build` of a new folder, runtime already in the cache (goal <= 3)
//   cli.build_first_s           the very first build (runtime built too; for reference)
//   cli.run_overhead_s          `contract run --duration 3s` wall minus 3 s (goal <= 1.5)
// About 40-60 s on the 2-core dev machine.
import { spawnSync } from 'node:child_process';
import { chmodSync, cpSync, mkdirSync, mkdtempSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { dirname, join } from 'node:path';
import { fileURLToPath } from 'node:url';

const repo = join(dirname(fileURLToPath(import.meta.url)), '..');
const bin = join(repo, 'packages', 'cli', 'bin', 'contract.js');
const root = mkdtempSync(join(tmpdir(), 'contract-cli-bench-'));
chmodSync(root, 0o711); // the sandboxed builds' own uids must reach the cache inside
const cache = join(root, 'cache');
const env = { ...process.env, CONTRACT_CACHE_DIR: cache };

function copyTutorial(name) {
  const dir = join(root, name);
  cpSync(join(repo, 'examples', 'tutorial'), dir, { recursive: true, filter: (src) => !/\/(logs|run)(\/|$)/.test(src) });
  return dir;
}

/** Runs `contract ...args`; returns wall seconds and output; throws when it fails. */
function contract(...args) {
  const t0 = process.hrtime.bigint();
  const r = spawnSync(process.execPath, [bin, ...args], { cwd: root, env, encoding: 'utf8', maxBuffer: 64 * 1024 * 1024 });
  const seconds = Number(process.hrtime.bigint() - t0) / 1e9;
  if (r.status !== 0) throw new Error(`contract ${args.join(' ')}: exit ${r.status}\n${r.stderr.slice(-3000)}`);
  return { seconds, stdout: r.stdout, stderr: r.stderr };
}

const median = (xs) => [...xs].sort((a, b) => a - b)[Math.floor(xs.length / 2)];
const round = (x) => Math.round(x * 1000) / 1000;

const out = {};
try {
  const t1 = copyTutorial('t1');
  out['cli.build_first_s'] = round(contract('build', t1).seconds);
  const checks = [];
  const noops = [];
  for (let i = 0; i < 3; i++) {
    checks.push(contract('check', t1).seconds);
    noops.push(contract('build', t1).seconds);
  }
  out['cli.check_s'] = round(median(checks));
  out['cli.build_noop_s'] = round(median(noops));
  out['cli.build_noop_ratio'] = round(median(noops) / median(checks));

  // one protected region of one module edited: make must compile that module only
  const msa = join(t1, 'src-gen/generated/architecture/modules/MSA_mod/module.c');
  const text = readFileSync(msa, 'utf8');
  const edited = text.replace(/(\/\*PROTECTED REGION ID\(protect_internal_vars_MSA\) ENABLED START\*\/)/, '$1\nstatic volatile int bench_edit = 1;');
  if (edited === text) throw new Error('no protect_internal_vars_MSA region in MSA module.c');
  writeFileSync(msa, edited);
  const one = contract('build', t1, '--verbose');
  const compiled = one.stderr.split('\n').filter((l) => /^cc /.test(l)).map((l) => /-o (\S+)/.exec(l)?.[1]);
  out['cli.build_one_module_s'] = round(one.seconds);
  out['cli.build_one_module_compiled'] = compiled.length;
  if (compiled.join(',') !== 'MSA') process.stderr.write(`[cli bench] one-module edit compiled: ${compiled.join(', ')} (expected MSA only)\n`);

  const t2 = copyTutorial('t2');
  out['cli.build_cold_s'] = round(contract('build', t2).seconds);

  out['cli.run_overhead_s'] = round(contract('run', t1, '--duration', '3s').seconds - 3);
} finally {
  spawnSync(process.execPath, [bin, 'cache', 'clear', '--cache-dir', cache], { env, stdio: 'ignore' });
  rmSync(root, { recursive: true, force: true });
}
mkdirSync(join(repo, 'bench', 'parts'), { recursive: true });
writeFileSync(join(repo, 'bench', 'parts', 'cli.json'), JSON.stringify(out, null, 2) + '\n');
console.log(JSON.stringify(out, null, 2));
