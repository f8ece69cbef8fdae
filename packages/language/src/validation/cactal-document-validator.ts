/**
 * Turns Langium's syntax and linking errors into Cactal diagnostics: every diagnostic gets a
 * code; an unresolved name that exists in a file this one does not import becomes
 * `import-not-imported` (with the import path for the quick fix); other unresolved references say
 * what would be valid in their context.
 */
import {
    Cancellation, DefaultDocumentValidator, DocumentValidator, URI,
    type LangiumDocument, type ValidationOptions, type ReferenceInfo
} from 'langium';
import type { Diagnostic } from 'vscode-languageserver-types';
import type { CactalServices } from '../cactal-module.js';
import { describeUnresolved, nearName } from './unresolved-messages.js';
import { ImportCodes } from './codes/imports.js';
import { SyntaxCodes } from './codes/syntax.js';
import { TypeCodes } from './codes/types.js';
import { isTypeRef, isVariableRef } from '../generated/ast.js';
import { conflictMarkers } from '@contract-studio/conventions';
import { conflictMarkerDiagnostics } from './conflict-marker-diagnostics.js';

export class CactalDocumentValidator extends DefaultDocumentValidator {
    private readonly services: CactalServices;

    constructor(services: CactalServices) {
        super(services);
        this.services = services;
    }

    override async validateDocument(document: LangiumDocument, options?: ValidationOptions, cancelToken?: Cancellation.CancellationToken): Promise<Diagnostic[]> {
        // an unresolved git merge: the markers alone, not the parser's tens of errors on them and on two sides read as one text
        const markers = conflictMarkers(document.textDocument.getText());
        if (markers.length > 0) return conflictMarkerDiagnostics(markers);
        const diagnostics = await super.validateDocument(document, options, cancelToken);
        for (const d of diagnostics) {
            if (d.code === undefined) {
                const code = (d.data as { code?: string } | undefined)?.code;
                if (code) d.code = code;
            }
        }
        return withoutFollowOnErrors(diagnostics);
    }

    /**
     * " ("encoder.contract" has a syntax error: fix it first, it may be where this is defined)" when a
     * file this one imports did not parse and its text has the unknown name: its elements may be
     * missing only because of that error (a misspelt `synchronus module ENC`, before misspelt
     * keywords were read as meant, made every use of ENC in three other files an error). A file
     * whose text does not have the name cannot be where it is defined, syntax error or not: naming
     * it sent the reader of "Unknown module 'PLM' ... Did you mean 'PLN'?" to a file with no PLM.
     */
    private brokenImportNote(document: LangiumDocument, info: ReferenceInfo, refText: string): string {
        const docs = this.services.shared.workspace.LangiumDocuments;
        const own = document.uri.toString();
        const broken: string[] = [];
        for (const uri of this.services.imports.ImportResolver.visibleUris(info.container)) {
            if (uri === own) continue;
            const other = docs.getDocument(URI.parse(uri));
            if (other && (other.parseResult.parserErrors.length > 0 || other.parseResult.lexerErrors.length > 0)
                && mentions(other.textDocument.getText(), refText)) {
                broken.push(this.services.imports.ImportResolver.relativeImportPath(document.uri, other.uri));
            }
        }
        if (broken.length === 0) return '';
        const names = broken.slice(0, 3).map((b) => `"${b}"`).join(', ') + (broken.length > 3 ? ', ...' : '');
        return ` (${names} ${broken.length === 1 ? 'has' : 'have'} a syntax error: fix ${broken.length === 1 ? 'it' : 'them'} first, it may be where this is defined)`;
    }

    protected override processLinkingErrors(document: LangiumDocument, diagnostics: Diagnostic[], _options: ValidationOptions): void {
        const reflection = this.services.shared.AstReflection;
        const index = this.services.shared.workspace.IndexManager;
        const imports = this.services.imports.ImportResolver;
        const projects = this.services.projects.Projects;
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
                const candidate = index.allElements(referenceType).find((d) => d.name === refText && !visible.has(d.documentUri.toString()) && projects.sameProject(d.documentUri, document.uri));
                if (candidate) {
                    const importPath = imports.relativeImportPath(document.uri, candidate.documentUri);
                    diagnostics.push(this.toDiagnostic(ImportCodes['import-not-imported'].severity,
                        `'${refText}' is defined in "${importPath}", which this file does not import: add import "${importPath}"; (imports are not transitive).`,
                        { ...base, code: 'import-not-imported', data: { code: 'import-not-imported', importPath, refText } }));
                    continue;
                }
            }
            // a supervisor where a module is expected (`SUP:1 =* MAB:0` in an event schema): say what it is
            if (referenceType === 'Module' && refText && index.allElements('Supervisor').some((d) => d.name === refText && projects.sameProject(d.documentUri, document.uri))) {
                diagnostics.push(this.toDiagnostic(SyntaxCodes['linking-error'].severity, supervisorNotModule(refText, info.container.$type), {
                    ...base,
                    code: DocumentValidator.LinkingError,
                    data: { code: DocumentValidator.LinkingError, containerType: info.container.$type, property: info.property, refText }
                }));
                continue;
            }
            // a top-level name: the closest one of that kind in the workspace (`LNI` -> 'LIN'); a
            // variable: the closest of those of its context and these (describeUnresolved)
            const globals = topLevel && referenceType && refText ? index.allElements(referenceType).filter((d) => projects.sameProject(d.documentUri, document.uri)).map((d) => d.name).distinct().toArray() : [];
            const described = describeUnresolved(info, refText, linkingError.message, globals);
            if (described === undefined) continue; // follows from another unresolved reference, reported there
            const near = isVariableRef(info.container) ? '' : nearName(refText, globals);
            const message = topLevel ? described + near + this.brokenImportNote(document, info, refText) : described;
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

/** Whether `text` has `name` as a whole word (not inside a longer name: `PLM` is not in `PLM2`). */
function mentions(text: string, name: string): boolean {
    if (!name) return false;
    for (let at = text.indexOf(name); at >= 0; at = text.indexOf(name, at + 1)) {
        if (!/[A-Za-z0-9_]/.test(text[at - 1] ?? '') && !/[A-Za-z0-9_]/.test(text[at + name.length] ?? '')) return true;
    }
    return false;
}

/**
 * A supervisor named where only a module may be: a schema's modules and flows, `parameterize`,
 * `activate resttime|critical module`. Its events (`notify :o`) reach only the supervisors that
 * subscribe to them; no module receives them.
 */
export function supervisorNotModule(name: string, containerType: string): string {
    const flow = containerType === 'EventCommunication'
        ? ` A supervisor's events (notify :o) reach only the supervisors that subscribe to them (subscribe ${name}:o =* :i in a rule); no module receives them, and a schema's event flows join modules.`
        : '';
    return `'${name}' is a supervisor, not a module: a schema's modules and flows, parameterize and activate resttime|critical module name modules only.${flow}`;
}

const SYNTAX = new Set(['parsing-error', 'lexing-error']);

/**
 * After a syntax error, the parser's recovery reads the rest of that line in a way the user never
 * meant: `[CAM:0<count > 3>(parts = count)]` gave five errors, the later ones about a rule label
 * `count` that does not exist. The first syntax error of a line is the one to fix, so every other
 * diagnostic starting on that line after it is dropped (the line's earlier diagnostics and the
 * other lines are kept). Exported for its test.
 */
export function withoutFollowOnErrors(diagnostics: Diagnostic[]): Diagnostic[] {
    const firstSyntax = new Map<number, number>();
    for (const d of diagnostics) {
        if (!SYNTAX.has(String(d.code))) continue;
        const { line, character } = d.range.start;
        const seen = firstSyntax.get(line);
        if (seen === undefined || character < seen) firstSyntax.set(line, character);
    }
    if (firstSyntax.size === 0) return diagnostics;
    const keptLines = new Set<number>();
    return diagnostics.filter((d) => {
        const { line, character } = d.range.start;
        const at = firstSyntax.get(line);
        if (at === undefined || character < at) return true;
        if (character === at && SYNTAX.has(String(d.code))) {
            // the first syntax error of the line itself (only one of several at the same place)
            if (keptLines.has(line)) return false;
            keptLines.add(line);
            return true;
        }
        return false;
    });
}
