import { describe, expect, test } from 'vitest';
import { PROCESS_LIMIT_ADVICE, RunIssues } from './run-issues.js';

describe('RunIssues', () => {
  test("a stuck module is one issue, whether seen in ORD's output, in its CSV log, or both", () => {
    const r = new RunIssues();
    r.line('STUCK: CTL has not finished release #2 after 100 periods: does its exec region set *stateindex = -1?');
    r.line('STUCK: CTL has not finished release #2 after 100 periods: does its exec region set *stateindex = -1?');
    r.log(Buffer.from(
      'mono_ns,wall_time,module,event,peer,port,size,detail\n' +
      '5,t,ORD,scheduler,,,0,stuck: CTL has not finished release #2 after 100 periods: does its exec region set *stateindex = -1? (goTo)\n' +
      '6,t,ORD,scheduler,,,0,stuck: LOC has not finished release #9 after 10 periods: does its exec region set *stateindex = -1? (goTo)\n' +
      // a release that outlived its activation (its supervisor deactivated the schema on ORD:0)
      '7,t,ORD,scheduler,,,0,stuck: GRP has not finished release #6 after 50 periods (of a deactivated activation): does its exec region set *stateindex = -1? (pick)\n',
    ));
    r.line('overrun: goTo cycle still running, release skipped');
    expect(r.all).toEqual([
      { kind: 'module-stuck', module: 'CTL', message: 'CTL has not finished release #2 after 100 periods: does its exec region set *stateindex = -1?' },
      { kind: 'module-stuck', module: 'LOC', message: 'LOC has not finished release #9 after 10 periods: does its exec region set *stateindex = -1?' },
      { kind: 'module-stuck', module: 'GRP', message: 'GRP has not finished release #6 after 50 periods (of a deactivated activation): does its exec region set *stateindex = -1?' },
    ]);
  });

  test('a collected log larger than a string can be (ORD\'s, up to RUN_LOG_MAX_BYTES) is still read for stuck records', () => {
    const r = new RunIssues();
    const head = Buffer.from('mono_ns,wall_time,module,event,peer,port,size,detail\n5,t,ORD,scheduler,,,0,start\n');
    const stuck = Buffer.from('6,t,ORD,scheduler,,,0,stuck: CTL has not finished release #2 after 100 periods: does its exec region set *stateindex = -1? (goTo)\n');
    // 600 MB of zeros (untouched pages: no memory taken) between them: past V8's longest string (2^29 - 24 characters)
    const big = Buffer.alloc(head.length + 600_000_000 + 1 + stuck.length);
    head.copy(big, 0);
    big[big.length - stuck.length - 1] = 10;
    stuck.copy(big, big.length - stuck.length);
    expect(() => r.log(big, 'ORD_7-Dec-2026-08h00m00s.csv')).not.toThrow();
    expect(r.all).toEqual([
      { kind: 'module-stuck', module: 'CTL', message: 'CTL has not finished release #2 after 100 periods: does its exec region set *stateindex = -1?' },
    ]);
  });

  test("the run's start request refused by its supervisor is an issue (once); a control tool's, or an activation another supervisor refused, is not", () => {
    const r = new RunIssues();
    r.line("STA: start request from contract-control refused: STA.station has no parameter 'sped'");
    r.line('SUP: start refused: activation #2 of SUP.action from GLB: function action already running');
    expect(r.all).toEqual([]);
    r.line("STA: start request from contract-launch refused: STA.station has no parameter 'sped'");
    r.line("STA: start request from contract-launch refused: STA.station has no parameter 'sped'");
    expect(r.all).toEqual([
      { kind: 'start-refused', module: 'STA', message: "STA refused the run's start request: STA.station has no parameter 'sped' (nothing was started by it)" },
    ]);
  });

  test("a start request naming no module of the run (the launcher could not send it) is an issue; a module's own failed START is not", () => {
    const r = new RunIssues();
    const line = 'error: START request to GLB: unknown module (no mailbox in the run directory) (No such file or directory)';
    r.line(line, 'MIS'); // a supervisor's request of its own, its tag taken off
    r.line(line);
    expect(r.all).toEqual([]);
    r.line(line, 'launcher');
    r.line(line, 'launcher');
    expect(r.all).toEqual([{
      kind: 'start-refused', module: 'GLB',
      message: "the run's start request names GLB, which the launcher could not reach: unknown module (no mailbox in the run directory) (No such file or directory) (nothing was started: is GLB a supervisor of this project?)",
    }]);
  });

  test("the launcher's words for a module that did not end on its KILL, or that its own code ended mid-run, are issues; a module's own lines of the same words are not", () => {
    const r = new RunIssues();
    for (const source of ['MSC', undefined]) {
      r.line('module MSC did not end on its KILL request within 2 s: terminating it (SIGTERM)', source);
      r.line("module MAA (pid 17) exited with status 0 before the run's end", source);
    }
    // a clean end, a stop-time end, a crash (the launcher's FAILED line is the crash's report)
    r.line('module MAB (pid 18) exited with status 0', 'launcher');
    r.line('module MSB (pid 19) terminated by signal 15 (Terminated)', 'launcher');
    r.line('module MSD (pid 20) died by signal 11 (Segmentation fault) while the run stopped', 'launcher');
    expect(r.all).toEqual([]);
    r.line('module MSC did not end on its KILL request within 2 s: terminating it (SIGTERM)', 'launcher');
    r.line("module MAA (pid 17) exited with status 0 before the run's end", 'launcher');
    expect(r.all).toEqual([
      { kind: 'module-hung', module: 'MSC', message: 'MSC did not end when the run stopped: it did not answer its KILL request for 2 s and was terminated (does a region of it loop or block: its exec or exit code?)' },
      { kind: 'module-ended', module: 'MAA', message: 'MAA ended before the run did: its code exited with status 0, and the run went on without it' },
    ]);
  });

  test('a module ORD saw stopped (SIGSTOP, a debugger) that then did not end is told so, not asked whether its code loops', () => {
    const r = new RunIssues();
    r.line('STUCK: MON has not finished release #7 after 100 periods: it is stopped (by SIGSTOP, or a debugger holds it)', 'ORD');
    r.line('module MON did not end on its KILL request within 2 s: terminating it (SIGTERM)', 'launcher');
    r.line('module LOC did not end on its KILL request within 2 s: terminating it (SIGTERM)', 'launcher');
    expect(r.all.filter((i) => i.kind === 'module-hung').map((i) => i.message)).toEqual([
      'MON did not end when the run stopped: it did not answer its KILL request for 2 s and was terminated (ORD saw it stopped: by SIGSTOP, or a debugger holds it)',
      'LOC did not end when the run stopped: it did not answer its KILL request for 2 s and was terminated (does a region of it loop or block: its exec or exit code?)',
    ]);
  });

  test('a stop fitted in the cancel grace (CONTRACT_STOP_BUDGET_MS) says its own wait, and the issue says the same', () => {
    const r = new RunIssues();
    r.line('module VEL did not end on its KILL request within 0.36 s: terminating it (SIGTERM)', 'launcher');
    expect(r.all).toEqual([
      { kind: 'module-hung', module: 'VEL', message: 'VEL did not end when the run stopped: it did not answer its KILL request for 0.36 s and was terminated (does a region of it loop or block: its exec or exit code?)' },
    ]);
  });

  test("the launcher's word for a module whose init never returned is an issue, told once (not again as hung at the stop)", () => {
    const r = new RunIssues();
    const notReady = 'module MSC is not ready after 10 s: its init has not returned (does its init region loop or block?); the run stops without its start request';
    r.line(notReady, 'MSC'); // a module's own words: not the launcher's
    expect(r.all).toEqual([]);
    r.line(notReady, 'launcher');
    r.line('module MSC did not end on its KILL request within 2 s: terminating it (SIGTERM)', 'launcher');
    r.line('module MAA did not end on its KILL request within 2 s: terminating it (SIGTERM)', 'launcher');
    expect(r.all).toEqual([
      { kind: 'module-not-ready', module: 'MSC', message: 'MSC was not ready after 10 s: its init region had not returned (does it loop or block?), so the run stopped before its start request' },
      { kind: 'module-hung', module: 'MAA', message: 'MAA did not end when the run stopped: it did not answer its KILL request for 2 s and was terminated (does a region of it loop or block: its exec or exit code?)' },
    ]);
  });

  test('capped and lost logs, limits and cut output are issues; a whole log is not', () => {
    const r = new RunIssues();
    r.artifacts({
      files: [
        { name: 'A_1.csv', path: 'logs/A_1.csv', size: 3, gzip: Buffer.alloc(0), capped: null },
        { name: 'B_1.csv', path: 'logs/B_1.csv', size: 3, gzip: Buffer.alloc(0), capped: 'the module reached its CSV log bound' },
      ],
      skipped: [{ name: 'link.csv', reason: 'not a regular file (symlink): not followed' }, { name: 'C_1.csv', reason: 'more than 256 files', bound: true }],
      runDirLeftovers: [],
    });
    r.line('module MSC (pid 29) died by signal 9 (Killed)', 'MSA'); // a module's own words: not the launcher's
    r.limit({ name: 'runSeconds', value: 60, unit: 's', mechanism: 'service-timer' });
    // at the memory limit, the module the kernel killed first is named (the launcher's line only)
    const memory = new RunIssues();
    memory.line('module MSC (pid 29) died by signal 9 (Killed)', 'launcher');
    memory.limit({ name: 'memory', value: 512 * 1024 * 1024, unit: 'bytes', mechanism: 'service-check' });
    expect(memory.all.map((i) => i.message)).toEqual([expect.stringMatching(/^the run was stopped by the memory limit 512 MiB.* \(the kernel killed MSC first: the module using the most memory\)$/)]);
    expect(memory.all.map((i) => i.module)).toEqual(['MSC']);
    // ... unless the job's cgroup says its tmpfs files (the work dir's logs) held most of the memory:
    // the kernel then kills processes that are not the cause, and no module is blamed
    const files = new RunIssues();
    files.line('module MSC (pid 29) died by signal 9 (Killed)', 'launcher');
    files.limit({ name: 'memory', value: 512 * 1024 * 1024, unit: 'bytes', mechanism: 'cgroup-v1', memoryFilesBytes: 490 * 1024 * 1024 });
    expect(files.all.map((i) => i.message)).toEqual([
      expect.stringMatching(/^the run was stopped by the memory limit 512 MiB.* \(490 MiB of it were the job's files in its tmpfs mounts, the work dir's logs among them, which no kill frees: the kernel killed MSC, not for its own memory\)$/),
    ]);
    expect(files.all.map((i) => i.module)).toEqual([undefined]);
    // a memory hog's own memory (the files a small part): named as before
    const hog = new RunIssues();
    hog.line('module MSC (pid 29) died by signal 9 (Killed)', 'launcher');
    hog.limit({ name: 'memory', value: 512 * 1024 * 1024, unit: 'bytes', mechanism: 'cgroup-v1', memoryFilesBytes: 3 * 1024 * 1024 });
    expect(hog.all.map((i) => [i.module, /the module using the most memory\)$/.test(i.message)])).toEqual([['MSC', true]]);
    // at the process limit, the module most of the job's processes descended from
    const forks = new RunIssues();
    forks.limit({ name: 'processes', value: 256, unit: 'count', mechanism: 'cgroup-v1', module: 'HMI', moduleProcesses: 241 });
    forks.limit({ name: 'processes', value: 256, unit: 'count', mechanism: 'cgroup-v1' });
    expect(forks.all.map((i) => [i.module, i.message])).toEqual([
      [undefined, `the run was stopped by the process limit 256${PROCESS_LIMIT_ADVICE}`],
      ['HMI', "the run was stopped by the process limit 256 (HMI had 241 of the job's processes: its code forks)"],
    ]);
    // a fork bomb's run: the modules that did not answer the stop's KILL in time are not blamed for looping
    const bomb = new RunIssues();
    bomb.line('module MSA did not end on its KILL request within 2 s: terminating it (SIGTERM)', 'launcher');
    bomb.line('module MAB did not end on its KILL request within 2 s: terminating it (SIGTERM)', 'launcher');
    bomb.limit({ name: 'processes', value: 256, unit: 'count', mechanism: 'cgroup-v1', module: 'MSA', moduleProcesses: 250 });
    expect(bomb.all.map((i) => [i.kind, i.module, i.message])).toEqual([
      ['limit', 'MSA', "the run was stopped by the process limit 256 (MSA had 250 of the job's processes: its code forks)"],
      ['module-hung', 'MSA', 'MSA did not end when the run stopped: it did not answer its KILL request for 2 s and was terminated (does a region of it loop or block: its exec or exit code?)'],
      ['module-hung', 'MAB', "MAB did not end when the run stopped: it did not answer its KILL request for 2 s and was terminated, while the process limit 256 held the job (MSA's doing): likely kept from answering by that, not by its own code"],
    ]);
    r.outputTruncated('stdout', 1024 * 1024);
    expect(r.all.map((i) => [i.kind, i.file ?? null, i.message])).toEqual([
      ['limit', null, 'the run was stopped by the run time limit 60 s'],
      ['log-capped', 'B_1.csv', 'log B_1.csv is not whole: the module reached its CSV log bound'],
      ['log-lost', 'C_1.csv', 'log C_1.csv was not collected: logs/ held more than 256 files'],
      ['output-truncated', null, "the run's stdout went past the output limit (1 MiB per stream) (MSA wrote 100 % of the run's output lines until then): later lines were not kept"],
    ]);
  });

  test('names the module that filled the output when it wrote half of it or more; not the launcher, not a module of a small share', () => {
    const flood = new RunIssues();
    flood.line('module CTL (pid 9) started', 'launcher');
    for (let i = 0; i < 30; i++) flood.line(`CTL flood line ${i}`, 'CTL');
    flood.line('ok', 'ENC');
    flood.outputTruncated('stdout', 1024 * 1024);
    expect(flood.all.map((i) => [i.module, i.message])).toEqual([
      ['CTL', expect.stringMatching(/^the run's stdout went past the output limit \(1 MiB per stream\) \(CTL wrote 9\d % of the run's output lines until then\): later lines were not kept$/)],
    ]);
    const launcher = new RunIssues();
    for (let i = 0; i < 30; i++) launcher.line(`a long line of the launcher's own, number ${i}`, 'launcher');
    launcher.line('x', 'CTL');
    launcher.outputTruncated('stderr', 1024);
    const shared = new RunIssues();
    for (let i = 0; i < 30; i++) ['A', 'B', 'C'].forEach((m) => shared.line(`line ${i}`, m));
    shared.outputTruncated('stdout', 1024);
    expect([...launcher.all, ...shared.all].map((i) => i.module)).toEqual([undefined, undefined]);
    expect(shared.all[0]!.message).toBe("the run's stdout went past the output limit (1 KiB per stream): later lines were not kept");
  });

  describe("a log a process of the run erased, cut or replaced (log-tampered)", () => {
    const H = 'mono_ns,wall_time,module,event,peer,port,size,detail\n';
    const ORD = 'ORD_7-Dec-2026-00h08m44s.csv';
    const whole = `${H}1,t,ORD,module_started,,,0,pid=24 priority=90\n2,t,ORD,priority,,,0,nice 1 (priority 90)\n3,t,ORD,module_exit,,,0,status=0 records=3\n`;
    const none = { files: [], skipped: [], runDirLeftovers: [] };
    const issuesOf = (data: string, launcher = 'module ORD (pid 24) exited with status 0') => {
      const r = new RunIssues();
      r.line(launcher, 'launcher');
      r.log(Buffer.from(data), ORD);
      r.artifacts(none);
      return r.all.map((i) => [i.kind, i.file ?? i.module, i.message]);
    };

    test("ORD's whole log is no issue; one truncated, replaced, grown by another process or gone is one, naming it", () => {
      expect(issuesOf(whole)).toEqual([]);
      // truncate(ORD's log, 0) then ORD appended on: no header any more
      expect(issuesOf('4,t,ORD,request_received,contract-launch,,0,KILL\n5,t,ORD,module_exit,,,0,status=0 records=5\n')).toEqual([['log-tampered', ORD, expect.stringMatching(/does not begin with the runtime's header/)]]);
      expect(issuesOf('')).toEqual([['log-tampered', ORD, expect.stringMatching(/it is empty/)]]);
      // a copy renamed over it: ORD wrote its exit record to the unlinked file
      expect(issuesOf(`${H}1,t,ORD,module_started,,,0,pid=24 priority=90\n`)).toEqual([['log-tampered', ORD, expect.stringMatching(/does not end with ORD's exit record although ORD exited normally/)]]);
      // ... which is said only of a module that exited normally (a killed one writes no exit record)
      expect(issuesOf(`${H}1,t,ORD,module_started,,,0,pid=24 priority=90\n`, 'module ORD (pid 24) terminated by signal 15')).toEqual([]);
      // lines added or removed by another process: the exit record counts what its module logged
      expect(issuesOf(whole.replace('\n3,', '\n2,t,ORD,ord_deadline_miss,,,0,schema=S cycle=1 tick_ns=1\n3,'))).toEqual([['log-tampered', ORD, expect.stringMatching(/holds 4 record\(s\) since its module started where its exit record counts 3/)]]);
      // a capped log is said by log-capped
      expect(issuesOf(`${H}1,t,ORD,log-capped,,,4096,log reached its 4096-byte bound\n`)).toEqual([]);
      // ... and it is collected: its module's log is not said gone (a real run's capped MSC was)
      const capped = new RunIssues();
      capped.line('module MSC (pid 31) exited with status 0', 'launcher');
      capped.log(Buffer.from(whole), ORD);
      capped.log(Buffer.from(`${H}1,t,MSC,log-capped,,,4096,log reached its 4096-byte bound\n`), 'MSC_7-Dec-2026-00h08m44s.csv');
      capped.artifacts(none);
      expect(capped.all).toEqual([]);
      // its log gone altogether (unlinked or renamed away), the others collected
      const r = new RunIssues();
      r.line('module ORD (pid 24) exited with status 0', 'launcher');
      r.log(Buffer.from(whole.replace(/ORD/g, 'MSA')), 'MSA_7-Dec-2026-00h08m44s.csv');
      r.artifacts(none);
      expect(r.all).toEqual([{ kind: 'log-tampered', module: 'ORD', message: 'ORD ran and exited normally, but no log of it was collected: a process of the run removed or renamed it' }]);
    });

    test("no log at all collected of a run whose modules exited normally (its logs/ moved away and made anew) is one log-tampered issue", () => {
      const r = new RunIssues();
      for (const [m, pid] of [['MIS', 23], ['LOC', 21], ['CTL', 22], ['ORD', 20]] as const) r.line(`module ${m} (pid ${pid}) exited with status 0`, 'launcher');
      r.artifacts(none);
      expect(r.all).toEqual([{ kind: 'log-tampered', message: 'no CSV log of the run was collected although MIS, LOC, CTL and 1 more ran and exited normally: a process of the run removed or renamed the logs (or logs/ itself)' }]);
      // at the disk limit, the full disk may have refused them
      const full = new RunIssues();
      full.line('module MIS (pid 23) exited with status 0', 'launcher');
      full.limit({ name: 'workDiskMiB', value: 256 * 1024 * 1024, unit: 'bytes', mechanism: 'service-check' });
      full.artifacts(none);
      expect(full.all.map((i) => [i.kind, i.message])).toEqual([
        ['limit', 'the run was stopped by the disk limit 256 MiB (work dir)'],
        ['log-tampered', 'no CSV log of the run was collected although MIS ran and exited normally: a process of the run removed or renamed the logs (or logs/ itself), or the full disk kept them from being written'],
      ]);
      // a run no module of which the launcher saw end normally (killed, crashed) has no such issue
      const killed = new RunIssues();
      killed.line('module ORD (pid 24) terminated by signal 15', 'launcher');
      killed.artifacts(none);
      expect(killed.all).toEqual([]);
    });

    test("files a bound of the collection left out are one log-lost issue, naming the modules whose log may be among them, not one per file nor a module's log said removed", () => {
      const r = new RunIssues();
      r.line('module MIS (pid 23) exited with status 0', 'launcher');
      r.line('module ORD (pid 24) exited with status 0', 'launcher');
      r.log(Buffer.from(whole), ORD);
      const skipped = Array.from({ length: 1244 }, (_, i) => ({ name: `F_${i + 256}.csv`, reason: 'more than 256 files', bound: true as const }));
      r.artifacts({ files: [], skipped: [{ name: '.x', reason: 'name not allowed (letters, digits, _ . - only)' }, ...skipped], runDirLeftovers: [] });
      expect(r.all).toEqual([{ kind: 'log-lost', message: '1244 files of logs/ were not collected: logs/ held more than 256 files (F_256.csv, F_257.csv, F_258.csv and 1241 more); no log of MIS, which exited normally, was collected: it may be among them' }]);
    });

    test("a start request's refusal text (a module's words) is written visibly in its issue", () => {
      const r = new RunIssues();
      r.line('STA: start request from contract-launch refused: bad\u001b[2J\u202eevil', 'STA');
      expect(r.all.map((i) => i.message)).toEqual(["STA refused the run's start request: bad\\u001b[2J\\u202eevil (nothing was started by it)"]);
    });

    test('a log the live trace saw shrink is one issue, once', () => {
      const r = new RunIssues();
      r.logTampered(ORD, 'it shrank while the run went on (219 -> 0 bytes; the runtime only appends to a log)');
      r.log(Buffer.from('5,t,ORD,module_exit,,,0,status=0 records=5\n'), ORD);
      r.artifacts(none);
      expect(r.all).toEqual([{ kind: 'log-tampered', file: ORD, message: `log ${ORD} was changed by a process of the run, not only appended to by its module: it shrank while the run went on (219 -> 0 bytes; the runtime only appends to a log); its records are not the module's whole record` }]);
    });
  });
  test('a run the process limit stopped: the limit first, the 127 modules it took down with the run in one line, every duration a number', () => {
    // the field tester's 120 modules + 7 supervisors + ORD at the default process limit: 127 of them did not answer the stop's KILL
    const r = new RunIssues();
    const names = Array.from({ length: 127 }, (_v, i) => `M${String(i).padStart(3, '0')}`);
    for (const [i, m] of names.entries()) r.line(`module ${m} did not end on its KILL request within ${i % 2 ? '0.36' : '1'} s: terminating it (SIGTERM)`, 'launcher');
    r.limit({ name: 'processes', value: 256, unit: 'count', mechanism: 'cgroup-v1' });
    expect(r.all.map((i) => [i.kind, i.message])).toEqual([
      ['limit', `the run was stopped by the process limit 256${PROCESS_LIMIT_ADVICE}`],
      ['module-hung', '127 modules were stopped with the run (M000, M001, M002, M003, M004, M005, M006, M007 and 119 more): they did not answer their KILL request for 0.36 to 1 s and were terminated, while the process limit 256 held the job: likely kept from answering by that, not by their own code'],
    ]);
    expect(r.all.map((i) => i.message).join('\n')).not.toContain('?');
    // past the 64th module's line the duration was lost (`for ? s`): every one is kept, at the memory limit too
    const one = new RunIssues();
    for (const m of names.slice(0, 70)) one.line(`module ${m} did not end on its KILL request within 2 s: terminating it (SIGTERM)`, 'launcher');
    one.limit({ name: 'memory', value: 512 * 1024 * 1024, unit: 'bytes', mechanism: 'service-check' });
    expect(one.all).toHaveLength(2);
    expect(one.all[1]!.message).toMatch(/^70 modules were stopped with the run \(M000, .* and 62 more\): they did not answer their KILL request for 2 s and were terminated, while the memory limit 512 MiB/);
    // the module whose code forks keeps its own line; the others are summarised after the limit
    const last = new RunIssues();
    for (const m of names.slice(0, 70)) last.line(`module ${m} did not end on its KILL request within 2 s: terminating it (SIGTERM)`, 'launcher');
    last.limit({ name: 'processes', value: 256, unit: 'count', mechanism: 'cgroup-v1', module: 'M000', moduleProcesses: 200 });
    expect(last.all[0]!.kind).toBe('limit');
    expect(last.all.map((i) => i.message).join('\n')).not.toContain('for ? s');
  });
  test("contract-launch's refusal before it starts anything (exit 2) is an issue, first; its exit 2 after starting the modules is not one", () => {
    const r = new RunIssues();
    r.line('make -C /work/gen run', 'run');
    r.line('too many modules: 257 module executables given, at most 256 (ORD and the supervisors count)', 'launcher');
    r.line('/tmp/x.contract:1:8: info: something else', 'run');
    expect(r.launcherExit(2)).toBe('contract-launch refused to start the run: too many modules: 257 module executables given, at most 256 (ORD and the supervisors count) (nothing was started)');
    expect(r.all.map((i) => [i.kind, i.message])).toEqual([
      ['launcher-refused', 'contract-launch refused to start the run: too many modules: 257 module executables given, at most 256 (ORD and the supervisors count) (nothing was started)'],
    ]);
    expect(r.launcherExit(2)).toBeUndefined(); // told once
    const started = new RunIssues();
    started.line('modules pinned to CPUs 1', 'launcher');
    started.line('run directory /tmp/contract-run-x', 'launcher');
    started.line('fork: Resource temporarily unavailable', 'launcher');
    expect(started.launcherExit(2)).toBeUndefined();
    expect(started.all).toEqual([]);
    const other = new RunIssues();
    other.line('--cpus 7: CPU 7 is not online', 'launcher');
    expect(other.launcherExit(1)).toBeUndefined(); // not a refusal's status
    expect(other.launcherExit(2)).toMatch(/^contract-launch refused to start the run: --cpus 7/);
  });

  test('failed event posts in a log are one events-lost issue per flow; those to a subscriber gone at the run\'s stop are none', () => {
    const H = 'mono_ns,wall_time,module,event,peer,port,size,detail\n';
    const full = '1,t,BAT,error,,,0,"EVENT request to GCS: mailbox full (Resource temporarily unavailable)"\n2,t,BAT,event_posted,GCS,0,8,to_port=1 failed\n';
    const atStop = '3,t,BAT,error,,,0,EVENT request to GCS: unknown module (No such file or directory; the run is stopping)\n4,t,BAT,event_posted,GCS,0,8,to_port=1 failed\n';
    const issues = (text: string) => {
      const r = new RunIssues();
      r.log(Buffer.from(H + text), 'BAT_7-Dec-2026-00h08m44s.csv');
      r.artifacts({ files: [], skipped: [], runDirLeftovers: [] });
      return r.all;
    };
    expect(issues(`0,t,BAT,event_posted,GCS,0,8,to_port=1\n${full}${full}${atStop}`)).toEqual([{
      kind: 'events-lost', module: 'BAT',
      message: '2 events BAT posted to GCS were lost (BAT:0 -> GCS:1): their posts failed (PostEvent gives up after waiting 2 s for room in GCS\'s full mailbox, at once when GCS is not running); the last: EVENT request to GCS: mailbox full (Resource temporarily unavailable)',
    }]);
    expect(issues(`0,t,BAT,event_posted,GCS,0,8,to_port=1\n${atStop}`)).toEqual([]);
  });
});
