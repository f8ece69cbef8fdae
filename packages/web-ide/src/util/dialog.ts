import { h } from './dom.js';
import { openModal } from './modal.js';

// Each dialog is a modal (util/modal.ts): focus inside, Tab cycles in it, Escape cancels, and the
// focus goes back to the element that opened it (a toolbar button, the editor).

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
    const dialog = h('div', { class: 'dialog', 'aria-label': title }, h('div', { class: 'dialog-title' }, title), hint ? h('div', { class: 'dialog-hint' }, hint) : null, input,
      h('div', { class: 'dialog-buttons' }, cancel, ok));
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
    const dialog = h('div', { class: 'dialog', 'aria-label': title }, h('div', { class: 'dialog-title' }, title), h('div', { class: 'dialog-hint' }, detail),
      h('div', { class: 'dialog-buttons' }, h('button', { class: 'btn', onclick: () => done(false) }, 'Cancel'), ok));
    const overlay = h('div', { class: 'dialog-overlay' }, dialog);
    modal = openModal(overlay, dialog, { onEscape: () => done(false), initialFocus: () => ok.focus() });
  });
}

/**
 * A small form of labelled fields (text, or a checkbox with `checkbox: true`, read as "yes" or "");
 * resolves the values, or null when cancelled.
 */
/** What is wrong with a dialog's values: said in the dialog, which stays open on the field `key` (what was typed kept). */
export interface FieldsProblem {
  key?: string;
  message: string;
}

export function askFields(
  title: string,
  fields: Array<{ key: string; label: string; value: string; hint?: string; checkbox?: boolean }>,
  check?: (values: Record<string, string>) => FieldsProblem | undefined,
): Promise<Record<string, string> | null> {
  return new Promise((resolve) => {
    const inputs = fields.map((f) =>
      f.checkbox
        ? h('input', { class: 'dialog-check', type: 'checkbox', checked: f.value === 'yes', 'data-key': f.key, 'aria-label': f.label })
        : h('input', { class: 'dialog-input', value: f.value, spellcheck: 'false', 'data-key': f.key, placeholder: f.hint ?? '', 'aria-label': f.label }),
    );
    const valueOf = (i: HTMLInputElement) => (i.type === 'checkbox' ? (i.checked ? 'yes' : '') : i.value.trim());
    let modal: { close(): void } | undefined;
    // a refused Save is said here, the dialog left open with what was typed (an alert: read out at once)
    const problemLine = h('div', { class: 'dialog-problem', role: 'alert' });
    const done = (ok: boolean) => {
      if (!modal) return;
      const values = Object.fromEntries(inputs.map((i, n) => [fields[n]!.key, valueOf(i)]));
      const problem = ok && check ? check(values) : undefined;
      if (problem) {
        problemLine.textContent = problem.message;
        const at = inputs.find((i) => i.dataset['key'] === problem.key);
        for (const i of inputs) i.toggleAttribute('aria-invalid', i === at);
        (at ?? inputs[0])?.focus();
        return;
      }
      modal.close();
      modal = undefined;
      resolve(ok ? values : null);
    };
    for (const i of inputs) {
      i.addEventListener('keydown', (e) => {
        if (e.key !== 'Enter' && e.key !== 'Escape') return;
        e.preventDefault(); // not a click on the button the focus goes back to
        done(e.key === 'Enter');
      });
    }
    const dialog = h('div', { class: 'dialog', 'aria-label': title }, h('div', { class: 'dialog-title' }, title),
      ...fields.flatMap((f, n) => (f.checkbox ? [h('label', { class: 'dialog-hint dialog-check-row' }, inputs[n]!, ` ${f.label}`)] : [h('label', { class: 'dialog-hint' }, f.label), inputs[n]!])),
      problemLine,
      h('div', { class: 'dialog-buttons' }, h('button', { class: 'btn', onclick: () => done(false) }, 'Cancel'), h('button', { class: 'btn primary', onclick: () => done(true) }, 'Save')));
    const overlay = h('div', { class: 'dialog-overlay' }, dialog);
    modal = openModal(overlay, dialog, { onEscape: () => done(false), initialFocus: () => inputs[0]?.focus() });
  });
}
