import type { BuildPanel } from '../build/build-panel.js';
import type { Workspace } from '../workspace/workspace.js';
import { fetchJobLogs, type RunLogs } from '../views/run-logs.js';
import { jobStatusText } from '../build/job-end.js';
import { askFields, type FieldsProblem, type FieldValues } from '../util/dialog.js';
import { toast } from '../util/toast.js';
import { Emitter } from '../util/emitter.js';
import { reportError } from './report-error.js';
import { StdinRowProblem, keptStdin, stdinFromRows, stdinRows } from './stdin-setting.js';
import { readRunSettings, saveRunSettings, isReadyTimeout } from './run-settings-store.js';
import { MIN_READY_TIMEOUT_SECONDS, isCpuList } from '@contract-studio/conventions';
import type { SharedJob } from '../../server/api-types.js';

/**
 * The job this tab follows or followed last, kept for a reload (sessionStorage: one per tab):
 * { jobId, action, project, ended, stopped, otherTabs, gone }. Replaced by the next job the tab follows;
 * removed when the build service no longer knows a job that had ended (it left the service's last
 * 50); one lost with the IDE server (`gone`) is kept, and every reload says it gone again.
 */
const FOLLOWED_JOB_KEY = 'contract-studio:followed-job';
/** How soon after this tab's job was cancelled from elsewhere a job another tab announces is taken for its replacement. */
const REPLACED_WITHIN_MS = 10_000;
const JOB_ID = /^[A-Za-z0-9_-]{1,100}$/;
/**
 * The job a tab follows or followed last, whether it had ended (a reload shows it again), whether
 * this tab stopped it, for a job another tab started, what it was (its status says so again
 * after a reload), and whether it was lost with the IDE server (a reload says it gone again, in
 * the tab that started it as in those that followed it, and the Monitor lists its run so). `action`:
 * a build or a Build & Run (not kept by earlier versions).
 */
type Followed = { jobId: string; action?: 'build' | 'run'; project: string; ended: boolean; stopped?: boolean; otherTabs?: SharedWhat; gone?: boolean };
type SharedWhat = 'Build & Run' | 'build';

/** Build & Run, Stop, the run settings dialog, the job's status, and the finished run's CSV logs. */
export class RunController {
  /** A finished run's logs, fetched from the build service (the Monitor and the Timeline show them). */
  readonly onRunLogs = new Emitter<{ jobId: string; logs: RunLogs }>();
  /**
   * After a reload: the Build & Run this tab followed is lost with the IDE server (the restarted
   * service does not know it, and collected no logs of it): the Monitor lists its run so.
   */
  readonly onLostRun = new Emitter<{ jobId: string }>();
  /** The project folder of the last Build & Run (gcc paths are relative to its src-gen/). */
  project = '';
  /** The last job another tab started while this tab was busy with its own (not followed then). */
  private passedOver: SharedJob | undefined;
  /**
   * This tab's last job cancelled from elsewhere, and when: the job another tab announces next, soon
   * after, is the one that replaced it, whichever of the two news came first (on a loaded machine the
   * announcement can come after the end of the job it replaced).
   */
  private cancelledHere: { jobId: string; at: number } | undefined;

  constructor(private readonly d: {
    workspace: Workspace; build: BuildPanel;
    toolbar: { run: HTMLButtonElement; stop: HTMLButtonElement; runSettings: HTMLButtonElement }; jobStatus: HTMLElement;
    showPanel(id: string): void; project(): string;
  }) {
    const { build, toolbar } = d;
    toolbar.runSettings.addEventListener('click', () => void this.editSettings());
    toolbar.run.addEventListener('click', () => void this.run());
    toolbar.stop.addEventListener('click', () => void this.stop());
    build.onStatus.on(({ status, message, running }) => {
      toolbar.run.disabled = running;
      toolbar.stop.disabled = !running;
      d.jobStatus.textContent = jobStatusText(status, message, running);
      d.jobStatus.dataset.status = status;
    });
    // a finished run's CSV logs (collected from the sandbox by the build service) feed the timeline
    // (the job stays this tab's after its end: a reload shows it again, its log, the Monitor and its logs)
    build.onFinished.on(({ jobId, action, cancelledElsewhere, gone }) => {
      const f = this.followed();
      if (f?.jobId === jobId) this.keep({ ...f, ended: true, ...(gone ? { gone: true } : {}) });
      // a job gone with the IDE server left no logs to fetch
      if (action === 'run' && !gone) void this.fetchLogs(jobId);
      // cancelled by another tab's Build & Run, announced while this tab was busy: its new run is
      // followed now (the run this one was replaced by); after any other end the log stays
      const next = this.passedOver;
      this.passedOver = undefined;
      this.cancelledHere = cancelledElsewhere ? { jobId, at: Date.now() } : undefined;
      if (cancelledElsewhere && next && next.id !== jobId) void this.followShared(next, { replacing: jobId });
    });
    build.onStarted.on(({ jobId, action }) => this.keep({ jobId, action, project: this.project, ended: false }));
  }

  private keep(f: Followed): void {
    try {
      sessionStorage.setItem(FOLLOWED_JOB_KEY, JSON.stringify(f));
    } catch {
      /* storage full or refused: a reload then loses the job's stream, not the job */
    }
  }

  /** The job this tab followed before a reload, as kept (anything else there is ignored). */
  private followed(): Followed | undefined {
    try {
      const v = JSON.parse(sessionStorage.getItem(FOLLOWED_JOB_KEY) ?? 'null') as { jobId?: unknown; action?: unknown; project?: unknown; ended?: unknown; stopped?: unknown; otherTabs?: unknown; gone?: unknown } | null;
      if (v && typeof v.jobId === 'string' && JOB_ID.test(v.jobId)) {
        const otherTabs = v.otherTabs === 'Build & Run' || v.otherTabs === 'build' ? { otherTabs: v.otherTabs as SharedWhat } : {};
        const action = v.action === 'build' || v.action === 'run' ? { action: v.action as 'build' | 'run' } : {};
        return { jobId: v.jobId, ...action, project: typeof v.project === 'string' ? v.project : '', ended: v.ended === true, stopped: v.stopped === true, ...otherTabs, ...(v.gone === true ? { gone: true } : {}) };
      }
    } catch {
      /* not JSON */
    }
    return undefined;
  }

  /**
   * After a reload: follows again the job this tab had started if the build service still runs it
   * (its log from the start, then live; the Monitor too; Stop cancels it), or shows it again when it
   * has ended (its whole log and its end; a run's Monitor and CSV logs). True when it does.
   */
  async resume(): Promise<boolean> {
    const f = this.followed();
    if (!f) {
      sessionStorage.removeItem(FOLLOWED_JOB_KEY);
      return false;
    }
    this.project = f.project;
    // a job that had ended may since have left the service's last 50 (other tabs' jobs): gone
    // without a word, not said to be lost with a restarted server — unless the tab saw it lost so
    // (`gone`: its stream lost, then the service no longer knew it), or it was running at the reload
    // another tab's job says so again, as before the reload (docs/ide.md "Several tabs")
    const lost = !f.ended || f.gone === true;
    const resumed = await this.d.build.resume(f.jobId, { ended: true, sayIfGone: lost, stoppedHere: f.stopped, ...(f.otherTabs ? { why: `${f.otherTabs} of another tab` } : {}) });
    // forgotten only when the service no longer knows it: a panel busy a moment, or a failed
    // request, keeps it for the next reload (it was dropped, and the job lost to this tab); one
    // lost with the server stays, said gone by every reload until the tab follows another job
    if (resumed === 'gone' && lost) {
      this.keep({ ...f, ended: true, gone: true });
      // its run too, in the Monitor's list (said lost there as before the reload), not gone from it without a word
      if (f.action === 'run' || f.otherTabs === 'Build & Run') this.onLostRun.fire({ jobId: f.jobId });
    } else if (resumed === 'gone') sessionStorage.removeItem(FOLLOWED_JOB_KEY);
    else if (resumed === 'followed') this.d.showPanel('output');
    return resumed === 'followed';
  }

  /**
   * A job another tab started (announced by the IDE server, docs/ide.md "Several tabs"): this tab
   * follows it when it follows none of its own — its log, the Monitor, Stop. True when it does.
   */
  async followShared(job: SharedJob, opts: { replacing?: string } = {}): Promise<boolean> {
    // this tab's own job before a reload is resume()'s
    if (!JOB_ID.test(job.id) || this.followed()?.jobId === job.id) return false;
    if (this.d.build.busy) {
      this.passedOver = job;
      return false;
    }
    // announced only after this tab's own job ended, cancelled from elsewhere a moment before: its replacement
    const cancelled = this.cancelledHere;
    this.cancelledHere = undefined;
    if (!opts.replacing && cancelled && cancelled.jobId !== job.id && Date.now() - cancelled.at < REPLACED_WITHIN_MS) opts = { ...opts, replacing: cancelled.jobId };
    const project = this.project;
    this.project = job.project;
    const what: SharedWhat = job.action === 'run' ? 'Build & Run' : 'build';
    const followed = (await this.d.build.resume(job.id, { why: `${what} of another tab` })) === 'followed';
    if (!followed) {
      if (this.project === job.project) this.project = project;
      return false;
    }
    // kept for a reload as this tab's followed job (onStarted): whose it is, too
    const f = this.followed();
    if (f?.jobId === job.id) this.keep({ ...f, otherTabs: what });
    this.d.showPanel('output');
    const where = job.project ? ` (${job.project})` : '';
    if (opts.replacing) {
      toast('info', `Your run was cancelled by another tab's ${what}${where}: following that one now (yours stays in the Monitor's run list)`);
    } else toast('info', `Following the ${what} another tab started${where}: its log, the Monitor; Stop ends it for every tab`);
    return true;
  }

  async run(): Promise<void> {
    const { workspace, build } = this.d;
    this.d.showPanel('output');
    try {
      await workspace.saveAll();
      this.project = this.d.project();
      const { stdin, ...settings } = readRunSettings(this.where(this.project));
      // a bad entry (one kept by an older page, or edited by hand) is said before anything is submitted
      await build.start(this.project ? `${workspace.root}/${this.project}` : workspace.root, 'run', { ...settings, stdin: keptStdin(stdin) });
    } catch (e) {
      reportError(e);
      build.append({ t: Date.now(), step: 'prepare', source: 'service', stream: 'system', line: `could not start: ${(e as Error).message}` });
    }
  }

  stop(): Promise<void> {
    // kept for a reload: the job's end then still says this tab stopped it
    const f = this.followed();
    if (f && this.d.build.running) this.keep({ ...f, stopped: true });
    return this.d.build.stop();
  }

  /** Which project the start request and stdin files of the run settings are kept for: the workspace root and the project folder. */
  private where(project: string): string {
    return `${this.d.workspace.root}/${project}`;
  }

  /** Marks Build & Run unavailable (no build service). */
  disable(reason: string): void {
    this.d.toolbar.run.disabled = true;
    this.d.toolbar.run.title = `Build & Run unavailable: ${reason}`;
    this.d.jobStatus.textContent = '■ build service unavailable';
  }

  /** The Run settings dialog (the toolbar's ⚙ beside Build & Run, or the command palette). */
  async editSettings(): Promise<void> {
    const where = this.where(this.d.project());
    const cur = readRunSettings(where);
    // the stdin files kept (a bad one, from an older page or edited by hand, shown to be mended: none then)
    let keptRows: string[][] = [];
    try {
      keptRows = stdinRows(keptStdin(cur.stdin));
    } catch (e) {
      toast('error', `${(e as Error).message}: not shown, give the stdin files again`);
    }
    /** The dialog's values read, or what is wrong (the dialog then stays open on that field, nothing saved). */
    const read = ({ values: r, rows }: FieldValues): { problem: FieldsProblem } | { duration: number; readyTimeout?: number; cpus: string; stdin: Record<string, string> } => {
      const duration = Number(r.duration);
      if (!Number.isFinite(duration) || duration <= 0) return { problem: { key: 'duration', message: `Duration must be a positive number of seconds, not "${r.duration}"` } };
      const readyText = (r.readyTimeout ?? '').trim();
      const readyTimeout = readyText ? Number(readyText) : undefined;
      if (readyTimeout !== undefined && !isReadyTimeout(readyTimeout)) return { problem: { key: 'readyTimeout', message: `The init time must be a number of seconds, ${MIN_READY_TIMEOUT_SECONDS} or more, not "${readyText}"` } };
      const cpus = (r.cpus ?? '').trim();
      if (cpus && !isCpuList(cpus)) return { problem: { key: 'cpus', message: `CPUs must be a list such as 1, 0-1 or 0,2, not "${cpus}"` } };
      try {
        return { duration, readyTimeout, cpus, stdin: stdinFromRows(rows.stdin ?? []) };
      } catch (e) {
        if (!(e instanceof StdinRowProblem)) throw e;
        return { problem: { key: 'stdin', row: e.row, column: e.column, message: e.message } };
      }
    };
    const r = await askFields('Run settings', [
      { key: 'duration', label: 'Duration of a run (seconds, capped by the build service)', value: String(cur.duration) },
      { key: 'start', label: "Start request (START=), empty = the generator's default (first function of the top supervisor)", value: cur.start ?? '', hint: 'SUPERVISOR.function(parameter = value, ...)' },
      { key: 'readyTimeout', label: "Time every module's init may take before the start request (seconds; READY_TIMEOUT=), empty = 10: a module not ready by then stops the run", value: cur.readyTimeout === undefined ? '' : String(cur.readyTimeout), hint: '10' },
      { key: 'cpus', label: 'Pin every module to these CPUs (CPUS=; steadier periods), empty = the system places them', value: cur.cpus ?? '', hint: '1 or 0-1' },
      {
        kind: 'rows', key: 'stdin', name: 'Stdin', label: 'Stdin: a module reads a file of the project on its stdin (one row per module; the path from the project folder), no row = every module reads /dev/null',
        columns: [{ label: 'Module', hint: 'MAA' }, { label: 'File', hint: 'input/commands.txt' }], rows: keptRows, addLabel: 'Add a module',
      },
      { key: 'realtime', label: 'Real-time: modules take their SCHED_FIFO priorities in the sandbox, bounded (refused, saying why, where the host cannot grant it)', value: cur.realtime ? 'yes' : '', checkbox: true },
    ], (values) => {
      const v = read(values);
      return 'problem' in v ? v.problem : undefined;
    });
    if (!r) return;
    const v = read(r);
    if ('problem' in v) return; // checked by the dialog
    const { duration, readyTimeout, cpus, stdin } = v;
    const start = r.values.start ?? '';
    const realtime = r.values.realtime === 'yes';
    saveRunSettings(where, { duration, start, readyTimeout, cpus, realtime, stdin });
    const reads = Object.entries(stdin).map(([module, file]) => `, ${module} reads ${file}`).join('');
    toast('info', `Runs last ${duration} s${start ? `, start ${start}` : ''}${readyTimeout !== undefined ? `, inits get ${readyTimeout} s` : ''}${cpus ? `, modules on CPUs ${cpus}` : ''}${reads}${realtime ? ', real-time priorities' : ''}`);
  }

  private async fetchLogs(jobId: string): Promise<void> {
    const { build } = this.d;
    try {
      const logs = await fetchJobLogs(jobId);
      for (const p of logs.problems) build.append({ t: Date.now(), step: 'run', source: 'service', stream: 'system', line: `timeline: ${p}` });
      if (!logs.files.length) return;
      this.onRunLogs.fire({ jobId, logs });
      toast('info', `Run logs of ${logs.files.length} module(s) ready: ▤ Timeline shows the run's activations`);
    } catch (e) {
      build.append({ t: Date.now(), step: 'run', source: 'service', stream: 'system', line: `timeline: could not fetch the run's logs: ${(e as Error).message}` });
    }
  }
}
