import { h } from './dom.js';

let host: HTMLElement | undefined;

/** Shows a transient notification at the bottom right; errors stay until clicked. */
export function toast(level: 'info' | 'warning' | 'error', text: string): void {
  host ??= document.body.appendChild(h('div', { class: 'toasts' }));
  const icon = level === 'error' ? '✖' : level === 'warning' ? '⚠' : 'ℹ';
  const el = h('div', { class: `toast ${level}`, role: 'status' }, h('span', { class: 'toast-icon' }, icon), h('span', {}, text));
  el.addEventListener('click', () => el.remove());
  host.append(el);
  while (host.childElementCount > 4) host.firstElementChild?.remove();
  if (level !== 'error') setTimeout(() => el.remove(), 5000);
}
