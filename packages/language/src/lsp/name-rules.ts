/**
 * Which new names a rename may give (docs/language-reference.md §3 naming rules): a Cactal identifier that is not a
 * keyword of Cactal or C nor a name the generated C already takes (validation/c-names/); modules and supervisors exactly three upper-case letters (not `ORD`);
 * no clash with a sibling member or with another top-level element of the same family.
 */
import { AstUtils, GrammarAST, type AstNode, type Grammar } from 'langium';
import type { ProjectIndex } from '../scoping/projects.js';
import {
    isConstant, isEnumMember, isEnumType, isDataType, isField, isFunctionPrototype, isLocalVariable, isModel, isModule, isParameter, isPort, isRule, isSchema,
    isSupervisionFunction, isSupervisor, isFunctionParameter, isSchemaParameter, isFunctionArgument
} from '../generated/ast.js';
import { localsOf, parametersOf, rulesOf } from '../model/blocks.js';
import { portsOf } from '../model/ports.js';
import { CommonHeaderIndex } from '../validation/c-names/common-headers.js';
import { cNameConflict, enumConstantConflict, enumConstantsOf } from '../validation/c-names/reserved-names.js';
import { C_KEYWORDS, cNameRole } from '../validation/identifier-checks.js';

const IDENTIFIER = /^[A-Za-z][A-Za-z0-9_]*$/;
const MODULE_NAME = /^[A-Z]{3}$/;

/** The word Cactal uses for a kind of named element in messages. */
export function kindWord(node: AstNode): string {
    const words: Record<string, string> = {
        DataType: 'datatype', Field: 'field', FunctionPrototype: 'function', FunctionArgument: 'argument',
        Module: 'module', Parameter: 'parameter', Port: 'port', Schema: 'schema', SchemaParameter: 'schema parameter',
        Supervisor: 'supervisor', SupervisionFunction: 'supervision function', FunctionParameter: 'parameter',
        LocalVariable: 'local', Rule: 'rule label', EnumType: 'enumeration', EnumMember: 'enumeration member', Constant: 'constant'
    };
    return words[node.$type] ?? 'element';
}

const keywordCache = new WeakMap<Grammar, Set<string>>();

/** Alphabetic keywords of the grammar (they cannot be identifiers, except where a rule allows them). */
export function grammarKeywords(grammar: Grammar): Set<string> {
    let words = keywordCache.get(grammar);
    if (!words) {
        words = alphabeticKeywords(grammar);
        keywordCache.set(grammar, words);
    }
    return words;
}

function alphabeticKeywords(node: AstNode): Set<string> {
    return new Set(AstUtils.streamAllContents(node).filter(GrammarAST.isKeyword).map((k) => k.value).filter((v) => /^[A-Za-z_]\w*$/.test(v)));
}

/** Keywords the grammar accepts as the name of a node of `type` (its `name=` calls a data type rule such as `Name`). */
function keywordsAllowedAsName(grammar: Grammar, type: string): Set<string> {
    const rule = grammar.rules.find((r) => GrammarAST.isParserRule(r) && r.name === type);
    if (!rule) return new Set();
    const assignment = AstUtils.streamAllContents(rule).filter(GrammarAST.isAssignment).find((a) => a.feature === 'name');
    const terminal = assignment?.terminal;
    const called = GrammarAST.isRuleCall(terminal) ? terminal.rule.ref : undefined;
    return GrammarAST.isParserRule(called) ? alphabeticKeywords(called) : new Set();
}

/** Names of the members that share a namespace with `node` (itself excluded). */
function siblingNames(node: AstNode): string[] {
    const owner = node.$container;
    let members: Array<{ name?: string }> = [];
    if (isField(node) && isDataType(owner)) members = owner.fields;
    else if (isEnumMember(node) && isEnumType(owner)) members = owner.members;
    else if (isFunctionArgument(node) && isFunctionPrototype(owner)) members = owner.args;
    else if (isParameter(node) || isPort(node)) {
        const holder = AstUtils.getContainerOfType(node, (n) => isModule(n) || isSupervisor(n));
        if (isModule(holder)) members = [...parametersOf(holder), ...portsOf(holder).map((p) => p.port)];
        else if (isSupervisor(holder)) members = portsOf(holder).map((p) => p.port);
    } else if (isSchemaParameter(node) && isSchema(owner)) members = owner.parameters;
    else if (isSupervisionFunction(node) && isSupervisor(owner)) members = owner.functions;
    else if (isFunctionParameter(node) || isLocalVariable(node)) {
        const fn = AstUtils.getContainerOfType(node, isSupervisionFunction);
        if (fn) members = [...fn.parameters, ...localsOf(fn)];
    } else if (isRule(node)) {
        const fn = AstUtils.getContainerOfType(node, isSupervisionFunction);
        if (fn) members = rulesOf(fn);
    }
    return members.filter((m) => m !== node).flatMap((m) => (m.name ? [m.name] : []));
}

/** The project's enumeration constants (reserved-names.ts enumConstantsOf), from the index. */
function projectEnumConstants(index: ProjectIndex): Map<string, string[]> {
    return enumConstantsOf(index.allElements('EnumType').map((d) => d.node).filter(isEnumType));
}

/** `a datatype`, `an enumeration`. */
function aWord(what: string): string {
    return `${/^[aeiou]/.test(what) ? 'an' : 'a'} ${what}`;
}

/** The kinds `contract rename DIR NAME` finds by their name alone (rename-entity.ts). */
const FOUND_BY_NAME = ['Module', 'Supervisor', 'Schema', 'DataType', 'EnumType', 'FunctionPrototype'] as const;

/**
 * Why `newName` would give `node` the name of an element of another kind that `contract rename`
 * finds by name alone (an enumeration named like a module: legal Cactal, but then neither could be
 * renamed by that name), or undefined. Clashes of one kind are said by the rules below.
 */
function renamedByNameClash(node: AstNode, newName: string, index: ProjectIndex): string | undefined {
    const foundByName = isModule(node) || isSupervisor(node) || isSchema(node) || isDataType(node) || isEnumType(node) || isFunctionPrototype(node);
    if (!foundByName) return undefined;
    const family: readonly string[] = isModule(node) || isSupervisor(node) ? ['Module', 'Supervisor'] : isDataType(node) || isEnumType(node) ? ['DataType', 'EnumType'] : [];
    const clash = FOUND_BY_NAME.flatMap((t) => index.allElements(t).toArray())
        .find((d) => d.name === newName && d.node !== node && !family.includes(d.type) && !(d.type === node.$type));
    if (!clash) return undefined;
    return `'${newName}' already names ${aWord(kindWord({ $type: clash.type } as AstNode))} (in ${clash.documentUri.path.split('/').pop()}): two elements of one name could not be told apart by a rename; choose another name.`;
}

/** Why `newName` cannot name `node`, or undefined when it can. */
export function renameProblem(node: AstNode & { name?: string }, newName: string, grammar: Grammar, index: ProjectIndex): string | undefined {
    const what = kindWord(node);
    if (!IDENTIFIER.test(newName)) {
        return `'${newName}' is not a valid name: ${aWord(what)} name starts with a letter and has only letters, digits and '_'.`;
    }
    if (grammarKeywords(grammar).has(newName) && !keywordsAllowedAsName(grammar, node.$type).has(newName)) {
        return `'${newName}' is a Cactal keyword and cannot name ${aWord(what)}.`;
    }
    if (C_KEYWORDS.has(newName)) return `'${newName}' is a C keyword and the generated C uses Cactal names as they are.`;
    const role = cNameRole(node);
    if (role && !newName.startsWith('_')) {
        const datatypes = new Set(index.allElements('DataType').map((d) => d.name).filter((n) => n !== node.name || role !== 'datatype'));
        const others = (type: string) => new Set(index.allElements(type).filter((d) => d.node !== node).map((d) => d.name));
        const why = cNameConflict(newName, role, { datatypes, constants: others('Constant'), functions: others('FunctionPrototype'), enumConstants: projectEnumConstants(index) });
        if (why) return `'${newName}' cannot name ${aWord(what)} in the generated C: ${why}.`;
    }
    const byName = renamedByNameClash(node, newName, index);
    if (byName) return byName;
    if (isModule(node) || isSupervisor(node)) {
        if (newName === 'ORD') return `'ORD' is the scheduler's name and cannot name ${aWord(what)}.`;
        if (!MODULE_NAME.test(newName)) return `'${newName}' is not a valid ${what} name: module and supervisor names are exactly three upper-case letters (A-Z).`;
        const clash = [...index.allElements('Module'), ...index.allElements('Supervisor')].find((d) => d.name === newName && d.node !== node);
        if (clash) return `'${newName}' already names a module or supervisor (in ${clash.documentUri.path.split('/').pop()}); names are unique across the project.`;
        return undefined;
    }
    if (isModel(node.$container)) {
        // datatypes, enumerations and constants share one namespace (type-duplicate-name)
        const family = isDataType(node) || isEnumType(node) || isConstant(node) ? ['DataType', 'EnumType', 'Constant'] : [node.$type];
        const clash = family.flatMap((t) => index.allElements(t).toArray()).find((d) => d.name === newName && d.node !== node);
        if (clash) return `'${newName}' already names ${aWord(kindWord({ $type: clash.type } as AstNode))} (in ${clash.documentUri.path.split('/').pop()}).`;
        if (isDataType(node) || isFunctionPrototype(node)) {
            const others = [...index.allElements('DataType'), ...index.allElements('FunctionPrototype')]
                .filter((d) => d.node !== node && (d.type === 'DataType' || d.type === 'FunctionPrototype'))
                .map((d) => ({ kind: d.type === 'DataType' ? 'datatype' as const : 'function' as const, name: d.name }));
            const header = new CommonHeaderIndex(others).clash({ kind: isDataType(node) ? 'datatype' : 'function', name: newName });
            if (header) return `'${newName}' would share the generated ${header.shared} with ${header.other.kind} '${header.other.name}'.`;
        }
        return undefined;
    }
    if (siblingNames(node).includes(newName)) return `'${newName}' is already used by another member next to this ${what}.`;
    // a member becomes the enumeration constant <Enum>_<member>: a file-scope name of its own
    if (isEnumMember(node) && isEnumType(node.$container) && node.$container.name && !newName.startsWith('_')) {
        const cName = `${node.$container.name}_${newName}`;
        const self = `member ${node.name} of enumeration ${node.$container.name}`;
        const why = enumConstantConflict(cName, self, {
            datatypes: new Set([...index.allElements('DataType'), ...index.allElements('EnumType')].map((d) => d.name)),
            constants: new Set(index.allElements('Constant').map((d) => d.name)),
            functions: new Set(index.allElements('FunctionPrototype').map((d) => d.name)),
            enumConstants: projectEnumConstants(index),
        });
        if (why) return `'${newName}' would make the C enumeration constant ${cName}, which cannot be used: ${why}.`;
    }
    return undefined;
}
