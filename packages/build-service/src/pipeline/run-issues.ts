/**
 * What went wrong in a run that did not crash (docs/build-service-api.md "Run issues"): a module
 * ORD declared stuck, a sandbox limit hit, events lost, output or CSV logs cut or left out. A run with any of
 * them does not end `succeeded`: its result says `ok: false` and lists them in `issues`, so a
 * 4 s run of a module that never ends is never reported as a success.
 */
import { visibleText } from '@contract-studio/conventions';
import { describeLimitHit, formatBytes, memoryHeldByFiles, type LimitHit } from '../limits.js';
import { LOG_DIR, type RunArtifacts } from './artifacts.js';
import { CSV_HEADER, moduleOfLog } from '../trace/parse.js';
import { splitCsvLine } from '../trace/csv-line.js';
import { LostEvents, lostFlowText, type PostRecordFields } from '../trace/lost-events.js';

/** The end of ORD's stuck sentence for a module whose thread it saw stopped (runtime ord_stuck_cause.c). */
const STOPPED_CAUSE = ': it is stopped (by SIGSTOP, or a debugger holds it)';

export type RunIssueKind = 'module-stuck' | 'module-not-ready' | 'module-hung' | 'module-ended' | 'start-refused' | 'launcher-refused' | 'limit' | 'output-truncated' | 'events-lost' | 'log-capped' | 'log-lost' | 'log-tampered';

export interface RunIssue {
  kind: RunIssueKind;
  /** One sentence for people. */
  message: string;
  /** The module it is about (module-stuck, module-not-ready, module-hung, module-ended; start-refused: the supervisor; limit: the module the kernel killed first at the memory limit; output-truncated: the module that wrote most of the output; events-lost: the producer), or the log file (log-capped, log-lost, log-tampered). */
  module?: string;
  file?: string;
}

/** ORD's line on stderr (runtime/src/engines/ord_main.c b_stuck). */
const STUCK_LINE = /^STUCK: (([A-Za-z_]\w*) has not finished release #(\d+) after \d+ periods.*)$/;
/** The same report in ORD's CSV log (its `scheduler` records, docs/runtime-api.md). */
const STUCK_MARK = ',scheduler,,,0,stuck: ';
/** A producer's record of one event post (runtime/src/eventflow.c PostEvent). */
const EVENT_POSTED_MARK = ',event_posted,';
const STUCK_RECORD = /,scheduler,,,0,stuck: (([A-Za-z_]\w*) has not finished release #(\d+) after \d+ periods[^\n]*?)(?: \([A-Za-z_]\w*\))?\n/g;

/** A supervisor's line on stderr when the run's start request cannot start anything (runtime/src/engines/sup_main.c handle_start). */
const START_REFUSED_LINE = /^([A-Za-z_]\w*): start request from contract-launch refused: (.*)$/;
/**
 * contract-launch's line when the start request cannot be sent: it names no module of the run (a
 * supervisor of another project, a typo the client did not check), libmodule's error (src/mailbox.c).
 */
const START_UNSENT_LINE = /^error: START request to ([A-Za-z_]\w*): (.*)$/;
/**
 * contract-launch's line when a module has not looked for its first request by its ready timeout:
 * its init has not returned, and the run stops without its start request (runtime/launcher main).
 */
const NOT_READY_LINE = /^module ([A-Za-z_]\w*) is not ready after (\d+(?:\.\d+)?) s: its init has not returned/;
/** contract-launch's line once it has made its run directory, just before it starts the modules (runtime/launcher main). */
const RUN_DIR_LINE = /^run directory /;

/** contract-launch's line when a module does not end on the KILL request of the run's stop (runtime/launcher stop_all). */
const HUNG_LINE = /^module ([A-Za-z_]\w*) did not end on its KILL request within (\d+(?:\.\d+)?) s: terminating it \(SIGTERM\)$/;
/** contract-launch's line when a module's own code ended it, status 0, before the run's stop (reap). */
const ENDED_LINE = /^module ([A-Za-z_]\w*) \(pid \d+\) exited with status 0 before the run's end$/;
/** contract-launch's line for a module killed by SIGKILL it did not send (the kernel's OOM killer, at the memory limit). */
const KILLED_LINE = /^module ([A-Za-z_]\w*) \(pid \d+\) died by signal 9 \(Killed\)/;

/** contract-launch's line for a module that ended normally at the run's stop (its main returned: its log ends with its exit record). */
const EXITED_LINE = /^module ([A-Za-z_]\w*) \(pid \d+\) exited with status 0$/;
/** A `module_exit` record's count of the records its module logged (runtime/src/module_main.c). */
const EXIT_RECORDS = /,module_exit,[^,\n]*,[^,\n]*,\d+,status=-?\d+ records=(\d{1,15})\s*$/;

/** contract-launch's line about one of the modules it started (its end, whatever the cause). */
const MODULE_PID_LINE = /^module ([A-Za-z_]\w*) \(pid \d+\) /;

/**
 * What the process limit's issue adds when no module's code forked: the architecture may be too
 * big for the limit (the run gave no hint of the fix; contract check's warning is the other place).
 */
export const PROCESS_LIMIT_ADVICE = ': the limit counts threads, 2 for each module, supervisor and ORD (contract check\'s architecture-over-process-limit names a limit that fits the architecture: contract run --limit processes=N)';

/** Modules named in the one line of those a limit took down with the run (the others counted). */
const HUNG_NAMED = 8;

/**
 * ` for 2 s`, ` for 0.36 to 2 s`: how long modules did not answer their KILL request, as the
 * launcher said it; nothing when it is not known (never a `?`).
 */
function forSeconds(seconds: readonly (string | undefined)[]): string {
  const known = [...new Set(seconds.filter((s): s is string => s !== undefined))].sort((a, b) => Number(a) - Number(b));
  if (!known.length) return '';
  return known.length === 1 ? ` for ${known[0]!} s` : ` for ${known[0]!} to ${known[known.length - 1]!} s`;
}

/** Sources of output lines counted apart (a run has far fewer modules; a hostile tag stream more). */
const MAX_SOURCES = 256;

export class RunIssues {
  private readonly list: RunIssue[] = [];
  private readonly stuckSeen = new Set<string>();
  /** Modules the launcher saw killed by SIGKILL during the run (at most 16): at the memory limit, the kernel's choice. */
  private readonly killed: string[] = [];
  /** How long each module-hung issue's module did not answer the stop's KILL (s, as the launcher said): one per issue of the list. */
  private readonly hungSeconds = new Map<RunIssue, string>();
  /** Modules the launcher found not ready (at most 16): their KILL unanswered at the stop is not told again. */
  private readonly notReady = new Set<string>();
  /** Characters of output lines per source (at most MAX_SOURCES: a module tag, `launcher`, `run`): who filled the output. */
  private readonly outputChars = new Map<string, number>();

  /** Modules the launcher named with their pid (at most 256): those it started, whose logs are collected first. */
  private readonly launched = new Set<string>();
  /** Modules the launcher saw end normally at the stop (at most 256): their logs must end with their exit record. */
  private readonly exitedClean = new Set<string>();
  /** What a collected log of a module named as the runtime names logs says of itself (at most 1024 logs). */
  private readonly logs: Array<{ file: string; module: string; notWhole?: string; noExit: boolean }> = [];
  /** The modules a log was collected of, those whose shape is not checked too (a capped log, past the first 1024). */
  private readonly collected = new Set<string>();
  /** Logs already named log-tampered (once each). */
  private readonly tampered = new Set<string>();
  /** The events the run's producers posted that were lost (their logs' failed posts). */
  private readonly lostEvents = new LostEvents();
  /** The disk limit stopped the run: a log may be missing because the full disk refused it. */
  private diskFull = false;

  /** contract-launch has said its run directory: it went on to start the modules (its refusals come before). */
  private launcherStarted = false;
  /** contract-launch's last line before that (at most 300 characters kept): its refusal, when it then exits 2. */
  private launcherBefore: string | undefined;

  get all(): readonly RunIssue[] {
    return this.list;
  }

  /** The modules the launcher started, as its lines named them (artifacts.ts collectionRank). */
  get launchedModules(): ReadonlySet<string> {
    return this.launched;
  }

  /**
   * A line of the run's output, without its source's tag (any source: ORD's module tag is the
   * scheduler's name); `source`: `launcher` for contract-launch's own lines.
   */
  line(text: string, source?: string): void {
    if (source !== undefined && (this.outputChars.has(source) || this.outputChars.size < MAX_SOURCES)) {
      this.outputChars.set(source, (this.outputChars.get(source) ?? 0) + text.length + 1);
    }
    const m = STUCK_LINE.exec(text);
    if (m) this.stuck(m[2]!, m[3]!, m[1]!);
    if (source === 'launcher') {
      const named = MODULE_PID_LINE.exec(text);
      if (named && this.launched.size < 256) this.launched.add(named[1]!);
      if (RUN_DIR_LINE.test(text)) this.launcherStarted = true;
      else if (!this.launcherStarted) this.launcherBefore = text.slice(0, 300);
      this.moduleEnd(text);
      const exited = EXITED_LINE.exec(text);
      if (exited && this.exitedClean.size < 256) this.exitedClean.add(exited[1]!);
    }
    if (this.list.some((i) => i.kind === 'start-refused')) return;
    const refused = START_REFUSED_LINE.exec(text);
    if (refused) {
      this.list.push({ kind: 'start-refused', module: refused[1]!, message: `${refused[1]!} refused the run's start request: ${visibleText(refused[2]!.slice(0, 300))} (nothing was started by it)` });
      return;
    }
    // the launcher sends one START, the run's: a module's own failed requests are not the start's
    const unsent = source === 'launcher' ? START_UNSENT_LINE.exec(text) : null;
    if (unsent) {
      this.list.push({ kind: 'start-refused', module: unsent[1]!, message: `the run's start request names ${unsent[1]!}, which the launcher could not reach: ${visibleText(unsent[2]!.slice(0, 300))} (nothing was started: is ${unsent[1]!} a supervisor of this project?)` });
    }
  }

  /**
   * A log changed under the runtime's feet while the run went on (the live trace saw it shrink: the
   * runtime only appends): a process of the run truncated or rewrote it, so its records are not the
   * module's whole record.
   */
  logTampered(file: string, why: string): void {
    if (this.tampered.has(file) || this.tampered.size >= 64) return;
    this.tampered.add(file);
    this.list.push({ kind: 'log-tampered', file, message: `log ${file} was changed by a process of the run, not only appended to by its module: ${why}; its records are not the module's whole record` });
  }

  /**
   * The bytes of a collected CSV log (`file`: its name): stuck reports the output may have lost
   * (truncated), and whether the log is as its module's runtime left it — its header first, its
   * exit record last (checked against the launcher's word in artifacts()), as many records as that
   * record counts. A log the runtime or the service capped is said by log-capped instead.
   */
  log(data: Buffer, file?: string): void {
    if (file !== undefined) this.logShape(data, file);
    this.lostEventsOf(data);
    // line by line, never the whole log as one string: a log may be larger than a string can be (RUN_LOG_MAX_BYTES)
    for (let at = data.indexOf(STUCK_MARK); at >= 0;) {
      const start = data.lastIndexOf(10, at) + 1;
      const nl = data.indexOf(10, at);
      const end = nl < 0 ? data.length : nl + 1;
      for (const m of data.toString('utf8', start, end).matchAll(STUCK_RECORD)) this.stuck(m[2]!, m[3]!, m[1]!);
      at = data.indexOf(STUCK_MARK, end);
    }
  }

  /**
   * The failed posts of a log (`event_posted ... failed`, each with the runtime's `error` record
   * just before it, lost-events.ts): read line by line where the mark is, never the whole log.
   */
  private lostEventsOf(data: Buffer): void {
    const record = (start: number, end: number): PostRecordFields | undefined => {
      const f = splitCsvLine(data.toString('utf8', start, Math.min(end, start + 2048)).replace(/\r?\n$/, ''));
      return f.length >= 8 ? { module: f[2]!, kind: f[3]!, peer: f[4]!, port: f[5]!, detail: f.slice(7).join(',') } : undefined;
    };
    for (let at = data.indexOf(EVENT_POSTED_MARK); at >= 0;) {
      const start = data.lastIndexOf(10, at) + 1;
      const nl = data.indexOf(10, at);
      const end = nl < 0 ? data.length : nl + 1;
      at = data.indexOf(EVENT_POSTED_MARK, end);
      const post = record(start, end);
      if (!post || !post.detail.endsWith(' failed')) continue;
      const prevStart = start > 0 ? data.lastIndexOf(10, start - 2) + 1 : -1;
      const prev = prevStart >= 0 ? record(prevStart, start) : undefined;
      if (prev?.kind === 'error' && prev.module === post.module) this.lostEvents.see(prev);
      this.lostEvents.see(post);
    }
  }

  limit(hit: LimitHit): void {
    if (hit.name === 'workDiskMiB') this.diskFull = true;
    // at the memory limit the kernel kills the process using the most memory first: the module to look at,
    // unless the job's cgroup says its tmpfs files held most of it (the logs in the work dir): no process's doing
    const files = memoryHeldByFiles(hit);
    const first = hit.name !== 'memory'
      ? ''
      : files !== undefined
        ? ` (${formatBytes(files)} of it were the job's files in its tmpfs mounts, the work dir's logs among them, which no kill frees${this.killed.length ? `: the kernel killed ${this.killed.join(', ')}, not for its own memory` : ''})`
        : this.killed.length ? ` (the kernel killed ${this.killed.join(', ')} first: the module using the most memory)` : '';
    // at the process limit, the module whose code forks: most of the job's processes had its name
    // no module's code forking: the architecture itself may not fit (a big one at the default limit)
    const forks = hit.name !== 'processes' ? '' : hit.module ? ` (${hit.module} had ${hit.moduleProcesses ?? 'most'} of the job's processes: its code forks)` : PROCESS_LIMIT_ADVICE;
    const module = hit.name === 'memory' ? (files === undefined ? this.killed[0] : undefined) : hit.name === 'processes' ? hit.module : undefined;
    // modules that did not answer the stop's KILL while a fork bomb or a memory hog held the
    // machine: not blamed for looping (every module of a fork bomb's run was "hung")
    if (hit.name === 'processes' || hit.name === 'memory') {
      const held = `while the ${describeLimitHit(hit)} held the job${module ? ` (${module}'s doing)` : ''}: likely kept from answering by that, not by their own code`;
      const others = this.list.filter((i) => i.kind === 'module-hung' && i.module !== module);
      if (others.length === 1) {
        const issue = others[0]!;
        issue.message = `${issue.module!} did not end when the run stopped: it did not answer its KILL request${forSeconds([this.hungSeconds.get(issue)])} and was terminated, ${held.replace('their own', 'its own')}`;
      } else if (others.length > 1) {
        // the modules a limit took down with the run: one line naming how many (a run of 127
        // modules stopped by the process limit printed 127 lines, burying the limit's own)
        const names = others.map((i) => i.module!);
        const named = names.length > HUNG_NAMED ? `${names.slice(0, HUNG_NAMED).join(', ')} and ${names.length - HUNG_NAMED} more` : names.join(', ');
        const summary: RunIssue = {
          kind: 'module-hung',
          message: `${others.length} modules were stopped with the run (${named}): they did not answer their KILL request${forSeconds(others.map((i) => this.hungSeconds.get(i)))} and were terminated, ${held}`,
        };
        const at = this.list.indexOf(others[0]!);
        for (const i of others) this.list.splice(this.list.indexOf(i), 1);
        this.list.splice(at, 0, summary);
      }
    }
    // the limit that stopped the run comes first: what followed from it (modules taken down with the run) after
    this.list.unshift({ kind: 'limit', message: `the run was stopped by the ${describeLimitHit(hit)}${first}${forks}`, ...(module ? { module } : {}) });
  }

  /**
   * contract-launch ended with `status` (make's `*** [...: run] Error N`). Exit 2 with a line of
   * its own before its run directory is its refusal to start the run (too many modules, a CPU list
   * it cannot use, an executable missing...): an issue, first, rather than make's status alone.
   * Returns the refusal's message, undefined when it was none.
   */
  launcherExit(status: number): string | undefined {
    if (status !== 2 || this.launcherStarted || this.launcherBefore === undefined || this.list.some((i) => i.kind === 'launcher-refused')) return undefined;
    const message = `contract-launch refused to start the run: ${this.launcherBefore} (nothing was started)`;
    this.list.unshift({ kind: 'launcher-refused', message });
    return message;
  }

  /** The output went past its cap: said with the module that wrote most of it (its issue's `module`), when one did. */
  outputTruncated(stream: 'stdout' | 'stderr', bytes: number): void {
    const top = this.topModuleOutput();
    const who = top ? ` (${top.module} wrote ${top.percent} % of the run's output lines until then)` : '';
    this.list.push({ kind: 'output-truncated', message: `the run's ${stream} went past the output limit (${formatBytes(bytes)} per stream)${who}: later lines were not kept`, ...(top ? { module: top.module } : {}) });
  }

  /** The module (not the launcher's or make's lines) that wrote the most output so far, with its share, when it wrote half of it or more. */
  private topModuleOutput(): { module: string; percent: number } | undefined {
    let all = 0, best: string | undefined, most = 0;
    for (const [source, chars] of this.outputChars) {
      all += chars;
      if (source !== 'launcher' && source !== 'run' && source !== 'service' && chars > most) [best, most] = [source, chars];
    }
    return best && most * 2 >= all ? { module: best, percent: Math.floor((most * 100) / all) } : undefined;
  }

  private logShape(data: Buffer, file: string): void {
    const module = moduleOfLog(file);
    if (module === undefined) return;
    this.collected.add(module);
    // a capped log ends with its cap record, not its exit record: its shape is the cap's (log-capped)
    if (this.logs.length >= 1024 || data.includes(',log-capped,')) return;
    const entry: { file: string; module: string; notWhole?: string; noExit: boolean } = { file, module, noExit: true };
    this.logs.push(entry);
    if (data.length === 0) {
      entry.notWhole = 'it is empty (the runtime writes its header and its module\'s first record at start)';
      return;
    }
    if (!data.subarray(0, CSV_HEADER.length + 1).equals(Buffer.from(`${CSV_HEADER}\n`))) {
      entry.notWhole = 'it does not begin with the runtime\'s header: its beginning was cut off or it was rewritten';
      return;
    }
    let end = data.length;
    while (end > 0 && (data[end - 1] === 10 || data[end - 1] === 13)) end--;
    const lastLine = data.toString('utf8', data.lastIndexOf(10, end - 1) + 1, end);
    entry.noExit = !lastLine.includes(',module_exit,') && !lastLine.includes(',module_crashed,');
    const counted = EXIT_RECORDS.exec(lastLine)?.[1];
    if (counted === undefined) return;
    // the records of its module's last start (a log a restarted module appended to holds two)
    const started = data.lastIndexOf(`,${module},module_started,`);
    let from = started < 0 ? CSV_HEADER.length + 1 : data.lastIndexOf(10, started) + 1;
    let lines = 0;
    for (; (from = data.indexOf(10, from)) >= 0 && from < end; from++) lines++;
    lines++; // the exit record's line
    if (lines !== Number(counted)) entry.notWhole = `it holds ${lines} record(s) since its module started where its exit record counts ${counted} (records were removed or added by another process)`;
  }

  artifacts(a: RunArtifacts): void {
    // logs that are not what the runtime left: said, so that a run whose ORD log was erased or
    // replaced by a module's code is not reported as a success with that log as its record
    const logged = this.collected;
    for (const l of this.logs) {
      if (l.notWhole) this.logTampered(l.file, l.notWhole);
      else if (l.noExit && this.exitedClean.has(l.module)) this.logTampered(l.file, `it does not end with ${l.module}'s exit record although ${l.module} exited normally (status 0): it was replaced or cut by another process (the runtime appends every record, its exit record last)`);
    }
    const missing = [...this.exitedClean].filter((m) => !logged.has(m));
    // a bound of the collection left files out: a module's log missing may be among them (said there, not blamed on the run)
    const lost = lostToBounds(a);
    if (!lost.length && logged.size) {
      for (const m of missing) this.list.push({ kind: 'log-tampered', module: m, message: `${m} ran and exited normally, but no log of it was collected: a process of the run removed or renamed it` });
    } else if (!lost.length && missing.length) {
      // not one log of the run left where the runtime writes them: its logs/ was emptied, moved or replaced
      this.list.push({ kind: 'log-tampered', message: `no CSV log of the run was collected although ${listModules(missing)} ran and exited normally: a process of the run removed or renamed the logs (or ${LOG_DIR}/ itself)${this.diskFull ? ', or the full disk kept them from being written' : ''}` });
    }
    for (const f of this.lostEvents.lostFlows()) this.list.push({ kind: 'events-lost', module: visibleText(f.producer), message: visibleText(lostFlowText(f)) });
    for (const f of a.files) {
      if (f.capped) this.list.push({ kind: 'log-capped', file: f.name, message: `log ${f.name} is not whole: ${f.capped}` });
    }
    lost.forEach((l, i) => this.list.push({ kind: 'log-lost', ...(l.files.length === 1 ? { file: l.files[0]! } : {}), message: describeLost(l, i === 0 ? missing : []) }));
  }

  /** A module that did not end when the run stopped, or whose own code ended it before (the launcher's lines). */
  private moduleEnd(text: string): void {
    const notReady = NOT_READY_LINE.exec(text);
    if (notReady) {
      if (this.notReady.size < 16) this.notReady.add(notReady[1]!);
      this.list.push({ kind: 'module-not-ready', module: notReady[1]!, message: `${notReady[1]!} was not ready after ${notReady[2]!} s: its init region had not returned (does it loop or block?), so the run stopped before its start request` });
      return;
    }
    const hung = HUNG_LINE.exec(text);
    const killed = KILLED_LINE.exec(text);
    if (killed && this.killed.length < 16) this.killed.push(killed[1]!);
    // a module not ready does not answer the stop's KILL either: the same fault, told once
    if (hung && this.notReady.has(hung[1]!)) return;
    if (hung) {
      // what ORD saw of it when it declared it stuck, when it saw it stopped: the advice about its code does not fit
      const stopped = this.list.some((i) => i.kind === 'module-stuck' && i.module === hung[1] && i.message.endsWith(STOPPED_CAUSE));
      const why = stopped ? 'ORD saw it stopped: by SIGSTOP, or a debugger holds it' : 'does a region of it loop or block: its exec or exit code?';
      const issue: RunIssue = { kind: 'module-hung', module: hung[1]!, message: `${hung[1]!} did not end when the run stopped: it did not answer its KILL request for ${hung[2]!} s and was terminated (${why})` };
      this.hungSeconds.set(issue, hung[2]!);
      this.list.push(issue);
      return;
    }
    const ended = ENDED_LINE.exec(text);
    if (ended) this.list.push({ kind: 'module-ended', module: ended[1]!, message: `${ended[1]!} ended before the run did: its code exited with status 0, and the run went on without it` });
  }

  private stuck(module: string, release: string, message: string): void {
    const key = `${module}#${release}`;
    if (this.stuckSeen.has(key)) return;
    this.stuckSeen.add(key);
    this.list.push({ kind: 'module-stuck', module, message });
  }
}

/** Files a bound of the collection left out, for one reason (the count bound, the total bound). */
interface LostToBound {
  reason: string;
  files: string[];
}

/** The files of `a` a bound left out, grouped by why, in the order they were met. */
function lostToBounds(a: RunArtifacts): LostToBound[] {
  const byReason = new Map<string, string[]>();
  for (const s of a.skipped) {
    if (s.bound) (byReason.get(s.reason) ?? byReason.set(s.reason, []).get(s.reason)!).push(s.name);
  }
  return [...byReason].map(([reason, files]) => ({ reason, files }));
}

/** Names shown of a list, the rest counted. */
const NAMES_SHOWN = 3;

function listNames(names: readonly string[]): string {
  const shown = names.slice(0, NAMES_SHOWN).join(', ');
  return names.length > NAMES_SHOWN ? `${shown} and ${names.length - NAMES_SHOWN} more` : shown;
}

const listModules = (modules: readonly string[]): string => (modules.length === 1 ? modules[0]! : listNames(modules));

/**
 * One sentence for all the files one bound left out (a module writing thousands of files into
 * logs/ is one problem, not one per file): `log X was not collected: …`, or `1244 files of logs/
 * were not collected: more than 256 files (F_1.csv, … )`, with the modules whose log was not collected.
 */
function describeLost(l: LostToBound, missing: readonly string[]): string {
  const what = l.files.length === 1 ? `log ${l.files[0]!} was` : `${l.files.length} files of ${LOG_DIR}/ were`;
  const where = l.files.length === 1 ? '' : ` (${listNames(l.files)})`;
  const modules = missing.length ? `; no log of ${listModules(missing)}, which exited normally, was collected: it may be among them` : '';
  const why = l.reason.startsWith('more than ') ? `${LOG_DIR}/ held ${l.reason}` : l.reason;
  return `${what} not collected: ${why}${where}${modules}`;
}

/** "run finished with 2 problem(s): CTL has not finished …; log X is not whole: …". */
export function describeIssues(issues: readonly RunIssue[]): string {
  return `${issues.length} problem(s): ${issues.map((i) => i.message).join('; ')}`;
}
