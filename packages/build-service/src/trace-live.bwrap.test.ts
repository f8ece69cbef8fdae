/**
 * The live trace channel (docs/build-service-api.md "Trace channel") on a real bwrap run of the
 * report's tutorial through the HTTP service: the trace events carry exactly the record lines of
 * the CSV logs collected after the run (per file, count and order), in non-decreasing mono_ns
 * across the stream, the supervisor's rule story among them, and a client subscribing from seq 0
 * after the run gets the identical trace (SSE and WebSocket). A run stopped mid-way (DELETE: the
 * IDE's Stop, the CLI's Ctrl+C) is stopped by its launcher as at the end of a run: every module's
 * log ends with its exit record, the supervisors' undos reach ORD, and the live trace is whole.
 */
import { expect, test } from 'vitest';
import { CANCEL_DEADLINE_MS } from './limits.js';
import WebSocket from 'ws';
import type { JobEvent, TraceEvent, TraceLine } from './pipeline/job-events.js';
import { useBuildServer } from './test-support/build-server.js';
import { getJob, jobEventFromWire, postJob, readEvents } from './test-support/client.js';
import { MAA_MODULE, tutorialFiles, withRegion } from './test-support/tutorial.js';
import { parseLogFile, parseRecordLine } from './trace/parse.js';
import type { RuleRecord } from './trace/records.js';

const served = useBuildServer({ concurrency: 1 }, { timeoutMs: 240_000 });

const traceLines = (events: JobEvent[]): TraceLine[] => events.filter((e): e is TraceEvent => e.type === 'trace').flatMap((e) => e.records);

function wsEvents(id: string): Promise<JobEvent[]> {
  return new Promise((resolve, reject) => {
    const out: JobEvent[] = [];
    const ws = new WebSocket(`${served.url.replace('http', 'ws')}/api/jobs/${id}/ws`);
    ws.on('message', (d) => out.push(jobEventFromWire(JSON.parse(String(d)) as Record<string, unknown>)));
    ws.on('close', () => resolve(out));
    ws.on('error', reject);
  });
}

test('the tutorial in bwrap: the live trace is the collected logs, in mono_ns order, replayable from seq 0', async () => {
  const files = await tutorialFiles();
  // MAA's user code sleeps 500 ms at a time inside its callbacks (nanosleep in a protected
  // region) with records in its log buffer (the runtime writes a module's log when the module
  // waits for requests): its flush mark says so, and the other modules' newer records wait for
  // MAA's instead of overtaking them (docs/build-service-api.md "Trace channel").
  expect(files[MAA_MODULE]!).toContain('nanosleep(&step, NULL);');
  const r = await postJob(served.url, { action: 'run', sandbox: 'bwrap', duration: 3, project: { files } });
  expect(r.status, JSON.stringify(r.json)).toBe(201);
  const id = r.json.id as string;
  const arrivals: number[] = [];
  const live = await readEvents(served.url, id, (e) => {
    if (e.type === 'trace') arrivals.push(Date.now());
  });
  const job = await getJob(served.url, id);
  const lines = live.filter((e) => e.type === 'line').map((e) => (e as { line: string }).line);
  expect(job.status, `${job.result?.message}\n${lines.slice(-20).join('\n')}`).toBe('succeeded');

  // the trace came while the run ran (several events), and before the artifacts and the end
  const kinds = live.map((e) => e.type);
  const firstTrace = kinds.indexOf('trace');
  const lastTrace = kinds.lastIndexOf('trace');
  expect(arrivals.length).toBeGreaterThan(3);
  expect(lastTrace).toBeLessThan(live.findIndex((e) => e.type === 'line' && /^collected \d+ artifact/.test((e as { line: string }).line)));
  expect(firstTrace).toBeLessThan(live.findIndex((e) => e.type === 'line' && /^run finished in/.test((e as { line: string }).line)));
  expect(lines.filter((l) => l.startsWith('trace:'))).toEqual([]);

  // per file: exactly the record lines of the collected log, in file order
  const trace = traceLines(live);
  const listing = moduleLogs(job.artifacts as { files: { name: string }[] });
  expect(listing.files).toHaveLength(9);
  let total = 0;
  for (const f of listing.files) {
    const text = await (await fetch(`${served.url}/api/jobs/${id}/artifacts/${encodeURIComponent(f.name)}`)).text();
    const want = parseLogFile({ name: f.name, text });
    const got = trace.filter((l) => l.file === f.name).map((l) => parseRecordLine(l.file, l.line, l.text));
    expect(got, f.name).toEqual(want);
    total += want.length;
  }
  expect(trace).toHaveLength(total);
  expect(total).toBeGreaterThan(100);

  // mono_ns never goes back across the stream
  const monos = trace.map((l) => BigInt(/^(\d+),/.exec(l.text)![1]!));
  for (let i = 1; i < monos.length; i++) expect(monos[i]! >= monos[i - 1]!, `record ${i}: ${trace[i]!.text} after ${trace[i - 1]!.text}`).toBe(true);

  // the supervisor's story: FIRST active, then SECOND active caused by MAA:2
  const rules = trace.map((l) => parseRecordLine(l.file, l.line, l.text)).filter((x): x is RuleRecord => x.kind === 'sup_rule' && (x as RuleRecord).active);
  const first = rules.findIndex((x) => x.rule === 'FIRST');
  const second = rules.findIndex((x) => x.rule === 'SECOND');
  expect(first).toBeGreaterThanOrEqual(0);
  expect(second).toBeGreaterThan(first);
  expect(rules[second]!.cause).toMatch(/^MAA:2 /);

  // a late client from seq 0 gets the same trace, over SSE and over WebSocket
  expect(traceLines(await readEvents(served.url, id))).toEqual(trace);
  expect(traceLines(await wsEvents(id))).toEqual(trace);
}, 240_000);

test('Stop mid-run: the launcher stops the tutorial as at the end of a run; logs and live trace end with every exit record', async () => {
  const files = await tutorialFiles();
  const r = await postJob(served.url, { action: 'run', sandbox: 'bwrap', duration: 60, project: { files } });
  expect(r.status, JSON.stringify(r.json)).toBe(201);
  const id = r.json.id as string;
  let asked = 0;
  let secondActive = false;
  const live = await readEvents(served.url, id, (e) => {
    if (e.type !== 'trace' || asked) return;
    // once SUP's SECOND rule is active (schemaCommande1 asked of ORD), half a second of run, then Stop
    if (e.records.some((l) => l.text.includes(',SUP,sup_rule,') && l.text.includes('action.SECOND active'))) secondActive = true;
    if (secondActive && !asked) {
      asked = Date.now() + 500;
      setTimeout(() => void fetch(`${served.url}/api/jobs/${id}`, { method: 'DELETE' }), 500);
    }
  });
  const stoppedMs = Date.now() - asked;
  const job = await getJob(served.url, id);
  const lines = live.filter((e) => e.type === 'line').map((e) => (e as { line: string }).line);
  expect(job.status, lines.slice(-20).join('\n')).toBe('cancelled');
  expect(stoppedMs).toBeLessThan(CANCEL_DEADLINE_MS + 1500); // + collecting the logs
  expect(lines, lines.slice(-30).join('\n')).toContain('all modules stopped cleanly');
  expect(lines.some((l) => l.startsWith('stopping the architecture as at the end of a run'))).toBe(true);
  expect(lines.filter((l) => /did not stop within|: killed|terminated/.test(l))).toEqual([]);
  // the service's line first, then the launcher's as it stops (they came the other way round)
  const launcherStops = lines.findIndex((l) => /^stopping(: |$)/.test(l));
  expect(launcherStops, lines.slice(-30).join('\n')).toBeGreaterThan(lines.findIndex((l) => l.startsWith('stopping the architecture as at the end of a run')));

  // every log is whole: it ends with its module's exit record, and the live trace has each of its records
  const trace = traceLines(live);
  const listing = moduleLogs(job.artifacts as { files: { name: string }[] });
  expect(listing.files).toHaveLength(9);
  const texts = new Map<string, string>();
  for (const f of listing.files) {
    const text = await (await fetch(`${served.url}/api/jobs/${id}/artifacts/${encodeURIComponent(f.name)}`)).text();
    texts.set(f.name.split('_')[0]!, text);
    const want = parseLogFile({ name: f.name, text });
    expect(want.at(-1)?.kind, f.name).toBe('module_exit');
    expect(trace.filter((l) => l.file === f.name).map((l) => parseRecordLine(l.file, l.line, l.text)), f.name).toEqual(want);
  }
  // the supervisors stopped first: SUP's undo of its schemas reached ORD, which deactivated them
  const undone = [...texts.get('SUP')!.matchAll(/,supervisor,ORD,,0,"undo: deactivate schema (\w+) \(activation #(\d+), to ORD\)"/g)].map((m) => [m[1]!, m[2]!] as const);
  expect(undone.length).toBeGreaterThan(0);
  // ORD's line names the activation it ends, as SUP numbered it
  for (const [schema, n] of undone) expect(texts.get('ORD')!, schema).toContain(`,scheduler,,,0,deactivate ${schema} (activation #${n} from SUP)\n`);
}, 240_000);

/** A job's collected module logs (its CSV files), the launcher's own lines file among the artifacts too. */
function moduleLogs(artifacts: { files: { name: string }[] }): { files: { name: string }[] } {
  expect(artifacts.files.map((f) => f.name)).toContain('contract-launch.log');
  return { files: artifacts.files.filter((f) => f.name.endsWith('.csv')) };
}

/**
 * The 9 collected logs of a job, by module, each checked to end with its module's exit record but
 * `killed`'s (a module SIGKILLed: its log does not); `context` is said with a failure. `why`: the
 * reason the launcher's KILL must give in each of those logs (the service's stop said why).
 */
async function logsEndingWithExit(id: string, job: Record<string, any>, killed?: string, context = '', why?: string): Promise<void> {
  const listing = moduleLogs(job.artifacts as { files: { name: string }[] });
  expect(listing.files).toHaveLength(9);
  for (const f of listing.files) {
    const text = await (await fetch(`${served.url}/api/jobs/${id}/artifacts/${encodeURIComponent(f.name)}`)).text();
    const last = parseLogFile({ name: f.name, text }).at(-1)?.kind;
    if (killed !== undefined && f.name.startsWith(`${killed}_`)) expect(last, f.name).not.toBe('module_exit');
    else {
      expect(last, `${f.name}${context ? `\n${context}` : ''}`).toBe('module_exit');
      if (why) expect(text, f.name).toContain(`,request_received,contract-launch,,${why.length + 1},KILL (${why})\n`);
    }
  }
}

test('a duration as long as the run time limit is capped to leave room to stop: the run ends on its own, its logs whole', async () => {
  const files = await tutorialFiles();
  const r = await postJob(served.url, { action: 'run', sandbox: 'bwrap', duration: 4, limits: { runSeconds: 4 }, project: { files } });
  expect(r.status, JSON.stringify(r.json)).toBe(201);
  const id = r.json.id as string;
  const lines = (await readEvents(served.url, id)).filter((e) => e.type === 'line').map((e) => (e as { line: string }).line);
  const job = await getJob(served.url, id);
  expect(job.status, lines.slice(-20).join('\n')).toBe('succeeded');
  expect(lines).toContain('duration 4 s capped to 2 s: the run time limit is 4 s, of which 2 s are kept to start and stop the architecture');
  expect(lines).toContain('all modules stopped cleanly');
  await logsEndingWithExit(id, job);
}, 240_000);

test('a run whose inits were slow stops by the longest duration after its launch, said: it ends on its own before the run time limit', async () => {
  // MSC's init takes 3 s (a calibration): its start comes 3 s after the launch, and 4 s of run
  // after it would end past the time limit (8 s, of which 4 s at most for the run)
  const files = withRegion(await tutorialFiles(), 'src-gen/generated/architecture/modules/MSC_mod/module.c', 'protect_init_MSC',
    '    { struct timespec cal = { 3, 0 }; nanosleep(&cal, NULL); }', true);
  const r = await postJob(served.url, { action: 'run', sandbox: 'bwrap', duration: 4, limits: { runSeconds: 8 }, project: { files } });
  expect(r.status, JSON.stringify(r.json)).toBe(201);
  const id = r.json.id as string;
  const lines = (await readEvents(served.url, id)).filter((e) => e.type === 'line').map((e) => (e as { line: string }).line);
  const job = await getJob(served.url, id);
  expect(job.status, lines.slice(-20).join('\n')).toBe('succeeded');
  const said = lines.find((l) => l.startsWith('the run stops '));
  const m = /^the run stops (\d+\.\d) s before the end of its 4 s: its start came (\d+\.\d) s after the launch \(the modules' inits\), and it must end 4 s after the launch \(the run time limit\)$/.exec(said ?? '');
  expect(m, lines.slice(-30).join('\n')).not.toBeNull();
  expect(Number(m![2])).toBeGreaterThanOrEqual(3); // after MSC's 3 s init
  expect(Number(m![1])).toBeGreaterThanOrEqual(2.9); // 4 s after the start would have been 7 s after the launch
  expect(lines).toContain('all modules stopped cleanly');
  await logsEndingWithExit(id, job);
}, 240_000);

test('the run time limit stops an architecture that runs on (no duration) as at the end of a run: failed on the limit, its logs whole', async () => {
  const files = await tutorialFiles();
  const r = await postJob(served.url, { action: 'run', sandbox: 'bwrap', limits: { runSeconds: 3 }, project: { files } });
  expect(r.status, JSON.stringify(r.json)).toBe(201);
  const id = r.json.id as string;
  const lines = (await readEvents(served.url, id)).filter((e) => e.type === 'line').map((e) => (e as { line: string }).line);
  const job = await getJob(served.url, id);
  expect(job.status).toBe('failed');
  expect(job.result.message).toBe('killed: run time limit 3 s');
  expect(lines.some((l) => l.startsWith('stopping the architecture as at the end of a run'))).toBe(true);
  expect(lines, lines.slice(-30).join('\n')).toContain('all modules stopped cleanly');
  // the logs say why the run stopped: each module's KILL from the launcher
  expect(lines).toContain("stopping: the build service's run time limit was reached");
  await logsEndingWithExit(id, job, undefined, '', "the build service's run time limit was reached");
}, 240_000);

test('the memory limit hit mid-run stops the architecture as at the end of a run: every module the kernel left writes its last records and its exit record, and the killed one\'s unwritten records are written for it', async () => {
  // MSC's first release allocates without end: at the job's memory limit the kernel kills it (the
  // process using the most memory); the service then asks the launcher to stop the rest. MSC never
  // waits again after its record: only the launcher's recovery from its log buffers writes it
  const msc = 'src-gen/generated/architecture/modules/MSC_mod/module.c';
  const leak = '    ContractLog("leak_begins", "", -1, 0, "allocating without end");\n    for (;;) { char *p = malloc((size_t)16 << 20); if (p) memset(p, 1, (size_t)16 << 20); }';
  const files = withRegion(withRegion(await tutorialFiles(), msc, 'protect_exec_MSC', leak, true), msc, 'protect_additional_import_MSC', '#include <stdlib.h>\n#include <string.h>', true);
  const r = await postJob(served.url, { action: 'run', sandbox: 'bwrap', duration: 20, project: { files } });
  expect(r.status, JSON.stringify(r.json)).toBe(201);
  const id = r.json.id as string;
  const lines = (await readEvents(served.url, id)).filter((e) => e.type === 'line').map((e) => (e as { line: string }).line);
  const job = await getJob(served.url, id);
  expect(job.result.message, lines.slice(-30).join('\n')).toBe('killed: memory limit 512 MiB');
  expect(lines).toContain('memory limit 512 MiB reached: stopping the architecture as at the end of a run (what still runs after 1000 ms is killed)');
  // the service's line first, then the launcher's as it stops
  expect(lines.findIndex((l) => /^stopping(: |$)/.test(l)), lines.slice(-30).join('\n')).toBeGreaterThan(lines.indexOf('memory limit 512 MiB reached: stopping the architecture as at the end of a run (what still runs after 1000 ms is killed)'));
  expect(lines.some((l) => /^module MSC \(pid \d+\) died by signal 9 \(Killed\)/.test(l)), lines.slice(-30).join('\n')).toBe(true);
  // a kill, not a crash of its code
  expect(lines, lines.slice(-30).join('\n')).toContain("FAILED: module MSC was killed (a SIGKILL the launcher did not send: the kernel's at a memory limit, or another process's)"); // no real-time CPU bound: not a real-time run
  expect(lines.some((l) => /^module MSC: \d+ record\(s\) it had logged and not written when it ended were written to its log MSC_\S+\.csv from its log buffers$/.test(l)), lines.slice(-30).join('\n')).toBe(true);
  expect(job.result.issues).toEqual(expect.arrayContaining([expect.objectContaining({ kind: 'limit', module: 'MSC' })]));
  const mscLog = (job.artifacts as { files: { name: string }[] }).files.find((f) => f.name.startsWith('MSC_'))!;
  const mscRecords = parseLogFile({ name: mscLog.name, text: await (await fetch(`${served.url}/api/jobs/${id}/artifacts/${encodeURIComponent(mscLog.name)}`)).text() });
  // its START, then its own last record, whole (none unreadable, none twice)
  expect(mscRecords.filter((k) => k.kind === 'unknown')).toEqual([]);
  const leaking = mscRecords.filter((k) => (k as { detail?: string }).detail === 'allocating without end');
  expect(leaking, mscRecords.slice(-5).map((k) => JSON.stringify(k)).join('\n')).toHaveLength(1);
  expect(mscRecords.indexOf(leaking[0]!)).toBeGreaterThan(0);
  // the 8 others stopped as at a run's end: each log ends with its exit record; MSC's does not
  await logsEndingWithExit(id, job, 'MSC', lines.slice(-30).join('\n'), "the build service's memory limit was reached");
}, 240_000);

test('a cancel (Stop, Ctrl+C) while a limit is stopping the run does not hide the limit: the run ends by it, the cancel said', async () => {
  // MSC leaks at its first release; MSA takes 2 s in its exit region, so the limit's stop lasts its whole grace
  const msc = 'src-gen/generated/architecture/modules/MSC_mod/module.c';
  const msa = 'src-gen/generated/architecture/modules/MSA_mod/module.c';
  const leak = '    for (;;) { char *p = malloc((size_t)16 << 20); if (p) memset(p, 1, (size_t)16 << 20); }';
  let files = withRegion(withRegion(await tutorialFiles(), msc, 'protect_exec_MSC', leak, true), msc, 'protect_additional_import_MSC', '#include <stdlib.h>\n#include <string.h>', true);
  files = withRegion(files, msa, 'protect_exit_MSA', '    { struct timespec slow = { 2, 0 }; nanosleep(&slow, NULL); }', true);
  const r = await postJob(served.url, { action: 'run', sandbox: 'bwrap', duration: 20, project: { files } });
  expect(r.status, JSON.stringify(r.json)).toBe(201);
  const id = r.json.id as string;
  let cancelled = false;
  const events = await readEvents(served.url, id, (e) => {
    if (cancelled || e.type !== 'line' || !(e as { line: string }).line.startsWith('memory limit 512 MiB reached: stopping the architecture')) return;
    cancelled = true;
    void fetch(`${served.url}/api/jobs/${id}`, { method: 'DELETE' });
  });
  const lines = events.filter((e) => e.type === 'line').map((e) => (e as { line: string }).line);
  const job = await getJob(served.url, id);
  expect(cancelled, lines.slice(-30).join('\n')).toBe(true);
  expect(job.status, lines.slice(-30).join('\n')).toBe('failed');
  expect(job.result.message).toBe('killed: memory limit 512 MiB');
  expect(job.result.issues).toEqual(expect.arrayContaining([expect.objectContaining({ kind: 'limit', module: 'MSC' })]));
  expect(lines).toContain('cancel asked while the run was being stopped by the memory limit 512 MiB: it ends by the limit');
}, 240_000);
