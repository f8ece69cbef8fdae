/**
 * Wires the Monitor (docs/watching-a-run.md) into the IDE, so main.ts only creates it:
 * - Build & Run of a run job opens the panel beside the editor on a fresh live model, fed by the
 *   job's `trace` events (whole CSV lines, build-service job-events.ts TraceEvent);
 * - when the job ends, its CSV logs (GET /api/jobs/:id/artifacts, run-logs.ts) become a recorded
 *   run: the same view fed from the same records, from the start;
 * - `*.csv` logs of the workspace (a folder of them: `make run` / `contract run` logs) replay the same way,
 *   and so does a trace file of the workspace (`*.jsonl`: `contract run --trace`, `contract simulate
 *   --trace`), read as the logs it stands for (build-service trace/jsonl.ts, the CSV reader's checks);
 * - a click on a rule opens its definition (document symbols, supervisor-symbols.ts).
 * Everything read from the stream or a log file is hostile: bounded and validated here or by the
 * trace reader (parseRecordLine never throws).
 */
import { TRACE_LINES_KEPT, isLogFileName, type TraceLine } from '@contract-studio/build-service/trace';
import type { EditorArea } from '../editor/editor-area.js';
import type { LspClient } from '../lsp/lsp-client.js';
import type { BuildPanel } from '../build/build-panel.js';
import type { Workspace } from '../workspace/workspace.js';
import { isContract } from '../workspace/file-kinds.js';
import { debounce } from '../util/dom.js';
import { toast } from '../util/toast.js';
import { runSliced } from '../util/sliced.js';
import { fetchJobLogs, MAX_RUN_LOG_BYTES, readTraceFile, readWorkspaceLogs, type LogFile, type RunLogs } from '../views/run-logs.js';
import { api, socketUrl } from '../api.js';
import { MonitorModel } from './monitor-model.js';
import { recordedRunSteps, type RecordedRun } from './recorded-run.js';
import { recordedRunsToLetGo } from './recorded-runs.js';
import { recentEntry, recentRunsOf, type RecentEntry } from './recent-runs.js';
import { applyFolderLauncherLines, applyLauncherLines } from './job-launcher-lines.js';
import type { MonitorView } from './model-view.js';
import { RemoteMonitorModel } from './remote-model.js';
import { jobOutcome, CONNECTION_LOST, LOST_TRACE } from './live-follow-protocol.js';
import { MonitorPanel, type SourceOption } from './monitor-panel.js';
import { readSupervisorSymbols, type SupervisorSymbols } from './supervisor-symbols.js';
import { NOT_IN_MODEL_LONG } from './panel-text.js';
import { crashSitesNote, csvLogsRunLabel, endedRunLabel, endKnownAfterLossLabel, liveRunLabel, streamedRunLabel } from './live-run-label.js';
import { LOST_WITH_SERVER } from '../build/job-end.js';
import { count, recordCounts, recordCountsText, unreadableNote } from './record-counts.js';
import type { ArchSchema } from '../lsp/architecture-model.js';

/** Live runs kept (each holds a worker and up to its model's bound of records); older ones go. */
const MAX_LIVE_RUNS = 4;
/** Longest stretch of folding a recorded run's records without yielding to rendering and input. */
/** How long the end of a run waits for its worker to fold the last of the stream. */
const SETTLE_MS = 5000;
/** CSV files read from the workspace for one replay. */
const MAX_FILES = 256;
/** A shown log folder whose files changed is read again this long after the last change (a run writing its logs changes them all the time). */
const REREAD_MS = 1000;
/**
 * While the Monitor is shown in a tab the user sees, its list of the workspace's recent Build & Run
 * jobs is read again this often (GET /api/recent-runs): a job another tab starts appears in it, still
 * running, to be followed live. Also at once when the tab is shown again or gets the focus.
 */
export const RECENT_RUNS_MS = 3000;
/**
 * The workspace log folder or trace file this tab's Monitor shows, kept for a reload (sessionStorage:
 * one per tab): `dir:FOLDER` or `file:PATH`. A job's run needs no such key: the run controller follows
 * its job again after a reload, and the Monitor with it.
 */
const SHOWN_REPLAY_KEY = 'contract-studio:monitor-replay';

interface Run {
  id: string;
  label: string;
  model: MonitorView;
  live: boolean;
  /**
   * Its records run to the run's end (a recorded run; a live one once its job's logs came): a module
   * with no exit record at its end ended without one (crashed, killed), and is not shown running.
   * Not a simulation's: its session goes on.
   */
  whole?: boolean;
  /** When it was made or last shown (the recorded runs used least recently are let go first). */
  used?: number;
  /** A job's run that ended: how (`succeeded`, `cancelled`, `failed: …`, `connection to the build service lost`, then how the job ended when the service answers again). */
  outcome?: string;
  /**
   * The project whose model it is read against (its schemas, its supervisors' rules): the one that
   * holds its log folder or trace file, the one a job ran; not the active editor tab's (a trace file
   * of another project showed every rule "not in the model" and that tab's schemas).
   */
  project: string;
}

export class MonitorController {
  /** The panel once the Monitor was first shown (public for the browser tests: `__ide.monitor`, app/ide-hook.ts). */
  panel: MonitorPanel | undefined;
  /** Jobs' recorded runs let go (recorded-runs.ts): id -> their label; fetched again when picked. */
  private readonly letGo = new Map<string, string>();
  /**
   * The workspace's recent Build & Run jobs the build service keeps (recent-runs.ts), by entry id
   * (`job:ID`): offered in the run list of every tab, read from the service when picked.
   */
  private recent = new Map<string, RecentEntry>();
  /** What the run list last offered of `recent` (its ids and labels): the list is rebuilt only when it changed (an open list stays open). */
  private recentSaid = '';
  /** The next read of the recent jobs while the Monitor is shown (RECENT_RUNS_MS), and whether one is being read. */
  private recentTimer: ReturnType<typeof setTimeout> | undefined;
  private recentReading = false;
  /** Jobs of that list picked while they ran, followed live here: their CSV logs are read from their entry once they ended. */
  private readonly followedFromList = new Set<string>();
  private uses = 0;
  /** The runs of the run list, by entry id (public for the browser tests: `__ide.monitor`, app/ide-hook.ts). */
  readonly runs = new Map<string, Run>();
  private shown: string | undefined;
  /** The supervisors' symbols of the shown run's project, once read (public for the browser tests: `__ide.monitor`, app/ide-hook.ts). */
  symbols: SupervisorSymbols | undefined;
  /** The project `symbols` were read for. */
  private symbolsProject: string | undefined;
  private previous: HTMLElement | undefined;
  /** The model of the last Build & Run's live trace (tests compare it with the job's logs). */
  lastLive: RemoteMonitorModel | undefined;
  /** Live runs report each record's wall_time and arrival with their snapshots (the benchmark sets it). */
  measure = false;
  /** Bytes of workspace logs one replay reads in all; the logs past it are left out and named (a test lowers it). */
  replayBytes = MAX_RUN_LOG_BYTES;
  /**
   * Bumped at each run the user asks to see (a source picked, a folder opened, a Build & Run, a
   * simulation): a
   * replay whose model is built after the user asked for something else is listed, not shown.
   */
  private picked = 0;
  /** The CSV logs each workspace folder replay was read from (to see that the folder changed). */
  private readonly folderFiles = new Map<string, string>();
  private rereadTimer: ReturnType<typeof setTimeout> | undefined;
  /** The run rereadTimer reads again; the one being read again (folderChanged), and whether it changed meanwhile. */
  private rereadDue: string | undefined;
  private rereading: string | undefined;
  private changedWhileRereading = false;

  constructor(
    private readonly deps: { editors: EditorArea; lsp: LspClient; workspace: Workspace; build: BuildPanel; button: HTMLButtonElement; project: () => string; projectOf: (path: string) => string },
  ) {
    deps.button.addEventListener('click', () => (this.panel && deps.editors.docked === this.panel.element ? this.hide() : void this.show()));
    deps.build.onStarted.on(({ jobId, action }) => {
      if (action === 'run') this.followLive(jobId);
    });
    // the recent jobs, read again when a job of this tab ends (its entry then says how)
    deps.build.onFinished.on(() => {
      if (this.panel) void this.loadRecent();
    });
    // and when the tab is seen again or focused, the Monitor shown (a job another tab started meanwhile)
    const seen = () => {
      if (this.isShown && document.visibilityState === 'visible') void this.loadRecent(true);
    };
    document.addEventListener('visibilitychange', seen);
    window.addEventListener('focus', seen);
    // the language server built the model, or built it again after an edit: the panel reads its
    // schemas and the rules' places again (a panel made before the server was ready, by a Build &
    // Run pressed at once, showed "PERIOD ?" and no CRITICAL_DELAY line for the whole run)
    const remodel = debounce(() => {
      this.symbols = undefined;
      if (this.panel) void this.panel.refreshModel();
    }, 400);
    deps.lsp.onDiagnostics.on(remodel);
    // the side pane given to something else (the docked diagram, hide): a reload no longer brings back a replay
    deps.editors.onDocked.on((element) => {
      if (!this.panel || element !== this.panel.element) this.keepShown(undefined);
    });
    // a workspace log folder changed on disk (a `contract run` wrote logs, a log was added or
    // removed): the run list offers new folders at once, and a folder's replay is read again —
    // now if it is shown, else when it is picked
    deps.workspace.onTree.on(() => {
      for (const [id, files] of [...this.folderFiles]) if (this.csvIn(id.slice(4)).join('\n') !== files) this.folderChanged(id);
      for (const id of [...this.runs.keys()]) if (id.startsWith('file:') && !deps.workspace.hasFile(id.slice(5))) this.folderChanged(id);
      if (this.panel) void this.refreshSources();
    });
    deps.workspace.onExternalChange.on((path) => {
      if (path.endsWith('.csv') && this.folderFiles.has(`dir:${dirOf(path)}`)) this.folderChanged(`dir:${dirOf(path)}`);
      if (path.endsWith('.jsonl') && this.runs.has(`file:${path}`)) this.folderChanged(`file:${path}`);
    });
    // the job's end as the build panel's own stream tells it: a run whose live trace did not say
    // so (its worker failed) is not left 'live'
    deps.build.onFinished.on(({ jobId, action, ok, message, gone }) => {
      // (or its logs' run, when the live one was forgotten for want of records)
      const run = this.runs.get(`live:${jobId}`) ?? this.runs.get(`job:${jobId}`);
      if (action === 'run' && run) this.ended(run, gone ? LOST_WITH_SERVER : jobOutcome({ ok, message }));
    });
  }

  /**
   * Follows a live run in a Web Worker (live-follower.ts) that opens the job's trace stream
   * itself (`url`: GET /api/jobs/:id/ws?trace=launcher), or that is fed by `feed` (url null: tests),
   * and shows it. The page's main thread only draws: it decodes and folds nothing.
   */
  followLive(jobId: string, url: string | null = socketUrl(`/api/jobs/${encodeURIComponent(jobId)}/ws?trace=launcher`), project = this.deps.project()): RemoteMonitorModel {
    this.runs.delete(`job:${jobId}`);
    this.forget(`live:${jobId}`);
    const worker = new Worker(new URL('./live-follow.worker.ts', import.meta.url), { type: 'module' });
    this.picked++;
    const model = new RemoteMonitorModel(worker, url, { measure: this.measure });
    worker.addEventListener('error', (e) => model.fail(`the live trace's worker failed (${e.message || 'it could not start'}): the run is shown from its CSV logs when it ends`));
    const run: Run = { id: `live:${jobId}`, label: liveRunLabel(jobId), model, live: true, project };
    let problems = 0;
    let missed = 0;
    model.onChange = () => {
      if (model.problems.length !== problems || model.missed !== missed) {
        problems = model.problems.length;
        missed = model.missed;
        // a stream attached late (a reload during a long run) or taken up again past the service's
        // bound gets the first records and the newest: the gap between them is said while it runs
        const notWhole = [...(missed ? [`${count(missed)} records not received (the build service keeps the first ${count(TRACE_LINES_KEPT)} for a page that attaches later); the whole run is shown from its logs when it ends`] : []), ...model.problems];
        run.label = `${run.label.replace(/ \(trace not whole: .*\)$/, '')} (trace not whole: ${notWhole.join('; ')})`;
        if (this.shown === run.id) this.panel?.setLabel(run.label);
        if (this.panel) void this.refreshSources(); // the run list says it too
      }
      if (model.ended && model.outcome !== undefined) this.ended(run, model.outcome);
      if (this.shown === run.id) this.panel?.schedule();
    };
    this.lastLive = model;
    this.runs.set(run.id, run);
    // the oldest live runs go (each holds a worker and its records): their CSV logs stay
    const lives = [...this.runs.values()].filter((r) => r.model instanceof RemoteMonitorModel);
    for (const old of lives.slice(0, Math.max(0, lives.length - MAX_LIVE_RUNS))) this.forget(old.id);
    void this.show(run.id);
    return model;
  }

  /**
   * Live run `run`'s job ended (its trace stream's `end`, or the stream lost for good, or the build
   * panel's end): the run is no longer live anywhere — run list, header, time line, follow button —
   * and says how it ended, once (the first of those to say it). Its CSV logs, when the job left
   * some, usually come after (showRecorded); when they came first (the stream's end was late past
   * SETTLE_MS, or only the build panel's end says it), the label they gave gets the outcome too.
   */
  private ended(run: Run, outcome: string): void {
    // once said, an outcome stays; but a lost stream's is only what this tab saw: the job's own end,
    // known after (the build panel asked the service once it answered again), says it instead
    if (run.outcome === CONNECTION_LOST && outcome !== CONNECTION_LOST) {
      run.outcome = outcome;
      run.label = endKnownAfterLossLabel(run.label, CONNECTION_LOST, LOST_TRACE, outcome);
      if (this.shown === run.id) this.panel?.setLabel(run.label);
      void this.refreshSources();
      return;
    }
    if (run.outcome !== undefined) return;
    run.outcome = outcome;
    run.label = endedRunLabel(run.label, run.live, outcome);
    run.live = false;
    if (this.shown === run.id) this.panel?.endLive(run.label, run.whole);
    // a job picked in the list while it ran: its entry, now saying how it ended, reads its CSV logs
    void (this.followedFromList.has(run.id.slice(5)) ? this.loadRecent() : this.refreshSources());
  }

  /**
   * After a reload: Build & Run job `jobId`, which this tab followed, was lost with the IDE server
   * (the restarted build service does not know it; it collected no CSV logs of it, its sandbox
   * died with the old one). Its run is listed, and shown unless another run is, ended so — the
   * same words as the tab said before the reload — with none of its records: what its stream
   * brought was in the page before the reload, and nothing is left to read them from again.
   */
  async listLost(jobId: string): Promise<void> {
    const id = `live:${jobId}`;
    if (this.runs.has(id) || this.runs.has(`job:${jobId}`)) return; // followed here: its end says it
    const label = endedRunLabel(liveRunLabel(jobId), true, LOST_WITH_SERVER);
    this.runs.set(id, { id, label, model: new MonitorModel(), live: false, outcome: LOST_WITH_SERVER, project: this.deps.project() });
    if (this.shown === undefined) await this.show(id);
    else await this.refreshSources();
  }

  /** Trace lines of live run `jobId` handed over by the page (tests): folded by its worker as if streamed. */
  feed(jobId: string, records: TraceLine[]): void {
    const m = this.runs.get(`live:${jobId}`)?.model;
    if (m instanceof RemoteMonitorModel) m.feed(records); // bounded by the worker
  }

  private forget(id: string): void {
    const run = this.runs.get(id);
    if (run?.model instanceof RemoteMonitorModel) run.model.dispose();
    this.runs.delete(id);
  }

  /** The panel (created on first use). */
  async ensurePanel(): Promise<MonitorPanel> {
    if (this.panel) return this.panel;
    const { lsp } = this.deps;
    this.panel = new MonitorPanel({
      schemas: () => this.projectSchemas(),
      supervisors: async () => (await this.readSymbols()).catalogue,
      modelModules: async () => (await this.readSymbols()).modules,
      openRule: (sup, fn, rule) => void this.openRule(sup, fn, rule),
      createDiagram: async () => new (await import('../views/architecture-view.js')).ArchitectureView(() => lsp.architecture(), undefined, undefined, { inScrolledPanel: true }),
      onSource: (id) => {
        this.picked++;
        void this.select(id, true);
      },
    });
    return this.panel;
  }

  /** Docks the panel beside the editor, showing run `id` (default: the last one). */
  async show(id?: string): Promise<void> {
    const panel = await this.ensurePanel();
    const before = this.deps.editors.docked;
    if (before !== panel.element) this.previous = before; // the docked diagram comes back when the Monitor is hidden
    this.deps.editors.dock(panel.element);
    this.deps.button.setAttribute('aria-pressed', 'true');
    await this.loadRecent();
    this.watchRecent();
    const pick = id ?? this.shown ?? [...this.runs.keys()].pop();
    if (pick) await this.select(pick);
  }

  /**
   * "Open Monitor" (Alt+Shift+M, the command palette): shows the Monitor — it stays shown when it
   * already is (the ◉ Monitor button is the toggle) — and puts the keyboard focus in it.
   */
  async open(): Promise<void> {
    if (!this.isShown) await this.show();
    // its ring shown: the focus came from a shortcut or the palette, even after a mouse click elsewhere
    this.panel?.element.focus({ focusVisible: true } as FocusOptions);
  }

  hide(): void {
    this.deps.editors.dock(this.previous);
    this.previous = undefined;
    this.deps.button.setAttribute('aria-pressed', 'false');
  }

  /** A finished run job's CSV logs: the recorded run, replayed from its start. */
  async showRecorded(jobId: string, logs: RunLogs): Promise<void> {
    const picked = this.picked;
    const live = this.runs.get(`live:${jobId}`);
    // the worker may still be folding the stream's last batches
    if (live?.model instanceof RemoteMonitorModel) await Promise.race([live.model.settled, new Promise((r) => setTimeout(r, SETTLE_MS))]);
    if (live) {
      live.live = false;
      live.whole = true;
      live.label = streamedRunLabel(jobId, live.outcome);
      if (!live.model.recordCount) this.forget(live.id); // no live trace (an older build service): the logs tell it all
    }
    // a live run forgotten for want of records: its logs' run says how the job ended
    const run = await this.recordedJobRun(jobId, logs, live && !live.model.recordCount ? live.outcome : undefined);
    // a monitor attached late, or reconnected, misses what the service did not keep (docs/build-service-api.md
    // "Trace channel": past traceLinesKept records go live only): then the logs, which hold the whole run, are shown
    const cut = !!live && live.model.recordCount > 0 && live.model.recordCount < run.model.recordCount;
    // (not "the first N": a stream attached late got the first records and the last ones, a gap between)
    if (cut) live!.label = streamedRunLabel(jobId, live!.outcome, { streamed: live!.model.live.records, logged: run.model.live.records });
    if (this.shown === live?.id && live?.model.recordCount && !cut) {
      this.panel?.endLive(live.label, true);
      await this.refreshSources();
    } else if (picked === this.picked && (this.shown === undefined || this.shown === live?.id)) {
      await this.show(run.id); // the view followed this job (its stream was cut), or showed no run
    } else {
      // the view shows a run the user picked (a simulation, a workspace log, a trace file, another
      // tab's job): it stays, this one is listed
      await this.refreshSources();
    }
  }

  /** Job `jobId`'s recorded run from its CSV logs, kept (and the least used recorded runs let go past the bounds). */
  private async recordedJobRun(jobId: string, logs: RunLogs, outcome?: string, recentProject?: string): Promise<Run> {
    const { model, leftOut: unread } = await recordedRun(logs.files);
    // the launcher's lines saying how its modules ended: a module killed from outside shown gone, as live
    applyLauncherLines(model, logs.files, logs.launcherLines);
    // a log the service left out or capped, one that could not be downloaded, or the rest of one
    // that is not a trace is said: the replay lacks it
    // what matters first (a file that is no log, two logs of one module: recorded-run.ts), then the files the service did not collect
    const problems = [...unread, ...logs.problems];
    const project = this.runs.get(`live:${jobId}`)?.project ?? this.runs.get(`job:${jobId}`)?.project ?? recentProject ?? this.deps.project();
    const run: Run = { id: `job:${jobId}`, label: csvLogsRunLabel(jobId, problems, outcome, recordCounts(model), logs.crashSites), model, live: false, whole: true, outcome, project };
    this.keepRecorded(run);
    return run;
  }

  /** Keeps recorded run `run`, and lets go of the least recently used ones past the bounds (recorded-runs.ts). */
  private keepRecorded(run: Run): void {
    run.used = ++this.uses;
    this.runs.set(run.id, run);
    this.letGo.delete(run.id);
    const kept = [...this.runs.values()].map((r) => ({ id: r.id, live: r.live, used: r.used, recordCount: r.model.recordCount }));
    for (const id of recordedRunsToLetGo(kept, new Set([run.id, ...(this.shown ? [this.shown] : [])]))) {
      const gone = this.runs.get(id)!;
      this.runs.delete(id);
      if (id.startsWith('job:')) this.letGo.set(id, `${gone.label} · read again when picked`);
    }
  }

  /** A job's recorded run that was let go, picked again: its logs fetched again from the build service. */
  private async fetchAgain(id: string, recent?: RecentEntry): Promise<void> {
    const mine = ++this.picked;
    const jobId = id.slice(4);
    try {
      if (recent) await this.reading(`the CSV logs of Build & Run job ${jobId}`);
      const logs = await fetchJobLogs(jobId);
      if (!logs.files.length) throw new Error(recent ? `it left no CSV logs${recent.outcome ? ` (ended: ${recent.outcome})` : ''}` : 'the build service has no CSV logs of it any more');
      await this.recordedJobRun(jobId, logs, recent?.outcome, recent?.project);
    } catch (e) {
      this.letGo.delete(id);
      this.recent.delete(id);
      toast('warning', `Build & Run job ${jobId}: its logs could not be read${recent ? '' : ' again'} (${(e as Error).message}); the build service keeps its last 50 jobs`);
      await this.refreshSources();
      return;
    }
    if (mine === this.picked) await this.show(id);
    else await this.refreshSources();
  }

  /** A simulation's state (@contract-studio/simulator/trace): the same view as runs, replacing the previous simulation. */
  async showSimulation(model: MonitorModel, label: string): Promise<void> {
    this.picked++;
    this.runs.set('sim', { id: 'sim', label, model, live: false, project: this.deps.project() });
    await this.show('sim');
  }

  /** The `*.csv` logs of workspace folder `folder` (those a replay reads). */
  private csvIn(folder: string): string[] {
    return this.deps.workspace.allFiles().filter((f) => isLogFileName(f.slice(f.lastIndexOf('/') + 1)) && dirOf(f) === folder).slice(0, MAX_FILES);
  }

  /**
   * Log folder or trace file run `id` changed on disk: read again if it is shown, else when it is
   * picked. Read again REREAD_MS after its first change not read yet — not after the changes pause:
   * a run writes its logs without a pause, and putting the read off at each change put it off for
   * as long as the run went on — and never twice at once: a change while it is read (a large folder
   * takes seconds) reads it again once that read is done.
   */
  private folderChanged(id: string): void {
    if (this.shown !== id || !this.isShown) {
      this.folderFiles.delete(id);
      this.runs.delete(id);
      return;
    }
    if (id.startsWith('dir:')) this.folderFiles.set(id, ''); // changed: still watched until read again
    if (this.rereading === id) {
      this.changedWhileRereading = true;
      return;
    }
    if (this.rereadTimer !== undefined && this.rereadDue === id) return; // already due
    clearTimeout(this.rereadTimer);
    this.rereadDue = id;
    this.rereadTimer = setTimeout(() => void this.reread(id), REREAD_MS);
  }

  /** Reads log folder or trace file run `id` again (folderChanged), if it is still shown. */
  private async reread(id: string): Promise<void> {
    this.rereadTimer = undefined;
    this.rereadDue = undefined;
    if (this.shown !== id || !this.isShown) {
      this.runs.delete(id);
      return;
    }
    this.rereading = id;
    this.changedWhileRereading = false;
    try {
      await (id.startsWith('file:') ? this.openTraceFile(id.slice(5), false) : this.openFolder(id.slice(4), false));
    } finally {
      this.rereading = undefined;
      if (this.changedWhileRereading) {
        this.changedWhileRereading = false;
        this.folderChanged(id);
      }
    }
  }

  /**
   * Replays the `*.csv` logs of a workspace folder, read now (a folder picked again is read
   * again: its logs may have changed). `asked`: the user asked for it (else it is read again
   * because it changed, and shown only if it still is the run shown).
   */
  async openFolder(folder: string, asked = true): Promise<void> {
    const mine = asked ? ++this.picked : this.picked;
    this.folderFiles.set(`dir:${folder}`, this.csvIn(folder).join('\n'));
    const where = folder || 'the workspace root';
    if (asked) await this.reading(`the CSV logs in ${where}`);
    // the folder as the server lists it: its links and FIFOs too, which the Explorer's tree does not show
    const listing = await api.logFolder(folder).catch((e: Error) => ({ logs: this.csvIn(folder), more: 0, max: MAX_FILES, notRead: [`${where} could not be listed (${e.message}): its logs the Explorer shows are read`], notReadCount: 1 }));
    const paths = listing.logs;
    // past the replay's bound the large module logs are left out, never ORD's nor the supervisors' (run-logs.ts replayOrder)
    const sizes = 'sizes' in listing ? listing.sizes : undefined;
    const { files, problems, partly, tooLarge } = await readWorkspaceLogs(paths, (p) => p.slice(p.lastIndexOf('/') + 1), this.replayBytes, { sizes, supervisors: await this.supervisorNames() });
    // said in the label: a replay never misses a log silently; a run too long for the page is told
    // whole by the CLI, which reads it as a stream
    const leftOut = [...problems, ...listing.notRead];
    if (listing.notReadCount > listing.notRead.length) leftOut.push(`${listing.notReadCount - listing.notRead.length} more entries that are no regular file`);
    if (listing.more) leftOut.push(`${count(listing.more)} more CSV log(s) past the first ${listing.max}: a replay reads ${listing.max} at most`);
    const whole = tooLarge || listing.more ? ` — \`contract trace ${folder || '.'}\` tells a run of any length` : '';
    // a log read in part does not run to the run's end: nothing is said of what its end leaves (ORD gone, undos unserved)
    const { model, leftOut: notRecords } = await recordedRun(files, undefined, !partly.length);
    // the launcher's own end lines (the folder's contract-launch.log): a module killed from outside shown gone at its end, as live
    applyFolderLauncherLines(model, 'launcherLines' in listing ? listing.launcherLines : undefined);
    // a log read in part (its first lines: past what the server sends of one) is said with how much, and where the rest is
    const unread = [...partly, ...notRecords, ...('launcherLinesProblem' in listing && listing.launcherLinesProblem ? [listing.launcherLinesProblem] : [])];
    const counted = unreadableNote(recordCounts(model));
    const inFolder = paths.length + listing.more + listing.notReadCount;
    // what matters first: what was read of the logs (a file that is no log, two logs of one module:
    // recorded-run.ts), then the entries not read (names a module's code may have made by the hundred)
    const read = leftOut.length ? `${files.length} of ${inFolder} CSV logs in ${where}${counted}` : `${files.length} CSV log(s) in ${where}${counted}`;
    const told = `${read}${unread.length ? ` (not whole: ${unread.join('; ')})` : ''}${leftOut.length ? ` (left out: ${leftOut.join('; ')})${whole}` : ''}`;
    // where its crashed modules crashed, from the folder's crash files (the server reads them: GET /api/log-folder)
    const crashSites = crashSitesNote('crashSites' in listing ? listing.crashSites ?? [] : [], "the logs' crash files");
    const label = `${told}${crashSites}`;
    // (a log read in part does not run to the run's end: its module is not taken for one that ended without an exit record)
    const run: Run = { id: `dir:${folder}`, label, model, live: false, whole: !partly.length, project: this.deps.projectOf(folder ? `${folder}/x` : 'x') };
    this.keepRecorded(run);
    // shown unless the user asked for another run while it was read and built: then listed
    if (mine === this.picked && (asked || this.shown === run.id)) await this.show(run.id);
    else await this.refreshSources();
  }

  /**
   * Replays a trace file of the workspace (`*.jsonl`, read again each time: it may have changed):
   * its records as the logs they stand for, through the reader of a run's logs. `asked`: as openFolder.
   */
  async openTraceFile(path: string, asked = true): Promise<void> {
    const mine = asked ? ++this.picked : this.picked;
    const id = `file:${path}`;
    if (asked) await this.reading(`trace file ${path}`);
    const { files, problems, skipped, unreadable, simulation, order, tooLarge, launcherLines } = await readTraceFile(path, (p) => p.slice(p.lastIndexOf('/') + 1), this.replayBytes);
    // in the file's order, as `contract trace FILE` tells it (a simulation's records of one time: causes first)
    // a simulation's (its sim_start): its modules ran no code, no flow is told silent
    const { model, leftOut: unread } = await recordedRun(files, order, true, simulation !== undefined);
    // the launcher's end lines the file holds (`launcher_line`, written by `contract run --trace`): a
    // module killed from outside shown gone at its end, as a logs folder's (its pid the module's own)
    applyFolderLauncherLines(model, launcherLines);
    const notWhole = [...problems, ...unread];
    // counted as `contract trace` counts them: the logs' unreadable lines the file carries, and its own lines that are no record
    const label = `Trace file ${path}${simulation === undefined ? '' : simulation ? ` · simulation of ${simulation}` : ' · a simulation'} · ${recordCountsText(recordCounts(model, skipped + unreadable))}${notWhole.length ? ` (not whole: ${notWhole.join('; ')})` : ''}${tooLarge ? ` — \`contract trace ${path}\` tells a run of any length` : ''}`;
    this.keepRecorded({ id, label, model, live: false, whole: simulation === undefined, project: this.deps.projectOf(path) });
    if (mine === this.picked && (asked || this.shown === id)) await this.show(id);
    else await this.refreshSources();
  }

  /** Keeps the workspace folder or trace file shown for a reload (any other run shown, or none: nothing kept). */
  private keepShown(id: string | undefined): void {
    try {
      if (id && /^(dir|file):/.test(id)) sessionStorage.setItem(SHOWN_REPLAY_KEY, id);
      else sessionStorage.removeItem(SHOWN_REPLAY_KEY);
    } catch {
      /* storage refused: a reload then shows the Monitor's default */
    }
  }

  /**
   * After a reload: the workspace log folder or trace file this tab's Monitor showed is read and
   * shown again, if the workspace still has it (its logs are read as they are now). Called once the
   * run controller has followed its job again: the replay the user looked at last comes back on
   * top, the job's run listed. True when it shows one.
   */
  async restore(): Promise<boolean> {
    let id: string | null = null;
    try {
      id = sessionStorage.getItem(SHOWN_REPLAY_KEY);
    } catch {
      return false;
    }
    // whatever is kept is checked against the workspace: only a folder with logs or an existing trace file opens
    const folder = id?.startsWith('dir:') ? id.slice(4) : undefined;
    const file = id?.startsWith('file:') ? id.slice(5) : undefined;
    const there = folder !== undefined ? this.csvIn(folder).length > 0 : file !== undefined && file.endsWith('.jsonl') && this.deps.workspace.hasFile(file);
    if (!there) {
      this.keepShown(undefined);
      return false;
    }
    if (folder !== undefined) await this.openFolder(folder);
    else await this.openTraceFile(file!);
    return true;
  }

  /** Says in the panel's label what is being read (a run of a minute at 1 kHz takes a few seconds): until it is shown. */
  private async reading(what: string): Promise<void> {
    (await this.ensurePanel()).setLabel(`Reading ${what}…`);
  }

  private get isShown(): boolean {
    return !!this.panel && this.deps.editors.docked === this.panel.element;
  }

  /** The run shown (tests and benchmarks read its model). */
  get current(): MonitorView | undefined {
    return this.shown ? this.runs.get(this.shown)?.model : undefined;
  }

  /** Shows run `id`; a workspace log folder is read (again, with `reread`: picked in the run list). */
  private async select(id: string, reread = false): Promise<void> {
    if (id.startsWith('dir:') && (reread || !this.runs.has(id))) return this.openFolder(id.slice(4));
    if (id.startsWith('file:') && (reread || !this.runs.has(id))) return this.openTraceFile(id.slice(5));
    if (this.letGo.has(id) && !this.runs.has(id)) return this.fetchAgain(id);
    const recent = this.runs.has(id) ? undefined : this.recent.get(id);
    // a job of the list still going: followed live (its stream from its first record), else its CSV logs read
    if (recent && recent.outcome === undefined) {
      this.followedFromList.add(recent.jobId);
      this.followLive(recent.jobId, undefined, recent.project);
      return;
    }
    if (recent) return this.fetchAgain(id, recent);
    const run = this.runs.get(id);
    const panel = await this.ensurePanel();
    if (!run) return;
    if (run.used !== undefined) run.used = ++this.uses;
    this.shown = id;
    this.keepShown(id);
    this.symbols = undefined; // the model may have changed since
    panel.setModel(run.model, run.label, run.live, !!run.whole);
    await this.refreshSources();
  }

  private async refreshSources(): Promise<void> {
    const panel = await this.ensurePanel();
    const options: SourceOption[] = [...this.runs.values()].map((r) => ({ id: r.id, label: r.label }));
    for (const [id, label] of this.letGo) if (!this.runs.has(id)) options.push({ id, label });
    for (const [id, entry] of this.recent) if (!this.knows(entry.jobId)) options.push({ id, label: entry.label });
    const folders = [...new Set(this.deps.workspace.allFiles().filter((f) => isLogFileName(f.slice(f.lastIndexOf('/') + 1))).map(dirOf))].sort();
    for (const f of folders) if (!this.runs.has(`dir:${f}`)) options.push({ id: `dir:${f}`, label: `Workspace logs: ${f || '(root)'}` });
    const traceFiles = this.deps.workspace.allFiles().filter((f) => f.endsWith('.jsonl')).sort().slice(0, MAX_FILES);
    for (const f of traceFiles) if (!this.runs.has(`file:${f}`)) options.push({ id: `file:${f}`, label: `Trace file: ${f}` });
    panel.setSources(options, this.shown);
  }

  /**
   * The workspace's recent Build & Run jobs, read again from the IDE server (GET /api/recent-runs)
   * and offered in the run list; a job the build service no longer keeps leaves it. A failed
   * request keeps the list as it was.
   */
  private async loadRecent(onlyWhenChanged = false): Promise<void> {
    if (onlyWhenChanged && this.recentReading) return;
    this.recentReading = true;
    try {
      const now = Date.now();
      this.recent = new Map(recentRunsOf(await api.recentRuns()).map((r) => [`job:${r.id}`, recentEntry(r, now)]));
    } catch {
      /* no build service, or the server away a moment: the list stays as it was */
    } finally {
      this.recentReading = false;
    }
    const said = [...this.recent.values()].map((e) => `${e.id} ${e.label}`).join('\n');
    if (onlyWhenChanged && said === this.recentSaid) return;
    this.recentSaid = said;
    await this.refreshSources();
  }

  /**
   * Reads the recent jobs again every RECENT_RUNS_MS while the Monitor is shown (a hidden tab's
   * reads are skipped until it is seen again); stops once it is no longer shown (show() starts it again).
   */
  private watchRecent(): void {
    if (this.recentTimer !== undefined) return;
    const tick = async () => {
      if (!this.isShown) {
        this.recentTimer = undefined;
        return;
      }
      if (document.visibilityState === 'visible') await this.loadRecent(true);
      this.recentTimer = setTimeout(() => void tick(), RECENT_RUNS_MS);
    };
    this.recentTimer = setTimeout(() => void tick(), RECENT_RUNS_MS);
  }

  /**
   * Whether job `jobId` is in the run list already as this tab's: its CSV logs' run (or that run let
   * go), or its live run — the tab's own job, whose CSV logs the tab reads when it ends, or a job
   * picked in the list while it ran, until it ended: its listed entry then reads its CSV logs.
   */
  private knows(jobId: string): boolean {
    const live = this.runs.get(`live:${jobId}`);
    if (this.runs.has(`job:${jobId}`) || this.letGo.has(`job:${jobId}`)) return true;
    return !!live && (live.live || !this.followedFromList.has(jobId));
  }

  /**
   * The model's supervisors' names, for the order a replay reads logs in under its bound: none when
   * the language server does not give them within 2 s (the smallest logs are read first then).
   */
  private async supervisorNames(): Promise<Set<string>> {
    let timer: ReturnType<typeof setTimeout> | undefined;
    const late = new Promise<undefined>((r) => (timer = setTimeout(() => r(undefined), 2000)));
    const symbols = await Promise.race([this.readSymbols().catch(() => undefined), late]);
    clearTimeout(timer);
    return new Set(symbols?.catalogue.keys() ?? []);
  }

  /** The project of the run shown (Run.project), else the active tab's. */
  private shownProject(): string {
    return (this.shown !== undefined ? this.runs.get(this.shown)?.project : undefined) ?? this.deps.project();
  }

  /** Whether workspace path `path` is in project `project` ('' : the workspace root's). */
  private inProject(path: string, project: string): boolean {
    return !project || path.startsWith(`${project}/`);
  }

  private async readSymbols(): Promise<SupervisorSymbols> {
    const project = this.shownProject();
    if (this.symbols && this.symbolsProject === project) return this.symbols;
    const { workspace, lsp } = this.deps;
    const files = workspace.allFiles().filter((p) => isContract(p) && this.inProject(p, project));
    const symbols = await readSupervisorSymbols(files.map((p) => workspace.uriOf(p).toString()), (uri) => lsp.documentSymbols(uri));
    this.symbols = symbols;
    this.symbolsProject = project;
    return symbols;
  }

  /** The schemas of the shown run's project (the language server gives the whole workspace's; the browser tests call it). */
  async projectSchemas(): Promise<ArchSchema[]> {
    const project = this.shownProject();
    const all = await this.deps.lsp.architecture();
    return all.filter((sc) => {
      const path = this.deps.workspace.pathOf(sc.uri);
      return path === undefined || this.inProject(path, project);
    });
  }

  /**
   * Opens a rule the Monitor lists in its .contract file. A rule the run names and the model no
   * longer has (renamed or removed since the run) opens its function, saying so; when the function
   * is gone too, it says that and opens nothing.
   */
  private async openRule(sup: string, fn: string, rule: string): Promise<void> {
    const { locations } = await this.readSymbols();
    const ruleAt = locations.get(`${sup}.${fn}.${rule}`);
    const loc = ruleAt ?? locations.get(`${sup}.${fn}`);
    const path = loc && this.deps.workspace.pathOf(loc.uri);
    if (!loc || !path) {
      toast('warning', `${sup}.${fn} is ${NOT_IN_MODEL_LONG} (the Monitor shows what the run recorded)`);
      return;
    }
    if (!ruleAt) toast('info', `Rule ${rule} is not in ${sup}.${fn} any more (renamed or removed since this run): its function is shown`);
    await this.deps.editors.open(path, { lineNumber: loc.range.start.line + 1, column: loc.range.start.character + 1 });
  }
}

/**
 * The model of a recorded run's logs (recorded-run.ts), built in slices (util/sliced.ts) with the
 * page's other work between them: a 60 s run of a 1 kHz schema is some 840,000 records, a second
 * or more of folding, during which the page would not draw nor answer a key.
 */
function recordedRun(files: readonly LogFile[], fileOrder?: Uint16Array, whole = true, simulation = false): Promise<RecordedRun> {
  return runSliced(recordedRunSteps(files, 500, simulation ? { simulation } : undefined, undefined, fileOrder, whole));
}

function dirOf(path: string): string {
  const i = path.lastIndexOf('/');
  return i < 0 ? '' : path.slice(0, i);
}
