/**
 * Turns Langium's syntax and linking errors into Cactal diagnostics: every diagnostic gets a
 * code; an unresolved name that exists in a file this one does not import becomes
 * `import-not-imported` (with the import path for the quick fix); other unresolved references say
 * what would be valid in their context.
 */
import {
    Cancellation, DefaultDocumentValidator, DocumentValidator,
    type LangiumDocument, type ValidationOptions, type ReferenceInfo
} from 'langium';
import type { Diagnostic } from 'vscode-languageserver-types';
import type { CactalServices } from '../cactal-module.js';
import { describeUnresolved } from './unresolved-messages.js';
import { ImportCodes } from './codes/imports.js';
import { SyntaxCodes } from './codes/syntax.js';
import { TypeCodes } from './codes/types.js';
import { isTypeRef } from '../generated/ast.js';

export class CactalDocumentValidator extends DefaultDocumentValidator {
    private readonly services: CactalServices;

    constructor(services: CactalServices) {
        super(services);
        this.services = services;
    }

    override async validateDocument(document: LangiumDocument, options?: ValidationOptions, cancelToken?: Cancellation.CancellationToken): Promise<Diagnostic[]> {
        const diagnostics = await super.validateDocument(document, options, cancelToken);
        for (const d of diagnostics) {
            if (d.code === undefined) {
                const code = (d.data as { code?: string } | undefined)?.code;
                if (code) d.code = code;
            }
        }
        return diagnostics;
    }

    protected override processLinkingErrors(document: LangiumDocument, diagnostics: Diagnostic[], _options: ValidationOptions): void {
        const reflection = this.services.shared.AstReflection;
        const index = this.services.shared.workspace.IndexManager;
        const imports = this.services.imports.ImportResolver;
        for (const reference of document.references) {
            const linkingError = reference.error;
            if (!linkingError) continue;
            const info: ReferenceInfo = linkingError.info;
            const range = reference.$refNode?.range;
            const refText = reference.$refText;
            const base = {
                node: info.container,
                range,
                property: info.property,
                index: info.index
            };
            let referenceType: string | undefined;
            try { referenceType = reflection.getReferenceType(info); } catch { referenceType = undefined; }
            const topLevel = referenceType && ['DataType', 'NamedType', 'Constant', 'ValueSymbol', 'FunctionPrototype', 'Module', 'Supervisor', 'Schema', 'EventSource'].includes(referenceType);
            if (topLevel && refText) {
                const visible = imports.visibleUris(info.container);
                const candidate = index.allElements(referenceType).find((d) => d.name === refText && !visible.has(d.documentUri.toString()));
                if (candidate) {
                    const importPath = imports.relativeImportPath(document.uri, candidate.documentUri);
                    diagnostics.push(this.toDiagnostic(ImportCodes['import-not-imported'].severity,
                        `'${refText}' is defined in "${importPath}", which this file does not import: add import "${importPath}"; (imports are not transitive).`,
                        { ...base, code: 'import-not-imported', data: { code: 'import-not-imported', importPath, refText } }));
                    continue;
                }
            }
            const message = describeUnresolved(info, refText, linkingError.message);
            if (message === undefined) continue; // follows from another unresolved reference, reported there
            if (isTypeRef(info.container)) {
                diagnostics.push(this.toDiagnostic(TypeCodes['type-unknown'].severity, message, {
                    ...base, code: 'type-unknown', data: { code: 'type-unknown', refText }
                }));
                continue;
            }
            diagnostics.push(this.toDiagnostic(SyntaxCodes['linking-error'].severity, message, {
                ...base,
                code: DocumentValidator.LinkingError,
                data: { code: DocumentValidator.LinkingError, containerType: info.container.$type, property: info.property, refText }
            }));
        }
    }
}
