import { h } from './dom.js';
import { openModal } from './modal.js';
import { RowsField, type RowsFieldSpec } from './rows-field.js';

// Each dialog is a modal (util/modal.ts): focus inside, Tab cycles in it, Escape cancels, and the
// focus goes back to the element that opened it (a toolbar button, the editor).

/**
 * A dialog's box: its title, a body that scrolls when the window is too short for it (a laptop at
 * 125 % or 150 %: the control with the focus is scrolled into view), and its buttons below the
 * body, always on screen (styles.css `.dialog`).
 */
function dialogBox(title: string, body: Array<HTMLElement | null>, buttons: HTMLElement[]): HTMLElement {
  return h('div', { class: 'dialog', 'aria-label': title }, h('div', { class: 'dialog-title' }, title),
    h('div', { class: 'dialog-body' }, ...body), h('div', { class: 'dialog-buttons' }, ...buttons));
}

/**
 * An in-page prompt (no native dialogs): resolves the entered text, or null when cancelled (Escape,
 * Cancel). An empty answer is null too, unless `allowEmpty` (then '': OK on an empty field is an answer).
 */
export function askText(title: string, initial = '', hint = '', opts: { allowEmpty?: boolean } = {}): Promise<string | null> {
  return new Promise((resolve) => {
    const input = h('input', { class: 'dialog-input', value: initial, spellcheck: 'false', 'aria-label': title });
    let modal: { close(): void } | undefined;
    const answer = (): string | null => input.value.trim() || (opts.allowEmpty ? '' : null);
    const done = (v: string | null) => {
      if (!modal) return;
      modal.close();
      modal = undefined;
      resolve(v);
    };
    const ok = h('button', { class: 'btn primary', onclick: () => done(answer()) }, 'OK');
    const cancel = h('button', { class: 'btn', onclick: () => done(null) }, 'Cancel');
    input.addEventListener('keydown', (e) => {
      // the key is used up: the focus goes back to the button that opened the dialog, which must
      // not get this Enter as a click (it would open the dialog again)
      if (e.key === 'Enter' || e.key === 'Escape') e.preventDefault();
      if (e.key === 'Enter') done(answer());
      if (e.key === 'Escape') done(null);
    });
    const dialog = dialogBox(title, [hint ? h('div', { class: 'dialog-hint' }, hint) : null, input], [cancel, ok]);
    const overlay = h('div', { class: 'dialog-overlay' }, dialog);
    modal = openModal(overlay, dialog, { onEscape: () => done(null), initialFocus: () => input.focus() });
    const dot = initial.lastIndexOf('.');
    input.setSelectionRange(0, dot > 0 ? dot : initial.length);
  });
}

export function confirmAction(title: string, detail: string, okLabel = 'Delete'): Promise<boolean> {
  return new Promise((resolve) => {
    let modal: { close(): void } | undefined;
    const done = (v: boolean) => {
      if (!modal) return;
      modal.close();
      modal = undefined;
      resolve(v);
    };
    const ok = h('button', { class: 'btn danger', onclick: () => done(true) }, okLabel);
    const dialog = dialogBox(title, [h('div', { class: 'dialog-hint' }, detail)], [h('button', { class: 'btn', onclick: () => done(false) }, 'Cancel'), ok]);
    const overlay = h('div', { class: 'dialog-overlay' }, dialog);
    modal = openModal(overlay, dialog, { onEscape: () => done(false), initialFocus: () => ok.focus() });
  });
}

/**
 * A small form of labelled fields (text, a checkbox with `checkbox: true`, read as "yes" or "", or
 * rows of entries: util/rows-field.ts); resolves the values (`values`: text and checkboxes, `rows`:
 * each rows field's rows as typed), or null when cancelled.
 */
/** What is wrong with a dialog's values: said in the dialog, which stays open on the field `key` (at `row` and `column` of a rows field; what was typed kept). */
export interface FieldsProblem {
  key?: string;
  row?: number;
  column?: number;
  message: string;
}

export type FieldSpec = { key: string; label: string; value: string; hint?: string; checkbox?: boolean } | (RowsFieldSpec & { kind: 'rows' });

export interface FieldValues {
  values: Record<string, string>;
  rows: Record<string, string[][]>;
}

export function askFields(
  title: string,
  fields: FieldSpec[],
  check?: (values: FieldValues) => FieldsProblem | undefined,
): Promise<FieldValues | null> {
  return new Promise((resolve) => {
    const keys = (i: HTMLInputElement) => i.addEventListener('keydown', (e) => {
      if (e.key !== 'Enter' && e.key !== 'Escape') return;
      e.preventDefault(); // not a click on the button the focus goes back to
      done(e.key === 'Enter');
    });
    const controls = fields.map((f) =>
      'kind' in f
        ? new RowsField(f, keys)
        : f.checkbox
          ? h('input', { class: 'dialog-check', type: 'checkbox', checked: f.value === 'yes', 'data-key': f.key, 'aria-label': f.label })
          : h('input', { class: 'dialog-input', value: f.value, spellcheck: 'false', 'data-key': f.key, placeholder: f.hint ?? '', 'aria-label': f.label }),
    );
    const inputs = controls.filter((c): c is HTMLInputElement => !(c instanceof RowsField));
    const rowsFields = controls.filter((c): c is RowsField => c instanceof RowsField);
    const allInputs = () => [...inputs, ...rowsFields.flatMap((r) => r.inputs())];
    const valueOf = (i: HTMLInputElement) => (i.type === 'checkbox' ? (i.checked ? 'yes' : '') : i.value.trim());
    let modal: { close(): void } | undefined;
    // a refused Save is said here, the dialog left open with what was typed (an alert: read out at once)
    const problemLine = h('div', { class: 'dialog-problem', role: 'alert' });
    const done = (ok: boolean) => {
      if (!modal) return;
      const answer: FieldValues = {
        values: Object.fromEntries(inputs.map((i) => [i.dataset['key']!, valueOf(i)])),
        rows: Object.fromEntries(rowsFields.map((r) => [r.key, r.values()])),
      };
      const problem = ok && check ? check(answer) : undefined;
      if (problem) {
        problemLine.textContent = problem.message;
        const rows = rowsFields.find((r) => r.key === problem.key);
        const at = rows ? rows.input(problem.row ?? 0, problem.column ?? 0) : inputs.find((i) => i.dataset['key'] === problem.key);
        for (const i of allInputs()) i.toggleAttribute('aria-invalid', i === at);
        (at ?? inputs[0])?.focus();
        return;
      }
      modal.close();
      modal = undefined;
      resolve(ok ? answer : null);
    };
    for (const i of inputs) keys(i);
    const dialog = dialogBox(title, [
      ...fields.flatMap((f, n) => {
        const c = controls[n]!;
        if (c instanceof RowsField) return [c.element];
        return 'checkbox' in f && f.checkbox ? [h('label', { class: 'dialog-hint dialog-check-row' }, c, ` ${f.label}`)] : [h('label', { class: 'dialog-hint' }, f.label), c];
      }),
      problemLine,
    ], [h('button', { class: 'btn', onclick: () => done(false) }, 'Cancel'), h('button', { class: 'btn primary', onclick: () => done(true) }, 'Save')]);
    const overlay = h('div', { class: 'dialog-overlay' }, dialog);
    modal = openModal(overlay, dialog, { onEscape: () => done(false), initialFocus: () => inputs[0]?.focus() });
  });
}
