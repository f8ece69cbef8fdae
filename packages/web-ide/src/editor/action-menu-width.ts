/**
 * Monaco's quick-fix menu (the "action widget") measures its rows before they are in the page and
 * falls back to 100 px, which cut every title (monaco-editor issue 4244, open upstream). styles.css
 * gives the menu 320 px, the list filling it; a longer title (`Add import "shared/navigation-and-
 * perception-types.contract"`) widens it here once its rows are drawn, up to 90% of the window.
 *
 * The menu is drawn in a context view, a direct child of the editor's `.monaco-editor` node
 * (fixedOverflowWidgets): only that node's children and the context view are watched, not what the
 * editor draws inside.
 */
import type * as monaco from 'monaco-editor';

/** Room for the row's icon and padding beside a title that overflows. */
const SLACK_PX = 8;

/** Widens `widget` to its longest title, if one is cut. Returns the width set, or undefined. */
export function fitActionMenu(widget: HTMLElement): number | undefined {
  let overflow = 0;
  for (const title of widget.querySelectorAll<HTMLElement>('.monaco-list-row .title')) overflow = Math.max(overflow, title.scrollWidth - title.clientWidth);
  if (overflow <= 0) return undefined;
  const width = Math.ceil(Math.min(widget.getBoundingClientRect().width + overflow + SLACK_PX, window.innerWidth * 0.9));
  widget.style.setProperty('min-width', `${width}px`, 'important');
  return width;
}

/** Fits every quick-fix menu `editor` opens; the watch ends with the editor. */
export function fitActionMenus(editor: monaco.editor.ICodeEditor): void {
  let pending = 0;
  const fitSoon = (view: Element) => {
    cancelAnimationFrame(pending);
    pending = requestAnimationFrame(() => {
      const widget = view.querySelector<HTMLElement>('.action-widget');
      if (widget) fitActionMenu(widget);
    });
  };
  // a context view is added when the first menu opens; each menu is drawn into it, and Monaco sets
  // the menu's width (its style) after its rows are in: fitted again after each of those
  const watch = { childList: true, attributes: true, attributeFilter: ['style'], subtree: true };
  const views = new MutationObserver((records) => {
    for (const r of records) {
      const view = r.target instanceof Element ? r.target.closest('.context-view') : null;
      if (view) fitSoon(view);
      for (const n of r.addedNodes) {
        if (!(n instanceof HTMLElement) || !n.classList.contains('context-view')) continue;
        fitSoon(n);
        views.observe(n, watch);
      }
    }
  });
  // the editor's node (getDomNode) is made with its view: when it gets a model, and anew at each
  // model it changes to (a file opened); each new one is watched
  const attach = (): void => {
    const node = editor.getDomNode();
    if (!node) return;
    views.observe(node, { childList: true });
    for (const view of node.querySelectorAll(':scope > .context-view')) views.observe(view, watch);
  };
  attach();
  editor.onDidChangeModel(attach);
  editor.onDidDispose(() => views.disconnect());
}
