/**
 * The Monitor panel (docs/watching-a-run.md): a run's state at the time cursor — each
 * supervisor's functions and rules (active rules lit, with their last cause and time; a click
 * opens the rule in its .contract file), the active schemas, per periodic schema its releases,
 * response-time histogram against CRITICAL_DELAY and PERIOD, deadline misses and overruns, the
 * architecture diagram with active modules and pulsing flows, and the timeline strip.
 *
 * A supervisor that keeps requests for a receiver's full mailbox says so under its name while it
 * does (keptRequestsLine).
 *
 * Live and replay are the same view over a MonitorView (a MonitorModel on the page, or a live run
 * folded in a Web Worker: remote-model.ts); the cursor follows the end (live) or
 * stays where it was put (paused, scrubbed, or played back). Feeding records only marks the view
 * dirty: it redraws at most once per animation frame, and only what changed.
 */
import './monitor.css';
import { h } from '../util/dom.js';
import type { ArchSchema } from '../lsp/architecture-model.js';
import type { ArchitectureView } from '../views/architecture-view.js';
import type { MonitorView } from './model-view.js';
import type { MonitorState } from './monitor-state.js';
import { activeSchemas, lastActivated, type SchemaInfo } from './active-schemas.js';
import { MarksStrip, markTooltip } from './marks-strip.js';
import { drawHistogram, fmtNs, timeNs } from './response-histogram.js';
import { unheardEventText } from '@contract-studio/build-service/trace';
import { notSupervisorText, notSupervisors, supervisorRows, type SupervisorCatalogue } from './supervisor-rows.js';
import { NOT_IN_MODEL, crashedModulesText, flowRow, notReleasedText, schedulingText, flowWaitTitle, fmtT, followButton, keptRequestsLine, moduleCpuText, namesPastBoundText, releaseLatenessText, lateReleasesText, ruleTexts, quietDataFlowRow, isSimulatedFlowsLine, noActiveSchemaText, timeReadout, unheardEventsRow } from './panel-text.js';
import { visibleText } from '@contract-studio/conventions';
import { shortAtWord } from '../util/short-text.js';

export type { SupervisorCatalogue } from './supervisor-rows.js';

/** Width of the rules' name column, in characters: the longest name of the supervisor within these (longer ones are cut, whole in the tooltip). */
const RULE_NAME_MIN_CH = 12;
const RULE_NAME_MAX_CH = 28;

export interface MonitorPanelDeps {
  schemas: () => Promise<ArchSchema[]>;
  supervisors: () => Promise<SupervisorCatalogue>;
  /** The model's modules that are no supervisor, and what each is (supervisor-symbols.ts `modules`). */
  modelModules?: () => Promise<ReadonlyMap<string, string>>;
  openRule: (supervisor: string, fn: string, rule: string) => void;
  /** Creates the (lazily loaded) diagram that the panel animates. */
  createDiagram: () => Promise<ArchitectureView>;
  /** The user picked another run to show (an id of setSources). */
  onSource: (id: string) => void;
}

export interface SourceOption {
  id: string;
  label: string;
}

const PULSE_NS = 300e6;
/** Least time between two draws of a periodic schema's counts and histogram while following live, and
 *  after a deadline miss or an overrun (wall ms). */
const COUNTS_REDRAW_MS = 200;
const URGENT_REDRAW_MS = 50;
/** The same for the cursor's time and the diagram's marks (running modules, pulsing flows). */
const CLOCK_REDRAW_MS = 100;
/** While following a live run, the time readout alone runs with the run's clock this often, records or not (wall ms). */
const CLOCK_TICK_MS = 250;

/** What a periodic schema's block shows, to draw it again only when one of them moved (releases -1: not released yet). */
interface DrawnCounts { releases: number; completions: number; misses?: number; lateReleases?: number; overruns?: number; cd?: number; period?: number; live: boolean; empty: boolean }

export class MonitorPanel {
  readonly element: HTMLElement;
  private model: MonitorView | undefined;
  private live = false;
  /** The records run to the run's end (setModel): at the end, a module with no exit record is said to have ended without one. */
  private whole = false;
  private follow = true;
  private cursor = 0;
  private playing = false;
  private lastPlayWall = 0;
  /** The state at the cursor was asked of the model's worker and has not come yet. */
  private awaiting = false;
  private dirty = false;
  /** Drawn at the next frame whatever `drawn` says (redrawAll). */
  private stale = false;
  /** What the last frame drew (the browser tests count frames by its version). */
  drawn = { version: -1, cursor: -1, model: undefined as MonitorView | undefined };
  /** What the supervisors' list shows: while following live, it is drawn again only when one of these moved. */
  private supsDrawn = { model: undefined as MonitorView | undefined, changes: -1, sups: undefined as SupervisorCatalogue | undefined };
  private schemas: ArchSchema[] = [];
  private catalogue: SchemaInfo[] = [];
  private sups: SupervisorCatalogue = new Map();
  private modelModules: ReadonlyMap<string, string> = new Map();
  private diagram: ArchitectureView | undefined;
  private userChoseSchema = false;
  private redrawTimer: ReturnType<typeof setTimeout> | undefined;
  private redrawDue = 0;
  /** While following a live run: writes the time readout alone, so that it runs with the run's clock through a quiet stretch. */
  private clockTimer: ReturnType<typeof setInterval> | undefined;
  /** When each throttled part ('clock', 'diagram', 'flows', 'hist:<schema>') was last drawn (performance.now()): see due(). */
  private readonly drawnAt = new Map<string, number>();
  /** Last frame's render time (ms), for the benchmark. */
  frameMs: number[] = [];

  private readonly label = h('span', { class: 'monitor-source muted' }, 'No run yet');
  private readonly sourceSelect = h('select', { class: 'monitor-sources', 'aria-label': 'Run to show', title: RUN_LIST_TITLE });
  private readonly timeText = h('span', { class: 'monitor-time', 'aria-live': 'off' }, '');
  private readonly slider = h('input', { type: 'range', min: 0, max: 1000, step: 1, value: 1000, class: 'monitor-slider', 'aria-label': 'Time cursor' });
  private readonly followBtn = h('button', { class: 'btn small', id: 'monitor-follow', title: 'Put the cursor at the end of the run (End)' }, '⇥ End');
  private readonly playBtn = h('button', { class: 'btn small', id: 'monitor-play', title: 'Play the run back from the cursor, in real time', 'aria-label': 'Play the run from the cursor' }, '▷ Play');
  private readonly strip: MarksStrip;
  /**
   * What the mark ◀ / ▶ ([ / ]) jumped to is, in its tooltip's words: shown under the strip and said
   * (polite); written on a jump only, emptied when the cursor moves otherwise.
   */
  private readonly markSaid = h('div', { class: 'monitor-mark-said', role: 'status', 'aria-live': 'polite' });
  /** The modules crashed at the cursor (crashedModulesText): drawn at every frame that moved, said at once (an alert). */
  private readonly crashEl = h('div', { class: 'monitor-crashed', role: 'alert', hidden: true });
  private readonly supEl = h('div', { class: 'monitor-sups', role: 'list', 'aria-label': 'Supervisors' });
  private readonly schemasEl = h('div', { class: 'monitor-schemas', role: 'group', 'aria-label': 'Active schemas' });
  private readonly periodicEl = h('div', { class: 'monitor-periodic' });
  /** ORD's priority: whether the run was real-time (the story's line after ORD's start). */
  private readonly schedEl = h('div', { class: 'monitor-sched muted', role: 'note', hidden: true });
  private readonly diagramEl = h('div', { class: 'monitor-diagram' });
  private readonly modulesEl = h('div', { class: 'monitor-modules' });
  private readonly flowsEl = h('div', { class: 'monitor-flows', role: 'group', 'aria-label': 'Deliveries' });
  /** Said when records named more than the state folds (MAX_NAMES): a log that is no run's. */
  private readonly boundEl = h('div', { class: 'monitor-bound', role: 'status', hidden: true });
  private readonly rows = new Map<string, HTMLElement>();
  private readonly hists = new Map<string, { root: HTMLElement; title: HTMLElement; canvas: HTMLCanvasElement; text: HTMLElement; misses: HTMLElement; counts?: DrawnCounts }>();
  /** Each periodic schema's CRITICAL_DELAY and PERIOD in ns, read once per schema definition. */
  private readonly schemaTimes = new WeakMap<object, { cd?: number; period?: number }>();

  /** ◀ ⇥ End ▷ Play ▶: disabled until a run is shown. */
  private readonly cursorButtons: HTMLButtonElement[];

  constructor(private readonly deps: MonitorPanelDeps) {
    this.strip = new MarksStrip((f) => this.seek(f * (this.model?.end ?? 0)));
    // live: pause / follow again; a run that ended: to its end (it says what it does: no toggle)
    this.followBtn.addEventListener('click', () => this.setFollow(this.live ? !this.follow : true));
    this.sourceSelect.addEventListener('change', () => {
      this.drawSourceLabel();
      this.deps.onSource(this.sourceSelect.value);
    });
    this.playBtn.addEventListener('click', () => this.setPlaying(!this.playing));
    this.slider.addEventListener('input', () => this.seek((Number(this.slider.value) / 1000) * (this.model?.end ?? 0)));
    const step = (dir: -1 | 1) => this.jumpMark(dir);
    this.cursorButtons = [
      h('button', { class: 'btn small', id: 'monitor-prev', title: 'Previous mark ([)', 'aria-label': 'Previous mark', onclick: () => step(-1) }, '◀'),
      this.followBtn, this.playBtn,
      h('button', { class: 'btn small', id: 'monitor-next', title: 'Next mark (])', 'aria-label': 'Next mark', onclick: () => step(1) }, '▶'),
    ];
    // no run shown yet: the cursor's buttons and the slider have nothing to move (enabled by setModel)
    for (const b of this.cursorButtons) b.disabled = true;
    this.slider.disabled = true;
    this.element = h('div', { class: 'monitor-view', tabindex: -1, 'aria-label': 'Run monitor' },
      h('div', { class: 'monitor-toolbar', role: 'toolbar', 'aria-label': 'Time cursor controls' },
        h('strong', {}, '◉ Monitor'), this.sourceSelect, this.label, h('span', { class: 'grow' }),
        // the cursor's buttons wrap together in a narrow pane, never one alone on a line
        h('span', { class: 'monitor-buttons' }, ...this.cursorButtons)),
      h('div', { class: 'monitor-cursor' }, this.slider, this.timeText),
      this.strip.canvas,
      this.markSaid,
      this.crashEl,
      h('div', { class: 'monitor-body' },
        this.boundEl,
        // how ORD ran is the run's, not one of its schemas: a note of its own, above the sections
        this.schedEl,
        h('section', { class: 'monitor-section' }, h('h3', {}, 'Supervisors'), this.supEl),
        h('section', { class: 'monitor-section' }, h('h3', {}, 'Active schemas'), this.schemasEl, this.periodicEl),
        h('section', { class: 'monitor-section monitor-arch' }, h('h3', {}, 'Architecture'), this.modulesEl, this.diagramEl, this.flowsEl)));
    // a control focused by Tab in a short pane (a laptop at 150 %) is scrolled into view, not left
    // below the pane's edge
    this.element.addEventListener('focusin', (e) => {
      if (e.target instanceof HTMLElement && e.target !== this.element) e.target.scrollIntoView({ block: 'nearest', inline: 'nearest' });
    });
    this.element.addEventListener('keydown', (e) => {
      // a control's own keys are its own: Space presses a focused button (▷ Play, ▶, a rule), the
      // run list and text fields take every key; the slider takes its arrows, Home and End (Space
      // and the brackets work there too)
      if (ownKey(e.target, e.key)) return;
      if (e.key === ' ') this.setFollow(!this.follow);
      else if (e.key === '[') step(-1);
      else if (e.key === ']') step(1);
      else if (e.key === 'End') this.setFollow(true);
      else if (e.key === 'Home') this.seek(0);
      else return;
      e.preventDefault();
    });
  }

  /** Shows `model` (live: follows its end as records come). */
  setModel(model: MonitorView, label: string, live: boolean, whole = false): void {
    this.model = model;
    for (const b of this.cursorButtons) b.disabled = false;
    this.slider.disabled = false;
    this.live = live;
    this.whole = whole;
    this.label.textContent = visibleText(label);
    this.drawSourceLabel();
    this.element.dataset.mode = live ? 'live' : 'replay';
    this.setPlaying(false);
    this.setFollow(true);
    void this.refreshModel();
  }

  /** The runs the user can pick (`selected` shown). */
  setSources(options: SourceOption[], selected: string | undefined): void {
    this.sourceSelect.replaceChildren(h('option', { value: '', disabled: true, selected: !selected }, options.length ? 'Choose a run…' : 'No run yet'),
      ...options.map((o) => runListOption(o, o.id === selected)));
    this.drawSourceLabel();
  }

  /**
   * The run list's tooltip is the chosen run's whole label (the list is as wide as that label, up to
   * the pane: monitor.css); the label beside the list is shown only when it says something the
   * chosen entry does not (`Reading …`, a label the entry has not caught up with yet).
   */
  private drawSourceLabel(): void {
    const chosen = this.sourceSelect.selectedOptions[0];
    const whole = chosen?.value ? (chosen.getAttribute('aria-label') ?? chosen.textContent ?? '') : '';
    const title = whole || RUN_LIST_TITLE;
    if (this.sourceSelect.title !== title) this.sourceSelect.title = title;
    this.label.hidden = whole !== '' && this.label.textContent === whole;
  }

  get current(): MonitorView | undefined {
    return this.model;
  }

  /** The label of the run shown (what it is, and what it lacks). */
  setLabel(label: string): void {
    this.label.textContent = visibleText(label);
    this.drawSourceLabel();
  }

  /** The live source ended (the model stays, as a recorded run); `whole`: its records are known to run to the run's end (setModel). */
  endLive(label: string, whole?: boolean): void {
    this.live = false;
    if (whole !== undefined) this.whole = whole;
    this.label.textContent = visibleText(label);
    this.drawSourceLabel();
    this.element.dataset.mode = 'replay';
    this.drawFollow();
    // the readout stops saying live now, not at the next frame: with a large run that frame can
    // come seconds later on a loaded machine, while the run list already says "ended"
    if (this.model) this.drawClock(this.model, this.time, performance.now());
    this.redrawAll(); // what was held back while following is drawn now
  }

  /** Re-reads the schemas and supervisors of the workspace model (after an edit, or on open). */
  async refreshModel(): Promise<void> {
    try {
      const [schemas, sups, modules] = await Promise.all([this.deps.schemas(), this.deps.supervisors(), this.deps.modelModules?.() ?? new Map<string, string>()]);
      this.schemas = schemas;
      this.catalogue = schemas.map((s) => ({ name: s.name, kind: s.kind, modules: s.modules.map((m) => m.name) }));
      this.sups = sups;
      this.modelModules = modules;
    } catch {
      /* the model does not parse: keep the last one */
    }
    if (!this.diagram) {
      this.diagram = await this.deps.createDiagram();
      this.diagramEl.replaceChildren(this.diagram.element);
      this.diagram.element.querySelector('select')?.addEventListener('change', () => (this.userChoseSchema = true));
    }
    await this.diagram.update();
    this.redrawAll();
  }

  setFollow(on: boolean): void {
    this.follow = on;
    setText(this.markSaid, '');
    if (on) this.setPlaying(false);
    else this.cursor = this.model?.end ?? 0; // paused where the run is now
    this.drawFollow();
    this.redrawAll(); // paused where the run is: what was held back while following is drawn now
  }

  setPlaying(on: boolean): void {
    this.playing = on && !!this.model;
    if (this.playing) {
      this.follow = false;
      setText(this.markSaid, '');
      this.drawFollow();
      if (this.model && this.cursor >= this.model.end) this.cursor = 0;
      this.lastPlayWall = performance.now();
    }
    // its name says what pressing it does (no aria-pressed, as for Pause/Follow)
    this.playBtn.textContent = this.playing ? '❚❚ Stop' : '▷ Play';
    this.playBtn.setAttribute('aria-label', this.playing ? 'Stop playing the run' : 'Play the run from the cursor');
    this.redrawAll();
  }

  /** Moves the cursor to t (ns since the start) and stops following. */
  seek(t: number): void {
    this.follow = false;
    setText(this.markSaid, '');
    this.drawFollow();
    this.cursor = Math.max(0, Math.min(t, this.model?.end ?? 0));
    this.schedule();
  }

  /**
   * The follow button (panel-text.ts followButton): on a live run it pauses (❚❚ Pause) and follows
   * the newest record again (⇥ Follow); on a run that ended (a replay, a job that finished, failed
   * or was cancelled) there is nothing to follow: it puts the cursor at the run's end (⇥ End). Its
   * name says what it does (no aria-pressed: "pressed" while following read as paused);
   * data-following says whether the cursor follows the end.
   */
  private drawFollow(): void {
    const b = this.followBtn;
    const v = followButton(this.live, this.follow);
    setText(b, v.text);
    setAttr(b, 'aria-label', v.label);
    setAttr(b, 'title', v.title);
    setAttr(b, 'data-following', String(this.follow));
    // the time readout runs with the run's clock only while it follows a live run
    const ticking = this.live && this.follow;
    if (ticking && !this.clockTimer) this.clockTimer = setInterval(() => this.tickClock(), CLOCK_TICK_MS);
    else if (!ticking && this.clockTimer) {
      clearInterval(this.clockTimer);
      this.clockTimer = undefined;
    }
  }

  /**
   * The time readout alone, with the run's clock (a quiet stretch of a live run does not look
   * stalled): nothing else is drawn, and it is written at most once per CLOCK_REDRAW_MS with the
   * frames' own writes of it.
   */
  private tickClock(): void {
    const m = this.model;
    if (!m || !this.live || !this.follow || !this.element.isConnected) return;
    const now = performance.now();
    if (now - (this.drawnAt.get('clock') ?? 0) < CLOCK_REDRAW_MS) return;
    this.drawnAt.set('clock', now);
    this.drawClock(m, m.end, now);
  }

  /** The time readout and the slider at `t` (`now`: performance.now()). */
  private drawClock(m: MonitorView, t: number, now: number): void {
    const following = this.live && this.follow;
    setText(this.timeText, timeReadout({ t, end: m.end, following, runClock: following ? m.runClock?.(now) : undefined, exact: m.exactAt(t) }));
    this.slider.value = String(m.end > 0 ? Math.round((t / m.end) * 1000) : 1000);
    setAttr(this.slider, 'aria-valuetext', fmtT(t));
  }

  /** The cursor's time (ns since the run's first record). */
  get time(): number {
    return this.follow ? (this.model?.end ?? 0) : this.cursor;
  }

  private jumpMark(dir: -1 | 1): void {
    const m = this.model;
    if (!m) return;
    const t = this.time;
    const marks = dir > 0 ? m.marksBetween(t + 1, m.end) : m.marksBetween(0, t - 1);
    const next = dir > 0 ? marks[0] : marks[marks.length - 1];
    this.seek(next ? next.t : dir > 0 ? m.end : 0);
    // said and shown: the marks at that time, in the strip's tooltip's words
    setText(this.markSaid, next ? markTooltip(m.marksBetween(next.t, next.t)) : dir > 0 ? 'No next mark: the end of the run' : 'No previous mark: the start of the run');
  }

  /** The next frame draws even if the model and the cursor are as drawn (what it draws changed: a throttled part is due, the workspace model was read again). */
  private redrawAll(): void {
    this.stale = true;
    this.schedule();
  }

  /** Marks the view dirty; it redraws on the next animation frame (coalesced). */
  schedule(): void {
    if (this.dirty) return;
    this.dirty = true;
    requestAnimationFrame(() => this.frame());
  }

  private frame(): void {
    this.dirty = false;
    const m = this.model;
    if (!m) return;
    if (this.playing) {
      // played back from a worker's model, the cursor waits for the state it asked for (else it
      // would ask for a newer time at every frame and draw none); the wall time it waited is caught up
      if (!this.awaiting) {
        const now = performance.now();
        this.cursor += (now - this.lastPlayWall) * 1e6;
        this.lastPlayWall = now;
      }
      if (this.cursor >= m.end) {
        this.cursor = m.end;
        this.setPlaying(false);
      } else this.schedule();
    }
    const t = this.time;
    if (!this.stale && this.drawn.model === m && this.drawn.version === m.version && this.drawn.cursor === t) return;
    this.stale = false;
    if (!this.element.isConnected) return;
    const t0 = performance.now();
    const s = m.stateAt(t);
    this.awaiting = !s;
    if (!s) return; // asked of the worker: drawn when it comes (the model's version then moves)
    this.render(m, t, s);
    this.drawn = { model: m, version: m.version, cursor: t };
    this.frameMs.push(performance.now() - t0);
    if (this.frameMs.length > 5000) this.frameMs.splice(0, 1000);
  }

  private render(m: MonitorView, t: number, s: MonitorState): void {
    this.element.dataset.t = String(Math.round(t));
    // at every frame of a live run of a fast schema, records come but the supervisors seldom
    // change: their list (strings and arrays for every rule) is rebuilt only when they did
    const d = this.supsDrawn;
    const supervisorsMoved = !(this.live && this.follow && d.model === m && d.changes === s.supervisorChanges && d.sups === this.sups);
    // the time readout is throttled, but never behind what the frame shows: drawn with a rule change
    if (supervisorsMoved) {
      this.drawnAt.set('clock', performance.now());
      this.drawClock(m, t, performance.now());
    } else if (this.due('clock', CLOCK_REDRAW_MS)) this.drawClock(m, t, performance.now());
    this.strip.draw(m.marks, m.end, t);
    const crashed = crashedModulesText(s.modules);
    this.crashEl.hidden = !crashed;
    setText(this.crashEl, crashed);
    if (supervisorsMoved) {
      this.renderSupervisors(s);
      this.supsDrawn = { model: m, changes: s.supervisorChanges, sups: this.sups };
    }
    const active = activeSchemas(s, this.catalogue);
    this.renderSchemas(m, s, active);
    this.renderDiagram(s, t, active.map((a) => a.name), lastActivated(s, active));
  }

  private row(key: string, make: () => HTMLElement): HTMLElement {
    let el = this.rows.get(key);
    if (!el) this.rows.set(key, (el = make()));
    return el;
  }

  private renderSupervisors(s: MonitorState): void {
    const blocks: HTMLElement[] = [];
    for (const { name: sup, state: st, functions: fns, inModel, notInModel } of supervisorRows(this.sups, s, this.modelModules)) {
      const block = this.row(`sup:${sup}`, () => h('div', { class: 'monitor-sup', role: 'listitem', 'data-supervisor': sup }));
      const header = this.row(`suph:${sup}`, () => h('div', { class: 'monitor-sup-name' }));
      setText(header, `${sup}${inModel === false ? ` ${NOT_IN_MODEL}` : ''}${st ? ` · ${st.actionsDone} action(s) done, ${st.actionsUndone} undone` : ''}`);
      setAttr(header, 'title', header.textContent ?? '');
      setAttr(header, 'data-in-model', String(inModel !== false));
      const children: HTMLElement[] = [header];
      // the receivers whose full mailbox makes it keep requests, while it does: rows by place, not
      // by name (a forged log may name a new receiver at each streak: the rows stay as few as shown)
      let i = 0;
      for (const [receiver, kept] of st?.keptFor ?? []) {
        const el = this.row(`kept:${sup}:${i++}`, () => h('div', { class: 'monitor-kept' }));
        setText(el, keptRequestsLine(receiver, kept));
        setAttr(el, 'title', el.textContent ?? '');
        setAttr(el, 'data-receiver', receiver);
        children.push(el);
      }
      const longest = Math.max(0, ...[...fns.values()].map((rules) => Math.max(0, ...rules.map((r) => r.length))));
      block.style.setProperty('--rule-name-ch', String(Math.min(RULE_NAME_MAX_CH, Math.max(RULE_NAME_MIN_CH, longest + 1))));
      for (const [fn, rules] of fns) {
        const fs = st?.functions.get(fn);
        const fnEl = this.row(`fn:${sup}.${fn}`, () => h('div', { class: 'monitor-fn', 'data-function': `${sup}.${fn}` }));
        setText(fnEl, `${fn}()${notInModel.has(fn) ? ` ${NOT_IN_MODEL}` : ''} — ${fs ? `${fs.state} since ${fmtT(fs.since)}` : 'not started'}`);
        setAttr(fnEl, 'title', fnEl.textContent ?? '');
        setAttr(fnEl, 'data-state', fs?.state ?? 'idle');
        setAttr(fnEl, 'data-in-model', String(!notInModel.has(fn)));
        children.push(fnEl);
        for (const rule of rules) {
          const gone = notInModel.has(`${fn}.${rule}`);
          const rs = st?.rules.get(`${fn}.${rule}`);
          const el = this.row(`rule:${sup}.${fn}.${rule}`, () => {
            const b = h('button', { class: 'monitor-rule', 'data-rule': `${sup}.${fn}.${rule}` },
              h('span', { class: 'rule-dot', 'aria-hidden': 'true' }), h('span', { class: 'rule-name' }, visibleText(rule)), h('span', { class: 'rule-cause' }), h('span', { class: 'rule-time' }));
            b.addEventListener('click', () => this.deps.openRule(sup, fn, rule));
            return b;
          });
          setAttr(el, 'data-active', String(!!rs?.active));
          const texts = ruleTexts(fn, rule, rs, gone, notInModel.has(fn));
          // a plain button (it opens the rule): its name says its state, no aria-pressed
          setAttr(el, 'aria-label', texts.label);
          setAttr(el, 'data-in-model', String(!gone));
          setText(el.children[2] as HTMLElement, texts.shown);
          setText(el.children[3] as HTMLElement, rs ? fmtT(rs.since) : '');
          // the cause is cut to the row's width: whole in the tooltip (and in the text read out)
          setAttr(el, 'title', texts.title);
          setAttr(el, 'data-cause', rs?.cause ?? '');
          setAttr(el, 'data-since', rs ? String(rs.since) : '');
          children.push(el);
        }
      }
      replaceIfChanged(block, children);
      blocks.push(block);
    }
    if (!blocks.length) blocks.push(this.row('sup:none', () => h('div', { class: 'muted' }, 'No supervisor in the trace yet')));
    // a module the model says is no supervisor, whose log holds supervisor records: said once, not listed
    for (const { name, is } of notSupervisors(this.sups, s, this.modelModules)) {
      const el = this.row(`notsup:${name}`, () => h('div', { class: 'muted monitor-not-supervisor', 'data-module': name }));
      setText(el, notSupervisorText(name, is));
      setAttr(el, 'title', el.textContent ?? '');
      blocks.push(el);
    }
    replaceIfChanged(this.supEl, blocks);
  }

  private renderSchemas(m: MonitorView, s: MonitorState, active: ReturnType<typeof activeSchemas>): void {
    const items = active.map((a) => {
      const el = this.row(`schema:${a.name}`, () => h('div', { class: 'monitor-schema', 'data-schema': a.name }));
      setText(el, `● ${a.name} (${a.kind})${a.by ? ` ← ${a.by}` : ''}`);
      return el;
    });
    // none active: once one has ended, which, when and why (a simulation's or a run's end reads as such)
    if (!items.length) {
      const none = this.row('schema:none', () => h('div', { class: 'muted monitor-schemas-none' }, 'none'));
      setText(none, noActiveSchemaText(s)); // setText writes it visibly
      items.push(none);
    }
    replaceIfChanged(this.schemasEl, items);
    setText(this.schedEl, s.ordPriority ? schedulingText(s.ordPriority) : ''); // setText writes it visibly
    if (this.schedEl.hidden !== !s.ordPriority) this.schedEl.hidden = !s.ordPriority;
    const periodic = [...new Set([...this.catalogue.filter((c) => c.kind === 'periodic').map((c) => c.name), ...s.periodic.keys()])];
    const blocks = periodic.map((name) => {
      const p = s.periodic.get(name);
      const def = this.schemas.find((x) => x.name === name);
      let times = def ? this.schemaTimes.get(def) : undefined;
      if (def && !times) this.schemaTimes.set(def, (times = { cd: timeNs(def.criticalDelay), period: timeNs(def.period) }));
      const cd = times?.cd, period = times?.period;
      let hist = this.hists.get(name);
      if (!hist) {
        const canvas = h('canvas', { class: 'monitor-hist', width: 320, height: 70, role: 'img', 'aria-label': visibleText(`Response times of ${name} against CRITICAL_DELAY and PERIOD`) });
        const text = h('div', { class: 'monitor-pstats' });
        const misses = h('div', { class: 'monitor-misses' });
        const title = h('div', { class: 'monitor-pname' });
        hist = { root: h('div', { class: 'monitor-pschema', 'data-periodic': name }, title, text, canvas, misses), title, canvas, text, misses };
        this.hists.set(name, hist);
      }
      // counts change every cycle of a fast schema: redrawn at most 5 times a second; a miss or an
      // overrun at once, or within 50 ms of the last one in a storm of them (a 1 kHz schema missing
      // every cycle would otherwise rebuild this block every frame)
      // (compared field by field: a key string built at every frame was a good part of the page's garbage)
      const was = hist.counts;
      // (a run that ends, or has no records at all, says so in a block never released)
      const empty = m.recordCount === 0;
      const urgent = !was || was.misses !== p?.deadlineMisses || was.lateReleases !== p?.lateReleases || was.overruns !== p?.overruns || was.cd !== cd || was.period !== period || was.live !== this.live || was.empty !== empty;
      const changed = urgent || (p ? was.releases !== p.releases || was.completions !== p.completions : was.releases !== -1);
      if (changed && this.due(`hist:${name}`, urgent ? URGENT_REDRAW_MS : COUNTS_REDRAW_MS)) {
        hist.counts = { releases: p?.releases ?? -1, completions: p?.completions ?? -1, misses: p?.deadlineMisses, lateReleases: p?.lateReleases, overruns: p?.overruns, cd, period, live: this.live, empty };
        setText(hist.title, `${name} · PERIOD ${def?.period ?? '?'} · CRITICAL_DELAY ${def?.criticalDelay ?? '?'}`);
        setText(hist.text, p
          ? `${p.releases} module release(s) · last cycle ${p.lastCycle} · ${p.completions} cycle(s) complete · ${p.completions ? `response last ${fmtNs(p.lastResponseNs)}, mean ${fmtNs(p.sumResponseNs / p.completions)}, max ${fmtNs(p.maxResponseNs)}` : 'no response time yet'} · ${p.deadlineMisses} deadline miss(es)${lateReleasesText(p.lateReleases)} · ${p.overruns} overrun(s)${p.overrunning ? ' (its last cycle overran: ORD tells how many releases it skipped only when it ends)' : ''}${p.missedTicks ? ` · ${p.missedTicks} missed tick(s)` : ''}${releaseLatenessText(p)}${moduleCpuText(p.modules, s.modules)}`
          : notReleasedText(this.live, empty));
        setAttr(hist.root, 'data-releases', String(p?.releases ?? 0));
        setAttr(hist.root, 'data-misses', String(p?.deadlineMisses ?? 0));
        setAttr(hist.root, 'data-late-releases', String(p?.lateReleases ?? 0));
        setAttr(hist.root, 'data-overruns', String(p?.overruns ?? 0));
        drawHistogram(hist.canvas, p?.histogram ?? [], cd, period);
        // each miss's tooltip: its mark's label, which names what the cycle was still waiting for
        // the last few of each, said so when there were more (the timeline marks the others)
        const misses = (p?.recentMisses ?? []).slice(-5);
        const overruns = (p?.recentOverruns ?? []).slice(-3);
        const lates = (p?.recentLateReleases ?? []).slice(-3);
        const lastOf = (shown: number, all: number, what: string) =>
          all > shown ? [h('span', { class: 'miss-more', title: 'The earlier ones are marked on the timeline ([ and ] step through the marks)' }, `the last ${shown} of ${all} ${what}:`)] : [];
        // each is a button: a click (or Enter) moves the cursor to it, as the strip's marks do
        const chip = (cls: string, t: number, label: string, text: string, cycle?: number) => {
          const b = h('button', { type: 'button', class: cls, ...(cycle !== undefined ? { 'data-cycle': cycle } : {}), title: `${visibleText(label)} (click: the cursor goes there)` }, text);
          b.addEventListener('click', () => this.seek(t));
          return b;
        };
        hist.misses.replaceChildren(...lastOf(misses.length, p?.deadlineMisses ?? 0, 'deadline misses'), ...misses.map((x) => chip('miss', x.t,
          m.marksBetween(x.t, x.t).find((k) => k.kind === 'miss' && k.where === name)?.label ?? `deadline miss (ORD:0) cycle ${x.cycle}`,
          `ORD:0 cycle ${x.cycle} at ${fmtT(x.t)}`, x.cycle)),
          ...lastOf(lates.length, p?.lateReleases ?? 0, 'late releases'),
          // each late release's tooltip: ORD's line, as `contract trace` tells it (no ORD:0: ORD itself was late)
          ...lates.map((x) => chip('late-release', x.t,
            m.marksBetween(x.t, x.t).find((k) => k.kind === 'late' && k.where === name)?.label ?? `late release: ${name} cycle ${x.cycle} (ORD late, no ORD:0)`,
            `late release cycle ${x.cycle} at ${fmtT(x.t)}`, x.cycle)),
          ...lastOf(overruns.length, p?.overruns ?? 0, 'overruns'),
          // each overrun's tooltip: its mark's label, ORD's line as it says it (the module the cycle still waits for, when it names one)
          ...overruns.map((x) => chip('overrun', x.t,
            m.marksBetween(x.t, x.t).find((k) => k.kind === 'overrun' && k.where === name)?.label ?? `overrun after cycle ${x.cycle}`,
            `overrun after cycle ${x.cycle} at ${fmtT(x.t)}`)));
      }
      return hist.root;
    });
    replaceIfChanged(this.periodicEl, blocks);
  }

  /**
   * Whether `part` is drawn in this frame. While following a live run, the parts that change at
   * every cycle of a fast schema (the cursor's time, the diagram's running modules and pulses, the
   * deliveries' counts, each periodic schema's counts and histogram) are drawn at most once per `ms`: each draw is a style, layout and paint
   * pass of the page, and nobody reads a number that changes 60 times a second. A part held back
   * is drawn by a frame `ms` later even when nothing new comes. Paused, scrubbed or replayed: every frame.
   */
  private due(part: string, ms: number): boolean {
    const now = performance.now();
    const wait = ms - (now - (this.drawnAt.get(part) ?? 0));
    if (this.live && this.follow && wait > 0) {
      this.redrawSoon(wait);
      return false;
    }
    this.drawnAt.set(part, now);
    return true;
  }

  /** A frame again in `ms` even when nothing new comes (a throttled part is then drawn). */
  private redrawSoon(ms: number): void {
    const due = performance.now() + ms;
    if (this.redrawTimer && this.redrawDue <= due) return;
    clearTimeout(this.redrawTimer);
    this.redrawDue = due;
    this.redrawTimer = setTimeout(() => {
      this.redrawTimer = undefined;
      this.redrawAll();
    }, ms);
  }

  private renderDiagram(s: MonitorState, t: number, active: string[], last: string | undefined): void {
    const d = this.diagram;
    if (!d) return;
    // the schema that became active last at the cursor's time, until the user picks one in the list:
    // the same in every tab, live or replayed, at the same time
    if (!this.userChoseSchema && last !== undefined && d.schema !== last) void d.choose(last);
    // both asked in this order at every frame, as each keeps its own time; while following, a frame
    // that draws neither computes nothing more
    const drawDiagram = this.due('diagram', CLOCK_REDRAW_MS);
    const drawFlows = this.due('flows', COUNTS_REDRAW_MS);
    if (!drawDiagram && !drawFlows) return;
    const modules = new Set<string>();
    for (const name of active) for (const m of this.catalogue.find((c) => c.name === name)?.modules ?? []) modules.add(m);
    // at the end of a whole run, a module still up has no exit record: it ended without one, not running
    const atEnd = this.whole && !this.live && t >= (this.model?.end ?? 0);
    const running = new Set<string>();
    const noExit: string[] = [];
    const crashed: string[] = [];
    const gone: string[] = [];
    for (const [k, m] of s.modules) {
      if (m.crashed !== undefined) crashed.push(k);
      else if (m.gone !== undefined) gone.push(k);
      else if (atEnd && m.alive) noExit.push(k);
      else if (m.running) running.add(k);
    }
    const pulsing = new Set<string>();
    const used = new Set<string>();
    for (const flows of [s.dataFlows, s.eventFlows]) {
      for (const [k, f] of flows) {
        used.add(k);
        if (t - f.last < PULSE_NS) pulsing.add(k);
      }
    }
    if (drawDiagram) d.highlight({ active: modules, running, pulsing, used });
    if (!drawFlows) return;
    setText(this.modulesEl, modulesText([...running], noExit, crashed, gone));
    this.boundEl.hidden = s.namesPastBound === 0;
    setText(this.boundEl, namesPastBoundText(s.namesPastBound));
    // deliveries: the busiest flows, with their count and last delivery
    // (a flow that drops values comes first: its consumer does not read it)
    // the events no one received first (why a rule waiting for them did not fire), each port's
    const unheard = [...s.unheardEvents].sort((a, b) => b[1].count - a[1].count).slice(0, 12).map(([port, f]) => {
      const el = this.row(`unheard:${port}`, () => h('div', { class: 'monitor-flow event unheard', 'data-unheard': port, title: visibleText(unheardEventText(port)) }));
      setText(el, unheardEventsRow(port, f));
      return el;
    });
    // the connected data flows that delivered nothing or far less than read, once the records are over (trace's words)
    const quiet = (this.model?.live ?? s).quietDataFlows.slice(0, 12 - unheard.length).map((line) => {
      const el = this.row(`quiet:${line}`, () => h('div', { class: `monitor-flow data quiet${isSimulatedFlowsLine(line) ? ' simulated' : ''}`, title: visibleText(line) }));
      setText(el, quietDataFlowRow(line));
      return el;
    });
    const flows = [...[...s.dataFlows].map(([k, f]) => ({ k, f, kind: 'data' as const })), ...[...s.eventFlows].map(([k, f]) => ({ k, f, kind: 'event' as const }))]
      .sort((a, b) => (b.f.dropped ?? 0) - (a.f.dropped ?? 0) || (b.f.waits ?? 0) - (a.f.waits ?? 0) || (b.f.unmatched ?? 0) - (a.f.unmatched ?? 0) || b.f.count - a.f.count).slice(0, Math.max(0, 12 - unheard.length - quiet.length));
    const rows = flows.map(({ k, f, kind }) => {
      const el = this.row(`flow:${kind}:${k}`, () => h('div', { class: `monitor-flow ${kind}`, 'data-flow': k }));
      setText(el, flowRow(kind, k, f));
      setAttr(el, 'data-unmatched', String(f.unmatched ?? 0));
      setAttr(el, 'data-pulse', String(pulsing.has(k)));
      setAttr(el, 'data-dropped', String(f.dropped ?? 0));
      setAttr(el, 'data-waited', String(f.waits ?? 0));
      setAttr(el, 'title', kind === 'event' ? flowWaitTitle(k, f) : '');
      return el;
    });
    replaceIfChanged(this.flowsEl, [...unheard, ...quiet, ...rows]);
  }
}

/**
 * `Running now: MAA, MAB`, then the modules whose code crashed (`· crashed: EST`), then those gone
 * with no record of their end (`· gone: SRT`: another module's record says so); at the end of a
 * whole run, the modules with no exit record are said as `contract trace` says them (its story's
 * `no exit record follows`), not as running.
 */
export function modulesText(running: string[], noExit: string[], crashed: string[] = [], gone: string[] = []): string {
  const now = `Running now: ${running.sort().join(', ') || 'none'}${crashed.length ? ` · crashed: ${crashed.sort().join(', ')}` : ''}${gone.length ? ` · gone: ${gone.sort().join(', ')}` : ''}`;
  if (!noExit.length) return now;
  return `${now} · no exit record: ${noExit.sort().join(', ')} (crashed, killed, or ended by its code's exit(): the run's messages say which)`;
}

/** The run list's tooltip while no run is chosen. */
const RUN_LIST_TITLE = 'Run to show: the live run, a finished job\'s CSV logs, or CSV logs of the workspace';

/** An entry of the run list longer than this is ended at a word with `…` (a failed job's message can be hundreds of characters). */
export const RUN_LIST_CHARS = 240;

/** An entry of the run list: its label, shortened when long (shortAtWord), the whole label then its tooltip and accessible name. */
function runListOption(o: SourceOption, selected: boolean): HTMLOptionElement {
  const label = visibleText(o.label);
  const text = shortAtWord(label, RUN_LIST_CHARS);
  const whole = text === label ? undefined : label;
  return h('option', { value: o.id, selected, title: whole, 'aria-label': whole }, text);
}

/** Whether `key` pressed on `target` is the focused control's own key, not the panel's shortcut. */
function ownKey(target: EventTarget | null, key: string): boolean {
  if (!(target instanceof HTMLElement)) return false;
  if (target instanceof HTMLInputElement) return target.type !== 'range' || (key !== ' ' && key !== '[' && key !== ']');
  if (target instanceof HTMLSelectElement || target instanceof HTMLTextAreaElement || target.isContentEditable) return true;
  const pressable = target instanceof HTMLButtonElement || target instanceof HTMLAnchorElement || /^(button|link|checkbox|switch|menuitem|tab|option)$/.test(target.getAttribute('role') ?? '');
  return pressable && (key === ' ' || key === 'Enter');
}

/**
 * The panel's text: what the rows say holds a record's names and values (anybody's), written
 * visibly at the last step too (conventions' visibleText, its line breaks kept: the crashed
 * modules' alert is a line each), whatever built it; the words of panel-text.ts already are.
 */
function setText(el: HTMLElement, text: string): void {
  const shown = visibleText(text, { keepNewlines: true });
  if (el.textContent !== shown) el.textContent = shown;
}

/** What is read or shown of an element (its tooltip, its accessible name) is written visibly; its data-* attributes keep the raw text. */
const SHOWN_ATTRIBUTES = new Set(['title', 'aria-label']);

function setAttr(el: HTMLElement, name: string, value: string): void {
  const shown = SHOWN_ATTRIBUTES.has(name) ? visibleText(value, { keepNewlines: true }) : value;
  if (el.getAttribute(name) !== shown) el.setAttribute(name, shown);
}

function replaceIfChanged(parent: HTMLElement, children: HTMLElement[]): void {
  const cur = parent.children;
  if (cur.length === children.length && children.every((c, i) => cur[i] === c)) return;
  parent.replaceChildren(...children);
}
