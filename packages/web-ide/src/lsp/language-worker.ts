/// <reference lib="webworker" />
/**
 * Web Worker entry: the Cactal Langium language server over postMessage. The main thread opens
 * every workspace .contract file (didOpen), so cross-file references resolve for files that have
 * no tab. Extra request `cactal/architecture` returns the schemas for the architecture view;
 * `cactal/validated` answers once every document opened before it is validated, its diagnostics
 * published (the IDE's ready mark waits for it). Notification `cactal/projectLayout` tells the
 * projects of the workspace (docs/codegen.md "Where a project is"): names and project-wide checks
 * are per project (the language's scoping/projects.ts).
 */
import { DocumentState, EmptyFileSystem, URI } from 'langium';
import { startLanguageServer } from 'langium/lsp';
import { BrowserMessageReader, BrowserMessageWriter, createConnection } from 'vscode-languageserver/browser.js';
import { addScenarioSupport, createCactalServices } from '@contract-studio/language';
import type { ProjectLayout } from './project-layout.js';
import { schemasOf, type ArchSchema } from './architecture-model.js';

declare const self: DedicatedWorkerGlobalScope;

const reader = new BrowserMessageReader(self);
const writer = new BrowserMessageWriter(self);
const connection = createConnection(reader, writer);
const { shared, Cactal } = createCactalServices({ connection, ...EmptyFileSystem });
addScenarioSupport(shared); // .scenario files: diagnostics, completion, hover (docs/simulation.md "Editing scenarios")
startLanguageServer(shared);

/** Rebuilds every open document. */
const rebuildAll = () => {
  const docs = shared.workspace.LangiumDocuments;
  const uris = shared.workspace.TextDocuments.all().map((d) => URI.parse(d.uri)).filter((u) => docs.hasDocument(u));
  if (uris.length) void shared.workspace.DocumentBuilder.update(uris, []);
};

// Project-wide checks (one scheduler configuration, names unique across files) depend on files a
// document does not reference: after files are added or removed, rebuild every document.
connection.onNotification('cactal/revalidateAll', rebuildAll);

// The IDE knows the file tree (the folders holding a src-gen/, every .contract file, also those not
// opened yet): each document's project follows from it, as for the CLI; a change of it rebuilds all.
connection.onNotification('cactal/projectLayout', (layout: ProjectLayout) => {
  const trees = new Set(layout.trees.map((t) => (t ? `${layout.root}/${t}` : layout.root)));
  Cactal.projects.Projects.configure({
    openedFolders: [URI.parse(layout.root)],
    probe: (folder) => trees.has(folder.toString()),
    contractFiles: () => layout.contracts
  });
  rebuildAll();
});

// After the builds of every change received before it (the update handler queues each as a write of
// the workspace lock once the workspace manager is ready; a read runs after the writes queued
// before it): the diagnostics of that validation are sent before this answer, on the same connection.
connection.onRequest('cactal/validated', async (): Promise<null> => {
  await shared.workspace.WorkspaceManager.ready;
  await shared.workspace.WorkspaceLock.read(() => shared.workspace.DocumentBuilder.waitUntil(DocumentState.Validated).catch(() => undefined));
  return null;
});

connection.onRequest('cactal/architecture', async (): Promise<ArchSchema[]> => {
  await shared.workspace.DocumentBuilder.waitUntil(DocumentState.Linked).catch(() => undefined);
  const out: ArchSchema[] = [];
  for (const doc of shared.workspace.LangiumDocuments.all) {
    out.push(...schemasOf(doc.parseResult.value as never, doc.uri.toString()));
  }
  return out;
});
