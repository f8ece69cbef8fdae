/**
 * Renaming an entity of a loaded workspace outside an editor (`contract rename`): the entity is
 * found by name (`MSC`, `TypeA`, `Mode`, `Mode.AUTO`, `SUP.mission`, `MSC:in_coordinates`, `SUP.action.FIRST`), the new name is checked by
 * the same rules as the editor's rename and the edits are the editor's rename edits
 * (`lsp/name-rules.ts`, `lsp/rename-edits.ts`), so that both rename the same references.
 * Pure over the workspace: the caller writes the new texts (docs/getting-started.md, "Renaming").
 */
import { AstUtils, type AstNode } from 'langium';
import { TextDocument } from 'vscode-languageserver-textdocument';
import {
    isDataType, isEnumMember, isEnumType, isFunctionParameter, isFunctionPrototype, isModel, isModule, isSchema, isSupervisionFunction, isSupervisor,
    type EnumType, type Module, type SupervisionFunction, type Supervisor,
} from '../generated/ast.js';
import { parametersOf } from '../model/blocks.js';
import { portsOf } from '../model/ports.js';
import { closestName } from '../model/near-names.js';
import { kindWord, renameProblem } from '../lsp/name-rules.js';
import { renameEdits } from '../lsp/rename-edits.js';
import type { LoadedWorkspace } from './load-workspace.js';

type Named = AstNode & { name: string };

/** A rename that cannot be done: unknown or ambiguous entity, invalid or taken name. */
export class RenameError extends Error {}

export interface PlannedFileEdit {
    /** Path relative to the workspace directory. */
    file: string;
    /** Absolute path. */
    path: string;
    /** The file's text after the rename. */
    text: string;
    /** How many occurrences of the name change in this file. */
    occurrences: number;
}

export interface RenamePlan {
    /** `module`, `datatype`, `port`, ... (the words of the editor's messages). */
    kind: string;
    oldName: string;
    newName: string;
    /**
     * Whether generated files and region IDs are named after the entity (modules, supervisors,
     * datatypes, enumerations, functions): their generated tree is carried over (codegen's renameInGeneratedTree).
     */
    generatedNames: boolean;
    /**
     * What the entity belongs to, as the scenarios and the generated tree name it: a port's or
     * parameter's module or supervisor, a supervision function's supervisor, a rule label's,
     * local's or function parameter's function (`SUP.function`), an enumeration member's
     * enumeration; undefined for a top-level name.
     */
    owner?: string;
    /** A renamed enumeration's members: its C constants `<Enum>_<member>` follow it (codegen's identifierRenames). */
    members?: string[];
    files: PlannedFileEdit[];
}

/** The owner of `node` (RenamePlan.owner), from where it stands in the model. */
function ownerOf(node: AstNode): string | undefined {
    if (isSupervisionFunction(node)) return node.$container.name;
    if (isEnumMember(node)) return isEnumType(node.$container) ? node.$container.name : undefined;
    const fn = AstUtils.getContainerOfType(node.$container, isSupervisionFunction);
    if (fn) return `${fn.$container.name}.${fn.name}`;
    if (isModule(node) || isSupervisor(node)) return undefined;
    return AstUtils.getContainerOfType(node.$container, (n): n is Module | Supervisor => isModule(n) || isSupervisor(n))?.name;
}

/** Top-level elements whose names the generated tree carries (paths and region IDs, docs/codegen.md). */
function namesGeneratedFiles(node: AstNode): boolean {
    return isModule(node) || isSupervisor(node) || isDataType(node) || isEnumType(node) || isFunctionPrototype(node);
}

function topLevelElements(ws: LoadedWorkspace): Named[] {
    return ws.documents.flatMap((d) => (isModel(d.model) ? d.model.elements : []))
        .filter((e): e is typeof e & Named => typeof (e as { name?: unknown }).name === 'string');
}

function located(node: Named, ws: LoadedWorkspace): string {
    const root = AstUtils.findRootNode(node);
    const doc = ws.documents.find((d) => d.model === root);
    return `${kindWord(node)} ${node.name}${doc ? ` (${doc.file})` : ''}`;
}

function owner(ws: LoadedWorkspace, name: string, spec: string): Module | Supervisor {
    const found = topLevelElements(ws).filter((e): e is Module | Supervisor => (isModule(e) || isSupervisor(e)) && e.name === name);
    if (found.length === 0) throw new RenameError(`no module or supervisor named '${name}' (in '${spec}')`);
    return found[0]!;
}

/** The supervision function `fn` of supervisor `sup` (named in `spec`), or a RenameError. */
function supervisionFunction(ws: LoadedWorkspace, sup: string, fn: string, spec: string): SupervisionFunction {
    // 'NAME.x' is SUPERVISOR.function or ENUM.MEMBER: a name that is neither says both, with the nearest
    const holders = topLevelElements(ws).filter((e) => isSupervisor(e) || isModule(e) || isEnumType(e));
    if (!holders.some((e) => e.name === sup)) {
        const near = closestName(sup, holders.filter((e) => isSupervisor(e) || isEnumType(e)).map((e) => e.name));
        throw new RenameError(`no supervisor or enumeration named '${sup}' (in '${spec}': 'SUPERVISOR.function' or 'ENUM.MEMBER')${near ? `. Did you mean '${near}'?` : ''}`);
    }
    const holder = owner(ws, sup, spec);
    if (!isSupervisor(holder)) throw new RenameError(`${holder.name} is a module; 'NAME.function' names a supervision function of a supervisor`);
    const found = holder.functions.find((f) => f.name === fn);
    if (!found) throw new RenameError(`supervisor ${holder.name} has no function '${fn}'; its functions: ${holder.functions.map((f) => f.name).join(', ') || 'none'}`);
    return found;
}

/** The member `name` of enumeration `e` (named in `spec`), or a RenameError. */
function enumerationMember(e: EnumType, name: string): Named {
    const found = e.members.find((m) => m.name === name);
    if (!found) throw new RenameError(`enumeration ${e.name} has no member '${name}'; its members: ${e.members.map((m) => m.name).join(', ') || 'none'}`);
    return found as Named;
}

/**
 * The entity `spec` designates: a top-level name (module, supervisor, schema, datatype,
 * enumeration, function), `OWNER:port` (a port or parameter of a module or supervisor, by name or
 * by index when only one port has it), `ENUM.MEMBER` (a member of an enumeration), `SUP.function`
 * (a supervision function), or `SUP.function.NAME` (a parameter, a local or a rule label of that function).
 */
export function findEntity(ws: LoadedWorkspace, spec: string): Named {
    const port = /^([^:.]+):([^:.]+)$/.exec(spec);
    if (port) {
        const holder = owner(ws, port[1]!, spec);
        const members = [
            ...(isModule(holder) ? parametersOf(holder).map((p) => ({ node: p as Named, index: p.index, what: `parameter :${p.index}` })) : []),
            ...portsOf(holder).map((p) => ({ node: p.port as Named, index: p.index, what: `${p.direction} ${p.kind} port :${p.index}` }))
        ];
        const byName = members.filter((m) => m.node.name === port[2]);
        const byIndex = /^[0-9]+$/.test(port[2]!) ? members.filter((m) => m.index === Number(port[2])) : [];
        const matches = byName.length > 0 ? byName : byIndex;
        const list = members.map((m) => `${m.node.name} (${m.what})`).join(', ') || 'none';
        if (matches.length === 0) throw new RenameError(`${holder.name} has no port or parameter '${port[2]}'; its ports and parameters: ${list}`);
        if (matches.length > 1) throw new RenameError(`'${spec}' is ambiguous: ${matches.map((m) => `${m.node.name} (${m.what})`).join(', ')}; name the port instead of its index`);
        return matches[0]!.node;
    }
    const member = /^([^:.]+)\.([^:.]+)\.([^:.]+)$/.exec(spec);
    if (member) {
        const fn = supervisionFunction(ws, member[1]!, member[2]!, spec);
        const members = [...fn.parameters, ...fn.locals.flatMap((b) => b.variables), ...fn.rules.flatMap((b) => b.rules)] as Named[];
        const matches = members.filter((m) => m.name === member[3]);
        const list = members.map((m) => `${m.name} (${kindWord(m)})`).join(', ') || 'none';
        if (matches.length === 0) throw new RenameError(`${member[1]}.${member[2]} has no parameter, local or rule '${member[3]}'; it has: ${list}`);
        if (matches.length > 1) throw new RenameError(`'${spec}' names several elements: ${matches.map((m) => kindWord(m)).join(', ')}; rename one by hand first`);
        return matches[0]!;
    }
    const fn = /^([^:.]+)\.([^:.]+)$/.exec(spec);
    if (fn) {
        // ENUM.MEMBER or SUP.function (a supervisor of the enumeration's name, if any, is meant)
        const enumeration = topLevelElements(ws).find((e): e is EnumType & Named => isEnumType(e) && e.name === fn[1]);
        if (enumeration && !topLevelElements(ws).some((e) => isSupervisor(e) && e.name === fn[1])) return enumerationMember(enumeration, fn[2]!);
        return supervisionFunction(ws, fn[1]!, fn[2]!, spec) as Named;
    }
    const found = topLevelElements(ws).filter((e) => e.name === spec && (isModule(e) || isSupervisor(e) || isSchema(e) || isDataType(e) || isEnumType(e) || isFunctionPrototype(e)));
    if (found.length === 0) {
        throw new RenameError(`no module, supervisor, schema, datatype, enumeration or function named '${spec}' (a port is 'MODULE:port', a supervision function 'SUPERVISOR.function', an enumeration member 'ENUM.MEMBER')`);
    }
    if (found.length > 1) throw new RenameError(`'${spec}' names several elements: ${found.map((e) => located(e, ws)).join(', ')}; rename one by hand first`);
    return found[0]!;
}

/**
 * Plans renaming `spec` to `newName` in the workspace: checks the name with the editor's rules
 * (identifier, keywords, three upper-case letters for modules and supervisors, no clash) and
 * computes each changed file's new text. Throws RenameError with a message for the user.
 */
export function planRename(ws: LoadedWorkspace, spec: string, newName: string): RenamePlan {
    const target = findEntity(ws, spec);
    const services = ws.services;
    // a supervision function's parameter is not a module's: no C variable of a module is named after it
    const kind = isFunctionParameter(target) ? 'function parameter' : kindWord(target);
    if (target.name === newName) throw new RenameError(`${kind} ${target.name} already has that name`);
    const problem = renameProblem(target, newName, services.Grammar, services.projects.Projects.indexOf(AstUtils.getDocument(target).uri));
    if (problem) throw new RenameError(problem);
    const edit = renameEdits(services.references.References, services.shared.workspace.LangiumDocuments, services.projects.Projects, target, newName);
    const files: PlannedFileEdit[] = [];
    for (const [uri, edits] of Object.entries(edit.changes ?? {})) {
        const doc = ws.documents.find((d) => d.document.uri.toString() === uri);
        if (!doc) throw new RenameError(`a reference to ${target.name} is in ${uri}, which is not a file of this workspace`);
        const text = doc.document.textDocument.getText();
        const copy = TextDocument.create(uri, 'cactal', 0, text);
        files.push({ file: doc.file, path: doc.path, text: TextDocument.applyEdits(copy, edits), occurrences: edits.length });
    }
    files.sort((a, b) => a.file.localeCompare(b.file));
    const members = isEnumType(target) ? target.members.map((m) => m.name) : undefined;
    return { kind, oldName: target.name, newName, generatedNames: namesGeneratedFiles(target), owner: ownerOf(target), ...(members ? { members } : {}), files };
}
