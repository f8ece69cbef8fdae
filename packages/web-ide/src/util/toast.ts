import { h } from './dom.js';

let host: HTMLElement | undefined;

/**
 * Shows a notification at the bottom right (click to dismiss); errors stay 15 s, others 5 s, a
 * `sticky` one until it is clicked or dismissed (dismissToasts).
 */
export function toast(level: 'info' | 'warning' | 'error', text: string, opts: { sticky?: boolean } = {}): void {
  host ??= document.body.appendChild(h('div', { class: 'toasts' }));
  const icon = level === 'error' ? '✖' : level === 'warning' ? '⚠' : 'ℹ';
  for (const old of Array.from(host.children)) if (old.textContent?.endsWith(text)) old.remove();
  const el = h('div', { class: `toast ${level}`, role: 'status' }, h('span', { class: 'toast-icon' }, icon), h('span', {}, text));
  el.addEventListener('click', () => el.remove());
  host.append(el);
  if (opts.sticky) el.dataset.sticky = 'true';
  const passing = () => Array.from(host!.children).filter((c) => !(c as HTMLElement).dataset.sticky);
  for (let list = passing(); host.childElementCount > 4 && list.length; list = passing()) list[0]!.remove();
  if (!opts.sticky) setTimeout(() => el.remove(), level === 'error' ? 15_000 : 5000);
}

/** Removes the notifications whose text contains `part` (e.g. a failed save that has since succeeded). */
export function dismissToasts(part: string): void {
  for (const el of Array.from(host?.children ?? [])) if (el.textContent?.includes(part)) el.remove();
}
