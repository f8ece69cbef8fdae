/**
 * A project's `src-gen/` made or removed on disk changes which project a file is in (conventions'
 * project-root.ts, rule 1: `contract generate` of one project of a workspace folder makes it a
 * project of its own). A client that watches files for the server (it offers
 * `workspace.didChangeWatchedFiles.dynamicRegistration`: VS Code; Langium then asks it for every
 * path, folders included) tells the server of the folder; a client that watches none (Neovim on
 * Linux, a plain LSP client) told nothing, and the server saw the new layout only at the next file
 * added or deleted. For such a client the server watches, itself, the folders where a `src-gen/`
 * would move a file into another project: each workspace folder and every folder between it and a
 * `.contract` file of the workspace (one `fs.watch` each, not recursive; MAX_WATCHED_FOLDERS at
 * most). A `src-gen` made or removed in one of them is handed to the document update handler as
 * the client's watcher event for that folder would be (created or deleted): the projects are worked
 * out again and the files that moved checked again at once.
 */
import { watch, type FSWatcher } from 'node:fs';
import { join } from 'node:path';
import { URI, type LangiumDocument } from 'langium';
import type { LangiumSharedServices } from 'langium/lsp';
import { FileChangeType, type FileEvent } from 'vscode-languageserver';
import { SRC_GEN_DIR } from '@contract-studio/conventions';
import { isTreeFolder } from './load-workspace.js';

/** The src-gen/ folders made or removed within this time of the first are told in one event. */
const TOLD_TOGETHER_MS = 20;

/** Bound on the folders watched (a workspace with more gets the first ones, workspace folders first). */
export const MAX_WATCHED_FOLDERS = 2000;

/** The folders (paths) where a `src-gen/` decides a project: `folder` itself and those between it and each document under it. */
export function treeFoldersOf(folder: string, documents: readonly string[]): string[] {
    const base = folder.replace(/\/$/, '');
    const out = new Set<string>([base]);
    for (const doc of documents) {
        if (!doc.startsWith(`${base}/`) || !doc.endsWith('.contract')) continue;
        const parts = doc.slice(base.length + 1).split('/').slice(0, -1);
        for (let i = 0; i < parts.length && parts[i] !== SRC_GEN_DIR; i++) out.add(`${base}/${parts.slice(0, i + 1).join('/')}`);
    }
    return [...out];
}

export function watchTreeFolders(shared: LangiumSharedServices): void {
    let clientWatches = false;
    const watchers = new Map<string, FSWatcher>();
    shared.lsp.LanguageServer.onInitialize((params) => {
        clientWatches = Boolean(params.capabilities.workspace?.didChangeWatchedFiles?.dynamicRegistration);
    });
    // the folders whose src-gen/ came or went, told together (contract generate of several projects: one update)
    const seen = new Set<string>();
    let timer: ReturnType<typeof setTimeout> | undefined;
    const tell = () => {
        timer = undefined;
        const changes = [...seen].map((folder): FileEvent => {
            const tree = join(folder, SRC_GEN_DIR);
            return { uri: URI.file(tree).toString(), type: isTreeFolder(tree) ? FileChangeType.Created : FileChangeType.Deleted };
        });
        seen.clear();
        shared.lsp.DocumentUpdateHandler.didChangeWatchedFiles?.({ changes });
    };
    const told = (folder: string) => {
        seen.add(folder);
        timer ??= setTimeout(tell, TOLD_TOGETHER_MS);
    };
    const refresh = () => {
        const folders = (shared.workspace.WorkspaceManager.workspaceFolders ?? []).map((f) => URI.parse(f.uri)).filter((u) => u.scheme === 'file').map((u) => u.fsPath);
        const documents = shared.workspace.LangiumDocuments.all.filter((d: LangiumDocument) => d.uri.scheme === 'file').map((d) => d.uri.fsPath).toArray();
        const wanted = new Set(folders.flatMap((f) => treeFoldersOf(f, documents)).slice(0, MAX_WATCHED_FOLDERS));
        for (const [folder, w] of watchers) if (!wanted.has(folder)) {
            w.close();
            watchers.delete(folder);
        }
        for (const folder of wanted) {
            if (watchers.has(folder)) continue;
            try {
                const w = watch(folder, { persistent: false }, (_event, name) => {
                    if (name === SRC_GEN_DIR) told(folder);
                });
                w.on('error', () => {
                    w.close();
                    watchers.delete(folder);
                });
                watchers.set(folder, w);
            } catch {
                // a folder gone, or no watch left (ENOSPC): its src-gen/ is seen at the next change, as before
            }
        }
    };
    shared.lsp.LanguageServer.onInitialized(() => {
        if (clientWatches) return;
        void shared.workspace.WorkspaceManager.ready.then(() => {
            refresh();
            shared.workspace.DocumentBuilder.onUpdate(() => refresh());
        });
    });
}
