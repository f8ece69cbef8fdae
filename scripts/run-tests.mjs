#!/usr/bin/env node
// Runs every test suite of the project in turn, streams their output, lists the ten slowest test
// files (what makes the run long), and ends with one
// summary line `N passed, N failed` (plus skipped) over all suites. Exit code 1 if any suite
// failed or ran no test.
//
// Suites: the C runtime (its runner prints `N passed, N failed`), each npm workspace's vitest run
// (read through vitest's JSON reporter), and the type check of every workspace's sources and tests
// (`npm run typecheck`: one check per workspace; vitest does not type-check). The suites that only
// compute (conventions, language, codegen, vscode, the type check) run in the background at the
// lowest CPU priority (nice 19), side by side, their output kept and printed whole at the end; the
// others run in three lanes meanwhile (LANES below), one suite at a time in each, the first lane
// streamed, the others printed at the end, and keep the CPUs whenever they want them (the computing
// suites fill the time the sandboxes, browsers and timed runs leave the CPUs idle; what they wait
// for, a language server's answer, is bounded generously: they may wait long for a CPU).
// Every suite's closing line says how long it took.
// `node scripts/run-tests.mjs NAME...` runs the suites whose names contain one of the NAMEs.
import { spawn } from 'node:child_process';
import { mkdtempSync, readFileSync, existsSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join, dirname, relative } from 'node:path';
import { fileURLToPath } from 'node:url';

const root = join(dirname(fileURLToPath(import.meta.url)), '..');
const rootPkg = JSON.parse(readFileSync(join(root, 'package.json'), 'utf8'));
const only = process.argv.slice(2);
const scratch = mkdtempSync(join(tmpdir(), 'contract-tests-'));
// one runtime build for the whole run: the test files that make fresh build caches copy it into
// them (packages/build-service/src/test-support/runtime-seed.ts) instead of compiling it again
process.env.CONTRACT_TEST_RUNTIME_SEED = join(scratch, 'runtime-seed');

/**
 * Runs a command, echoing its output live (or, for a suite run beside others, only keeping it:
 * `echo` false); resolves with its exit code and full output.
 */
function run(cmd, args, opts = {}, echo = true) {
  if (opts.niced) [cmd, args] = ['nice', ['-n', '19', cmd, ...args]];
  return new Promise((resolve) => {
    const child = spawn(cmd, args, { cwd: root, stdio: ['ignore', 'pipe', 'pipe'], ...opts });
    let out = '';
    child.stdout.on('data', (d) => { out += d; if (echo) process.stdout.write(d); });
    child.stderr.on('data', (d) => { out += d; if (echo) process.stderr.write(d); });
    child.on('close', (code, signal) => resolve({ code: code ?? (signal ? 128 : 1), out }));
  });
}

/**
 * Starts dockerd when none answers (scripts/docker-up.sh --daemon; the image is left to the docker
 * tests, which build it when missing) and holds a lease on the engine for the whole run (the
 * docker test files' own leases, released at their end, then never stop it under the other
 * lanes): the lease to release at the end (which stops the daemon when docker-up started it and
 * no one else holds it), else undefined (Docker cannot run here: the docker tests then say why
 * and are skipped).
 */
async function startDockerd() {
  const lease = `${process.pid}-run`;
  const r = await run('bash', ['scripts/docker-up.sh', '--daemon', '--lease', lease], {}, false);
  if (r.code !== 0) console.log(`(no Docker engine for the run: ${r.out.trim().split('\n').slice(-1)[0]})`);
  return r.code === 0 ? lease : undefined;
}

/** Sums every `N passed, N failed` line a C runner printed. */
function countCRunner(out) {
  let passed = 0, failed = 0, seen = false;
  for (const m of out.matchAll(/^\s*(?:\w+:\s*)?(\d+) passed, (\d+) failed/gm)) {
    passed += Number(m[1]); failed += Number(m[2]); seen = true;
  }
  // the runners' own failure lines (`FAIL name`, `FAILED file:line: …`, `CHECK failed: …`)
  const failures = out.split('\n').filter((l) => /^(FAIL |\s+FAILED |\s+.*CHECK failed)/.test(l)).slice(0, 40).map((l) => l.trim());
  return seen ? { passed, failed, skipped: 0, failures } : null;
}

/** Workspaces whose tests only compute (no sandbox, no browser, no timing): run beside each other. */
const CPU_ONLY = new Set(['packages/conventions', 'packages/language', 'packages/codegen', 'packages/vscode']);
/**
 * The lanes of the suites with sandboxes, browsers or timing: each runs its suites one after the
 * other, at normal priority, beside the other lanes. A suite is a workspace's vitest run, or some
 * of its test files run as a suite of their own (`files`; the workspace's own suite then runs the
 * rest). With one lane the two CPUs sat idle about half of the time (the suites wait for sandboxes,
 * timers and browsers); with two the second (the CLI, then the IDE) ended about three minutes
 * after the first and the CPUs were still idle 40 % of the time (25.5 min of CPU in 21 min on two
 * cores). Three lanes of about the same length in a full run (lane 1 1,114 s and lane 2 1,094 s
 * when the third held only the IDE's seven longest browser files, 491 s): the C runtime and the
 * build service; the CLI and the rest of the IDE; twenty of the IDE's browser files, its longest (each
 * has its own server on its own port and its own copy of the workspace), the installed CLI and
 * the CLI's Docker runs, the simulator. Packing and installing the CLI is about a minute of CPU: at
 * nice 19 in the background it once waited over five minutes for a CPU, hence its place in a lane.
 */
const LANES = [
  ['runtime', 'packages/build-service'],
  ['packages/cli', 'packages/web-ide'],
  [
    {
      ws: 'packages/web-ide',
      files: ['test/e2e/ide.e2e.test.ts', 'test/e2e/monitor.e2e.test.ts', 'test/e2e/keyboard.e2e.test.ts', 'test/e2e/two-tabs.e2e.test.ts',
        'test/e2e/editor-field-test.e2e.test.ts', 'test/e2e/server-killed-during-run.e2e.test.ts', 'test/e2e/large-workspace-ready.e2e.test.ts',
        'test/e2e/run-stdin.e2e.test.ts', 'test/e2e/small-screens.e2e.test.ts', 'test/e2e/offline-two-tabs.e2e.test.ts',
        'test/e2e/architecture-laptop-widths.e2e.test.ts', 'test/e2e/monitor-launcher-gone.e2e.test.ts', 'test/e2e/generated-guard.e2e.test.ts',
        'test/e2e/eclipse-layout.e2e.test.ts', 'test/e2e/monitor-field-test.e2e.test.ts', 'test/e2e/architecture-layout-fallbacks.e2e.test.ts',
        'test/e2e/editor-colours.e2e.test.ts', 'test/e2e/delete-folder.e2e.test.ts', 'test/e2e/timeline-async-module.e2e.test.ts',
        'test/e2e/monitor-recent-jobs.e2e.test.ts', 'test/e2e/monitor-late-release.e2e.test.ts', 'test/e2e/monitor-recent-jobs-fresh.e2e.test.ts',
        'test/e2e/timeline-launcher-gone.e2e.test.ts'],
    },
    { ws: 'packages/cli', files: ['test/e2e/installed-cli.e2e.test.ts', 'test/e2e/docker.e2e.test.ts'] },
    'packages/simulator',
  ],
];
/** The test files of a workspace that run as suites of their own (excluded from its own suite). */
const ownFiles = (ws) => LANES.flat().filter((e) => typeof e === 'object' && e.ws === ws).flatMap((e) => e.files);
/** The lane of a suite: its workspace's name, or its files. */
const laneOf = (ws, files) => LANES.findIndex((lane) => lane.some((e) => isEntry(e, ws, files))) + 1;
/** Where a suite comes in its lane. */
const placeInLane = (s) => LANES[s.lane - 1].findIndex((e) => isEntry(e, s.ws, s.files));
const isEntry = (e, ws, files) => (typeof e === 'string' ? e === ws && !files : e.ws === ws && e.files === files);

/** A suite's files in its name: their names, or how many from which on. */
const describeFiles = (files) => {
  const names = files.map((f) => f.replace(/^.*\//, ''));
  return names.length <= 3 ? names.join(', ') : `${names.length} files: ${names.slice(0, 2).join(', ')}, …`;
};

/** A vitest run in a workspace (its files, or all but `exclude`), read through the JSON reporter. */
function vitestSuite(name, ws, { beside, files, exclude = [] }) {
  return {
    name,
    ws,
    files,
    lane: beside ? 0 : laneOf(ws, files),
    // pure computation, no sandbox timing: run side by side in the background, niced
    // (vitest gives each one worker on a two-core machine)
    beside,
    exec: (echo) => {
      const pkg = JSON.parse(readFileSync(join(root, ws, 'package.json'), 'utf8'));
      if (!pkg.scripts?.test) return Promise.resolve(null);
      const json = join(scratch, name.replace(/\W/g, '_') + '.json');
      return run('npx', ['vitest', 'run', ...(files ?? []), ...exclude.flatMap((f) => ['--exclude', f]), '--reporter=default', '--reporter=json', `--outputFile=${json}`],
        { cwd: join(root, ws), niced: beside }, echo).then((r) => ({ ...r, json }));
    },
    count: (r) => {
      if (!r.json || !existsSync(r.json)) return null;
      const j = JSON.parse(readFileSync(r.json, 'utf8'));
      for (const f of j.testResults ?? []) {
        if (f.startTime && f.endTime) fileTimes.push({ file: `${ws}/${relative(join(root, ws), f.name)}`, s: (f.endTime - f.startTime) / 1000 });
      }
      return { passed: j.numPassedTests, failed: j.numFailedTests, skipped: j.numPendingTests + (j.numTodoTests ?? 0), failures: vitestFailures(j, ws) };
    },
  };
}

const suites = [
  {
    name: 'runtime (C, plain + ASan/UBSan, engines)',
    ws: 'runtime',
    lane: laneOf('runtime'),
    exec: () => run('make', ['-s', '-C', 'runtime', 'test']),
    count: (r) => countCRunner(r.out),
  },
  ...rootPkg.workspaces.flatMap((ws) => {
    const own = LANES.flat().filter((e) => typeof e === 'object' && e.ws === ws);
    return [
      vitestSuite(ws, ws, { beside: CPU_ONLY.has(ws), exclude: ownFiles(ws) }),
      ...own.map((e) => vitestSuite(`${ws} (${describeFiles(e.files)})`, ws, { beside: false, files: e.files })),
    ];
  }),
  {
    name: 'typecheck (tsc --noEmit of sources and tests, per workspace)',
    beside: true,
    exec: async (echo) => {
      let passed = 0, failed = 0, out = '';
      const failures = [];
      for (const ws of rootPkg.workspaces) {
        const pkg = JSON.parse(readFileSync(join(root, ws, 'package.json'), 'utf8'));
        if (!pkg.scripts?.typecheck) continue;
        const r = await run('npm', ['run', '-s', 'typecheck'], { cwd: join(root, ws), niced: true }, echo);
        out += r.out;
        const said = `typecheck ${ws}: ${r.code === 0 ? 'ok' : 'FAILED'}\n`;
        out += said;
        if (echo) process.stdout.write(said);
        if (r.code === 0) passed++; else failed++;
        if (r.code !== 0) failures.push(...r.out.split('\n').filter((l) => /error TS\d+/.test(l)).slice(0, 20).map((l) => `${ws}/${l.trim()}`));
      }
      return { code: failed ? 1 : 0, out, counts: { passed, failed, skipped: 0, failures } };
    },
    count: (r) => r.counts,
  },
];

/**
 * The failed tests of a vitest JSON report, each with the first lines of its message: repeated in
 * the closing summary, because a CI log is often read from its tail only.
 */
function vitestFailures(report, ws) {
  const out = [];
  for (const file of report.testResults ?? []) {
    const rel = relative(join(root, ws), file.name);
    const failed = (file.assertionResults ?? []).filter((a) => a.status === 'failed');
    for (const a of failed) {
      const msg = (a.failureMessages ?? []).join('\n').split('\n').slice(0, 6).map((l) => `      ${l.slice(0, 300)}`).join('\n');
      out.push(`${rel} > ${a.fullName}\n${msg}`);
    }
    // a file that failed to load or whose hooks failed has no failed assertion of its own
    if (failed.length === 0 && file.status === 'failed') {
      const why = String(file.message || 'failed outside its tests (a beforeAll/afterAll hook, or loading the file): see the suite output above');
      out.push(`${rel}: ${why.split('\n').slice(0, 6).join('\n      ')}`);
    }
  }
  return out;
}

const totals = { passed: 0, failed: 0, skipped: 0 };
/** Every vitest file's own time, for the closing list of the slowest (what makes the run long). */
const fileTimes = [];
const problems = [];
const failureDetails = [];

/** Counts a finished suite into the totals and prints its closing line. */
function record(s, r) {
  if (r === null) { console.log('(no tests)'); return; }
  const c = s.count(r);
  if (!c) { problems.push(`${s.name}: exit ${r.code}, no test count found`); return; }
  totals.passed += c.passed; totals.failed += c.failed; totals.skipped += c.skipped;
  if (r.code !== 0 || c.failed > 0) problems.push(`${s.name}: exit ${r.code}, ${c.failed} failed`);
  for (const f of c.failures ?? []) failureDetails.push(`${s.name}: ${f}`);
  if (c.passed + c.failed === 0) problems.push(`${s.name}: ran no test`);
  console.log(`=== ${s.name}: ${c.passed} passed, ${c.failed} failed, ${c.skipped} skipped (${r.seconds.toFixed(0)} s) ===`);
}

const chosen = suites.filter((s) => !only.length || only.some((o) => s.name.includes(o)));
for (const s of chosen) if (!s.beside && s.lane < 1) throw new Error(`${s.name}: in no lane of LANES`);
// the suites marked `beside` start together in the background (niced), their output printed whole
// one after the other once the others are done; the others run in their lanes, each one suite at a
// time: the first lane's output streamed, the other lanes' kept and printed whole at the end
// (sandboxes, browsers and timed runs come first for the CPUs)
const together = chosen.filter((s) => s.beside);
const lanes = LANES.map((_, i) => chosen.filter((s) => !s.beside && s.lane === i + 1).sort((a, b) => placeInLane(a) - placeInLane(b)));
const [firstLane, ...otherLanes] = lanes;
const t0 = Date.now();
/** Runs a suite, noting how long it took (said in its closing line). */
const timed = async (s, echo) => {
  const start = Date.now();
  const r = await s.exec(echo);
  return r && { ...r, seconds: (Date.now() - start) / 1000 };
};
// one Docker engine for the whole run, started here when none answers and stopped at the end: the
// run's lease keeps it up while the docker test files of the lanes take and release theirs
const dockerLease = chosen.some((s) => !s.beside) ? await startDockerd() : undefined;
const background = Promise.all(together.map((s) => timed(s, false)));
if (together.length) {
  console.log(`\n=== in the background, niced: ${together.map((s) => s.name.replace(/ \(.*$/, '')).join(', ')} ===`);
}
otherLanes.forEach((lane, i) => {
  if (lane.length) console.log(`\n=== in lane ${i + 2}, printed at the end: ${lane.map((s) => s.name).join(', ')} ===`);
});
const otherLanesDone = otherLanes.map(async (lane) => {
  const results = [];
  for (const s of lane) results.push(await timed(s, false));
  return results;
});
for (const s of firstLane) {
  console.log(`\n=== ${s.name} ===`);
  record(s, await timed(s, true));
}
const printKept = (list, results, how) => list.forEach((s, i) => {
  console.log(`\n=== ${s.name} (${how}) ===`);
  if (results[i]) process.stdout.write(results[i].out);
  record(s, results[i]);
});
for (const [i, lane] of otherLanes.entries()) printKept(lane, await otherLanesDone[i], `ran in lane ${i + 2}`);
if (together.length) printKept(together, await background, 'ran in the background');
if (dockerLease) await run('bash', ['scripts/docker-up.sh', '--release', dockerLease], {}, false);
const slowest = fileTimes.sort((a, b) => b.s - a.s).slice(0, 10);
if (slowest.length) console.log(`\n=== slowest test files ===\n${slowest.map((f) => `${f.s.toFixed(0).padStart(5)} s  ${f.file}`).join('\n')}`);
console.log(`=== all suites: ${((Date.now() - t0) / 1000).toFixed(0)} s ===`);
rmSync(scratch, { recursive: true, force: true });
if (failureDetails.length) console.log(`\nFAILED tests:\n  ${failureDetails.join('\n  ')}`);
if (problems.length) console.log(`\nFAILED suites:\n  ${problems.join('\n  ')}`);
console.log(`\n${totals.passed} passed, ${totals.failed} failed, ${totals.skipped} skipped`);
process.exit(problems.length ? 1 : 0);
