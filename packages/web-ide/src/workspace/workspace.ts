import { monaco } from '../editor/monaco.js';
import { api, ApiError, staleDetails, type TreeEntry, type Snapshot } from '../api.js';
import { Emitter } from '../util/emitter.js';
import { languageOf, isContract } from './file-kinds.js';
import { SRC_GEN_DIR, projectRootOf, type ProjectRoot } from '@contract-studio/conventions';
import { projectLayout, type ProjectLayout } from '../lsp/project-layout.js';
import { replaceKeepingCursor } from '../editor/replace-keeping-cursor.js';
import { replaceByDiff } from '../editor/replace-by-diff.js';
import type { BrowserCopy } from './browser-copies.js';
import { BrowserCopyStore } from './browser-copy-store.js';
import { threeWayMerge } from './three-way-merge.js';

/** `conflict`: the tab's edits and a change made elsewhere overlap; nothing is saved until the user chose. */
export type SaveState = 'saved' | 'dirty' | 'saving' | 'error' | 'conflict';

/** Overlapping edits waiting for the user's choice (shown side by side: src/editor/conflict-view.ts). */
export interface Conflict {
  path: string;
  /** The text both sides were edited from. */
  base: string;
  /** The tab's text when the conflict was found. */
  mine: string;
  /** The disk's text and version. */
  theirs: string;
  theirsVersion: string;
  /** Both sides of each conflicting block between markers (a start for "edit the merge"). */
  marked: string;
}

export interface FileState {
  path: string;
  model: monaco.editor.ITextModel;
  /** Text last confirmed on disk by the server: the base the tab's edits are made on. */
  diskText: string;
  /** The version of `diskText` (the server's SHA-256): every save names it (If-Match). */
  diskVersion?: string;
  state: SaveState;
  error?: string;
  conflict?: Conflict;
  /** The text of a save sent and not answered yet (a reload before the answer must know it may have landed). */
  sending?: string;
  /** The disk's bytes are not all UTF-8 (the first such line): the tab is read-only (server/undecodable.ts). */
  undecodableLine?: number;
}

const SAVE_DELAY_MS = 300;
/** How long after this tab saved a file it takes up the copies of it that tabs closed since left. */
const TAKE_UP_AFTER_MS = 2000;
/** How long a tab asked whether it is open has to answer (a loaded machine: generous). */
const TAB_ANSWER_MS = 1000;

/**
 * The open workspace: its file tree, one Monaco model per loaded file, and autosave.
 * Every edit is first kept in localStorage (so a reload or a server crash loses nothing), then
 * written atomically by the server; the backup is dropped only once the server confirms.
 * A failed write is reported and retried with backoff; the text stays in the browser. A write the
 * server refuses (4xx: e.g. a generated file whose protected regions no longer match) is reported
 * and not retried until the text changes. When the server merged a save of a generated file into
 * a newer skeleton on disk, the tab is reloaded from the server's answer.
 * Every save names the version it was edited from; when the disk moved on (another tab, another
 * program) the server refuses it (409 + the disk's text) and the tab merges three-way: disjoint
 * edits are merged and saved, overlapping ones become a `conflict` the user resolves side by side.
 * A watcher change under unsaved edits is merged the same way (docs/ide.md, "Saves, versions and merges").
 */
/** A save the server refused for want of this tab's session (its notice goes when the session is back: external-changes.ts). */
export const SAVE_SESSION_LOST = 'Not saved: the IDE server no longer knows this tab\'s session (was it restarted?).';

export class Workspace {
  root = '';
  name = '';
  entries: TreeEntry[] = [];
  readonly files = new Map<string, FileState>();
  readonly onTree = new Emitter<TreeEntry[]>();
  readonly onFileState = new Emitter<FileState>();
  readonly onNotice = new Emitter<{ level: 'info' | 'warning' | 'error'; text: string }>();
  /** Overlapping edits found: the UI shows both versions and calls resolveConflict. */
  readonly onConflict = new Emitter<Conflict>();
  /** A file changed on disk by another program (the server's watcher), open or not (the Monitor re-reads a log folder). */
  readonly onExternalChange = new Emitter<string>();
  /** A file's bytes became, or stopped being, all UTF-8 on disk (its tab's read-only state follows). */
  readonly onEncodingChanged = new Emitter<string>();
  /** Files whose watcher change arrived while a save was in flight: looked at again after it. */
  private readonly recheck = new Set<string>();
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
    for (const [path, content] of Object.entries(snap.files)) this.adopt(path, content, snap.versions?.[path]);
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

  /**
   * Whether the workspace's tree (as last listed) has file `path`. A set made once per listing:
   * each call walked the whole tree, and Quick open's check of every file took 100 s of the page
   * in a workspace of 40,000 files.
   */
  hasFile(path: string): boolean {
    if (this.fileSetOf !== this.entries) {
      this.fileSet = new Set(this.allFiles());
      this.fileSetOf = this.entries;
    }
    return this.fileSet.has(path);
  }

  private fileSet = new Set<string>();
  private fileSetOf: TreeEntry[] | undefined;

  /**
   * The project a workspace path belongs to, by the rule the CLI and a build follow (conventions'
   * project-root.ts, docs/codegen.md "Where a project is"), from the tree as last listed: its root
   * ('' = the workspace root) and the trees of it that are not used.
   */
  projectRootOf(path: string): ProjectRoot {
    const { dirs, contracts } = this.treeLayout();
    return projectRootOf(path, (folder) => dirs.has(folder ? `${folder}/${SRC_GEN_DIR}` : SRC_GEN_DIR), contracts);
  }

  /** The projects' layout as the language worker needs it (src/lsp/project-layout.ts), from the tree as last listed. */
  projectLayout(): ProjectLayout {
    const { dirs, contracts } = this.treeLayout();
    return projectLayout(this.uriOf('').toString().replace(/\/$/, ''), dirs, contracts);
  }

  /** The folders and `.contract` files of the tree as last listed (computed once per listing). */
  private treeLayout(): { dirs: Set<string>; contracts: string[] } {
    if (this.layoutOf !== this.entries) {
      const dirs = new Set<string>();
      const walk = (entries: TreeEntry[]): void => {
        for (const e of entries) {
          if (e.type !== 'dir') continue;
          dirs.add(e.path);
          if (e.children) walk(e.children);
        }
      };
      walk(this.entries);
      const contracts = this.allFiles().filter(isContract);
      this.layout = { dirs, contracts };
      this.layoutOf = this.entries;
    }
    return this.layout;
  }

  private layout: { dirs: Set<string>; contracts: string[] } = { dirs: new Set(), contracts: [] };
  private layoutOf: TreeEntry[] | undefined;

  async refreshTree(): Promise<void> {
    const t = await api.tree();
    this.entries = t.entries;
    this.onTree.fire(this.entries);
  }

  /** Loads a file into a model (once). */
  async ensureModel(path: string): Promise<FileState> {
    const existing = this.files.get(path);
    if (existing) return existing;
    const { content, version, undecodableLine } = await api.read(path);
    const fs = this.adopt(path, content, version);
    fs.undecodableLine = undecodableLine;
    return fs;
  }

  /** Creates the model of a file whose disk content is known (once). */
  private adopt(path: string, content: string, version: string | undefined): FileState {
    const again = this.files.get(path);
    if (again) return again;
    const model = monaco.editor.getModel(this.uriOf(path)) ?? monaco.editor.createModel(content, languageOf(path), this.uriOf(path));
    const fs: FileState = { path, model, diskText: content, diskVersion: version, state: 'saved' };
    this.files.set(path, fs);
    model.onDidChangeContent(() => {
      if (this.applyingExternal) return;
      this.markDirty(fs);
    });
    return fs;
  }

  private markDirty(fs: FileState): void {
    const text = fs.model.getValue();
    if (fs.state === 'conflict') {
      // kept (with its base) until the user chose in the conflict view; nothing is written meanwhile
      this.backup(fs, text);
      return;
    }
    if (text === fs.diskText && fs.state !== 'error') {
      // back to what is on disk: nothing to write (a pending write could overwrite a newer disk version)
      this.cancelPendingSave(fs.path);
      this.clearBackup(fs.path);
      this.setState(fs, 'saved');
      return;
    }
    this.backup(fs, text);
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

  /** The write of each file in flight: a file has at most one (the next waits for it). */
  private readonly writing = new Map<string, Promise<boolean>>();

  /**
   * Writes the model's text now; resolves when the server confirmed (or the write failed). While a
   * write of the file is in flight, this one waits for it: two writes on the same base would make
   * the second a conflict with the first, and a reload in between would keep in the browser copy
   * only the second's text as the one sent, so the first, landed on disk, would look like a change
   * made elsewhere (an overlap with the user's own edit).
   */
  async save(path: string): Promise<boolean> {
    for (let running = this.writing.get(path); running; running = this.writing.get(path)) await running.catch(() => false);
    const write = this.saveNow(path);
    this.writing.set(path, write);
    try {
      return await write;
    } finally {
      if (this.writing.get(path) === write) this.writing.delete(path);
    }
  }

  private async saveNow(path: string): Promise<boolean> {
    const fs = this.files.get(path);
    if (!fs || fs.model.isDisposed()) return false;
    this.cancelPendingSave(path);
    if (this.held.has(path)) return false; // a rename's server write is on its way (holdSaves): saved after it, if still needed
    if (fs.state === 'conflict') return false; // the conflict view decides what is written
    const text = fs.model.getValue();
    if (text === fs.diskText && fs.state !== 'error') {
      this.clearBackup(path);
      this.setState(fs, 'saved');
      return true;
    }
    this.setState(fs, 'saving');
    fs.sending = text;
    this.backup(fs, text);
    try {
      const answer = await api.write(path, text, fs.diskVersion);
      fs.sending = undefined;
      this.retryDelay.delete(path);
      if (answer.merged && answer.content !== undefined) {
        this.adoptMerged(fs, text, answer.content, answer.version, answer.reason ?? 'merged into the file on disk');
        return true;
      }
      fs.diskText = text;
      fs.diskVersion = answer.version;
      if (fs.model.getValue() === text) {
        this.clearBackup(path);
        this.setState(fs, 'saved');
      } else this.markDirty(fs);
      return true;
    } catch (e) {
      fs.sending = undefined;
      const stale = staleDetails(e);
      if (stale) {
        // the disk moved on since this tab's base (another tab, a program): merge, never overwrite
        this.retryDelay.delete(path);
        this.setState(fs, 'dirty');
        this.reconcile(fs, stale.content, stale.version);
        return (fs.state as SaveState) !== 'conflict';
      }
      fs.error = e instanceof ApiError ? e.message : String(e);
      if (e instanceof ApiError && e.status === 401) {
        // the server does not know this tab's session: restarted (a new token). The edit is in
        // localStorage: opening the new address restores it and saves it; dropping it would lose it
        this.retryDelay.delete(path);
        this.setState(fs, 'error');
        this.onNotice.fire({
          level: 'error',
          text: `${SAVE_SESSION_LOST} Open the address it printed ` +
            '(…/?token=…) in this tab: your text is kept in this browser for this address, comes back there, and is saved then ' +
            '(the same port: contract serve --port N; on another port the browser does not give it back).',
        });
        return false;
      }
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
    } finally {
      if (this.recheck.delete(path)) void this.externalChange(path);
    }
  }

  /**
   * The disk holds `theirs` (version `theirsVersion`), not the tab's base: merges the tab's text
   * with it on that base (three-way-merge.ts). Disjoint edits: the tab shows the merge (cursor
   * kept), whose base is now `theirs`, and saves it. Overlapping edits: state `conflict`, the
   * tab's text stays (and its browser copy, with the base), onConflict asks the user.
   */
  private reconcile(fs: FileState, theirs: string, theirsVersion: string): void {
    if (fs.model.isDisposed()) return;
    const mine = fs.model.getValue();
    const result = threeWayMerge(fs.diskText, mine, theirs);
    if (!result.clean) {
      const conflict: Conflict = { path: fs.path, base: fs.diskText, mine, theirs, theirsVersion, marked: result.marked };
      fs.conflict = conflict;
      this.cancelPendingSave(fs.path);
      this.backup(fs, mine);
      this.setState(fs, 'conflict');
      this.onNotice.fire({ level: 'warning', text: `${fs.path}: your edits and a change made elsewhere overlap — choose in the side-by-side view (your text is kept)` });
      this.onConflict.fire(conflict);
      return;
    }
    if (fs.state === 'conflict') {
      // a newer disk text merges cleanly with the user's: the overlap is gone (its view closes)
      fs.conflict = undefined;
      this.setState(fs, 'dirty');
    }
    fs.diskText = theirs;
    fs.diskVersion = theirsVersion;
    if (result.text !== mine) this.showText(fs, result.text);
    if (result.text !== theirs) this.onNotice.fire({ level: 'info', text: `${fs.path}: merged with a change made elsewhere` });
    this.markDirty(fs); // saves the merge on its new base (or nothing: it is the disk's text)
  }

  /**
   * Shows the overlapping edits of a file again (the user closed the side-by-side view with Escape
   * and pressed Ctrl+S in the tab): true when the file has some.
   */
  showConflict(path: string): boolean {
    const fs = this.files.get(path);
    if (fs?.state !== 'conflict' || !fs.conflict) return false;
    this.onConflict.fire(fs.conflict);
    return true;
  }

  /** The user's choice for a conflict: `text` is written on the disk's version the conflict showed. */
  resolveConflict(path: string, text: string): void {
    const fs = this.files.get(path);
    if (!fs?.conflict || fs.model.isDisposed()) return;
    fs.diskText = fs.conflict.theirs;
    fs.diskVersion = fs.conflict.theirsVersion;
    fs.conflict = undefined;
    this.setState(fs, 'dirty');
    if (fs.model.getValue() !== text) this.showText(fs, text);
    this.markDirty(fs);
    if (fs.state === 'dirty') void this.save(path);
  }

  /**
   * The server wrote our protected regions into a newer generated file (Generate All changed the
   * code around them): show what is on disk now, unless the user typed since the save was sent
   * (then that text is saved, and merged, again).
   */
  private adoptMerged(fs: FileState, sent: string, onDisk: string, version: string, reason: string): void {
    fs.diskText = onDisk;
    fs.diskVersion = version;
    if (fs.model.isDisposed()) return; // the file was closed or deleted meanwhile
    if (fs.model.getValue() === sent) {
      this.showText(fs, onDisk, true);
      this.clearBackup(fs.path);
      this.setState(fs, 'saved');
    } else this.markDirty(fs);
    this.onNotice.fire({ level: 'info', text: `${fs.path}: ${reason}` });
  }

  /**
   * Puts `text` in the file's editor model without taking it for a user edit: line by line
   * (replace-by-diff.ts: the cursor moves with its text), or, for a generated file the server
   * merged, whole with the cursor kept in its protected region (replace-keeping-cursor.ts).
   */
  private showText(fs: FileState, text: string, byRegion = false): void {
    this.applyingExternal = true;
    try {
      if (byRegion) replaceKeepingCursor(fs.model, text);
      else replaceByDiff(fs.model, text);
    } finally {
      this.applyingExternal = false;
    }
  }

  /** Drops the unsaved text of a file (browser copy included) and shows what is on disk. */
  async revertToDisk(path: string): Promise<void> {
    const fs = this.files.get(path);
    if (!fs) return;
    const { content, version, undecodableLine } = await api.read(path);
    fs.undecodableLine = undecodableLine;
    this.cancelPendingSave(path);
    this.retryDelay.delete(path);
    fs.conflict = undefined;
    if (fs.model.getValue() !== content) {
      this.showText(fs, content);
    }
    fs.diskText = content;
    fs.diskVersion = version;
    this.clearBackup(path);
    this.setState(fs, 'saved');
  }

  /** Files the server is writing for a rename (rename-carryover.ts): their saves wait for releaseSaves. */
  private readonly held = new Set<string>();

  /**
   * Holds the saves of `paths` (the files a rename is about to edit): the server writes their
   * renamed text under the rename's journal, so no autosave may write it before that journal is.
   * Returns the version on disk each was loaded or last saved as (the rename's base).
   */
  holdSaves(paths: readonly string[]): Map<string, string> {
    const bases = new Map<string, string>();
    for (const path of paths) {
      const fs = this.files.get(path);
      if (!fs || fs.diskVersion === undefined) continue;
      this.held.add(path);
      this.cancelPendingSave(path);
      bases.set(path, fs.diskVersion);
    }
    return bases;
  }

  /**
   * The rename's server write is over: `written` (the file now holds `text`, version `version`) is
   * the tab's new base; every held file then saves whatever differs from its disk text.
   */
  releaseSaves(paths: readonly string[], written: ReadonlyMap<string, { text: string; version: string }>): void {
    for (const path of paths) {
      this.held.delete(path);
      const fs = this.files.get(path);
      if (!fs || fs.model.isDisposed()) continue;
      const w = written.get(path);
      if (w) {
        fs.diskText = w.text;
        fs.diskVersion = w.version;
      }
      if (fs.state === 'conflict') continue;
      if (fs.model.getValue() === fs.diskText) {
        this.clearBackup(path);
        this.setState(fs, 'saved');
      } else this.markDirty(fs);
    }
  }

  async saveAll(): Promise<void> {
    await Promise.all([...this.files.values()].filter((f) => f.state !== 'saved').map((f) => this.save(f.path)));
  }

  isBusy(): boolean {
    return [...this.files.values()].some((f) => f.state !== 'saved');
  }

  /**
   * Applies a change made on disk by someone else (watcher event). A tab without unsaved edits
   * shows the new text; one with unsaved edits merges it (reconcile) instead of moving its base to
   * the new text and then overwriting it. While a save is in flight the change is looked at again
   * after the save (its answer may already be the newer version, or a 409 that merges it).
   */
  async externalChange(path: string): Promise<void> {
    this.onExternalChange.fire(path);
    const fs = this.files.get(path);
    if (!fs) return;
    if (fs.state === 'saving') {
      this.recheck.add(path);
      return;
    }
    let content: string;
    let version: string;
    try {
      let undecodableLine: number | undefined;
      ({ content, version, undecodableLine } = await api.read(path));
      if (undecodableLine !== fs.undecodableLine) {
        fs.undecodableLine = undecodableLine;
        this.onEncodingChanged.fire(path);
      }
    } catch {
      return; // deleted (the tree refresh handles it) or unreachable (the reconnect re-saves)
    }
    if (fs.model.isDisposed() || version === fs.diskVersion) return; // nothing new (our own write echoing back)
    if ((fs.state as SaveState) === 'saving') {
      this.recheck.add(path);
      return;
    }
    // the disk text the conflict view shows already (a re-read after a reconnect, a late event):
    // nothing new, and the view, with what the user is merging in it, stays as it is
    if (fs.state === 'conflict' && fs.conflict?.theirsVersion === version) return;
    if (content === fs.model.getValue()) {
      fs.conflict = undefined;
      fs.diskText = content;
      fs.diskVersion = version;
      this.clearBackup(path);
      this.setState(fs, 'saved');
      return;
    }
    if (fs.state === 'saved') {
      this.showText(fs, content);
      fs.diskText = content;
      fs.diskVersion = version;
      // Regenerated C is expected to change: only user files get a notice.
      if (!/(^|\/)src-gen\//.test(path)) this.onNotice.fire({ level: 'info', text: `${path} changed on disk: reloaded` });
      return;
    }
    // unsaved edits, or a conflict whose view showed an older disk text: the user's text is compared
    // with the newest one, on the same base (a conflict again replaces the view's left side)
    this.cancelPendingSave(path);
    this.reconcile(fs, content, version);
  }

  /** Forgets a model after its file was deleted or renamed. */
  dropFile(path: string): void {
    const fs = this.files.get(path);
    if (!fs) return;
    this.files.delete(path);
    this.dropCopy(path, this.tabId); // this tab's only: another tab's unsaved text is its to save (or recreate)
    this.cancelPendingSave(path);
    fs.model.dispose();
  }

  private setState(fs: FileState, state: SaveState): void {
    fs.state = state;
    if (state !== 'error') fs.error = undefined;
    this.onFileState.fire(fs);
  }

  /** The browser copies of this workspace's unsaved edits (browser-copy-store.ts: one entry per file and tab). */
  private get copies(): BrowserCopyStore {
    return new BrowserCopyStore(localStorage, this.root);
  }

  /** This page's copies among the browser's (browser-copies.ts): a reload is a new page, whose copy the old one's does not hide. */
  private readonly tabId = `${Date.now().toString(36)}-${Math.random().toString(36).slice(2, 10)}`;

  /** Keeps the tab's text and the base it was edited from (a reload can then still merge), beside other tabs' copies. */
  private backup(fs: FileState, text: string): void {
    const copy: BrowserCopy = { text, baseText: fs.diskText, ...(fs.diskVersion !== undefined ? { baseVersion: fs.diskVersion } : {}), ...(fs.sending !== undefined ? { sentText: fs.sending } : {}), at: Date.now() };
    try {
      this.copies.put(fs.path, this.tabId, copy);
    } catch {
      this.onNotice.fire({ level: 'warning', text: 'Browser storage full: unsaved text is only in memory until the server confirms' });
    }
  }

  /** Drops this tab's copy of `path` (other tabs' stay); once saved, any copy another tab left is taken up after a while. */
  private clearBackup(path: string): void {
    this.dropCopy(path, this.tabId);
    if (this.copies.others(path, this.tabId).length && !this.takeUpTimers.has(path)) {
      this.takeUpTimers.set(path, setTimeout(() => {
        this.takeUpTimers.delete(path);
        void this.takeUpCopies(path);
      }, TAKE_UP_AFTER_MS));
    }
  }

  private readonly takeUpTimers = new Map<string, ReturnType<typeof setTimeout>>();

  /** Drops tab `tab`'s copy of `path`: this tab's own, or that of a tab gone whose text this tab took up. */
  private dropCopy(path: string, tab: string): void {
    try {
      this.copies.drop(path, tab);
    } catch {
      /* storage refused: the copy stays, taken up again later (merged, nothing doubled) */
    }
  }

  /**
   * Re-applies text that was edited but not confirmed by the server before the last reload, or by
   * another tab of this browser that could not save it (closed, or reloaded, while the server was
   * away): every copy, each of its own tab. When the disk moved on since a copy's base, the copy is
   * merged with it (or becomes a conflict) rather than written over it. The copies an earlier
   * version kept (one entry per file for every tab) are first moved to one entry per tab.
   */
  private restoreBackups(): void {
    const copies = this.copies;
    copies.migrateLegacy();
    for (const path of copies.paths()) void this.takeUpCopies(path);
  }

  /** Files whose other tabs' copies are being taken up (one pass at a time). */
  private readonly takingUp = new Set<string>();

  /**
   * Takes up the copies other tabs left of `path`, oldest first, one at a time: each while the
   * file is saved in this tab (its own edits on disk), so that it is merged with the disk (the
   * other copies and this tab's edits included) as a restored copy is, never put over unsaved text;
   * a copy is dropped only once this tab holds its text (and keeps its own copy of it).
   */
  private async takeUpCopies(path: string): Promise<void> {
    if (this.takingUp.has(path)) return;
    this.takingUp.add(path);
    try {
      for (const [tab] of this.copies.others(path, this.tabId)) {
        // a tab still open saves its own text (taken up here too, its overlap would be asked twice)
        if (await this.tabOpen(tab)) continue;
        const copy = this.copies.get(path, tab);
        if (!copy) continue; // saved by its tab meanwhile
        let fs: FileState;
        try {
          fs = await this.ensureModel(path);
        } catch {
          // The file is gone on disk: recreate it rather than lose the text.
          this.onNotice.fire({ level: 'warning', text: `${path} no longer existed on disk: recreated from your unsaved edits` });
          await api.write(path, copy.text).then(() => this.refreshTree()).then(() => this.dropCopy(path, tab)).catch(() => undefined);
          return;
        }
        if (fs.state !== 'saved' && !(await this.savedAgain(fs))) return; // taken up again after this tab's next save
        if (fs.model.isDisposed()) return;
        if (fs.model.getValue() === copy.text) {
          this.dropCopy(path, tab);
          continue;
        }
        this.onNotice.fire({ level: 'info', text: `Restored unsaved edits of ${path} kept in this browser (by this tab before a reload, or by another tab that could not save them)` });
        // the disk still holds the copy's base, or the save in flight at the reload landed (then it is the base)
        if (copy.baseText === undefined || copy.baseVersion === fs.diskVersion || copy.baseText === fs.diskText || copy.sentText === fs.diskText) {
          fs.model.setValue(copy.text); // triggers markDirty -> this tab's copy, and a save on the disk's version
        } else {
          // edited from an older text: merge with the disk's (whose text the model shows now)
          const disk = { text: fs.diskText, version: fs.diskVersion ?? '' };
          fs.diskText = copy.baseText;
          fs.diskVersion = copy.baseVersion;
          this.showText(fs, copy.text);
          this.setState(fs, 'dirty');
          this.reconcile(fs, disk.text, disk.version);
        }
        this.dropCopy(path, tab); // its text is this tab's now, in this tab's copy
      }
    } finally {
      this.takingUp.delete(path);
    }
  }

  /**
   * The tabs of this browser on this address (BroadcastChannel: the origin, as localStorage): each
   * answers when asked whether it is open, so that only the copies of tabs gone are taken up.
   */
  private readonly tabs = (() => {
    const channel = new BroadcastChannel('contract-studio:tabs');
    channel.addEventListener('message', (e: MessageEvent<{ open?: string }>) => {
      if (e.data?.open === this.tabId) channel.postMessage({ isOpen: this.tabId });
    });
    return channel;
  })();

  /** Whether tab `tab` is open in this browser (it answers within TAB_ANSWER_MS). */
  private tabOpen(tab: string): Promise<boolean> {
    return new Promise((done) => {
      const heard = (e: MessageEvent<{ isOpen?: string }>) => {
        if (e.data?.isOpen !== tab) return;
        clearTimeout(timer);
        this.tabs.removeEventListener('message', heard);
        done(true);
      };
      const timer = setTimeout(() => {
        this.tabs.removeEventListener('message', heard);
        done(false);
      }, TAB_ANSWER_MS);
      this.tabs.addEventListener('message', heard);
      this.tabs.postMessage({ open: tab });
    });
  }

  /** Resolves true once `fs` is saved (its text on disk), false when its model went away first. */
  private savedAgain(fs: FileState): Promise<boolean> {
    return new Promise((done) => {
      const off = this.onFileState.on((f) => {
        if (f !== fs || (f.state !== 'saved' && !f.model.isDisposed())) return;
        off();
        done(!f.model.isDisposed());
      });
    });
  }
}
