/**
 * The Simulate panel's step field: a one-line Monaco editor on a scenario-language model, so that
 * typing a step gets the scenario language's completion, hover and checks (docs/simulation.md
 * "Editing scenarios": `MAA:` -> its out event ports, `MAA:2 ` -> the values the rules compare it
 * with). The model is a file URI in the project's folder (never saved: the scenario's project is
 * found from its folder), holding just the line being typed. Enter injects it unless a suggestion
 * is being chosen; Tab and Shift+Tab leave it for the next or previous control, Escape goes back to
 * the editor (with a suggestion list open, these keys are the list's).
 *
 * Monaco registers an editor's addCommand keybinding for every editor of the page: each of these
 * is bound under a context key only this editor holds (STEP_CONTEXT_KEY), or Enter would inject in
 * the code editors too.
 */
import { monaco } from '../editor/monaco.js';
import { SCENARIO_LANGUAGE_ID } from '../editor/scenario-language.js';
import { h } from '../util/dom.js';
import { focusableIn } from '../util/focusable.js';

/** The model's file name: main.ts keeps its diagnostics out of the Problems panel. */
export const STEP_INPUT_FILE = '.simulate-step.scenario';

/** The context key set in the step editor's own context only: its keys are bound under it. */
const STEP_CONTEXT_KEY = 'contractSimulateStep';
const ITS_OWN = `${STEP_CONTEXT_KEY} && !suggestWidgetVisible`;

/** What the step field's keys do (besides typing). */
export interface StepKeys {
  enter(text: string): void;
  escape(): void;
}

export class StepInput {
  readonly element = h('div', { class: 'sim-step', role: 'textbox', 'aria-label': 'step to inject' });
  private editor: monaco.editor.IStandaloneCodeEditor | undefined;
  private model: monaco.editor.ITextModel | undefined;

  constructor(private readonly keys: StepKeys, private readonly placeholder: string) {}

  /** Creates (or moves) the editor's model in `folderUri` (the project's folder). */
  attach(uri: monaco.Uri): void {
    if (this.model?.uri.toString() === uri.toString()) return;
    const text = this.value;
    this.model?.dispose();
    this.model = monaco.editor.getModel(uri) ?? monaco.editor.createModel(text, SCENARIO_LANGUAGE_ID, uri);
    if (!this.editor) {
      this.editor = monaco.editor.create(this.element, {
        model: this.model, lineNumbers: 'off', minimap: { enabled: false }, scrollBeyondLastLine: false, wordWrap: 'off',
        glyphMargin: false, folding: false, renderLineHighlight: 'none', overviewRulerLanes: 0, lineDecorationsWidth: 4,
        scrollbar: { vertical: 'hidden', horizontal: 'hidden', handleMouseWheel: false }, fontSize: 12, automaticLayout: true,
        fixedOverflowWidgets: true, placeholder: this.placeholder,
      });
      this.editor.createContextKey(STEP_CONTEXT_KEY, true);
      // Enter injects; with the suggestions open it accepts one (Monaco's own binding)
      this.editor.addCommand(monaco.KeyCode.Enter, () => this.keys.enter(this.value), ITS_OWN);
      // a one-line field is no place for a tab character: Tab moves on, as in any form
      this.editor.addCommand(monaco.KeyCode.Tab, () => this.moveFocus(false), ITS_OWN);
      this.editor.addCommand(monaco.KeyMod.Shift | monaco.KeyCode.Tab, () => this.moveFocus(true), ITS_OWN);
      this.editor.addCommand(monaco.KeyCode.Escape, () => this.keys.escape(), ITS_OWN);
      // one line: a pasted text keeps its first line only
      this.editor.onDidChangeModelContent(() => {
        const m = this.model;
        if (m && m.getLineCount() > 1) m.setValue(m.getLineContent(1));
      });
    } else this.editor.setModel(this.model);
  }

  get value(): string {
    return this.model?.getValue() ?? '';
  }

  set value(text: string) {
    this.model?.setValue(text);
  }

  /** Puts `text` in the field, the cursor at its end, and opens the completion (the port's values). */
  prefill(text: string): void {
    if (!this.editor || !this.model) return;
    this.model.setValue(text);
    this.editor.setPosition({ lineNumber: 1, column: text.length + 1 });
    this.editor.focus();
    this.editor.trigger('simulate', 'editor.action.triggerSuggest', {});
  }

  focus(): void {
    this.editor?.focus();
  }

  /** Focuses the next (or, `back`, the previous) control of the page outside this field. */
  private moveFocus(back: boolean): void {
    const outside = focusableIn(document).filter((el) => !this.element.contains(el));
    const after = outside.filter((el) => this.element.compareDocumentPosition(el) & Node.DOCUMENT_POSITION_FOLLOWING);
    const before = outside.filter((el) => this.element.compareDocumentPosition(el) & Node.DOCUMENT_POSITION_PRECEDING);
    (back ? before.at(-1) : after[0])?.focus();
  }
}
