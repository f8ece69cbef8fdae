import { h } from './dom.js';

/** An in-page prompt (no native dialogs): resolves the entered text, or null when cancelled. */
export function askText(title: string, initial = '', hint = ''): Promise<string | null> {
  return new Promise((resolve) => {
    const input = h('input', { class: 'dialog-input', value: initial, spellcheck: 'false', 'aria-label': title });
    const done = (v: string | null) => {
      overlay.remove();
      resolve(v);
    };
    const ok = h('button', { class: 'btn primary', onclick: () => done(input.value.trim() || null) }, 'OK');
    const cancel = h('button', { class: 'btn', onclick: () => done(null) }, 'Cancel');
    input.addEventListener('keydown', (e) => {
      if (e.key === 'Enter') done(input.value.trim() || null);
      if (e.key === 'Escape') done(null);
    });
    const overlay = h('div', { class: 'dialog-overlay' },
      h('div', { class: 'dialog', role: 'dialog' }, h('div', { class: 'dialog-title' }, title), hint ? h('div', { class: 'dialog-hint' }, hint) : null, input,
        h('div', { class: 'dialog-buttons' }, cancel, ok)));
    document.body.append(overlay);
    input.focus();
    const dot = initial.lastIndexOf('.');
    input.setSelectionRange(0, dot > 0 ? dot : initial.length);
  });
}

export function confirmAction(title: string, detail: string, okLabel = 'Delete'): Promise<boolean> {
  return new Promise((resolve) => {
    const done = (v: boolean) => {
      overlay.remove();
      resolve(v);
    };
    const ok = h('button', { class: 'btn danger', onclick: () => done(true) }, okLabel);
    const overlay = h('div', { class: 'dialog-overlay' },
      h('div', { class: 'dialog', role: 'dialog' }, h('div', { class: 'dialog-title' }, title), h('div', { class: 'dialog-hint' }, detail),
        h('div', { class: 'dialog-buttons' }, h('button', { class: 'btn', onclick: () => done(false) }, 'Cancel'), ok)));
    document.body.append(overlay);
    ok.focus();
  });
}

/**
 * A small form of labelled fields (text, or a checkbox with `checkbox: true`, read as "yes" or "");
 * resolves the values, or null when cancelled.
 */
export function askFields(title: string, fields: Array<{ key: string; label: string; value: string; hint?: string; checkbox?: boolean }>): Promise<Record<string, string> | null> {
  return new Promise((resolve) => {
    const inputs = fields.map((f) =>
      f.checkbox
        ? h('input', { class: 'dialog-check', type: 'checkbox', checked: f.value === 'yes', 'data-key': f.key, 'aria-label': f.label })
        : h('input', { class: 'dialog-input', value: f.value, spellcheck: 'false', 'data-key': f.key, placeholder: f.hint ?? '', 'aria-label': f.label }),
    );
    const valueOf = (i: HTMLInputElement) => (i.type === 'checkbox' ? (i.checked ? 'yes' : '') : i.value.trim());
    const done = (ok: boolean) => {
      overlay.remove();
      resolve(ok ? Object.fromEntries(inputs.map((i, n) => [fields[n]!.key, valueOf(i)])) : null);
    };
    for (const i of inputs) i.addEventListener('keydown', (e) => (e.key === 'Enter' ? done(true) : e.key === 'Escape' ? done(false) : undefined));
    const overlay = h('div', { class: 'dialog-overlay' },
      h('div', { class: 'dialog', role: 'dialog' }, h('div', { class: 'dialog-title' }, title),
        ...fields.flatMap((f, n) => (f.checkbox ? [h('label', { class: 'dialog-hint dialog-check-row' }, inputs[n]!, ` ${f.label}`)] : [h('label', { class: 'dialog-hint' }, f.label), inputs[n]!])),
        h('div', { class: 'dialog-buttons' }, h('button', { class: 'btn', onclick: () => done(false) }, 'Cancel'), h('button', { class: 'btn primary', onclick: () => done(true) }, 'Save'))));
    document.body.append(overlay);
    inputs[0]?.focus();
  });
}
