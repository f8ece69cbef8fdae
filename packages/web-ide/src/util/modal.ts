import { focusableIn } from './focusable.js';

/** One place the keyboard can go inside a modal: an element, or a widget (a Monaco editor) with its own focus. */
export interface FocusStop {
  el: HTMLElement;
  focus(): void;
}

export interface Modal {
  /**
   * Gives the focus back (to what had it before, or to `fallbackFocus`), then runs `teardown` (what
   * lives inside the dialog is disposed while still in the page, nothing of it focused), then
   * removes the overlay.
   */
  close(teardown?: () => void): void;
}

/**
 * Makes `dialog` a modal dialog (WAI-ARIA dialog pattern): `role="dialog"`, `aria-modal="true"`, the
 * rest of the page inert while it is open (no focus, no clicks, hidden from assistive technology),
 * Tab and Shift+Tab cycle through its stops (its focusable elements unless `stops` says which), and
 * Escape calls `onEscape` (a key a widget inside used — a Monaco suggestion list — is left to it).
 * `overlay` (the dialog or an element around it) is appended to the body. On close the focus goes
 * back to the element that had it when the modal opened, else to `fallbackFocus`.
 */
export function openModal(overlay: HTMLElement, dialog: HTMLElement, opts: {
  onEscape(): void;
  initialFocus?: () => void;
  stops?: () => FocusStop[];
  fallbackFocus?: () => void;
}): Modal {
  const previous = document.activeElement instanceof HTMLElement && document.activeElement !== document.body ? document.activeElement : undefined;
  dialog.setAttribute('role', 'dialog');
  dialog.setAttribute('aria-modal', 'true');
  const stops = (): FocusStop[] =>
    opts.stops?.() ?? focusableIn(dialog).map((el) => ({ el, focus: () => el.focus() }));
  const onKey = (e: KeyboardEvent) => {
    if (e.key !== 'Tab' || e.ctrlKey || e.altKey || e.metaKey) return;
    const list = stops();
    e.preventDefault();
    e.stopPropagation();
    if (!list.length) return;
    const at = list.findIndex((s) => s.el.contains(document.activeElement));
    const next = at < 0 ? (e.shiftKey ? list.length - 1 : 0) : (at + (e.shiftKey ? list.length - 1 : 1)) % list.length;
    list[next]!.focus();
  };
  const onEscape = (e: KeyboardEvent) => {
    if (e.key !== 'Escape' || e.defaultPrevented) return;
    e.preventDefault();
    e.stopPropagation();
    opts.onEscape();
  };
  // the page behind never keeps the focus while the modal is open (a script focusing something
  // there); menus and widgets a dialog's own editor adds to the page are left alone
  let madeInert: HTMLElement[] = [];
  const onFocusIn = (e: FocusEvent) => {
    if (e.target instanceof Node && madeInert.some((el) => el.contains(e.target as Node))) (opts.initialFocus ?? (() => stops()[0]?.focus()))();
  };
  overlay.addEventListener('keydown', onKey, { capture: true });
  overlay.addEventListener('keydown', onEscape);
  document.addEventListener('focusin', onFocusIn);
  if (overlay.parentElement !== document.body) document.body.append(overlay);
  // everything else on the page is inert (toasts stay readable: they are role=status)
  madeInert = [...document.body.children].filter((el): el is HTMLElement => el instanceof HTMLElement && el !== overlay && !el.classList.contains('toasts') && !el.inert);
  for (const el of madeInert) el.inert = true;
  (opts.initialFocus ?? (() => stops()[0]?.focus()))();
  let open = true;
  return {
    close(teardown) {
      if (!open) return;
      open = false;
      document.removeEventListener('focusin', onFocusIn);
      overlay.removeEventListener('keydown', onKey, { capture: true });
      overlay.removeEventListener('keydown', onEscape);
      for (const el of madeInert) el.inert = false;
      dialog.removeAttribute('aria-modal');
      // the focus leaves the dialog before it goes away (a widget inside must not keep it while disposed)
      if (previous?.isConnected && !overlay.contains(previous)) previous.focus();
      else if (opts.fallbackFocus) opts.fallbackFocus();
      if (overlay.contains(document.activeElement)) (document.activeElement as HTMLElement).blur();
      teardown?.();
      overlay.remove();
    },
  };
}
