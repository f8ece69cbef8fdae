/** Conversions between LSP protocol shapes and Monaco's. Pure functions. */
import { monaco } from '../editor/monaco.js';
import type * as lsp from 'vscode-languageserver-protocol';

export const toRange = (r: lsp.Range): monaco.IRange => ({
  startLineNumber: r.start.line + 1,
  startColumn: r.start.character + 1,
  endLineNumber: r.end.line + 1,
  endColumn: r.end.character + 1,
});

export const toPosition = (p: monaco.IPosition): lsp.Position => ({ line: p.lineNumber - 1, character: p.column - 1 });

export function toSeverity(s: lsp.DiagnosticSeverity | undefined): monaco.MarkerSeverity {
  switch (s) {
    case 1: return monaco.MarkerSeverity.Error;
    case 2: return monaco.MarkerSeverity.Warning;
    case 3: return monaco.MarkerSeverity.Info;
    default: return monaco.MarkerSeverity.Hint;
  }
}

export function toMarker(d: lsp.Diagnostic): monaco.editor.IMarkerData {
  return {
    ...toRange(d.range),
    severity: toSeverity(d.severity),
    message: d.message,
    source: d.source ?? 'cactal',
    code: d.code === undefined ? undefined : String(d.code),
  };
}

const K = monaco.languages.CompletionItemKind;
const COMPLETION_KINDS: Record<number, monaco.languages.CompletionItemKind> = {
  1: K.Text, 2: K.Method, 3: K.Function, 4: K.Constructor, 5: K.Field, 6: K.Variable, 7: K.Class, 8: K.Interface,
  9: K.Module, 10: K.Property, 11: K.Unit, 12: K.Value, 13: K.Enum, 14: K.Keyword, 15: K.Snippet, 16: K.Color,
  17: K.File, 18: K.Reference, 19: K.Folder, 20: K.EnumMember, 21: K.Constant, 22: K.Struct, 23: K.Event,
  24: K.Operator, 25: K.TypeParameter,
};

export function toCompletion(item: lsp.CompletionItem, fallback: monaco.IRange): monaco.languages.CompletionItem {
  const edit = item.textEdit;
  let range: monaco.IRange | monaco.languages.CompletionItemRanges = fallback;
  let insertText = item.insertText ?? item.label;
  if (edit) {
    insertText = edit.newText;
    range = 'range' in edit ? toRange(edit.range) : { insert: toRange(edit.insert), replace: toRange(edit.replace) };
  }
  return {
    label: item.label,
    kind: COMPLETION_KINDS[item.kind ?? 1] ?? K.Text,
    detail: item.detail,
    documentation: typeof item.documentation === 'string' ? item.documentation : item.documentation ? { value: item.documentation.value } : undefined,
    insertText,
    insertTextRules: item.insertTextFormat === 2 ? monaco.languages.CompletionItemInsertTextRule.InsertAsSnippet : undefined,
    range,
    sortText: item.sortText,
    filterText: item.filterText,
  };
}

export function toMarkdown(contents: lsp.Hover['contents']): monaco.IMarkdownString[] {
  const list = Array.isArray(contents) ? contents : [contents];
  return list.map((c) => (typeof c === 'string' ? { value: c } : 'kind' in c ? { value: c.value } : { value: '```' + c.language + '\n' + c.value + '\n```' }));
}

export function toLocations(result: lsp.Definition | lsp.LocationLink[] | null): monaco.languages.Location[] {
  if (!result) return [];
  const list = Array.isArray(result) ? result : [result];
  return list.map((l) =>
    'targetUri' in l
      ? { uri: monaco.Uri.parse(l.targetUri), range: toRange(l.targetSelectionRange ?? l.targetRange) }
      : { uri: monaco.Uri.parse(l.uri), range: toRange(l.range) },
  );
}

export function toWorkspaceEdit(edit: lsp.WorkspaceEdit | null | undefined): monaco.languages.WorkspaceEdit {
  const edits: monaco.languages.IWorkspaceTextEdit[] = [];
  if (!edit) return { edits };
  for (const [uri, list] of Object.entries(edit.changes ?? {})) {
    for (const e of list) edits.push({ resource: monaco.Uri.parse(uri), textEdit: { range: toRange(e.range), text: e.newText }, versionId: undefined });
  }
  for (const dc of edit.documentChanges ?? []) {
    if (!('textDocument' in dc)) continue;
    for (const e of dc.edits) {
      edits.push({ resource: monaco.Uri.parse(dc.textDocument.uri), textEdit: { range: toRange(e.range), text: e.newText }, versionId: undefined });
    }
  }
  return { edits };
}

export const SYMBOL_ICONS: Record<number, string> = {
  2: '▣', 5: '◆', 6: 'ƒ', 7: '◆', 8: '◇', 10: '▤', 12: 'ƒ', 13: '𝑥', 14: 'π', 22: '▦', 23: '⚡', 24: '±', 26: 'T',
};
