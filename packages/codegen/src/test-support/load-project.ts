import { URI, type LangiumDocument } from 'langium';
import type { CactalServices, Model } from '@contract-studio/language';

/** Parses, links and validates in-memory Cactal files (name -> text) with `services`; returns the documents and the errors. */
export async function loadProject(services: CactalServices, files: Record<string, string>) {
    const shared = services.shared;
    const previous = shared.workspace.LangiumDocuments.all.map((d) => d.uri).toArray();
    if (previous.length) await shared.workspace.DocumentBuilder.update([], previous);
    const docs: Array<LangiumDocument<Model>> = [];
    for (const [file, text] of Object.entries(files)) {
        const doc = shared.workspace.LangiumDocumentFactory.fromString<Model>(text, URI.parse(`file:///ws/${file}`));
        shared.workspace.LangiumDocuments.addDocument(doc);
        docs.push(doc);
    }
    await shared.workspace.DocumentBuilder.build(docs, { validation: true });
    const errors = docs.flatMap((d) => (d.diagnostics ?? []).filter((x) => x.severity === 1)
        .map((x) => `${d.uri.path}:${x.range.start.line + 1} ${x.code} ${x.message}`));
    return { docs, models: docs.map((d) => d.parseResult.value), errors };
}
