/**
 * The text edits that rename a named element everywhere (its declaration and every reference in
 * every file of its project). Port and parameter references written as their index (`MSC:1`, `(v :0)`) designate
 * the port by number, not by name: only the segments whose text is the old name are replaced.
 * A schema's name is also written as a string in ORD event tests (`ORD:0<ord_schema == "s">`):
 * those strings are renamed with it (model/ord-schema-tests.ts).
 */
import { AstUtils, type AstNode, type LangiumDocuments, type References } from 'langium';
import type { TextEdit, WorkspaceEdit } from 'vscode-languageserver-types';
import { isSchema } from '../generated/ast.js';
import { ordSchemaNamesIn } from '../model/ord-schema-tests.js';
import type { CactalProjects } from '../scoping/projects.js';

export function renameEdits(references: References, documents: LangiumDocuments, projects: CactalProjects, target: AstNode & { name?: string }, newName: string): WorkspaceEdit {
    const changes: Record<string, TextEdit[]> = {};
    const oldName = target.name;
    if (!oldName) return { changes };
    const seen = new Set<string>();
    for (const ref of references.findReferences(target, { includeDeclaration: true })) {
        const uri = ref.sourceUri.toString();
        const key = `${uri}#${ref.segment.offset}`;
        if (seen.has(key)) continue;
        seen.add(key);
        const doc = documents.hasDocument(ref.sourceUri) ? documents.getDocument(ref.sourceUri) : undefined;
        const text = doc?.textDocument.getText().slice(ref.segment.offset, ref.segment.end);
        if (text !== oldName) continue; // a reference by index
        (changes[uri] ??= []).push({ range: ref.segment.range, newText: newName });
    }
    if (isSchema(target)) {
        // the strings of its own project: another project's schema may have the same name
        for (const doc of projects.documentsOf(AstUtils.getDocument(target).uri)) {
            for (const literal of ordSchemaNamesIn(doc.parseResult.value, oldName)) {
                if (literal.$cstNode) (changes[doc.uri.toString()] ??= []).push({ range: literal.$cstNode.range, newText: `"${newName}"` });
            }
        }
    }
    return { changes };
}
