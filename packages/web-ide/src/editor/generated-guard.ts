import { monaco } from './monaco.js';
import { scanProtectedRegions, editsAllowed, type ProtectedRegion } from './protected-regions.js';

/**
 * Makes a generated C model "protected-regions only": edits outside a region's editable span
 * are undone at once (paste, drag, multi-cursor included), and a decoration greys out the
 * read-only skeleton. The editor itself is switched read-only while the cursor is outside a
 * region, so typing there is refused with Monaco's read-only message.
 * The regions are scanned again after every change of the model's text, whoever made it (the
 * user, an undo, a reload from disk or a merge after another tab's Generate All), before
 * `onRescan` tells the editor, which then recomputes its read-only state: a cursor that a reload
 * carried into a region whose offsets moved can type there at once.
 */
export class GeneratedGuard {
  private regions: ProtectedRegion[] = [];
  private decorations: monaco.editor.IEditorDecorationsCollection | undefined;
  private reverting = false;
  readonly malformed: string[] = [];

  constructor(
    readonly model: monaco.editor.ITextModel,
    private readonly onRejected: (msg: string) => void,
    /** True while the change is not the user's (reload from disk after Generate All or an external edit). */
    private readonly isExternal: () => boolean,
    /** After every rescan (the regions may have moved): the editor recomputes its read-only state and decorations. */
    private readonly onRescan: () => void = () => undefined,
  ) {
    this.rescan();
    model.onDidChangeContent((e) => {
      const checked = !this.reverting && !this.isExternal() && !e.isUndoing && !e.isRedoing;
      if (checked) {
        const ranges = e.changes.map((c) => ({ start: c.rangeOffset, end: c.rangeOffset + c.rangeLength }));
        if (!editsAllowed(this.regions, ranges)) {
          this.reverting = true;
          queueMicrotask(() => {
            model.undo();
            this.reverting = false;
            this.onRejected('Generated code is read-only: write inside a PROTECTED REGION');
          });
        }
      }
      // always: the regions of the text the model holds now (the undo above rescans again)
      this.rescan();
      this.onRescan();
    });
  }

  get hasRegions(): boolean {
    return this.regions.length > 0;
  }

  /** Whether every selection of the editor lies within a region. */
  selectionsEditable(selections: monaco.Selection[]): boolean {
    return editsAllowed(
      this.regions,
      selections.map((s) => ({ start: this.model.getOffsetAt(s.getStartPosition()), end: this.model.getOffsetAt(s.getEndPosition()) })),
    );
  }

  private rescan(): void {
    const scan = scanProtectedRegions(this.model.getValue());
    this.regions = scan.regions;
    this.malformed.length = 0;
    for (const e of scan.errors) this.malformed.push(`line ${this.model.getPositionAt(e.offset).lineNumber}: ${e.message}`);
  }

  /** (Re)applies the read-only / protected decorations in an editor showing this model. */
  decorate(editor: monaco.editor.IStandaloneCodeEditor): void {
    const decos: monaco.editor.IModelDeltaDecoration[] = [];
    let pos = 0;
    const text = this.model.getValue();
    const addReadOnly = (from: number, to: number) => {
      if (to <= from) return;
      const a = this.model.getPositionAt(from);
      const b = this.model.getPositionAt(to);
      decos.push({ range: new monaco.Range(a.lineNumber, a.column, b.lineNumber, b.column), options: { inlineClassName: 'gen-readonly-text', className: 'gen-readonly', isWholeLine: false } });
    };
    for (const r of this.regions) {
      addReadOnly(pos, r.start);
      const a = this.model.getPositionAt(r.start);
      const b = this.model.getPositionAt(r.end);
      decos.push({ range: new monaco.Range(a.lineNumber, 1, b.lineNumber, 1), options: { isWholeLine: true, className: 'gen-region', linesDecorationsClassName: 'gen-region-gutter' } });
      pos = r.end;
    }
    addReadOnly(pos, text.length);
    this.decorations?.clear();
    this.decorations = editor.createDecorationsCollection(decos);
  }
}
