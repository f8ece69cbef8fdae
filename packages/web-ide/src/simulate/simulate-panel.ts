/**
 * The Simulate panel's DOM (docs/simulation.md "In the IDE"): the supervisor function and its
 * parameters, Start, the virtual time (step by a time, run to a time), a step to inject, Undo,
 * Save as scenario; then the state after the last step: rules (active/inactive with their
 * causes), active schemas, locals, and each step with the rule changes and actions it produced
 * (in a run's words, with what the module and flow holds decided: simulator/trace action-lines.ts).
 * It only draws and reports clicks: simulate-controller.ts owns the session and the server calls.
 */
import { formatTime } from '@contract-studio/language/scenario';
import { readableCause } from '@contract-studio/build-service/trace';
import { visibleText } from '@contract-studio/conventions';
import { actionLines } from '@contract-studio/simulator/trace';
import { h } from '../util/dom.js';
import './simulate.css';
import type { SimulateResponse } from '../../server/api-types.js';
import { ruleStates } from './scenario-session.js';
import { StepInput } from './step-input.js';

export interface SimulatePanelActions {
  start(fn: string, params: string): void;
  advance(time: string): void;
  /** To the next thing the engines do by themselves (a timer, a release). */
  next(): void;
  inject(step: string): void;
  undo(): void;
  save(path: string): void;
}

const MAX_SHOWN_STEPS = 200;

export class SimulatePanel {
  readonly element: HTMLElement;
  private readonly fnSelect = h('select', { class: 'sim-fn', 'aria-label': 'supervisor function' });
  private readonly params = h('input', { class: 'sim-params', 'aria-label': 'the function\'s parameters (empty: its defaults)', placeholder: 'parameters: consigne = {1.0, 2.0, 3.0} (empty: defaults)', spellcheck: false });
  private readonly timeInput = h('input', { class: 'sim-time', value: '+1ms', 'aria-label': 'time: +1ms steps, 1ms runs to', spellcheck: false });
  /** A one-line scenario editor (completion from the language server): step-input.ts. */
  readonly stepInput: StepInput;
  private readonly savePath = h('input', { class: 'sim-save-path', value: 'scenarios/session.scenario', 'aria-label': 'scenario file', spellcheck: false });
  private readonly now = h('span', { class: 'sim-now' }, 'not started');
  private readonly message = h('div', { class: 'sim-message' });
  private readonly rules = h('div', { class: 'sim-rules' });
  private readonly schemas = h('div', { class: 'sim-schemas' });
  private readonly locals = h('div', { class: 'sim-locals' });
  private readonly steps = h('div', { class: 'sim-steps' });

  constructor(actions: SimulatePanelActions) {
    this.fnSelect.addEventListener('change', () => this.showSignature());
    const btn = (cls: string, label: string, title: string, on: () => void) => h('button', { class: `btn ${cls}`, title, onclick: on }, label);
    this.stepInput = new StepInput({ enter: (text) => actions.inject(text), escape: () => this.onEscape?.() }, 'MAA:2 connection_status = "disconnected"   (Ctrl+Space: completion)');
    this.timeInput.addEventListener('keydown', (e) => {
      if (e.key === 'Enter') actions.advance(this.timeInput.value);
    });
    this.element = h('div', { class: 'simulate-panel' },
      h('div', { class: 'sim-bar' },
        this.fnSelect, this.params,
        btn('sim-start', '▶ Start', 'Start a new session: the function started at t=0', () => actions.start(this.fnSelect.value, this.params.value)),
        h('span', { class: 'sim-sep' }, 't ='), this.now,
        btn('sim-next', 'Next', 'Step to the next thing the engines do by themselves: a timer, a release, a deadline', () => actions.next()),
        this.timeInput, btn('sim-advance', 'Step / Run to', '+TIME steps by TIME, TIME runs to that virtual time', () => actions.advance(this.timeInput.value))),
      h('div', { class: 'sim-bar' },
        this.stepInput.element, btn('sim-inject', 'Inject', 'Add this step at the current virtual time (Enter)', () => actions.inject(this.stepInput.value)),
        btn('sim-undo', '↶ Undo', 'Drop the last injected step', () => actions.undo()),
        this.savePath, btn('sim-save', 'Save as scenario', 'Write the session, with the state shown as expectations, to this workspace file', () => actions.save(this.savePath.value))),
      this.message,
      h('div', { class: 'sim-state' },
        h('div', {}, h('h4', {}, 'Rules'), this.rules),
        h('div', {}, h('h4', {}, 'Active schemas'), this.schemas, h('h4', {}, 'Locals'), this.locals),
        h('div', { class: 'sim-steps-col' }, h('h4', {}, 'Steps'), this.steps)));
    // Escape on a control goes back to the editor, as in the panel tabs (the step's own editor
    // binds it itself: there it closes the completion list first)
    this.element.addEventListener('keydown', (e) => {
      if (e.key !== 'Escape' || e.defaultPrevented || (e.target as HTMLElement | null)?.closest('.monaco-editor')) return;
      e.preventDefault();
      this.onEscape?.();
    });
  }

  /** What Escape on one of the panel's controls does (main.ts: focus the editor). */
  onEscape?: () => void;

  /** The functions to pick from (`SUP.fn`) with their parameters (`(TypeA consigne)`), shown in the parameters' hint. */
  setFunctions(fns: Array<{ name: string; signature: string }>): void {
    const keep = this.fnSelect.value;
    this.fnSelect.replaceChildren(...fns.map((f) => h('option', { value: f.name, 'data-signature': f.signature }, `${f.name}${f.signature}`)));
    if (fns.some((f) => f.name === keep)) this.fnSelect.value = keep;
    this.showSignature();
  }

  private showSignature(): void {
    const sig = this.fnSelect.selectedOptions[0]?.getAttribute('data-signature') ?? '';
    const names = sig.replace(/^\(|\)$/g, '').split(',').map((p) => p.trim().split(/\s+/).pop()).filter(Boolean);
    this.params.placeholder = names.length ? `${names.map((n) => `${n} = value`).join(', ')}   (empty: the defaults)` : 'no parameters';
  }

  /** Shows the function and parameters of a session grown again after a reload. */
  showStart(fn: string, params: string): void {
    if ([...this.fnSelect.options].some((o) => o.value === fn)) this.fnSelect.value = fn;
    this.params.value = params;
    this.showSignature();
  }

  clearStep(): void {
    this.stepInput.value = '';
  }

  showMessage(text: string, level: 'info' | 'error' = 'info', lines: string[] = []): void {
    this.message.className = `sim-message ${level}`;
    this.message.replaceChildren(h('div', {}, text), ...lines.slice(0, 50).map((l) => h('div', { class: 'sim-diag' }, l)));
  }

  showTime(ns: number | undefined): void {
    this.now.textContent = ns === undefined ? 'not started' : formatTime(ns);
  }

  /** Puts the keyboard focus on the supervisor function (the panel's first control). */
  focus(): void {
    this.fnSelect.focus();
  }

  /** The result of the session's last run: state after its last step, and the steps. */
  showResult(r: SimulateResponse): void {
    const rules = ruleStates(r.steps);
    this.rules.replaceChildren(...[...rules].map(([name, s]) =>
      h('div', { class: `sim-rule ${s.active ? 'active' : 'inactive'}`, 'data-rule': name },
        h('span', { class: 'sim-rule-name' }, `${s.active ? '●' : '○'} ${name}`), ' ',
        h('span', { class: 'sim-cause' }, `← ${visibleText(readableCause(s.cause))} at ${formatTime(s.timeNs)}`))));
    if (!rules.size) this.rules.textContent = 'no rule changed yet';
    const last = r.steps.at(-1);
    // a step the simulator kept without its lists (its bound on a scenario's records): what it
    // holds is not the state, and is not shown as one
    const notKept = (what: string, from: number | undefined) => h('div', { class: 'sim-not-kept' }, `${what} not kept from ${from ? `line ${from}` : 'the end'} on (the simulator's bound on a scenario's records)`);
    if (last?.trimmed === 'bare') this.rules.append(notKept('rule changes', r.trimmed?.bareLine));
    if (last?.trimmed) {
      this.schemas.replaceChildren(notKept('schemas', r.trimmed?.line));
      this.locals.replaceChildren(notKept('locals', r.trimmed?.line));
    } else {
      this.schemas.replaceChildren(...(last?.schemas ?? []).map((s) => h('div', { class: 'sim-schema', 'data-schema': s }, s)));
      this.locals.replaceChildren(...(last?.locals ?? []).map((l) =>
        h('div', { class: 'sim-local' }, visibleText(`${l.supervisor}.${l.function}.${l.name}: ${l.type} = ${l.value}`))));
    }
    const shown = r.steps.slice(-MAX_SHOWN_STEPS);
    this.steps.replaceChildren(...shown.map((s) => {
      // what happened since the step before, at its own time: what came before the step (a timer,
      // a release) above its line, as `contract simulate` prints it (an expectation looks at the
      // state after its time: what happened at its time too)
      const before = (t: number) => t < s.timeNs || (t === s.timeNs && (s.kind === 'expect' || s.kind === 'end'));
      const at = (t: number) => (t === s.timeNs ? '' : `${formatTime(t)}  `);
      const changes = s.rules.map((c) => ({ t: c.timeNs, el: h('div', { class: 'sim-change' }, `${at(c.timeNs)}${c.active ? '+' : '-'} ${c.supervisor}.${c.function}.${c.rule} ${c.active ? 'active' : 'inactive'}  ← ${visibleText(readableCause(c.cause))}`) }));
      // in a run's words (`undo: stop module SCN`) with what the holds decided, as `simulate --verbose` shows them
      const actions = actionLines(s.actions, s.records).slice(0, 50).map((a) => ({ t: a.t, el: h('div', { class: 'sim-action' }, visibleText(`${at(a.t)}${a.who}: ${a.text}`)) }));
      const lines = [...changes, ...actions].map((x, i) => ({ ...x, i })).sort((x, y) => x.t - y.t || x.i - y.i);
      return h('div', { class: `sim-step-row ${s.ok ? '' : 'failed'}` },
        ...lines.filter((x) => before(x.t)).map((x) => x.el),
        h('div', { class: 'sim-step-head' }, `${formatTime(s.timeNs)}  ${s.kind === 'end' ? '(end)' : s.source}${s.message ? `  ✖ ${s.message}` : ''}${s.trimmed ? `  (kept without its ${s.trimmed === 'bare' ? 'lists' : 'actions and records'}: the simulator's bound)` : ''}`),
        ...lines.filter((x) => !before(x.t)).map((x) => x.el),
        // what the project's C printed: its lines kept, every other control or invisible character as its escape
        s.output ? h('pre', { class: 'sim-output' }, visibleText(s.output, { keepNewlines: true })) : null);
    }));
    this.steps.scrollTop = this.steps.scrollHeight;
  }
}
