import { h } from './dom.js';

/**
 * A dialog field of rows: one entry a row, each column a text input of its own (a value holds any
 * character: no separator to escape), a ✕ that removes its row and a button that adds one. Keyboard:
 * Tab along the inputs and buttons, Enter or Space on a button, Enter in an input as in the
 * dialog's other fields (`keys`). Every input is named by its column and row (`Stdin module 2`).
 */
export interface RowsFieldSpec {
  key: string;
  /** The field's label, above its rows. */
  label: string;
  /** The field's short name in its inputs' names (`Stdin` -> "Stdin module 1"). */
  name: string;
  columns: Array<{ label: string; hint?: string }>;
  /** The rows shown first (an empty one when none: ready to type in). */
  rows: string[][];
  /** The add button's text (`Add a module`). */
  addLabel: string;
}

export class RowsField {
  readonly element: HTMLElement;
  private readonly list: HTMLElement;
  private readonly add: HTMLButtonElement;

  readonly key: string;

  constructor(private readonly spec: RowsFieldSpec, private readonly keys: (input: HTMLInputElement) => void) {
    this.key = spec.key;
    this.list = h('div', { class: 'dialog-rows-list' });
    this.add = h('button', { class: 'btn dialog-rows-add', type: 'button', onclick: () => this.addRow([], true) }, `+ ${spec.addLabel}`);
    const head = h('div', { class: 'dialog-row dialog-rows-head', 'aria-hidden': 'true' }, ...spec.columns.map((c) => h('span', {}, c.label)), h('span', {}));
    this.element = h('div', { class: 'dialog-rows', role: 'group', 'aria-label': spec.label, 'data-key': spec.key },
      h('div', { class: 'dialog-hint' }, spec.label), head, this.list, this.add);
    for (const row of spec.rows.length ? spec.rows : [[]]) this.addRow(row, false);
  }

  /** Every row's values as typed (not trimmed: they are read by the field's owner). */
  values(): string[][] {
    return this.rowElements().map((r) => [...r.querySelectorAll('input')].map((i) => i.value));
  }

  /** The input at `row`, `column` (undefined past the rows). */
  input(row: number, column: number): HTMLInputElement | undefined {
    return this.rowElements()[row]?.querySelectorAll('input')[column];
  }

  inputs(): HTMLInputElement[] {
    return [...this.list.querySelectorAll('input')];
  }

  private rowElements(): HTMLElement[] {
    return [...this.list.children] as HTMLElement[];
  }

  private addRow(values: string[], focus: boolean): void {
    const inputs = this.spec.columns.map((c, n) => {
      const i = h('input', { class: 'dialog-input', value: values[n] ?? '', spellcheck: 'false', placeholder: c.hint ?? '' });
      this.keys(i);
      return i;
    });
    const row = h('div', { class: 'dialog-row' }, ...inputs);
    row.append(h('button', { class: 'btn dialog-row-remove', type: 'button', onclick: () => this.remove(row) }, '✕'));
    this.list.append(row);
    this.name();
    if (focus) inputs[0]?.focus();
  }

  /** Removes `row`; the focus goes to the row that takes its place, else to the add button. */
  private remove(row: HTMLElement): void {
    const next = (row.nextElementSibling ?? row.previousElementSibling) as HTMLElement | null;
    row.remove();
    this.name();
    (next?.querySelector('input') ?? this.add).focus();
  }

  /** Names every input and ✕ by its row (numbers from 1, again after a removal). */
  private name(): void {
    const name = this.spec.name;
    this.rowElements().forEach((r, n) => {
      r.querySelectorAll('input').forEach((i, c) => i.setAttribute('aria-label', `${name} ${this.spec.columns[c]!.label.toLowerCase()} ${n + 1}`));
      r.querySelector('button')?.setAttribute('aria-label', `Remove ${name.toLowerCase()} row ${n + 1}`);
    });
  }
}
