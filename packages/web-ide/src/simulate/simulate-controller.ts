/**
 * Wires the Simulate panel into the IDE (docs/simulation.md "In the IDE"), so main.ts only creates
 * it: the functions to pick come from the workspace model (the language server's document symbols,
 * monitor/supervisor-symbols.ts); each session change re-runs the session's whole scenario on the
 * server (POST /api/simulate: the simulator's own API, virtual time) and shows its last state in
 * the panel and, as trace records (@contract-studio/simulator/trace), in the Monitor beside the editor: one view for
 * live runs, replays and simulations. "Save as scenario" writes through the file API.
 */
import { api, ApiError } from '../api.js';
import type { LspClient } from '../lsp/lsp-client.js';
import type { Workspace } from '../workspace/workspace.js';
import { isContract } from '../workspace/file-kinds.js';
import type { MonitorController } from '../monitor/monitor-controller.js';
import { readSupervisorSymbols } from '../monitor/supervisor-symbols.js';
import type { SimulateResponse } from '../../server/api-types.js';
import { formatTime } from '@contract-studio/language/scenario';
import { ScenarioSession, type SchedulerFigures } from './scenario-session.js';
import { SimulatePanel } from './simulate-panel.js';
import { simulationModel } from './simulation-model.js';
import { STEP_INPUT_FILE } from './step-input.js';
import { shellWord } from '../util/shell-word.js';

/**
 * Where the browser keeps the session (its start, its steps, its time) across a reload: one per
 * browser, the last one changed in any tab, with the project it simulates.
 */
export const SESSION_KEY = 'contract-studio:sim-session';

/** How far "Next" looks for the engines' next change (virtual time). */
const LOOK_AHEAD_NS = 10_000_000_000;

export class SimulateController {
  readonly panel: SimulatePanel;
  readonly session = new ScenarioSession();
  /** The last run's answer (tests read it). */
  last: SimulateResponse | undefined;
  /** The Monitor's state of `last`'s steps (Save as scenario reads its deadline misses and overruns). */
  private lastShown: SchedulerFigures | undefined;
  /** Runs one after the other: each is the whole session again. */
  private running: Promise<unknown> = Promise.resolve();
  /** The existing file Save as scenario was last asked to write: a second ask replaces it. */
  private replaceAsked: string | undefined;

  constructor(private readonly deps: { lsp: LspClient; workspace: Workspace; monitor: MonitorController; project: () => string; reveal: () => void }) {
    this.panel = new SimulatePanel({
      start: (fn, params) => void this.start(fn, params),
      advance: (t) => void this.change(() => this.session.advance(t)),
      next: () => void this.next(),
      inject: (step) => void this.change(() => this.session.inject(step)).then((ok) => ok && this.panel.clearStep()),
      undo: () => void this.change(() => (this.session.undo(), undefined)),
      save: (path) => void this.save(path),
    });
    // a click on an out event port of the Monitor's diagram starts that step: `MAA:2 ` and its values
    document.addEventListener('click', (e) => {
      const port = (e.target as Element | null)?.closest?.('.monitor-diagram rect.port.event[data-dir="out"][data-port]');
      const name = port?.getAttribute('data-port');
      if (!name || !this.session.start || !/^[A-Za-z_]\w*:\d+$/.test(name)) return;
      this.deps.reveal();
      this.panel.stepInput.prefill(`${name} `);
    });
  }

  /** Reads the supervisor functions of the current project into the picker. */
  async refreshFunctions(): Promise<void> {
    const { workspace, lsp } = this.deps;
    const project = this.deps.project();
    const files = workspace.allFiles().filter((p) => isContract(p) && (!project || p.startsWith(`${project}/`)));
    const { catalogue, signatures } = await readSupervisorSymbols(files.map((p) => workspace.uriOf(p).toString()), (uri) => lsp.documentSymbols(uri));
    this.panel.stepInput.attach(workspace.uriOf(project ? `${project}/${STEP_INPUT_FILE}` : STEP_INPUT_FILE));
    const names = [...catalogue].flatMap(([sup, fns]) => [...fns.keys()].map((fn) => `${sup}.${fn}`)).sort();
    this.panel.setFunctions(names.map((name) => ({ name, signature: signatures.get(name) ?? '' })));
    if (!this.session.start && !this.restoring) {
      this.restoring = true;
      await this.restoreSaved(project);
    }
  }

  /** Set once the session kept across a reload was looked for (once per page). */
  private restoring = false;

  /**
   * Grows again the session this browser kept for `project` (a reload, a crash of the tab), and
   * simulates it. A session the model no longer accepts (a rule renamed meanwhile) is kept, its
   * steps shown with the diagnostics: Undo or a new Start drops it.
   */
  private async restoreSaved(project: string): Promise<void> {
    let saved: { project?: unknown } | null = null;
    try {
      saved = JSON.parse(localStorage.getItem(SESSION_KEY) ?? 'null') as { project?: unknown } | null;
    } catch {
      return; // not JSON: nothing to restore (the next change overwrites it)
    }
    if (!saved || saved.project !== project) return;
    const run = this.running.then(async () => {
      if (this.session.start) return; // a session was started meanwhile
      const error = this.session.restore(saved);
      if (error) return this.panel.showMessage(`the session kept from before the reload cannot be read (${error}): start a new one`, 'error');
      const s = this.session.start!;
      this.panel.showStart(`${s.supervisor}.${s.fn}`, s.params);
      this.panel.showTime(this.session.nowNs);
      if (await this.simulate()) {
        this.panel.showMessage(`restored the session of ${s.supervisor}.${s.fn} from before the reload: ${this.session.lines.length} step(s), at ${formatTime(this.session.nowNs)}`);
      }
    });
    this.running = run.catch(() => undefined);
    await run;
  }

  /** Keeps the session in the browser (a full storage: not kept, said once). */
  private keep(): void {
    const snapshot = this.session.snapshot();
    try {
      if (snapshot) localStorage.setItem(SESSION_KEY, JSON.stringify({ project: this.deps.project(), ...snapshot }));
      else localStorage.removeItem(SESSION_KEY);
    } catch (e) {
      if (!this.keepFailed) this.panel.showMessage(`the session is not kept across a reload: ${(e as Error).message}`, 'error');
      this.keepFailed = true;
    }
  }

  private keepFailed = false;

  private async start(fn: string, params: string): Promise<void> {
    const [supervisor = '', name = ''] = fn.split('.');
    const error = this.session.begin({ supervisor, fn: name, params });
    if (error) return this.panel.showMessage(error, 'error');
    // a start the checks refuse (a misspelt parameter) leaves no session behind
    if (!(await this.change(() => undefined))) {
      this.session.start = undefined;
      this.panel.showTime(undefined);
    }
  }

  /** Applies one session change and re-simulates; a refused run (diagnostics) undoes the change. */
  private async change(edit: () => string | undefined): Promise<boolean> {
    const run = this.running.then(async () => {
      const before = { now: this.session.nowNs, lines: [...this.session.lines] };
      const error = edit();
      if (error) {
        this.panel.showMessage(error, 'error');
        return false;
      }
      const ok = await this.simulate();
      if (!ok) {
        this.session.nowNs = before.now;
        this.session.lines.splice(0, this.session.lines.length, ...before.lines);
      } else {
        this.keep();
      }
      this.panel.showTime(this.session.start ? this.session.nowNs : undefined);
      return ok;
    });
    this.running = run.catch(() => undefined);
    return run;
  }

  /**
   * Steps to the next thing the engines do by themselves (FIRST's `elapsed=1ms` timer, a release,
   * a deadline): a look-ahead run of the session up to LOOK_AHEAD_NS later finds its time, then the
   * session runs to it.
   */
  private async next(): Promise<void> {
    if (!this.session.start) return this.panel.showMessage('start a supervisor function first', 'error');
    const from = this.session.nowNs;
    let at: number | undefined;
    try {
      const ahead = await api.simulate(this.deps.project(), this.session.text('look-ahead', from + LOOK_AHEAD_NS));
      at = ScenarioSession.nextChange(ahead.steps, from);
    } catch (e) {
      return this.panel.showMessage((e as Error).message, 'error');
    }
    if (at === undefined) return this.panel.showMessage(`nothing happens in the ${LOOK_AHEAD_NS / 1e9} s after ${formatTime(from)}: step by a time or inject an event`);
    await this.change(() => this.session.advance(formatTime(at)));
  }

  private async simulate(): Promise<boolean> {
    if (!this.session.start) {
      this.panel.showMessage('start a supervisor function first', 'error');
      return false;
    }
    const text = this.session.text();
    try {
      const r = await api.simulate(this.deps.project(), text);
      this.last = r;
      this.lastShown = undefined;
      this.panel.showResult(r);
      const failed = r.failures.map((f) => `line ${f.line}: ${f.message}`);
      if (r.trimmed) failed.push(r.trimmed.message);
      this.panel.showMessage(r.error ?? `simulated to ${formatTime(r.steps.at(-1)?.timeNs ?? 0)} in ${r.ms} ms (${r.eventsProcessed} engine inputs)`, r.error || failed.length ? 'error' : 'info', failed);
      const model = simulationModel(r.steps, this.session.nowNs);
      this.lastShown = model.live;
      // an answer keeps 200,000 records of all steps (the harness 100,000 of each kind a step): what was left out is said
      const dropped = r.steps.reduce((n, s) => n + (s.dropped ?? 0), 0);
      const notWhole = r.trimmed ? ` (not whole: the records stop before ${r.trimmed.line ? `line ${r.trimmed.line}` : 'the end'}, the simulator's bound)` : dropped ? ` (not whole: ${dropped} records left out, from the longest steps on)` : '';
      await this.deps.monitor.showSimulation(model, `Simulation: ${this.session.start.supervisor}.${this.session.start.fn}${notWhole}`);
      return true;
    } catch (e) {
      const diags = e instanceof ApiError && Array.isArray(e.details['diagnostics']) ? (e.details['diagnostics'] as Array<{ line: number; column: number; message: string; file?: string }>) : [];
      // a session line is shown as the user typed it: the diagnostics name the scenario's line
      const lines = diags.map((d) => `${d.file ? `${d.file}:` : 'line '}${d.line}:${d.column}: ${d.message}${d.file ? '' : `  (${this.lineText(d.line)})`}`);
      this.panel.showMessage((e as Error).message, 'error', lines);
      return false;
    }
  }

  private lineText(line: number): string {
    return this.session.text().split('\n')[line - 1] ?? '';
  }

  private async save(path: string): Promise<void> {
    const p = path.trim();
    if (!this.session.start || !this.last) return this.panel.showMessage('nothing to save: start a session first', 'error');
    if (!p.endsWith('.scenario')) return this.panel.showMessage('the file name must end in .scenario', 'error');
    const project = this.deps.project();
    const rel = project && !p.startsWith(`${project}/`) ? `${project}/${p}` : p;
    const text = this.session.withExpectations(this.last.steps, this.lastShown ?? { periodic: new Map() }, `session of ${this.session.start.supervisor}.${this.session.start.fn}`);
    // a file that exists (a scenario written by hand, maybe) is replaced only when asked twice
    const exists = this.deps.workspace.hasFile(rel);
    if (exists && this.replaceAsked !== rel) {
      this.replaceAsked = rel;
      return this.panel.showMessage(`${rel} exists: Save as scenario again to replace it with this session (${text.split('\n').length - 1} lines)`, 'error');
    }
    this.replaceAsked = undefined;
    try {
      if (exists) await api.write(rel, text);
      else await api.create(rel, 'file', text);
      this.panel.showMessage(`saved ${rel}: run it with \`contract simulate ${shellWord(project || '.')} ${shellWord(rel)}\``);
    } catch (e) {
      this.panel.showMessage(`could not save ${rel}: ${(e as Error).message}`, 'error');
    }
  }
}
