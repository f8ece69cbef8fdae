import { h } from './dom.js';

/** An in-page prompt (no native dialogs): resolves the entered text, or null when cancelled. */
export function askText(title: string, initial = '', hint = ''): Promise<string | null> {
  return new Promise((resolve) => {
    const input = h('input', { class: 'dialog-input', value: initial, spellcheck: 'false' });
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
