import { diffPatch } from 'node-diff3';
import { monaco } from './monaco.js';

const lines = (t: string): string[] => t.split(/(?<=\n)/);

/**
 * Makes a model hold `text` by editing only the lines that differ (one undo step of its own: the
 * user's typing before it is a separate step, so Ctrl+Z after a reload takes back the reload only,
 * never the user's last edit with it), so the cursor
 * and the scroll of every editor showing it stay with the text around them: a line added above
 * by a merge moves the cursor down with the line the user is typing on, instead of leaving it at
 * the same line number (src/workspace/workspace.ts shows merges and reloads this way).
 */
export function replaceByDiff(model: monaco.editor.ITextModel, text: string): void {
  const old = lines(model.getValue());
  const patch = diffPatch(old, lines(text)) as Array<{ buffer1: { offset: number; length: number }; buffer2: { chunk: string[] } }>;
  const end = model.getFullModelRange().getEndPosition();
  const at = (line: number) => (line < old.length ? new monaco.Position(line + 1, 1) : end);
  const edits = patch.map((p) => ({
    range: monaco.Range.fromPositions(at(p.buffer1.offset), at(p.buffer1.offset + p.buffer1.length)),
    text: p.buffer2.chunk.join(''),
  }));
  if (!edits.length) return;
  model.pushStackElement(); // close the user's open undo group (typing stays one group until then)
  model.pushEditOperations(null, edits, () => null);
  model.pushStackElement();
  // the line splitting must give the text back exactly; if it ever does not, take it whole
  if (model.getValue() !== text) model.setValue(text);
}
