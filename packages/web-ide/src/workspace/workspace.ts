import { monaco } from '../editor/monaco.js';
import { api, ApiError, type TreeEntry, type Snapshot } from '../api.js';
import { Emitter } from '../util/emitter.js';
import { languageOf, isContract, isGeneratedC } from './file-kinds.js';
import { replaceKeepingCursor } from '../editor/replace-keeping-cursor.js';

export type SaveState = 'saved' | 'dirty' | 'saving' | 'error';

export interface FileState {
  path: string;
  model: monaco.editor.ITextModel;
  /** Text last confirmed on disk by the server. */
  diskText: string;
  state: SaveState;
  error?: string;
}

const SAVE_DELAY_MS = 300;
const BACKUP_PREFIX = 'contract-studio:unsaved:';

/**
 * The open workspace: its file tree, one Monaco model per loaded file, and autosave.
 * Every edit is first kept in localStorage (so a reload or a server crash loses nothing), then
 * written atomically by the server; the backup is dropped only once the server confirms.
 * A failed write is reported and retried with backoff; the text stays in the browser. A write the
 * server refuses (4xx: e.g. a generated file whose protected regions no longer match) is reported
 * and not retried until the text changes. When the server merged a save of a generated file into
 * a newer skeleton on disk, the tab is reloaded from the server's answer.
 */
export class Workspace {
  root = '';
  name = '';
  entries: TreeEntry[] = [];
  readonly files = new Map<string, FileState>();
  readonly onTree = new Emitter<TreeEntry[]>();
  readonly onFileState = new Emitter<FileState>();
  readonly onNotice = new Emitter<{ level: 'info' | 'warning' | 'error'; text: string }>();
  private readonly timers = new Map<string, ReturnType<typeof setTimeout>>();
  private readonly retryDelay = new Map<string, number>();
  /** True while a change read from disk is being applied to a model (not a user edit). */
  applyingExternal = false;

  uriOf(path: string): monaco.Uri {
    return monaco.Uri.from({ scheme: 'file', path: `/workspace/${path}` });
  }

  pathOf(uri: monaco.Uri | string): string | undefined {
    const p = typeof uri === 'string' ? monaco.Uri.parse(uri).path : uri.path;
    return p.startsWith('/workspace/') ? p.slice('/workspace/'.length) : undefined;
  }

  async load(): Promise<void> {
    const prefetched = (window as unknown as { __snapshot?: Promise<Snapshot | null> }).__snapshot;
    const snap = (prefetched && (await prefetched)) || (await api.snapshot());
    this.name = snap.name;
    this.root = snap.root;
    this.entries = snap.entries;
    this.onTree.fire(this.entries);
    for (const [path, content] of Object.entries(snap.files)) this.adopt(path, content);
    await Promise.all(this.allFiles().filter(isContract).map((p) => this.ensureModel(p)));
    this.restoreBackups();
  }

  allFiles(entries: TreeEntry[] = this.entries): string[] {
    const out: string[] = [];
    for (const e of entries) {
      if (e.type === 'file') out.push(e.path);
      else if (e.children) out.push(...this.allFiles(e.children));
    }
    return out;
  }

  hasFile(path: string): boolean {
    return this.allFiles().includes(path);
  }

  async refreshTree(): Promise<void> {
    const t = await api.tree();
    this.entries = t.entries;
    this.onTree.fire(this.entries);
  }

  /** Loads a file into a model (once). */
  async ensureModel(path: string): Promise<FileState> {
    const existing = this.files.get(path);
    if (existing) return existing;
    const { content } = await api.read(path);
    return this.adopt(path, content);
  }

  /** Creates the model of a file whose disk content is known (once). */
  private adopt(path: string, content: string): FileState {
    const again = this.files.get(path);
    if (again) return again;
    const model = monaco.editor.getModel(this.uriOf(path)) ?? monaco.editor.createModel(content, languageOf(path), this.uriOf(path));
    const fs: FileState = { path, model, diskText: content, state: 'saved' };
    this.files.set(path, fs);
    model.onDidChangeContent(() => {
      if (this.applyingExternal) return;
      this.markDirty(fs);
    });
    return fs;
  }

  private markDirty(fs: FileState): void {
    const text = fs.model.getValue();
    if (text === fs.diskText && fs.state !== 'error') {
      // back to what is on disk: nothing to write (a pending write could overwrite a newer disk version)
      this.cancelPendingSave(fs.path);
      this.clearBackup(fs.path);
      this.setState(fs, 'saved');
      return;
    }
    this.backup(fs.path, text);
    this.setState(fs, 'dirty');
    this.scheduleSave(fs, SAVE_DELAY_MS);
  }

  private cancelPendingSave(path: string): void {
    const pending = this.timers.get(path);
    if (pending) clearTimeout(pending);
    this.timers.delete(path);
  }

  private scheduleSave(fs: FileState, delay: number): void {
    this.cancelPendingSave(fs.path);
    this.timers.set(fs.path, setTimeout(() => void this.save(fs.path), delay));
  }

  /** Writes the model's text now; resolves when the server confirmed (or the write failed). */
  async save(path: string): Promise<boolean> {
    const fs = this.files.get(path);
    if (!fs || fs.model.isDisposed()) return false;
    this.cancelPendingSave(path);
    const text = fs.model.getValue();
    if (text === fs.diskText && fs.state !== 'error') {
      this.clearBackup(path);
      this.setState(fs, 'saved');
      return true;
    }
    this.setState(fs, 'saving');
    try {
      const answer = await api.write(path, text);
      this.retryDelay.delete(path);
      if (answer.merged && answer.content !== undefined) {
        this.adoptMerged(fs, text, answer.content, answer.reason ?? 'merged into the file on disk');
        return true;
      }
      fs.diskText = text;
      if (fs.model.getValue() === text) {
        this.clearBackup(path);
        this.setState(fs, 'saved');
      } else this.markDirty(fs);
      return true;
    } catch (e) {
      fs.error = e instanceof ApiError ? e.message : String(e);
      if (e instanceof ApiError && e.status >= 400 && e.status < 500) {
        // refused (not a network or server failure): retrying the same text cannot succeed
        this.retryDelay.delete(path);
        this.setState(fs, 'error');
        this.onNotice.fire({
          level: 'error',
          text: `Not saved: ${fs.error}. Your text stays in this browser and is not retried until you change it; ` +
            'copy what you need, then right-click › "Reload from disk" to drop it.',
        });
        return false;
      }
      const delay = Math.min(30_000, (this.retryDelay.get(path) ?? 1000) * 2);
      this.retryDelay.set(path, delay);
      this.setState(fs, 'error');
      this.onNotice.fire({
        level: 'error',
        text: `Could not save ${path}: ${fs.error}. Your text is kept in this browser; retrying in ${Math.round(delay / 1000)} s.`,
      });
      this.scheduleSave(fs, delay);
      return false;
    }
  }

  /**
   * The server wrote our protected regions into a newer generated file (Generate All changed the
   * code around them): show what is on disk now, unless the user typed since the save was sent
   * (then that text is saved, and merged, again).
   */
  private adoptMerged(fs: FileState, sent: string, onDisk: string, reason: string): void {
    fs.diskText = onDisk;
    if (fs.model.isDisposed()) return; // the file was closed or deleted meanwhile
    if (fs.model.getValue() === sent) {
      this.showText(fs, onDisk);
      this.clearBackup(fs.path);
      this.setState(fs, 'saved');
    } else this.markDirty(fs);
    this.onNotice.fire({ level: 'info', text: `${fs.path}: ${reason}` });
  }

  /** Puts `text` in the file's editor model (cursor kept) without taking it for a user edit. */
  private showText(fs: FileState, text: string): void {
    this.applyingExternal = true;
    try {
      replaceKeepingCursor(fs.model, text);
    } finally {
      this.applyingExternal = false;
    }
  }

  /** Drops the unsaved text of a file (browser copy included) and shows what is on disk. */
  async revertToDisk(path: string): Promise<void> {
    const fs = this.files.get(path);
    if (!fs) return;
    const { content } = await api.read(path);
    this.cancelPendingSave(path);
    this.retryDelay.delete(path);
    if (fs.model.getValue() !== content) {
      this.showText(fs, content);
    }
    fs.diskText = content;
    this.clearBackup(path);
    this.setState(fs, 'saved');
  }

  async saveAll(): Promise<void> {
    await Promise.all([...this.files.values()].filter((f) => f.state !== 'saved').map((f) => this.save(f.path)));
  }

  isBusy(): boolean {
    return [...this.files.values()].some((f) => f.state !== 'saved');
  }

  /** Applies a change made on disk by someone else (watcher event). */
  async externalChange(path: string): Promise<void> {
    const fs = this.files.get(path);
    if (!fs) return;
    let content: string;
    try {
      content = (await api.read(path)).content;
    } catch (e) {
      if (e instanceof ApiError && e.status === 404) return; // deleted: the tree refresh handles it
      return;
    }
    if (content === fs.model.getValue()) {
      fs.diskText = content;
      if (fs.state !== 'saving') this.setState(fs, 'saved');
      return;
    }
    if (content === fs.diskText) return; // our own earlier write echoing back
    if (fs.state === 'saved') {
      this.showText(fs, content);
      fs.diskText = content;
      // Regenerated C is expected to change: only user files get a notice.
      if (!/(^|\/)src-gen\//.test(path)) this.onNotice.fire({ level: 'info', text: `${path} changed on disk: reloaded` });
    } else {
      fs.diskText = content;
      this.onNotice.fire({
        level: 'warning',
        text: isGeneratedC(path)
          ? `${path} was regenerated while you were editing: your protected regions will be saved into the new file`
          : `${path} changed on disk while you were editing: your version is kept and will be saved`,
      });
    }
  }

  /** Forgets a model after its file was deleted or renamed. */
  dropFile(path: string): void {
    const fs = this.files.get(path);
    if (!fs) return;
    this.files.delete(path);
    this.clearBackup(path);
    this.cancelPendingSave(path);
    fs.model.dispose();
  }

  private setState(fs: FileState, state: SaveState): void {
    fs.state = state;
    if (state !== 'error') fs.error = undefined;
    this.onFileState.fire(fs);
  }

  private backupKey(path: string): string {
    return `${BACKUP_PREFIX}${this.root}:${path}`;
  }

  private backup(path: string, text: string): void {
    try {
      localStorage.setItem(this.backupKey(path), text);
    } catch {
      this.onNotice.fire({ level: 'warning', text: 'Browser storage full: unsaved text is only in memory until the server confirms' });
    }
  }

  private clearBackup(path: string): void {
    localStorage.removeItem(this.backupKey(path));
  }

  /** Re-applies text that was edited but not confirmed by the server before the last reload. */
  private restoreBackups(): void {
    const prefix = `${BACKUP_PREFIX}${this.root}:`;
    for (let i = 0; i < localStorage.length; i++) {
      const key = localStorage.key(i);
      if (!key?.startsWith(prefix)) continue;
      const path = key.slice(prefix.length);
      const text = localStorage.getItem(key) ?? '';
      void this.ensureModel(path)
        .then((fs) => {
          if (fs.model.getValue() === text) return this.clearBackup(path);
          fs.model.setValue(text); // triggers markDirty -> save
          this.onNotice.fire({ level: 'info', text: `Restored unsaved edits of ${path}` });
        })
        .catch(() => {
          // The file is gone on disk: recreate it rather than lose the text.
          void api.write(path, text).then(() => this.refreshTree()).then(() => this.clearBackup(path));
          this.onNotice.fire({ level: 'warning', text: `${path} no longer existed on disk: recreated from your unsaved edits` });
        });
    }
  }
}
