/** What kind of editor a workspace path gets. */
export function languageOf(path: string): string {
  if (path.endsWith('.contract')) return 'cactal';
  if (path.endsWith('.scenario')) return 'cactal-scenario';
  if (/\.(c|h)$/.test(path)) return 'c';
  if (/(^|\/)(Makefile|makecontrol\w*)$/.test(path)) return 'plaintext';
  return 'plaintext';
}

export const isContract = (path: string) => path.endsWith('.contract');

/** What the status bar names a file's language: the editor's language, and for C whether it is generated. */
export function languageLabel(path: string, languageId: string): string {
  if (languageId === 'cactal') return 'Cactal';
  if (languageId === 'cactal-scenario') return 'Cactal scenario';
  if (languageId === 'c') return isGeneratedC(path) ? 'C (generated)' : 'C';
  return path.endsWith('.csv') ? 'CSV' : 'Plain text';
}

/** Generated C under a src-gen/ folder: protected regions editable, the rest read-only. */
export const isGeneratedC = (path: string) => /(^|\/)src-gen\//.test(path) && /\.(c|h)$/.test(path);
