import { monaco } from './monaco.js';
import { scanProtectedRegions } from './protected-regions.js';

/** Where a cursor was: inside a protected region (by ID and offset in its content), else by line/column. */
type Anchor = { region: string; delta: number } | { lineNumber: number; column: number };

function anchorOf(model: monaco.editor.ITextModel, position: monaco.Position): Anchor {
  const offset = model.getOffsetAt(position);
  const inRegion = scanProtectedRegions(model.getValue()).regions.find((r) => offset >= r.start && offset <= r.end);
  return inRegion ? { region: inRegion.id, delta: offset - inRegion.start } : { lineNumber: position.lineNumber, column: position.column };
}

function positionOf(model: monaco.editor.ITextModel, anchor: Anchor): monaco.Position {
  if ('region' in anchor) {
    const r = scanProtectedRegions(model.getValue()).regions.find((g) => g.id === anchor.region);
    if (r) return model.getPositionAt(Math.min(r.start + anchor.delta, r.end));
    return model.getPositionAt(0);
  }
  return model.validatePosition(new monaco.Position(anchor.lineNumber, anchor.column));
}

/**
 * Replaces the whole text of a model (one undo step of its own, apart from the user's typing
 * before it) and puts the cursor of every editor showing
 * it back roughly where it was: at the same offset in the same protected region when it was in
 * one (the generated code around may have moved it many lines), else on the same line and column.
 */
export function replaceKeepingCursor(model: monaco.editor.ITextModel, text: string): void {
  const editors = monaco.editor.getEditors().filter((e) => e.getModel() === model);
  const anchors = editors.map((e) => { const p = e.getPosition(); return p ? anchorOf(model, p) : undefined; });
  model.pushStackElement(); // close the user's open undo group
  model.pushEditOperations([], [{ range: model.getFullModelRange(), text }], () => null);
  model.pushStackElement();
  editors.forEach((editor, i) => {
    const anchor = anchors[i];
    if (!anchor) return;
    const pos = positionOf(model, anchor);
    editor.setPosition(pos);
    editor.revealPositionInCenterIfOutsideViewport(pos);
  });
}
