import { monaco } from '../editor/monaco.js';
import { replaceByDiff } from '../editor/replace-by-diff.js';
import { threeWayMerge } from '../workspace/three-way-merge.js';

/** How long a file's rename edit may take to reach its model after the rename was computed. */
const EDIT_APPLIED_WITHIN_MS = 2000;

/** A file a rename edited: its model, its text before the rename and once renamed. */
export interface RenamedText {
  uri: string;
  before: string;
  text: string;
}

/**
 * Takes an F2 rename back in every model it edited (the server refused to carry it over, or did
 * not answer: docs/ide.md "Rename carry-over"), as an edit of the user's (autosave then finds each
 * file back at its disk text and writes nothing). Edits typed since the rename are kept (merged
 * three-way on the renamed text); a file whose edits overlap the rename is left as it is: its path
 * is returned, to be said.
 */
export async function undoRename(files: readonly RenamedText[], pathOf: (uri: string) => string): Promise<string[]> {
  const left: string[] = [];
  for (const f of files) {
    const model = monaco.editor.getModel(monaco.Uri.parse(f.uri));
    if (!model || model.isDisposed() || f.before === f.text) continue;
    await editApplied(model, f.before);
    const now = model.getValue();
    if (now === f.before) continue; // the editor never applied it (cancelled, or the model changed first)
    const merged = threeWayMerge(f.text, now, f.before); // the renamed text itself: `before` again
    if (!merged.clean) {
      left.push(pathOf(f.uri));
      continue;
    }
    if (merged.text !== now) replaceByDiff(model, merged.text);
  }
  return left;
}

/**
 * Resolves once `model` no longer holds `before` (the rename's edit applied: the editor applies it
 * after the rename provider answered, the server's answer may come first), or after
 * EDIT_APPLIED_WITHIN_MS.
 */
function editApplied(model: monaco.editor.ITextModel, before: string): Promise<void> {
  if (model.getValue() !== before) return Promise.resolve();
  return new Promise((done) => {
    const finish = () => {
      clearTimeout(timer);
      sub.dispose();
      done();
    };
    const sub = model.onDidChangeContent(() => {
      if (model.getValue() !== before) finish();
    });
    const timer = setTimeout(finish, EDIT_APPLIED_WITHIN_MS);
  });
}
