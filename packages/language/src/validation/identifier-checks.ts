/**
 * Identifiers become C names as they are (report §5.3): no C keyword, no leading `_`, and no name
 * that the generated C or the headers it includes already take (c-names/reserved-names.ts;
 * docs/language-reference.md, "Reserved names").
 */
import { AstUtils, type AstNode, type MultiMap, type AstNodeDescription, type ValidationAcceptor, type ValidationChecks } from 'langium';
import { isFunctionPrototype, isModule, type CactalAstType, type DataType, type EnumMember, type EnumType, type FunctionPrototype, type Module } from '../generated/ast.js';
import { parametersOf } from '../model/blocks.js';
import { portsOf } from '../model/ports.js';
import type { CactalServices } from '../cactal-module.js';
import { CommonHeaderIndex } from './c-names/common-headers.js';
import { cNameConflict, enumConstantConflict, enumConstantsOf, suggestName, type CNameRole, type ProjectCNames } from './c-names/reserved-names.js';
import { ModuleCodes } from './codes/modules.js';
import { ProjectNames } from './project-index.js';
import { report } from './report.js';

/**
 * C11 keywords, the C23 ones (bool, true, false, alignas, ...: keywords when the generated tree is
 * built with a newer -std, stdbool.h/stdalign.h macros before) and GNU C's `asm` and `typeof`
 * (keywords when CFLAGS drops -std=c11 for gcc's default gnu dialect).
 */
export const C_KEYWORDS = new Set([
    'auto', 'break', 'case', 'char', 'const', 'continue', 'default', 'do', 'double', 'else', 'enum', 'extern',
    'float', 'for', 'goto', 'if', 'inline', 'int', 'long', 'register', 'restrict', 'return', 'short', 'signed',
    'sizeof', 'static', 'struct', 'switch', 'typedef', 'union', 'unsigned', 'void', 'volatile', 'while',
    '_Alignas', '_Alignof', '_Atomic', '_Bool', '_Complex', '_Generic', '_Imaginary', '_Noreturn', '_Static_assert',
    '_Thread_local', 'bool', 'true', 'false', 'alignas', 'alignof', 'constexpr', 'nullptr', 'static_assert',
    'thread_local', 'typeof', 'typeof_unqual', 'asm'
]);

/** The longest name (docs/language-reference.md §1): `.SharedFunction<name>.h.tmp-<pid>` stays under 255 bytes. */
export const MAX_NAME_LENGTH = 200;

const NAMED_TYPES = [
    'Constant', 'DataType', 'EnumType', 'Field', 'FunctionPrototype', 'FunctionArgument', 'Module', 'Parameter', 'Port', 'Schema',
    'SchemaParameter', 'Supervisor', 'SupervisionFunction', 'FunctionParameter', 'LocalVariable', 'Rule'
] as const;

/** What a named node becomes in the generated C (see c-names/reserved-names.ts), or undefined for names only used in strings. */
export function cNameRole(node: AstNode): CNameRole | undefined {
    switch (node.$type) {
        case 'DataType': case 'EnumType': return 'datatype'; // an enumeration is a typedef and a tag too
        case 'FunctionPrototype': return 'function';
        case 'Constant': return 'constant'; // a macro of common/constants.h
        case 'Port': case 'Parameter': return AstUtils.getContainerOfType(node, isModule) ? 'module-variable' : undefined;
        case 'Field': case 'SchemaParameter': case 'FunctionParameter': case 'LocalVariable': return 'member';
        case 'FunctionArgument': return 'argument';
        default: return undefined;
    }
}

const datatypeSets = new WeakMap<MultiMap<string, AstNodeDescription>, ProjectCNames>();

/**
 * The project's names that the reserved-name rules depend on (cached per workspace build: the
 * tables of one build are all rebuilt together, so the datatype table keys the others too).
 */
export function projectCNames(names: ProjectNames, context: AstNode): ProjectCNames {
    const byName = names.byName(['DataType', 'EnumType'], context);
    let project = datatypeSets.get(byName);
    if (!project) {
        const enumConstants = enumConstantsOf(names.nodesOf('EnumType', context) as EnumType[]);
        const moduleVariables = new Set<string>();
        for (const node of names.nodesOf('Module', context)) {
            const m = node as Module;
            for (const v of [...parametersOf(m), ...portsOf(m).map((p) => p.port)]) if (v.name) moduleVariables.add(v.name);
        }
        project = {
            datatypes: new Set(byName.keys()),
            constants: new Set(names.byName(['Constant'], context).keys()),
            functions: new Set(names.byName(['FunctionPrototype'], context).keys()),
            enumConstants,
            moduleVariables
        };
        datatypeSets.set(byName, project);
    }
    return project;
}

function checkIdentifier(node: AstNode & { name?: string }, accept: ValidationAcceptor, names: ProjectNames): void {
    const name = node.name;
    if (!name) return;
    if (C_KEYWORDS.has(name)) {
        report(accept, ModuleCodes['identifier-c-keyword'], `'${name}' is a C keyword and the generated C uses Cactal names as they are: choose another name (e.g. '${name}_').`, { node, property: 'name' as never });
        return;
    }
    if (name.length > MAX_NAME_LENGTH) {
        report(accept, ModuleCodes['identifier-too-long'], `A name is at most ${MAX_NAME_LENGTH} characters (this one has ${name.length}): generated file names are made of names, and a file name is at most 255 bytes.`, { node, property: 'name' as never });
        return;
    }
    if (name.startsWith('_')) {
        report(accept, ModuleCodes['identifier-reserved-prefix'], `'${name}' starts with '_', which is reserved for generated code: choose a name starting with a letter.`, { node, property: 'name' as never });
        return;
    }
    const role = cNameRole(node);
    if (!role) return;
    const project = projectCNames(names, node);
    const why = cNameConflict(name, role, project);
    if (!why) return;
    const suggestion = suggestName(name, (candidate) => cNameConflict(candidate, role, project) === undefined);
    report(accept, ModuleCodes['identifier-c-reserved'],
        `'${name}' cannot name ${/^[aeiou]/.test(kindWord(node)) ? 'an' : 'a'} ${kindWord(node)} in the generated C: ${why}. Choose another name (e.g. '${suggestion}').`,
        { node, property: 'name' as never, data: { suggestion } });
}

const KIND_WORDS: Record<string, string> = {
    Constant: 'constant', DataType: 'datatype', EnumType: 'enumeration', FunctionPrototype: 'function', Port: 'port', Parameter: 'parameter', Field: 'field',
    SchemaParameter: 'schema parameter', FunctionParameter: 'parameter', LocalVariable: 'local', FunctionArgument: 'argument'
};
function kindWord(node: AstNode): string {
    return KIND_WORDS[node.$type] ?? 'element';
}

const headerIndexes = new WeakMap<MultiMap<string, AstNodeDescription>, CommonHeaderIndex>();

/** The common/ headers of the project's datatypes and functions (cached per workspace build). */
export function commonHeaders(names: ProjectNames, context: AstNode): CommonHeaderIndex {
    const datatypes = names.byName(['DataType', 'EnumType'], context);
    let index = headerIndexes.get(datatypes);
    if (!index) {
        const functions = names.byName(['FunctionPrototype'], context);
        index = new CommonHeaderIndex([
            ...[...datatypes.keys()].map((name) => ({ kind: 'datatype' as const, name })),
            ...[...functions.keys()].map((name) => ({ kind: 'function' as const, name }))
        ]);
        headerIndexes.set(datatypes, index);
    }
    return index;
}

/**
 * An enumeration member becomes the C enumeration constant `<Enum>_<member>` (`Mode_AUTO`), a
 * file-scope name wherever `common/Shared<Enum>.h` is included: it must not collide like a datatype name.
 */
function checkEnumMember(member: EnumMember, accept: ValidationAcceptor, names: ProjectNames): void {
    const owner = member.$container;
    if (!member.name || !owner?.name) return;
    if (member.name.length > MAX_NAME_LENGTH) {
        report(accept, ModuleCodes['identifier-too-long'], `A name is at most ${MAX_NAME_LENGTH} characters (this one has ${member.name.length}).`, { node: member, property: 'name' });
        return;
    }
    const cName = `${owner.name}_${member.name}`;
    const project = projectCNames(names, member);
    const self = `member ${member.name} of enumeration ${owner.name}`;
    // a datatype name never equals a constant's (type-checks.ts), but a member's C name may
    const conflict = (c: string) => enumConstantConflict(c, self, project);
    const why = conflict(cName);
    if (!why) return;
    const suggestion = suggestName(member.name, (candidate) => conflict(`${owner.name}_${candidate}`) === undefined);
    report(accept, ModuleCodes['identifier-c-reserved'],
        `Member '${member.name}' of enumeration ${owner.name} becomes the C name ${cName}, which cannot be used: ${why}. Choose another name (e.g. '${suggestion}').`,
        { node: member, property: 'name', data: { suggestion } });
}

/** A datatype, enumeration or function whose generated `common/` header would share a file or an include guard with another's. */
function checkCommonHeader(node: DataType | EnumType | FunctionPrototype, accept: ValidationAcceptor, names: ProjectNames): void {
    if (!node.name) return;
    const owner = { kind: isFunctionPrototype(node) ? 'function' as const : 'datatype' as const, name: node.name };
    const index = commonHeaders(names, node);
    const clash = index.clash(owner);
    if (!clash) return;
    const suggestion = suggestName(node.name, (candidate) => index.clash({ kind: owner.kind, name: candidate }) === undefined);
    report(accept, ModuleCodes['identifier-generated-clash'],
        `${owner.kind} '${node.name}' and ${clash.other.kind} '${clash.other.name}' would share the generated ${clash.shared}: rename one of them (e.g. '${suggestion}').`,
        { node, property: 'name', data: { suggestion } });
}

export function identifierChecks(services: CactalServices): ValidationChecks<CactalAstType> {
    const names = new ProjectNames(services);
    const check = (node: AstNode & { name?: string }, accept: ValidationAcceptor) => checkIdentifier(node, accept, names);
    const checks: Record<string, (node: never, accept: ValidationAcceptor) => void> = {};
    for (const type of NAMED_TYPES) checks[type] = check;
    const header = (node: DataType | EnumType | FunctionPrototype, accept: ValidationAcceptor) => checkCommonHeader(node, accept, names);
    checks['DataType'] = (node: DataType, accept) => { check(node, accept); header(node, accept); };
    checks['EnumType'] = (node: EnumType, accept) => { check(node, accept); header(node, accept); };
    checks['EnumMember'] = (node: EnumMember, accept) => checkEnumMember(node, accept, names);
    checks['FunctionPrototype'] = (node: FunctionPrototype, accept) => { check(node, accept); header(node, accept); };
    return checks as ValidationChecks<CactalAstType>;
}
